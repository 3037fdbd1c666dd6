"""Self-consistent rotation δ(F_T) = ∫dF/K: against a closed form, brute force and its own convergence order."""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from ropemodel.numerics.capstan_rotation import fixed_step_function, regime1_rotation, rotation, unwrap_load
from ropemodel.papers import li_capstan as li

P = dict(mu=0.25, EA=5e4, R=0.075, L=0.36, alpha_0=math.radians(64.0), F_p=60.0)


def brute_force(F_T, continuous=False, **kw):
    """Reference: DOP853 at rtol 1e-12 with steps of at most 0.05 N, K re-evaluated (regime included) at
    every stage; it steps over the switches blindly, so its error is bounded by the step, not by luck."""
    p = {**P, **kw}

    def rate(F, d):
        if F == 0.0:
            return [p["L"] / (2 * p["EA"])]  # the limit of 1/K at zero load (also for L = 0)
        a1, a2 = li.wrap_angles(p["alpha_0"], d[0], p["R"])
        return [1.0 / li.drive_stiffness(F, p["F_p"], p["mu"], p["EA"], p["R"], p["L"], a1, a2, continuous)]

    sol = solve_ivp(rate, (0.0, F_T), [0.0], method="DOP853", rtol=1e-12, atol=1e-16, max_step=0.05)
    return sol.y[0, -1]


def test_closed_form_of_regime_one_matches_quadrature():
    # the derivation in regime1_rotation, checked against adaptive quadrature of 1/K(row 1)
    mu, EA, R, L, F_p = (P[k] for k in ("mu", "EA", "R", "L", "F_p"))
    for F in (1.0, 8.0, 14.0):
        ref, _ = quad(lambda x: 1.0 / li.drive_stiffness(x, F_p, mu, EA, R, L, 1e3, 1e3), 0.0, F, epsabs=0,
                      epsrel=1e-13)
        assert regime1_rotation(F, mu, EA, R, L, F_p) == pytest.approx(ref, rel=1e-11)


def test_rotation_in_regime_one_equals_the_closed_form():
    F_sw = li.slack_switch_load(P["F_p"], P["mu"], P["alpha_0"])
    F = np.linspace(0.0, 0.99 * F_sw, 7)
    exact = regime1_rotation(F, P["mu"], P["EA"], P["R"], P["L"], P["F_p"])
    np.testing.assert_allclose(rotation(F, **P), exact, rtol=1e-9, atol=0)


@pytest.mark.parametrize("variant", ["li", "continuous"])
def test_rotation_across_switches_matches_brute_force(variant):
    # 20 N: past the slack and tight switches; 100 N: past the preload as well (regimes 1, 2, 3, 4)
    for F in (20.0, 100.0):
        ref = brute_force(F, continuous=variant == "continuous")
        assert rotation(F, **P, variant=variant) == pytest.approx(ref, rel=1e-8)


@pytest.mark.parametrize("variant", ["li", "continuous"])
def test_at_least_fourth_order_across_switches(variant):
    # located switches keep the order of Dormand-Prince 5(4): with n equal steps (no error control)
    # halving the step divides the error by more than 16 (a stepped-over jump of K would leave first
    # order, a factor 2; a kink second order).  100 N: past the slack, tight and preload switches.
    args = [100.0, *P.values()]
    ref = float(fixed_step_function(variant, 1024)(*args))
    e = [abs(float(fixed_step_function(variant, n)(*args)) - ref) for n in (8, 16, 32)]
    assert e[0] / e[1] > 16 and e[1] / e[2] > 16, e


def test_rotation_with_a_large_wrap_and_small_free_length():
    # a completed case on the way (F_T >= F_p with the tight side not saturated) and L = 0
    kw = dict(alpha_0=4.0, L=0.0)
    assert rotation(150.0, **{**P, **kw}) == pytest.approx(brute_force(150.0, **kw), rel=1e-8)


def test_unwrap_load_is_where_the_rotation_reaches_the_wrap():
    F_u = unwrap_load(**P)
    assert rotation(F_u, **P) / P["R"] == pytest.approx(P["alpha_0"], rel=1e-9)


def test_zero_load_gives_zero_rotation():
    assert rotation(0.0, **P) == 0.0


@pytest.mark.parametrize("variant", ["li", "continuous", "smooth"])
def test_parameter_derivatives_through_located_switches(variant):
    # AD of the event-located scheme (switch locations move with the parameters) against central
    # differences of the rotation, at a load past all three switches
    import casadi as ca

    from ropemodel.numerics.capstan_rotation import ARGS, rotation_function

    fun = rotation_function(variant)
    x = ca.MX.sym("x", len(ARGS))
    jac = ca.Function("j", [x], [ca.jacobian(fun(*ca.vertsplit(x))[0], x)])
    point = np.array([100.0, P["mu"], P["EA"], P["R"], P["L"], P["alpha_0"], P["F_p"]])
    ad = np.asarray(jac(point)).ravel()
    for i in range(len(ARGS)):
        h = 1e-5 * point[i]
        up, dn = point.copy(), point.copy()
        up[i] += h
        dn[i] -= h
        fd = (float(fun(*up)[0]) - float(fun(*dn)[0])) / (2 * h)
        assert ad[i] == pytest.approx(fd, rel=1e-5), ARGS[i]


@pytest.mark.parametrize("variant", ["li", "continuous", "smooth"])
def test_derivatives_finite_at_edge_loads_and_zero_free_length(variant):
    # values and derivatives in every input stay finite at F_T = 0, at and just past F_p, with L = 0 (K(0)
    # infinite) and over the documented range (identification and inverse solves differentiate the rotation)
    import casadi as ca

    from ropemodel.numerics.capstan_rotation import rotation_function

    fun = rotation_function(variant)
    x = ca.MX.sym("x", 7)
    y = ca.vertcat(*fun(*ca.vertsplit(x)))
    jac = ca.Function("j", [x], [y, ca.jacobian(y, x)])
    rng = np.random.default_rng(3)
    n = 0
    for _ in range(60):
        F_p = 10 ** rng.uniform(0, 4)
        load = rng.choice([0.0, 1e-9, 0.5, 1.0, 1.0 + 1e-12, 2.0, rng.uniform(0, 2)])
        point = [F_p * load, rng.uniform(0.05, 1), 10 ** rng.uniform(3, 7), 10 ** rng.uniform(-2, 0),
                 rng.choice([0.0, 10 ** rng.uniform(-2, 1)]), rng.uniform(0.1, 40), F_p]
        value, J = (np.asarray(v) for v in jac(point))
        if point[5] - value[0, 0] / point[3] <= 0:
            continue  # unwrapped: refused by the callers
        n += 1
        assert np.all(np.isfinite(value)) and np.all(np.isfinite(J)), (point, J)
    assert n > 40
