"""Property tests (hypothesis) of the lined-sheave tension ratio."""

import math

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ropemodel as rm
from ropemodel.sheave import closed_log_ratio, ode_log_ratio
from ropemodel.papers import hajduk1992 as hj

mus = st.floats(0.05, 0.6)
alphas = st.floats(1e-3, 10 * math.pi)
qs = st.floats(0.0, 1e3)
log_ks = st.floats(-5.0, 2.0)


@settings(max_examples=200, deadline=None)
@given(mus, alphas, qs, log_ks)
def test_ratio_never_exceeds_euler_eytelwein(mu, alpha, q, log_k):
    s = hj.tension_ratio(mu, alpha, q, 10**log_k)
    assert 0 < s <= math.exp(mu * alpha) * (1 + 1e-15)


@settings(max_examples=25, deadline=None)
@given(mus, alphas, qs, log_ks, st.floats(-5.0, 2.0))
def test_ode_ratio_never_exceeds_euler_eytelwein(mu, alpha, q, log_kR, log_kT):
    y = ode_log_ratio(mu, alpha, q / 2, 10**log_kR, q / 2, 10**log_kT)
    assert np.isfinite(y) and y <= mu * alpha + 1e-6


@settings(max_examples=200, deadline=None)
@given(mus, alphas, st.floats(1e-6, 1e3), log_ks, st.floats(0.01, 3.0))
def test_ratio_rises_toward_euler_eytelwein_with_speed(mu, alpha, q, log_k, dlog):
    """k = λω grows with ω: the ratio does not fall, and tends to e^{μα}."""
    k1, k2 = 10**log_k, 10 ** (log_k + dlog)
    s1, s2 = hj.tension_ratio(mu, alpha, q, k1), hj.tension_ratio(mu, alpha, q, k2)
    assert s1 <= s2 * (1 + 1e-14)
    # far beyond the lining's retardation: Euler–Eytelwein; 1 − e^{−α/k} ≈ α/k, so the
    # deviation of ln s is ≈ q s α/k <= 1e-12 for this k
    k_fast = 1e12 * alpha * (1 + q) * math.exp(mu * alpha)
    assert hj.tension_ratio(mu, alpha, q, k_fast) == pytest.approx(math.exp(mu * alpha), rel=1e-9)


def sheave(method):
    return rm.from_dict({"scene": {"model": "sheave"}, "effects": {"lining": "voigt"},
                         "parameters": {"S_0": 1e4, "mu": 0.2, "alpha": 3.0, "Q": 1e-5, "lambda": 0.01,
                                        "omega": 1.0},
                         "numerics": {"method": method}}, bare="si")


def ratio_and_jacobian(method):
    """S_ratio as a Function of the scene's parameters, and its CasADi Jacobian."""
    prob = rm.Problem(sheave(method))
    f = prob.function
    names = list(prob.knowns)
    x = ca.MX.sym("x", len(names))
    out = f(*[x[i] for i in range(len(names))])
    s = out[prob.unknowns.index("S_ratio")]
    return names, ca.Function("s", [x], [s]), ca.Function("J", [x], [ca.jacobian(s, x)])


FUNS = {m: ratio_and_jacobian(m) for m in ("closed", "ode")}


POINTS = dict(S_0=st.floats(1e2, 1e6), mu=mus, alpha=alphas, log_Q=st.floats(-9.0, -2.0),
              log_lam=st.floats(-4.0, 1.0), log_omega=st.floats(-2.0, 2.0))


def _point(names, S_0, mu, alpha, log_Q, log_lam, log_omega):
    point = {"S_0": S_0, "mu": mu, "alpha": alpha, "Q": 10**log_Q, "lambda": 10**log_lam, "omega": 10**log_omega}
    return np.array([point[n] for n in names])


