"""Rope on a friction sheave with a Voigt (visco-elastic) lining: Hajduk (1992).

J. Hajduk (1992), *Theoretical distribution of the tension in the rope encircling
the driving disc with the elastic lining* (in Polish, English summary).  Equation
numbers below are the paper's; see ``docs/physics.md`` §3 for the errata.

Notation (SI): S [N] rope tension, S_0 [N] entering (slack-side) tension, α [rad]
angle of contact reached (α = ω t), μ [-] rope–lining friction coefficient,
Q_R, Q_T [1/N] radial and tangential compliances of the lining, λ_R, λ_T [s] their
retardation times, ω [rad/s] sheave speed.  Dimensionless: s = S/S_0,
q = Q·S_0 [-], k = λ·ω [rad] (the angle the sheave turns in one retardation time).

Every function works on floats, numpy arrays and CasADi symbols.

Limits handled as limits, not errors
------------------------------------
* k = λω → 0 (purely elastic lining, λ → 0, *or* a slow sheave, ω → 0 with λ
  fixed: t = α/ω → ∞ so every Voigt body has fully crept): 1 − e^{−α/k} → 1 for
  any α > 0, the lining acts as an elastic spring in equilibrium, and the closed
  form becomes ln s + q s = μα (with the jump of s at α = 0⁺ that the boundary
  layer of width ~k shrinks to).  At α = 0 exactly the factor stays 0 (s = 1).
* k → ∞ (fast sheave or very viscous lining: the lining has no time to deform):
  1 − e^{−α/k} → 0 and s → e^{μα}, Euler–Eytelwein.
* q → 0 (rigid lining): s = e^{μα} exactly.
"""

from __future__ import annotations

from ropemodel._math import exp, expm1, fabs, fmax, if_else, log, log1p

#: exponent beyond which e^{-x} is treated as 0 (e^{-700} ≈ 1e-304)
_XMAX = 700.0
#: tiny angle that keeps α/k finite for α = k = 0
_TINY = 1e-30
#: Newton iterations of the closed form (measured on 2e5 random points, c ∈ [1e-12, 1e6],
#: μα ∈ [0, 60]: 3 steps reach 6e-12 in ln s, 4 reach machine precision; 2 more for margin)
NEWTON_STEPS = 6
#: how :func:`log_tension_ratio` solves eq. (19), for reports
NEWTON_METHOD = (f"Newton's method in ln s from Winitzki's approximation of Lambert's W, {NEWTON_STEPS} steps "
                 "(machine precision for μα up to 60)")


def radial_compliance(h, E, R, a):
    """Radial compliance of the lining, Q_R = h/(E R² a) [1/N].  Hajduk (1992), eq. (3)-(6).

    h [m] lining thickness, E [Pa] Young's modulus of the lining, R [m] sheave
    radius (to the rope centre), a [m] width of the lining in contact; all > 0.
    """
    return h / (E * R**2 * a)


def tangential_compliance(mu, G, R, a):
    """Tangential compliance of the lining, Q_T = μ/(G R a) [1/N].  Hajduk (1992), eq. (3)-(6).

    mu [-] friction coefficient, G [Pa] shear modulus of the lining, R [m] sheave
    radius, a [m] lining width; all > 0.
    """
    return mu / (G * R * a)


def retardation_time(eta, modulus):
    """Retardation time of a Voigt body, λ = η/E [s].  Hajduk (1992), eq. (1).

    eta [Pa·s] viscosity, >= 0; modulus [Pa] elastic modulus (E radially, G
    tangentially), > 0.
    """
    return eta / modulus


def _safe_k(alpha, k):
    """k, raised where α/k would exceed _XMAX (there e^{-α/k} is 0 to machine precision
    either way); keeps every value and derivative finite for k → 0."""
    return fmax(k, alpha / _XMAX + _TINY)


def creep_factor(alpha, k):
    """Crept fraction of a Voigt body's deformation, 1 − e^{−α/k} [-].  Hajduk (1992), eq. (1), (19).

    alpha [rad] angle of contact reached, >= 0; k = λω [rad] >= 0.  The limit
    k → 0 gives 1 for α > 0 (and 0 at α = 0).
    """
    return -expm1(-alpha / _safe_k(alpha, k))


def creep_rate(alpha, k):
    """d/dα of :func:`creep_factor`, e^{−α/k}/k [1/rad].  Hajduk (1992), eq. (4)-(6).

    alpha [rad] >= 0; k [rad] >= 0.  Tends to 0 for k → 0 at α > 0 (a δ at α = 0).
    """
    kk = _safe_k(alpha, k)
    return exp(-alpha / kk) / kk


