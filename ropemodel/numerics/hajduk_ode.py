"""Right side of the lining ODE in a stretched angle, as CasADi SX expressions.

Dimensionless variables (Hajduk 1992; docs/physics.md §3): s = S/S_0, q = Q S_0,
k = λω.  The ODE (eq. (5)-(6), corrected) in y = ln s is

    dy/dα = (μ(s) − s [q_R e^{−α/k_R}/k_R + q_T e^{−α/k_T}/k_T]) / (1 + s C(α)),
    C(α)  = q_R (1 − e^{−α/k_R}) + q_T (1 − e^{−α/k_T}),

and μ(s) = μ/(1 + β s) for a pressure-dependent friction (Thirion's law, β =
S_0/(p_c R a); β = 0 is constant friction).

Boundary layer.  For small k the lining creeps within α ~ k, and for large q
the tension falls there like s ≈ 1/(1 + qα/k), i.e. over α ~ k/q: the ODE in α
has eigenvalues ~ −q s/k (stiff, up to 1e8 in the required range).  In the
stretched variable τ = ln(1 + α/k_e), k_e = min(k_R, k_T)/(1 + q_R + q_T),
dα/dτ = α + k_e and the layer spans τ ∈ [0, ~ln(1+q)] with O(1) slopes, so
explicit and implicit methods alike step through it; the whole arc is
τ ≤ ln(1 + α(1+q)/k) (≈ 22 for α = 10π, q = 1e3, k = 1e-5).  The integration
variable is σ ∈ [0, 1], τ = τ_a + σ(τ_b − τ_a) for a segment [α_a, α_b].

Limit k → 0.  k is raised to κ = 1e-12 rad (the layer is then thinner than
1e-12 rad; the tension at any α ≥ 1e-9 rad equals the limit's to machine
precision, since e^{−1000} = 0).

State choice.  ``"log"`` integrates y = ln s with the ODE above (the general
equation).  ``"invariant"`` integrates z = ln s + s C(α), for which the
equation of equilibrium reads exactly dz/dα = μ(s) (the ODE is an exact
differential, docs/physics.md §3), recovering s from z by the closed-form Newton;
there is no stiffness left at all, but for constant μ it is the closed form
itself, so the accuracy studies use ``"log"``.
"""

from __future__ import annotations

import casadi as ca

from ropemodel._math import exp, expm1, fmax, fmin, if_else, log1p
from ropemodel.papers import hajduk1992 as hj

#: parameter vector of the right side, in order
PARAMS = ("mu", "q_R", "k_R", "q_T", "k_T", "beta", "alpha_a", "alpha_b")
#: k below KAPPA [rad] is raised to it (see the module doc)
KAPPA = 1e-12


def friction(mu, beta, s):
    """Friction coefficient at tension ratio s: μ/(1 + β s) [-] (β = 0: constant μ).

    β < 0 is unphysical, but a Newton iterate of an outer solve (e.g. for p_c) may visit it:
    there μ(2 − 1/(1 − β s)) continues the law with equal value and slope at β = 0, stays in
    [μ, 2μ) (no blow-up of the ODE) and keeps a derivative that leads Newton back.
    """
    physical = mu / (1.0 + fmax(beta, 0.0) * s)
    continued = mu * (2.0 - 1.0 / (1.0 - fmin(beta, 0.0) * s))
    return if_else(beta >= 0, physical, continued)


def stretch(q_R, k_R, q_T, k_T, alpha_a, alpha_b):
    """(k_R', k_T', k_e, τ_a, τ_b): floored k's, the stretch scale and the segment in τ."""
    kR, kT = fmax(k_R, KAPPA), fmax(k_T, KAPPA)
    k_e = fmin(kR, kT) / (1.0 + q_R + q_T)
    return kR, kT, k_e, log1p(alpha_a / k_e), log1p(alpha_b / k_e)


def rhs(state: str):
    """SX expressions (x, sigma, p, dx/dsigma) of the stretched ODE for ``state`` "log" or "invariant"."""
    x = ca.SX.sym("x")
    sigma = ca.SX.sym("sigma")
    p = ca.SX.sym("p", len(PARAMS))
    mu, q_R, k_R, q_T, k_T, beta, alpha_a, alpha_b = (p[i] for i in range(len(PARAMS)))
    kR, kT, k_e, tau_a, tau_b = stretch(q_R, k_R, q_T, k_T, alpha_a, alpha_b)
    alpha = k_e * expm1(tau_a + sigma * (tau_b - tau_a))
    dalpha = (tau_b - tau_a) * (alpha + k_e)
    if state == "log":
        s = exp(x)
        rate = q_R * hj.creep_rate(alpha, kR) + q_T * hj.creep_rate(alpha, kT)
        # (α + k_e)·rate is O(q) at most: the stretch cancels the 1/k of the creep rate
        dx = dalpha * (friction(mu, beta, s) - s * rate) / (1.0 + hj.lining_term(s, alpha, q_R, kR, q_T, kT))
    else:
        c = q_R * hj.creep_factor(alpha, kR) + q_T * hj.creep_factor(alpha, kT)
        s = exp(hj._log_ratio(x, c))
        dx = dalpha * friction(mu, beta, s)
    return x, sigma, p, ca.cse(dx)


def state_of(state: str, y, alpha, q_R, k_R, q_T, k_T, alpha_b):
    """The integrated state from y = ln s at α ("log": y; "invariant": y + s C(α))."""
    if state == "log":
        return y
    kR, kT, *_ = stretch(q_R, k_R, q_T, k_T, alpha, alpha_b)
    return y + hj.lining_term(exp(y), alpha, q_R, kR, q_T, kT)


def log_ratio_of(state: str, x, alpha, q_R, k_R, q_T, k_T, alpha_b):
    """y = ln s from the integrated state at α (inverse of :func:`state_of`)."""
    if state == "log":
        return x
    kR, kT, *_ = stretch(q_R, k_R, q_T, k_T, alpha, alpha_b)
    c = q_R * hj.creep_factor(alpha, kR) + q_T * hj.creep_factor(alpha, kT)
    return hj._log_ratio(x, c)