@settings(max_examples=30, deadline=None)
@given(**POINTS)
def test_closed_derivatives_finite_and_match_finite_differences(**point):
    names, s, J = FUNS["closed"]
    x = _point(names, **point)
    jac = np.array(J(x)).ravel()
    assert np.all(np.isfinite(jac))
    s0 = float(s(x))
    for i, n in enumerate(names):
        h = 1e-6 * abs(x[i])
        xp, xm = x.copy(), x.copy()
        xp[i] += h
        xm[i] -= h
        fd = (float(s(xp)) - float(s(xm))) / (2 * h)
        # central-difference error bound: truncation ~h² s''' and rounding ~eps·s/h = 2e-10 s/x
        assert abs(jac[i] - fd) <= 1e-5 * abs(jac[i]) + 1e-8 * abs(s0) / abs(x[i]), n


@settings(max_examples=30, deadline=None)
@given(**POINTS)
def test_ode_derivatives_match_the_closed_form(**point):
    """The ODE's derivatives against a second method, the closed form's (checked by differences above).

    Finite differences of the ODE itself are no truth here: its value is right to rtol = 1e-7, so a
    difference over h = 1e-6·x carries up to 0.1 of noise whenever a step decision flips.  The
    derivative of the adaptive solution (steps frozen) solves the variational equation on the same
    steps; its error is not controlled directly and was measured at most 1e-6 in elasticity over 3000
    random points of this box, hence the bound 10·rtol·(1 + largest elasticity).
    """
    rtol = 1e-7
    elasticities = []
    for method in ("closed", "ode"):
        names, s, J = FUNS[method]
        x = _point(names, **point)
        jac = np.array(J(x)).ravel()
        assert np.all(np.isfinite(jac)), method
        elasticities.append(dict(zip(names, jac * x / float(s(x)))))
    closed, ode = elasticities
    scale = 1 + max(abs(e) for e in closed.values())
    for n, e in closed.items():
        assert abs(ode[n] - e) <= 10 * rtol * scale, n


def test_anisotropic_derivatives_match_finite_differences():
    """Every parameter of the anisotropic lining (Q_R, Q_T, λ_R, λ_T too), closed and ODE."""
    for method in ("closed", "ode"):
        scene = rm.from_dict({"scene": {"model": "sheave"}, "effects": {"lining": "voigt_anisotropic"},
                              "parameters": {"S_0": 2e4, "mu": 0.3, "alpha": 5.0, "Q_R": 3e-6, "Q_T": 2e-5,
                                             "lambda_R": 0.002, "lambda_T": 0.5, "omega": 2.0},
                              "numerics": {"method": method}}, bare="si")
        prob = rm.Problem(scene)
        names = list(prob.knowns)
        x = ca.MX.sym("x", len(names))
        out = prob.function(*[x[i] for i in range(len(names))])[prob.unknowns.index("S_ratio")]
        s, J = ca.Function("s", [x], [out]), ca.Function("J", [x], [ca.jacobian(out, x)])
        x0 = np.array([scene.parameters[n] for n in names])
        jac, s0 = np.array(J(x0)).ravel(), float(s(x0))
        assert np.all(np.isfinite(jac))
        for i, n in enumerate(names):
            h = 1e-6 * abs(x0[i])
            xp, xm = x0.copy(), x0.copy()
            xp[i] += h
            xm[i] -= h
            fd = (float(s(xp)) - float(s(xm))) / (2 * h)
            assert abs(jac[i] - fd) <= 1e-5 * abs(jac[i]) + 1e-8 * abs(s0) / abs(x0[i]), (method, n)


def test_derivatives_finite_at_the_limits():
    """λω = 0 and q = 0: derivatives exist and are finite (no NaN from the guarded exponentials)."""
    names, s, J = FUNS["closed"]
    for over in ({"omega": 0.0}, {"lambda": 0.0}, {"Q": 0.0}):
        point = {"S_0": 1e4, "mu": 0.2, "alpha": 3.0, "Q": 1e-5, "lambda": 0.01, "omega": 1.0, **over}
        jac = np.array(J(np.array([point[n] for n in names])))
        assert np.all(np.isfinite(jac)), over


def test_closed_vectorised_matches_scalar():
    mu, a, q, k = 0.3, np.linspace(0.1, 30, 7), 5.0, 0.02
    np.testing.assert_allclose(closed_log_ratio(mu, a, q, k), [hj.log_tension_ratio(mu, ai, q, k) for ai in a],
                               rtol=1e-15)