def lining_term(S, alpha, Q_R, k_R, Q_T, k_T):
    """C(α)·S with C = Q_R(1 − e^{−α/k_R}) + Q_T(1 − e^{−α/k_T}) [-].

    The lining's compliance crept in by angle α, times the tension: the second
    term of eq. (19) generalised to λ_R ≠ λ_T.  S [N]; Q_R, Q_T [1/N] >= 0;
    k_R, k_T [rad] >= 0.
    """
    return S * (Q_R * creep_factor(alpha, k_R) + Q_T * creep_factor(alpha, k_T))


def tension_slope(S, alpha, mu, Q_R, k_R, Q_T, k_T):
    """dS/dα along the arc [N/rad].  Hajduk (1992), eq. (5)-(6), corrected.

    dS/dα = S (μ − S [Q_R e^{−α/k_R}/k_R + Q_T e^{−α/k_T}/k_T]) / (1 + S C(α)).

    Erratum: the printed eq. (4)/(5) write λ_R in the tangential terms; the
    tangential Voigt bodies relax with λ_T (docs/physics.md §3).  The printed eq. (7)
    is garbled; this is eq. (6) divided by ω = dα/dt.  ``mu`` may be a function
    value μ(p) (pressure-dependent friction): the equation of equilibrium holds
    for any μ, only the closed form needs μ constant.

    S [N] > 0; alpha [rad] >= 0; mu [-] > 0; Q_R, Q_T [1/N] >= 0; k_R = λ_R ω,
    k_T = λ_T ω [rad] >= 0.
    """
    rate = Q_R * creep_rate(alpha, k_R) + Q_T * creep_rate(alpha, k_T)
    return S * (mu - S * rate) / (1.0 + lining_term(S, alpha, Q_R, k_R, Q_T, k_T))


def log_tension_slope(y, alpha, mu, q_R, k_R, q_T, k_T):
    """d(ln s)/dα for y = ln(S/S_0) [1/rad]: :func:`tension_slope` divided by S, in q = Q·S_0.

    y [-] log tension ratio; q_R = Q_R S_0, q_T = Q_T S_0 [-] >= 0; others as
    :func:`tension_slope`.
    """
    s = exp(y)
    rate = q_R * creep_rate(alpha, k_R) + q_T * creep_rate(alpha, k_T)
    return (mu - s * rate) / (1.0 + lining_term(s, alpha, q_R, k_R, q_T, k_T))


def tension_ratio_residual(s, mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0):
    """Residual of the exact implicit solution, ln s + s C(α) S_0 − μα [-].  Hajduk (1992), eq. (19).

    Generalised to λ_R ≠ λ_T (docs/physics.md §3): ln s + s [q_R(1 − e^{−α/k_R}) +
    q_T(1 − e^{−α/k_T})] = μα, zero at the tension ratio s = S/S_0 > 0.
    """
    return log(s) + lining_term(s, alpha, q_R, k_R, q_T, k_T) - mu * alpha


def tension_residual(S, S_0, mu, alpha, Q_R, k_R, Q_T=0.0, k_T=1.0):
    """Residual of the exact implicit solution in the tensions, ln(S/S_0) + S C(α) − μα [-].  Hajduk (1992),
    eq. (19), generalised to λ_R ≠ λ_T: zero at the tension S [N] leaving the arc, S_0 [N] > 0 entering it.

    Q_R, Q_T [1/N] >= 0; k_R, k_T [rad] >= 0; mu [-] > 0; alpha [rad] >= 0 (:func:`tension_ratio_residual`
    in q = Q S_0).

    Examples
    --------
    >>> import math
    >>> S_0, Q = 1e4, 1e-5                      # q = Q S_0 = 0.1, Fig. 5's setting
    >>> S = S_0 * tension_ratio(0.2, math.pi, Q * S_0, 0.01 * math.pi)
    >>> abs(tension_residual(S, S_0, 0.2, math.pi, Q, 0.01 * math.pi)) < 1e-14
    True
    """
    return log(S / S_0) + lining_term(S, alpha, Q_R, k_R, Q_T, k_T) - mu * alpha


