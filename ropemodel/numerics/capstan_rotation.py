"""Self-consistent rotation of a capstan under load: δ(F_T) = ∫₀^{F_T} dF / K(F, α1, α2).

Li et al. define the stiffness as K = dF/dδ (eq. 11) but do not say how the
rotation follows from the load.  Since K depends on the wraps α1 = α0 + δ/R and
α2 = α0 − δ/R (eq. 13, 19), δ solves the ODE

    dδ/dF = 1/K(F, α0 + δ/R, α0 − δ/R),   δ(0) = 0,

whose right side switches regime (:mod:`ropemodel.numerics.capstan_laws`).  It is
integrated in u = ln(1 + F/F_p) (the slip angles are linear in u), so
dδ/du = (F_p + F)/K, u from 0 to ln(1 + F_T/F_p), in ``steps`` equal steps of the
classical Runge–Kutta method.

Switches are *located*, not stepped over: in each step the regime is frozen at the
step's start; if a switching function (tight, slack, unloaded) changes sign over
the trial step, its root along the step's cubic Hermite interpolant is found by
Newton's method, the step is split there, and the rest of the step is integrated
in the new regime (which may itself be split once more; two switches per step).
Within each piece the right side is smooth, so the method keeps its fourth order
across switches.  The whole scheme is one CasADi SX Function of
(F_T, mu, EA, R, L, alpha_0, F_p), differentiable in every input, with the switch
locations' dependence on the parameters included.

The ``smooth`` law has no switches; it is integrated with max(steps, 6·sharpness)
plain RK4 steps so the logistic transitions (width ≈ 1/sharpness in u) are resolved.

Outside the model: if δ reaches Rα0 the slack side unwraps (α2 ≤ 0); the
integrand is kept finite there (α2 is floored at 1e-9 rad), and callers refuse the
result (:func:`check_wrap`).
"""

from __future__ import annotations

import math
from functools import lru_cache

import casadi as ca
import numpy as np

from ropemodel.numerics.capstan_laws import LAWS, switching_functions
from ropemodel.errors import InputError
from ropemodel.papers import li_capstan as li

ARGS = ("F_T", "mu", "EA", "R", "L", "alpha_0", "F_p")
NEWTON_ITERATIONS = 3
ALPHA_FLOOR = 1e-9  # [rad] floor of the wraps inside the integrand (outside the valid domain only)
F_FLOOR = 1e-13     # [-] floor of F/F_p inside the integrand: finite 1/K when L = 0 at F = 0


def _rate(law, sharpness, u, delta, flags, p):
    """dδ/du = (F_p + F)/K with the regime frozen at ``flags`` (crisp laws) [m]."""
    mu, EA, R, L, alpha_0, F_p = p
    F = F_p * ca.fmax(ca.expm1(u), F_FLOOR)
    a1 = ca.fmax(alpha_0 + delta / R, ALPHA_FLOOR)
    a2 = ca.fmax(alpha_0 - delta / R, ALPHA_FLOOR)
    if flags is None:
        k_ti, k_sl = law.parts(F, F_p, mu, EA, R, L, a1, a2, sharpness)
    else:
        tight, slack, unloaded = flags
        k_ti = ca.if_else(tight, li.tight_side_stiffness_saturated(mu, EA, R, L, a1),
                          li.tight_side_stiffness_slipping(F, F_p, mu, EA, R, L))
        k_sl = ca.if_else(unloaded, 0.0, ca.if_else(
            slack, li.slack_side_stiffness_saturated(mu, EA, R, L, a2, law.name == "continuous"),
            li.slack_side_stiffness_slipping(F, F_p, mu, EA, R, L)))
    return (F_p + F) / (k_ti + k_sl)


def _switch(u, delta, p):
    """The three switching functions at (u, δ) as a list."""
    mu, EA, R, L, alpha_0, F_p = p
    F = F_p * ca.expm1(u)
    return list(switching_functions(F, F_p, mu, alpha_0 + delta / R, alpha_0 - delta / R))


def _rk4(rate, u, delta, h):
    k1 = rate(u, delta)
    k2 = rate(u + h / 2, delta + h / 2 * k1)
    k3 = rate(u + h / 2, delta + h / 2 * k2)
    k4 = rate(u + h, delta + h * k3)
    return delta + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), k1


def _hermite(theta, h, d0, d1, f0, f1):
    t2, t3 = theta * theta, theta * theta * theta
    return ((2 * t3 - 3 * t2 + 1) * d0 + (t3 - 2 * t2 + theta) * h * f0
            + (-2 * t3 + 3 * t2) * d1 + (t3 - t2) * h * f1)


