"""Koepe hoist on a Voigt-lined wheel (ropemodel.papers.koepe_lining) against Hajduk's closed form solved by brentq.

Truths written here: eq. (19), ln s + s S_0 [Q_R (1 − e^{−α/k_R}) + Q_T (1 − e^{−α/k_T})] = μα with S_0 the
slack side's tension per rope and k = λ v/R, solved by scipy's brentq; the slip acceleration by bisection on
a where the high side's tension reaches what eq. (19) lets the arc hold; its limits (no lining compliance:
the rigid wheel's closed form; at rest: fully crept; fast: Euler–Eytelwein).
"""

import math

import casadi as ca
import numpy as np
import pytest
from scipy.optimize import brentq

from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_lining as kl
from ropemodel.papers import koepe_slip as ks

G = 9.80665


def crept(alpha, lam, v, R):
    """1 − e^{−α/k}, k = λ v/R (1 when k = 0: fully crept)."""
    k = lam * v / R
    return 1.0 if k == 0 else -math.expm1(-alpha / k)


def hajduk_ratio(T_2, n, mu, alpha, R, v, Q_R, lam_R, Q_T=0.0, lam_T=0.0):
    """s = S/S_0 from eq. (19) by brentq, S_0 = T_2/n."""
    C = Q_R * crept(alpha, lam_R, v, R) + Q_T * crept(alpha, lam_T, v, R)
    q = C * T_2 / n
    return brentq(lambda s: math.log(s) + q * s - mu * alpha, 1e-300, math.exp(mu * alpha) * (1 + 1e-12),
                  xtol=1e-300, rtol=1e-15)


def test_static_traction_ratio_against_brentq():
    rng = np.random.default_rng(11)
    for _ in range(400):
        T_2, n = rng.uniform(5e4, 2e6), int(rng.integers(1, 9))
        mu, alpha, R, v = rng.uniform(0.1, 0.5), rng.uniform(2.5, 4.0), rng.uniform(1.0, 3.5), rng.uniform(0, 20)
        Q_R, Q_T = 10 ** rng.uniform(-11, -5), 10 ** rng.uniform(-11, -5)
        lam_R, lam_T = 10 ** rng.uniform(-3, 1), 10 ** rng.uniform(-3, 1)
        ref = hajduk_ratio(T_2, n, mu, alpha, R, v, Q_R, lam_R, Q_T, lam_T)
        assert kl.voigt_traction_ratio(T_2, n, mu, alpha, R, v, Q_R, lam_R, Q_T, lam_T) == pytest.approx(ref,
                                                                                                        rel=1e-12)


# docs/physics.md §3 (Hajduk's Fig. 5 setting, computed independently): mu, q, k/pi, s(pi/2), s(pi), s(2pi)
TABLE = [(0.2, 0.1, 0.01, 1.212743, 1.597677, 2.685966), (0.2, 100, 0.01, 0.036301, 0.038781, 0.043839),
         (0.3, 0.1, 0.5, 1.460686, 2.133928, 4.312762), (0.3, 100, 2.0, 0.117940, 0.086236, 0.071543)]


@pytest.mark.parametrize("row", TABLE)
def test_the_reference_table_on_a_wheel(row):
    # q = Q T_2/n with 3 ropes of 150 kN and Q = q/150 kN; k = λ v/R with R = 2.5 m, λ = 0.5 s
    mu, q, k_pi, *ref = row
    v = k_pi * math.pi * 2.5 / 0.5
    for alpha, s in zip((math.pi / 2, math.pi, 2 * math.pi), ref):
        assert round(kl.voigt_traction_ratio(450e3, 3, mu, alpha, 2.5, v, q / 150e3, 0.5), 6) == s


def test_limits_rigid_lining_fast_wheel_and_rest():
    E = math.exp(0.25 * math.pi)
    assert kl.voigt_traction_ratio(6e5, 4, 0.25, math.pi, 2.25, 10.0, 0.0, 0.5) == pytest.approx(E, rel=1e-15)
    # fast: no time to creep (k = λ v/R = 1e8 rad: the crept fraction is 3e-8)
    fast = kl.voigt_traction_ratio(6e5, 4, 0.25, math.pi, 2.25, 4.5e8, 1e-6, 0.5)
    assert fast == pytest.approx(E, rel=1e-6) and fast < E
    # at rest the lining has fully crept: ln s + q s = mu alpha with q = Q T_2/n
    q = 1e-6 * 6e5 / 4
    rest = kl.voigt_traction_ratio(6e5, 4, 0.25, math.pi, 2.25, 0.0, 1e-6, 0.5)
    assert rest == pytest.approx(brentq(lambda s: math.log(s) + q * s - 0.25 * math.pi, 1e-6, E), rel=1e-13)


def brute_force_slip(F_U, F_D, M_U, M_D, n, mu, alpha, R, v, Q_R, lam_R, Q_T=0.0, lam_T=0.0):
    """a at which T_U = s(T_D) T_D, s from eq. (19) by brentq, bisected (the excess decreases with a)."""
    def excess(a):
        T_U, T_D = F_U + M_U * a, F_D - M_D * a
        return hajduk_ratio(T_D, n, mu, alpha, R, v, Q_R, lam_R, Q_T, lam_T) * T_D - T_U

    return brentq(excess, -F_U / M_U * (1 - 1e-9), F_D / M_D * (1 - 1e-9), xtol=1e-14, rtol=1e-15)


def hoist_sides(y_L, F_r=2e3):
    """The issue's example (4 head ropes): each manoeuvre's (F_U, F_D, M_U, M_D) at the loaded depth y_L."""
    T_L, T_E = kp.side_tensions(y_L, 29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5, 3.0)
    return ks.manoeuvre_sides(T_L, T_E, kp.side_mass(T_L), kp.side_mass(T_E, 1500.0), F_r)