def _log_ratio(mu_alpha, c):
    """u = ln s solving u + c e^u = μα for c >= 0 (u = μα − W(c e^{μα}), W Lambert's).

    Newton in u: f(u) = u + c e^u − μα is convex and increasing, f' = 1 + c e^u
    >= 1, so Newton converges monotonically from the right of the root and
    quadratically near it.  The start is Winitzki's approximation of W (relative
    error < 2 %), computed from ln x = ln c + μα so nothing overflows; then a
    fixed number of Newton steps (unrolled: the result is one smooth expression
    that CasADi differentiates).  c = 0 gives u = μα exactly after one step.
    """
    # c < 0 is unphysical (a Newton iterate of an outer solve may visit it): treated as 0 so
    # every value and derivative stays finite; c >= 0 is untouched (derivative 1 at c = 0)
    c = if_else(c < 0, 0.0 * c, c)
    ln_x = log(fmax(c, 1e-300)) + mu_alpha
    # softplus(ln x) = ln(1 + x), stable for any ln x
    pos, neg = fmax(ln_x, 0.0), fmax(-ln_x, 0.0)
    L = pos + log1p(exp(-(pos + neg)))
    w0 = L * (1.0 - log(1.0 + L) / (2.0 + L))
    u = mu_alpha - w0
    for _ in range(NEWTON_STEPS):
        ce = c * exp(u)
        u = u - (u + ce - mu_alpha) / (1.0 + ce)
    return u


#: rounding allowance of the closed form, in units of (1 + μα): a few ulps of the terms of eq. (19)
ROUNDING = 8 * 2.0**-52


def _log_ratio_error(mu_alpha, c):
    """Estimate of the error of :func:`_log_ratio` [-]: the size of the next Newton step from its
    result (Newton converges quadratically, so this bounds the remaining error) plus rounding."""
    c = if_else(c < 0, 0.0 * c, c)
    u = _log_ratio(mu_alpha, c)
    ce = c * exp(u)
    return fabs((u + ce - mu_alpha) / (1.0 + ce)) + ROUNDING * (1.0 + fabs(mu_alpha))


def log_tension_ratio_error(mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0):
    """Estimated error of :func:`log_tension_ratio`, i.e. the relative error of S [-].

    The next Newton step of eq. (19) from the returned ln s, plus a rounding allowance of
    8 ulp·(1 + μα).  Arguments as :func:`log_tension_ratio`.
    """
    c = q_R * creep_factor(alpha, k_R) + q_T * creep_factor(alpha, k_T)
    return _log_ratio_error(mu * alpha, c)


def log_tension_ratio(mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0):
    """ln(S/S_0) at angle α from the exact solution [-].  Hajduk (1992), eq. (19), generalised.

    Solves ln s + s [q_R(1 − e^{−α/k_R}) + q_T(1 − e^{−α/k_T})] = μα by Newton in
    u = ln s (see :func:`_log_ratio`).  mu [-] > 0 (constant); alpha [rad] >= 0;
    q_R = Q_R S_0, q_T = Q_T S_0 [-] >= 0; k_R = λ_R ω, k_T = λ_T ω [rad] >= 0
    (0 is the limit of a purely elastic lining or a slow sheave).
    """
    c = q_R * creep_factor(alpha, k_R) + q_T * creep_factor(alpha, k_T)
    return _log_ratio(mu * alpha, c)


def tension_ratio(mu, alpha, q, k):
    """Tension ratio S/S_0 of an isotropic Voigt lining [-].  Hajduk (1992), eq. (19).

    ln s + q s (1 − e^{−α/k}) = μα, with q = Q S_0 = (Q_R + Q_T) S_0 [-] >= 0 and
    k = λω [rad] >= 0.  q = 0 gives Euler–Eytelwein, e^{μα} (eq. (8)).
    mu [-] > 0; alpha [rad] >= 0.

    Examples
    --------
    Fig. 5's setting μ = 0.2, q = 0.1, λω = 0.01π at α = π (docs/physics.md §3 lists the
    reference values, computed independently), and the rigid lining q = 0:

    >>> import math
    >>> round(tension_ratio(0.2, math.pi, 0.1, 0.01 * math.pi), 6)
    1.597677
    >>> tension_ratio(0.2, math.pi, 0.0, 1.0) == math.exp(0.2 * math.pi)
    True
    """
    return exp(log_tension_ratio(mu, alpha, q, k))


def tension_ratio_anisotropic(mu, alpha, q_R, k_R, q_T, k_T):
    """Tension ratio S/S_0 with λ_R ≠ λ_T [-].  Hajduk (1992), eq. (19) generalised (docs/physics.md §3).

    q_R = Q_R S_0, q_T = Q_T S_0 [-] >= 0; k_R = λ_R ω, k_T = λ_T ω [rad] >= 0.
    """
    return exp(log_tension_ratio(mu, alpha, q_R, k_R, q_T, k_T))
