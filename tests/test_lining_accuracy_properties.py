"""The lined sheave meets its stated tolerances over the whole documented range, on 10⁴ random points each.

Documented range (README, ``ropemodel.effects.sheave``): μ ∈ [0.05, 0.6], q = Q·S_0 ∈ [0, 10³],
k = λω ∈ [10⁻⁵, 10²] rad, α ∈ [0, 10π], isotropic and anisotropic (λ_R, λ_T, Q_R, Q_T independent).
Stated tolerances: the closed form 1e-12 relative in S; the ODE path at its default (dopri5,
rtol 1e-7) rtol, with an error estimate that is not far below the true error.

Truths independent of the library:
* isotropic: u = ln s = μα − W(c e^{μα}), c = q(1 − e^{−α/k}) (Lambert's W from scipy; where
  c e^{μα} would overflow, W from ln x by the fixed point w = ln x − ln w, written here);
* anisotropic: brentq on the residual ln s + s [q_R(1 − e^{−α/k_R}) + q_T(1 − e^{−α/k_T})] − μα
  written here;
* pressure-dependent friction on a rigid lining: ln s + β(s − 1) = μα (separable), Lambert's W.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import lambertw

from ropemodel.numerics.hajduk_integrators import INTEGRATORS
from ropemodel.sheave import closed_log_ratio, ode_log_ratio

N = 10_000
RTOL = 1e-7          # the ODE path's default [numerics] rtol
CLOSED_TOL = 1e-12   # the closed form's stated tolerance


def lambert_w_of_log(ln_x):
    """W(x) from ln x, x ≥ 0 (ln x = −inf: 0); scipy where x is representable, else w = ln x − ln w."""
    ln_x = np.asarray(ln_x, float)
    w = np.zeros_like(ln_x)
    small = ln_x < 600
    w[small] = lambertw(np.exp(ln_x[small])).real
    big = ~small
    wb = ln_x[big].copy()
    for _ in range(60):
        wb = ln_x[big] - np.log(wb)
    w[big] = wb
    return w


def crept(alpha, k):
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        f = -np.expm1(-alpha / k)
    return np.where(k > 0, f, np.where(alpha > 0, 1.0, 0.0))


def truth_isotropic(mu, alpha, q, k):
    c = q * crept(alpha, k)
    with np.errstate(divide="ignore"):
        ln_x = np.log(c) + mu * alpha
    return mu * alpha - lambert_w_of_log(ln_x)


def truth_anisotropic(mu, alpha, q_R, k_R, q_T, k_T):
    c = q_R * crept(alpha, k_R) + q_T * crept(alpha, k_T)
    out = np.empty_like(mu)
    for i in range(mu.size):
        # f(u) = u + c e^u − μα is increasing; the root lies in [μα − c·e^{μα}, μα] clipped below
        lo = min(0.0, mu[i] * alpha[i]) - 50.0 - math.log1p(c[i])
        out[i] = brentq(lambda u: u + c[i] * math.exp(u) - mu[i] * alpha[i], lo, mu[i] * alpha[i] + 1e-300,
                        xtol=1e-300, rtol=1e-15) if c[i] > 0 else mu[i] * alpha[i]
    return out


def sample(n, seed, anisotropic):
    """Uniform μ, α; log-uniform q (a tenth exactly 0) and k; endpoints included."""
    rng = np.random.default_rng(seed)
    mu = rng.uniform(0.05, 0.6, n)
    alpha = rng.uniform(0.0, 10 * np.pi, n)
    q = np.where(rng.random(n) < 0.1, 0.0, 10 ** rng.uniform(-8, 3, n))
    k = 10 ** rng.uniform(-5, 2, n)
    mu[:4], alpha[:4], q[:4], k[:4] = [0.05, 0.6, 0.6, 0.05], [10 * np.pi, 10 * np.pi, 0.0, 1e-9], [1e3, 1e3, 1.0, 0], \
        [1e-5, 1e2, 1e-5, 1e-5]
    if not anisotropic:
        return mu, alpha, q, k
    share = rng.uniform(0.0, 1.0, n)
    k_T = 10 ** rng.uniform(-5, 2, n)
    return mu, alpha, q * share, k, q * (1 - share), k_T


def rel_err(y, u):
    return np.abs(np.expm1(y - u))


def test_closed_form_isotropic_10k_against_lambert_w():
    mu, alpha, q, k = sample(N, 1, False)
    err = rel_err(closed_log_ratio(mu, alpha, q, k), truth_isotropic(mu, alpha, q, k))
    assert err.max() <= CLOSED_TOL, err.max()


def test_closed_form_anisotropic_10k_against_brentq():
    args = sample(N, 2, True)
    err = rel_err(closed_log_ratio(*args), truth_anisotropic(*args))
    assert err.max() <= CLOSED_TOL, err.max()


def test_default_ode_isotropic_10k_meets_rtol_with_an_honest_estimate():
    mu, alpha, q, k = sample(N, 3, False)
    y, est = ode_log_ratio(mu, alpha, q, k, with_error=True)
    assert np.all(np.isfinite(y)) and np.all(np.isfinite(est))
    err = rel_err(y, truth_isotropic(mu, alpha, q, k))
    assert err.max() <= RTOL, err.max()
    assert est.max() <= RTOL
    # the estimate is not far below the truth (measured: true error <= 1.6x the estimate)
    assert np.all(err <= 2.0 * est + 1e-13)


def test_default_ode_anisotropic_10k_meets_rtol():
    args = sample(N, 4, True)
    y, est = ode_log_ratio(*args, with_error=True)
    assert np.all(np.isfinite(y))
    err = rel_err(y, truth_anisotropic(*args))
    assert err.max() <= RTOL, err.max()
    assert np.all(err <= 2.0 * est + 1e-13)


def test_default_ode_small_q_small_k_long_wraps():
    """The corner the old fixed-step RK4 missed (1.6e-6): q·S_0 ∈ [1e-6, 1e-4], λω ∈ [1e-5, 1e-3], long wraps."""
    rng = np.random.default_rng(5)
    mu, alpha = rng.uniform(0.05, 0.6, N), rng.uniform(np.pi, 10 * np.pi, N)
    q, k = 10 ** rng.uniform(-6, -4, N), 10 ** rng.uniform(-5, -3, N)
    err = rel_err(ode_log_ratio(mu, alpha, q, k), truth_isotropic(mu, alpha, q, k))
    assert err.max() <= RTOL, err.max()


def test_pressure_dependent_friction_rigid_10k():
    """Thirion friction, rigid lining: ds/dα = μ s/(1 + β s) ⇒ s = W(β e^{β + μα})/β."""
    rng = np.random.default_rng(6)
    mu, alpha, beta = rng.uniform(0.05, 0.6, N), rng.uniform(0.0, 10 * np.pi, N), 10 ** rng.uniform(-4, 1, N)
    y = ode_log_ratio(mu, alpha, 0.0, 1.0, beta=beta)
    s = lambert_w_of_log(np.log(beta) + beta + mu * alpha) / beta
    assert np.max(np.abs(np.exp(y) / s - 1)) <= RTOL


@pytest.mark.parametrize("plugin", sorted(set(INTEGRATORS) - {"dopri5"}))
def test_every_integrator_meets_its_rtol(plugin):
    """Every [numerics] integrator, at the default rtol: a sample here (SUNDIALS and the CasADi plugins
    run on the virtual machine, ms per point); 10⁴ points in the slow test below."""
    n = 40 if plugin in ("cvodes", "idas", "rk", "collocation") else 300
    args = sample(n, 7, True)
    y, est = ode_log_ratio(*args, plugin=plugin, with_error=True)
    err = rel_err(y, truth_anisotropic(*args))
    assert np.all(np.isfinite(y)) and err.max() <= RTOL and est.max() <= RTOL


@pytest.mark.slow
@pytest.mark.exhaustive     # minutes: not in CI (CONTRIBUTING, "Test tiers")
@pytest.mark.parametrize("plugin", sorted(INTEGRATORS))
def test_every_integrator_10k(plugin):
    args = sample(N, 8, True)
    y = ode_log_ratio(*args, plugin=plugin)
    assert rel_err(y, truth_anisotropic(*args)).max() <= RTOL


def test_a_tolerance_that_cannot_be_met_is_an_error():
    from ropemodel.errors import SolveError

    with pytest.raises(SolveError, match="could not meet rtol"):
        ode_log_ratio(0.3, 30.0, 1e3, 1e-5, plugin="rk4", rtol=1e-14)