@pytest.mark.parametrize("manoeuvre", ks.MANOEUVRES)
@pytest.mark.parametrize("lining", [(2e-9, 0.5, 0.0, 0.0), (3e-7, 0.05, 1e-7, 2.0), (5e-6, 0.3, 2e-6, 0.01)])
def test_slip_acceleration_against_bisection_on_hajduks_closed_form(manoeuvre, lining):
    for y_L in (0.0, 905.0):
        sides = hoist_sides(y_L)[manoeuvre]
        for v in (0.0, 3.0, 12.0):
            ref = brute_force_slip(*sides, 4, 0.25, math.pi, 2.25, v, *lining)
            got = kl.voigt_slip_acceleration(*sides, 4, 0.25, math.pi, 2.25, v, *lining)
            assert got == pytest.approx(ref, rel=1e-10, abs=1e-12)
            rigid = ks.slip_acceleration(*sides, 0.25, math.pi)
            assert got <= rigid   # the lining only costs traction


def test_no_compliance_is_the_rigid_wheel_and_arrays_work():
    sides = [np.array(x) for x in zip(*(hoist_sides(y)["hoist_decel"] for y in np.linspace(0, 905, 9)))]
    rigid = ks.slip_acceleration(*sides, 0.3, 3.3)
    np.testing.assert_allclose(kl.voigt_slip_acceleration(*sides, 4, 0.3, 3.3, 2.25, 5.0, 0.0, 0.5), rigid,
                               rtol=1e-13)
    assert kl.voigt_slip_acceleration(*(float(s[0]) for s in sides), 4, 0.3, 3.3, 2.25, 5.0, 0.0, 0.5) == \
        pytest.approx(float(rigid[0]), rel=1e-13)


def test_newton_converges_in_ten_steps_over_two_hundred_thousand_cases(monkeypatch):
    # the claim behind MAX_NEWTON; every result checked against eq. (19) written out here
    monkeypatch.setattr(kl, "MAX_NEWTON", 10)
    rng = np.random.default_rng(1)
    n = 200_000
    F_U = 10 ** rng.uniform(4, 7, n)
    F_D = F_U * 10 ** rng.uniform(-1.5, 1.5, n)
    M_U, M_D = F_U / G * 10 ** rng.uniform(0, 0.5, n), F_D / G * 10 ** rng.uniform(0, 0.5, n)
    ropes = rng.integers(1, 10, n).astype(float)
    mu, alpha = rng.uniform(0.05, 0.6, n), rng.uniform(0.5, 4 * np.pi, n)
    R, v = rng.uniform(0.5, 4.0, n), rng.uniform(0.0, 25.0, n)
    Q, lam = 10 ** rng.uniform(-14, -2, n), 10 ** rng.uniform(-3, 1, n)
    a = kl.voigt_slip_acceleration(F_U, F_D, M_U, M_D, ropes, mu, alpha, R, v, Q, lam)
    T_U, T_D = F_U + M_U * a, F_D - M_D * a
    k = lam * v / R
    C = Q * np.where(k > 0, -np.expm1(-alpha / np.where(k > 0, k, 1.0)), 1.0)
    residual = np.log(T_U / T_D) + T_U * C / ropes - mu * alpha
    assert np.all(T_U > 0) and np.all(T_D > 0)
    # what a correctly rounded a leaves: its rounding (a few ulp of the terms a is made of) times
    # |df/da| = M_U/T_U + M_D/T_D + M_U C/n, plus the rounding of the residual's terms
    eps = np.finfo(float).eps
    slope = M_U / T_U + M_D / T_D + M_U * C / ropes
    allowed = 8 * eps * ((np.abs(a) + F_D / M_D + F_U / M_U) * slope + 1 + mu * alpha + T_U * C / ropes)
    assert np.all(np.abs(residual) <= allowed)


def test_the_casadi_rootfinder_form_with_its_derivative():
    names = ("F_U", "F_D", "M_U", "M_D", "n", "mu", "alpha", "C")
    p = [ca.MX.sym(name) for name in names]
    y = ca.MX.sym("y")
    rf = ca.rootfinder("slip", "newton", {"x": y, "p": ca.vertcat(*p), "g": kl.voigt_slip_residual(y, *p)},
                       {"abstol": 1e-14, "max_iter": 50})
    y_star = rf(kl.voigt_slip_guess(*p), ca.vertcat(*p))
    a = kl.acceleration_from_log(y_star, p[1], p[3])
    f = ca.Function("a_slip", p, [a, ca.gradient(a, p[1])], list(names), ["a", "da_dF_D"])
    lining = (2.25, 6.0, 4e-7, 0.2)   # R, v, Q_R, lambda_R
    for manoeuvre in ks.MANOEUVRES:
        sides = hoist_sides(905.0)[manoeuvre]
        C = kl.lining_compliance(math.pi, *lining)
        value, slope = (float(x) for x in f(*sides, 4, 0.25, math.pi, C))
        ref = kl.voigt_slip_acceleration(*sides, 4, 0.25, math.pi, *lining)
        assert value == pytest.approx(ref, rel=1e-12)
        h = 1.0   # N, on about 8e5 N
        up = kl.voigt_slip_acceleration(sides[0], sides[1] + h, *sides[2:], 4, 0.25, math.pi, *lining)
        down = kl.voigt_slip_acceleration(sides[0], sides[1] - h, *sides[2:], 4, 0.25, math.pi, *lining)
        assert slope == pytest.approx((up - down) / (2 * h), rel=1e-6)
