"""Integration of the lining ODE against the exact solution, at the extremes of the required range."""

import itertools
import math

import numpy as np
import pytest
from scipy.special import lambertw

from ropemodel.sheave import closed_log_ratio, ode_log_ratio
from ropemodel.numerics.hajduk_integrators import INTEGRATORS

MU = [0.05, 0.3, 0.6]
ALPHA = [0.0, 1e-4, math.pi / 4, math.pi, 10 * math.pi]
Q = [0.0, 1e-3, 1.0, 30.0, 1e3]
K = [1e-5, 1e-3, 0.1, 10.0, 1e2]


def grid(*axes):
    return [np.array(a, float) for a in zip(*itertools.product(*axes))]


def rel_err(y, ref):
    return np.abs(np.expm1(y - ref))


def test_default_ode_isotropic_extremes():
    """Default path (rk4, rtol 1e-7, ln S in the stretched angle): 1e-6 over the whole range."""
    mu, a, q, k = grid(MU, ALPHA, Q, K)
    y = ode_log_ratio(mu, a, q, k)
    assert np.all(np.isfinite(y))
    assert rel_err(y, closed_log_ratio(mu, a, q, k)).max() < 1e-6


def test_default_ode_anisotropic_extremes():
    mu, a, qR, qT, kR, kT = grid([0.05, 0.6], [1e-4, math.pi, 10 * math.pi], [0.0, 1.0, 1e3], [1e-3, 1e3],
                                 [1e-5, 1e2], [1e-5, 0.1, 1e2])
    y = ode_log_ratio(mu, a, qR, kR, qT, kT)
    assert np.all(np.isfinite(y))
    assert rel_err(y, closed_log_ratio(mu, a, qR, kR, qT, kT)).max() < 1e-6


def test_zero_lambda_omega_is_the_limit():
    """λω = 0 (slow sheave / elastic lining) integrates to the closed form's limit, no failure."""
    mu, a, q = grid(MU, [1e-4, math.pi, 10 * math.pi], [0.0, 1.0, 1e3])
    y = ode_log_ratio(mu, a, q, 0.0)
    assert rel_err(y, closed_log_ratio(mu, a, q, 0.0)).max() < 1e-6


@pytest.mark.parametrize("plugin", sorted(INTEGRATORS))
def test_every_integrator_meets_1e6_at_rtol_1e8(plugin):
    mu, a, q, k = grid([0.05, 0.6], [1e-4, math.pi, 10 * math.pi], [0.0, 1.0, 1e3], [1e-5, 0.1, 1e2])
    y = ode_log_ratio(mu, a, q, k, plugin=plugin, rtol=1e-8)
    assert np.all(np.isfinite(y))
    assert rel_err(y, closed_log_ratio(mu, a, q, k)).max() < 1e-6


def thirion_rigid_ratio(mu, alpha, beta):
    """Rigid lining with μ(s) = μ/(1 + β s): ds/dα = μ s/(1 + β s) separates to
    ln s + β (s − 1) = μα, i.e. s = W(β e^{β + μα})/β (independent truth)."""
    return lambertw(beta * np.exp(beta + mu * alpha)).real / beta


@pytest.mark.parametrize("state", ["log", "invariant"])
def test_pressure_dependent_friction_rigid_against_separable_solution(state):
    mu, a, beta = grid([0.1, 0.5], [0.5, math.pi, 10 * math.pi], [1e-3, 0.3, 5.0])
    y = ode_log_ratio(mu, a, 0.0, 1.0, beta=beta, state=state)
    np.testing.assert_allclose(np.exp(y), thirion_rigid_ratio(mu, a, beta), rtol=1e-6)


def test_pressure_dependent_friction_voigt_two_states_agree():
    """With a Voigt lining and μ(p) there is no closed form: the general ODE (state ln S)
    and the invariant form (state ln S + S C(α)) are two different integrations."""
    mu, a, q, k, beta = grid([0.1, 0.5], [math.pi, 10 * math.pi], [0.1, 30.0], [1e-4, 1.0], [0.05, 2.0])
    y_log = ode_log_ratio(mu, a, q, k, beta=beta, state="log", rtol=1e-9)
    y_inv = ode_log_ratio(mu, a, q, k, beta=beta, state="invariant", rtol=1e-9)
    assert rel_err(y_log, y_inv).max() < 1e-7
    # friction falls with pressure, so the ratio is below the constant-friction one
    assert np.all(y_log < closed_log_ratio(mu, a, q, k))


def test_vanishing_pressure_sensitivity_is_constant_friction():
    mu, a, q, k = grid([0.2], [math.pi, 2 * math.pi], [0.1, 100.0], [0.01 * math.pi, 2 * math.pi])
    y = ode_log_ratio(mu, a, q, k, beta=1e-12)
    assert rel_err(y, closed_log_ratio(mu, a, q, k)).max() < 1e-6