@lru_cache(maxsize=1)
def _crossing_function() -> ca.Function:
    """(θ, u0, h, δ0, δ1, f0, f1, params) -> switching functions and their θ-derivatives on the interpolant."""
    th, u0, h, d0, d1, f0, f1 = (ca.SX.sym(n) for n in ("th", "u0", "h", "d0", "d1", "f0", "f1"))
    p = [ca.SX.sym(n) for n in ARGS[1:]]
    G = ca.vertcat(*_switch(u0 + th * h, _hermite(th, h, d0, d1, f0, f1), p))
    return ca.Function("crossing", [th, u0, h, d0, d1, f0, f1, *p], [G, ca.jacobian(G, th)])


def _locate(k, u0, h, d0, d1, f0, f1, g0, g1, p):
    """Fraction θ ∈ [0, 1] of the step where switching function k crosses zero (Newton on the interpolant)."""
    den = g0 - g1
    theta = ca.fmin(ca.fmax(g0 / ca.if_else(ca.fabs(den) > 0, den, 1.0), 0.0), 1.0)
    fun = _crossing_function()
    for _ in range(NEWTON_ITERATIONS):
        G, dG = fun(theta, u0, h, d0, d1, f0, f1, *p)
        g, dg = G[k], dG[k]
        theta = ca.fmin(ca.fmax(theta - g / ca.if_else(ca.fabs(dg) > 1e-300, dg, 1.0), 0.0), 1.0)
    return theta


def _step(law, sharpness, u0, d0, h, flags, p, depth):
    """One step of length h from (u0, δ0) in the regime ``flags``, splitting at up to ``depth`` switches."""
    rate = lambda u, d: _rate(law, sharpness, u, d, flags, p)  # noqa: E731
    d1, f0 = _rk4(rate, u0, d0, h)
    if depth == 0:
        return d1
    f1 = rate(u0 + h, d1)
    g0, g1 = _switch(u0, d0, p), _switch(u0 + h, d1, p)
    big = 2.0
    thetas, crossed = [], []
    for k in range(3):
        c = flags[k] != (g1[k] >= 0)  # the regime assumed vs the sign at the step's end
        crossed.append(c)
        thetas.append(ca.if_else(c, _locate(k, u0, h, d0, d1, f0, f1, g0[k], g1[k], p), big))
    first = ca.fmin(thetas[0], ca.fmin(thetas[1], thetas[2]))
    which = ca.if_else(thetas[0] == first, 0, ca.if_else(thetas[1] == first, 1, 2))
    any_cross = first < big
    theta = ca.fmin(first, 1.0)
    d_star, _ = _rk4(rate, u0, d0, theta * h)
    new_flags = tuple(ca.if_else(which == k, 1 - flags[k], flags[k]) for k in range(3))
    d_end = _step(law, sharpness, u0 + theta * h, d_star, (1 - theta) * h, new_flags, p, depth - 1)
    return ca.if_else(any_cross, d_end, d1)


@lru_cache(maxsize=8)
def _regular_step(variant: str, sharpness: float) -> ca.Function:
    """One step (u0, δ0, h, params) -> δ1 with the regime taken at its start and up to two located switches."""
    u0, d0, h = ca.SX.sym("u0"), ca.SX.sym("d0"), ca.SX.sym("h")
    p = [ca.SX.sym(n) for n in ARGS[1:]]
    flags = tuple(g >= 0 for g in _switch(u0, d0, p))
    d1 = _step(LAWS[variant], sharpness, u0, d0, h, flags, p, depth=2)
    return ca.Function("capstan_step", [u0, d0, h, *p], [d1])


@lru_cache(maxsize=32)
def rotation_function(variant: str = "li", steps: int = 32, sharpness: float = 30.0) -> ca.Function:
    """CasADi Function ``capstan_delta(F_T, mu, EA, R, L, alpha_0, F_p) -> delta`` [m], event-located RK4.

    variant: a key of :data:`ropemodel.numerics.capstan_laws.LAWS`; steps: RK4 steps in u = ln(1 + F/F_p);
    sharpness [-]: of the ``smooth`` law.  Inputs in SI: F_T [N] ≥ 0, mu [-], EA [N], R [m], L [m],
    alpha_0 [rad], F_p [N].  Output δ [m], the cable's displacement at the capstan rim (Δα = δ/R).
    """
    law = LAWS[variant]
    sym = {n: ca.SX.sym(n) for n in ARGS}
    p = tuple(sym[n] for n in ARGS[1:])
    F_p = sym["F_p"]
    U = ca.log1p(sym["F_T"] / F_p)
    delta = ca.SX(0.0)
    if law.crisp:
        h = U / steps
        step = _regular_step(variant, sharpness)
        for i in range(steps):
            delta = step(i * h, delta, h, *p)
    else:
        n = max(steps, math.ceil(6 * sharpness))
        h = U / n
        rate = lambda u, d: _rate(law, sharpness, u, d, None, p)  # noqa: E731
        for i in range(n):
            delta, _ = _rk4(rate, i * h, delta, h)
    return ca.Function("capstan_delta", [sym[n] for n in ARGS], [delta], list(ARGS), ["delta"])


