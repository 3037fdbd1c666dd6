"""Hajduk (1992) closed form: reference table, limits, independent Lambert-W solution."""

import math

import casadi as ca
import numpy as np
import pytest
from scipy.special import lambertw

from ropemodel.papers import friction as fr
from ropemodel.papers import hajduk1992 as hj

# docs/physics.md §3 reference table (independently computed): mu, q, k/pi, s(pi/2), s(pi), s(2pi)
TABLE = [
    (0.2, 0.1, 0.01, 1.212743, 1.597677, 2.685966),
    (0.2, 0.1, 2.0, 1.329433, 1.749747, 2.921169),
    (0.2, 100, 0.01, 0.036301, 0.038781, 0.043839),
    (0.3, 0.1, 0.5, 1.460686, 2.133928, 4.312762),
    (0.3, 100, 2.0, 0.117940, 0.086236, 0.071543),
]


@pytest.mark.parametrize("row", TABLE)
def test_reference_table_to_6_digits(row):
    mu, q, k_pi, *ref = row
    for alpha, s_ref in zip((math.pi / 2, math.pi, 2 * math.pi), ref):
        assert round(float(hj.tension_ratio(mu, alpha, q, k_pi * math.pi)), 6) == s_ref


@pytest.mark.parametrize("mu", [0.05, 0.2, 0.6])
@pytest.mark.parametrize("alpha", [1e-3, 1.0, math.pi, 10 * math.pi])
@pytest.mark.parametrize("k", [0.0, 1e-5, 1.0, 1e2])
def test_q_zero_is_euler_eytelwein(mu, alpha, k):
    assert hj.tension_ratio(mu, alpha, 0.0, k) == pytest.approx(math.exp(mu * alpha), rel=1e-12)
    assert fr.euler_eytelwein_ratio(mu, alpha) == pytest.approx(math.exp(mu * alpha), rel=1e-15)


def lambert_ratio(mu, alpha, c):
    """Independent truth: s = W(c e^{μα})/c (c > 0), scipy's Lambert W."""
    return lambertw(c * np.exp(mu * alpha)).real / c


def test_closed_form_against_lambert_w():
    rng = np.random.default_rng(7)
    n = 20000
    mu = rng.uniform(0.05, 0.6, n)
    alpha = rng.uniform(0, 10 * np.pi, n)
    q = 10 ** rng.uniform(-6, 3, n)
    k = 10 ** rng.uniform(-5, 2, n)
    c = q * -np.expm1(-alpha / k)
    ok = c > 1e-300
    s = hj.tension_ratio(mu, alpha, q, k)
    np.testing.assert_allclose(s[ok], lambert_ratio(mu[ok], alpha[ok], c[ok]), rtol=1e-12)
    # and the implicit equation (19) holds
    assert np.max(np.abs(hj.tension_ratio_residual(s, mu, alpha, q, k))) < 1e-12


def test_anisotropic_reduces_to_isotropic_and_matches_lambert():
    mu, alpha = 0.3, 2 * math.pi
    iso = hj.tension_ratio(mu, alpha, 3.0, 0.2)
    assert hj.tension_ratio_anisotropic(mu, alpha, 1.0, 0.2, 2.0, 0.2) == pytest.approx(iso, rel=1e-14)
    q_R, k_R, q_T, k_T = 5.0, 1e-3, 40.0, 3.0
    c = q_R * -math.expm1(-alpha / k_R) + q_T * -math.expm1(-alpha / k_T)
    assert hj.tension_ratio_anisotropic(mu, alpha, q_R, k_R, q_T, k_T) == pytest.approx(
        lambert_ratio(mu, alpha, c), rel=1e-13)


def test_limit_k_to_zero_is_the_fully_crept_lining():
    """λω → 0 (elastic lining or slow sheave): ln s + q s = μα, for α > 0."""
    mu, alpha, q = 0.25, math.pi, 7.0
    limit = lambert_ratio(mu, alpha, q)
    assert hj.tension_ratio(mu, alpha, q, 0.0) == pytest.approx(limit, rel=1e-14)
    assert hj.tension_ratio(mu, alpha, q, 1e-9) == pytest.approx(limit, rel=1e-14)
    # at alpha = 0 the lining has not crept: s = 1
    assert hj.tension_ratio(mu, 0.0, q, 0.0) == 1.0


def test_limit_k_to_infinity_is_euler_eytelwein():
    mu, alpha, q = 0.25, math.pi, 7.0
    assert hj.tension_ratio(mu, alpha, q, 1e12) == pytest.approx(math.exp(mu * alpha), rel=1e-9)


def test_casadi_derivatives_finite_at_the_limits():
    """d s / d(every argument) finite at k = 0 and α = 0 (no NaN from unused exponentials)."""
    x = ca.SX.sym("x", 4)
    s = hj.tension_ratio(x[0], x[1], x[2], x[3])
    J = ca.Function("J", [x], [ca.jacobian(s, x)])
    for point in ([0.2, math.pi, 5.0, 0.0], [0.2, 0.0, 5.0, 0.0], [0.2, 0.0, 5.0, 1e-3], [0.2, 1.0, 0.0, 1e-300]):
        assert np.all(np.isfinite(np.array(J(point))))


def test_casadi_numpy_agree():
    x = ca.SX.sym("x", 4)
    f = ca.Function("f", [x], [hj.tension_ratio(x[0], x[1], x[2], x[3])])
    for p in ([0.2, 1.0, 0.1, 0.03], [0.6, 30.0, 1000.0, 1e-5], [0.05, 0.5, 1e-4, 50.0]):
        assert float(f(p)) == pytest.approx(float(hj.tension_ratio(*p)), rel=1e-15)


def test_lining_data_functions():
    # Q_R = h/(E R^2 a), Q_T = mu/(G R a), lambda = eta/E: by hand for a 20 mm rubber lining
    assert hj.radial_compliance(0.02, 5e7, 1.0, 0.03) == pytest.approx(0.02 / (5e7 * 0.03))
    assert hj.tangential_compliance(0.25, 1.7e7, 1.0, 0.03) == pytest.approx(0.25 / (1.7e7 * 0.03))
    assert hj.retardation_time(5e5, 5e7) == pytest.approx(0.01)


def test_ode_right_side_is_the_derivative_of_the_closed_form():
    """dS/dα of eq. (5)-(6) equals the slope of the exact solution (finite difference)."""
    mu, q, k = 0.3, 2.0, 0.4
    for alpha in (0.05, 0.5, 3.0):
        s = hj.tension_ratio(mu, alpha, q, k)
        h = 1e-6
        fd = (hj.tension_ratio(mu, alpha + h, q, k) - hj.tension_ratio(mu, alpha - h, q, k)) / (2 * h)
        assert hj.tension_slope(s, alpha, mu, q, k, 0.0, 1.0) == pytest.approx(fd, rel=1e-7)