def rotation(F_T, mu, EA, R, L, alpha_0, F_p, variant="li", steps=32, sharpness=30.0):
    """δ [m] at load(s) F_T [N] (float or array); the other inputs SI floats.  Δα = δ/R [rad]."""
    fun = rotation_function(variant, steps, sharpness)
    F = np.atleast_1d(np.asarray(F_T, dtype=float))
    out = np.asarray(fun.map(F.size)(F.reshape(1, -1), mu, EA, R, L, alpha_0, F_p)).ravel()
    return out if np.ndim(F_T) else float(out[0])


def regime1_rotation(F_T, mu, EA, R, L, F_p):
    """Closed-form δ [m] while the drive stays in regime 1 (both slip zones inside their wraps).

    Not in the paper; derived here.  In regime 1, K (eq. 26, row 1) does not depend
    on the wraps, and with a = 2R/μ
        1/K = N(F) / (2 EA D(F)),  N = (a² − L²)F² + 2aLF_pF + L²F_p²,  D = −LF² + aF_pF + LF_p².
    Dividing, N/D = c0 + (c1 F + c2)/D with c0 = −(a² − L²)/L, c1 = aF_p(a² + L²)/L,
    c2 = a²F_p²; D = −L(F − r1)(F − r2) with r1,2 = F_p(a ± √(a² + 4L²))/(2L) (r1 > F_p,
    r2 < 0), and partial fractions give
        δ(F) = [c0 F + A ln(1 − F/r1) + B ln(1 − F/r2)] / (2EA),
        A = (c1 r1 + c2)/(−L(r1 − r2)),  B = (c1 r2 + c2)/(−L(r2 − r1)).
    Valid for L > 0 [m] and 0 ≤ F_T below the first switch; F_T [N], mu [-], EA [N], R [m], F_p [N].
    """
    a = 2.0 * R / mu
    s = math.sqrt(a * a + 4.0 * L * L)
    r1, r2 = F_p * (a + s) / (2.0 * L), F_p * (a - s) / (2.0 * L)
    c0 = -(a * a - L * L) / L
    c1 = a * F_p * (a * a + L * L) / L
    c2 = a * a * F_p * F_p
    A = (c1 * r1 + c2) / (-L * (r1 - r2))
    B = (c1 * r2 + c2) / (-L * (r2 - r1))
    F = np.asarray(F_T, dtype=float)
    return (c0 * F + A * np.log1p(-F / r1) + B * np.log1p(-F / r2)) / (2.0 * EA)


def unwrap_load(mu, EA, R, L, alpha_0, F_p, variant="li", steps=32, sharpness=30.0) -> float:
    """The load F_T [N] at which the rotation reaches α0 (slack side unwrapped, α2 = 0)."""
    from scipy.optimize import brentq

    def excess(F):
        return rotation(F, mu, EA, R, L, alpha_0, F_p, variant, steps, sharpness) / R - alpha_0

    hi = max(F_p, 1.0)
    while excess(hi) < 0:
        hi *= 4.0
        if hi > 1e15:
            return math.inf
    return brentq(excess, 0.0, hi, xtol=1e-12 * hi, rtol=1e-12)


def check_wrap(F_T, delta, mu, EA, R, L, alpha_0, F_p, variant="li", steps=32, sharpness=30.0) -> None:
    """:class:`InputError` if the rotation δ/R at load F_T has unwrapped the slack side (α2 ≤ 0)."""
    if alpha_0 - delta / R > 0:
        return
    limit = unwrap_load(mu, EA, R, L, alpha_0, F_p, variant, steps, sharpness)
    raise InputError(
        f"F_T = {F_T:.6g} N rotates the capstan by {math.degrees(delta / R):.4g} deg, at least the initial "
        f"wrap alpha_0 = {math.degrees(alpha_0):.4g} deg: the slack side unwraps (alpha_2 <= 0) and the model "
        f"no longer applies; the largest load is F_T < {limit:.6g} N"
    )
