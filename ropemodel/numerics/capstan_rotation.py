"""Self-consistent rotation of a capstan under load: δ(F_T) = ∫₀^{F_T} dF / K(F, α1, α2).

Li et al. define the stiffness as K = dF/dδ (eq. 11) but do not say how the
rotation follows from the load.  Since K depends on the wraps α1 = α0 + δ/R and
α2 = α0 − δ/R (eq. 13, 19), δ solves the ODE

    dδ/dF = 1/K(F, α0 + δ/R, α0 − δ/R),   δ(0) = 0,

whose right side switches regime (:mod:`ropemodel.numerics.capstan_laws`).  It is
integrated in u = ln(1 + F/F_p) (the slip angles are linear in u), dδ/du = (F_p + F)/K,
u from 0 to U = ln(1 + F_T/F_p), by an adaptive Dormand–Prince 5(4) method
(:mod:`ropemodel.numerics.adaptive`; local extrapolation, error per unit step):

* **Regimes frozen, switches located.**  Each step integrates the law of the regime
  held at its start (1/K in the compliance form of
  :func:`~ropemodel.numerics.capstan_laws.inverse_stiffness`, smooth within a regime).
  If the tight or slack switching function changes sign over an accepted step, its
  root is found by Newton's method on the step's continuous extension (order 4), the
  step is redone to end there, the regime flips, and the state is corrected by
  (f⁺ − f⁻)·g/g' for the switching function's residual g (so a location error of the
  interpolant does not leave a jump of K stepped over).  F = F_p (u = ln 2) is a step
  end: the slack side unloads exactly there.
* **Error control.**  A step of length h is accepted when its local error estimate
  le = |x5 − x4| is at most ``tol``·Δδ (Δδ > 0 the step's increment; plus rounding),
  ``tol`` = ``SHARE``·rtol.  le estimates the embedded 4th-order solution's local error,
  as a rule far above that of the 5th-order one propagated; where 1/K does not depend
  on δ (a quadrature in u) le is also checked against the 5th-order solution's own error
  by an order-6 quadrature on the same stages (:data:`Q6`), so a le that vanishes by
  cancellation does not pass a step unseen.  The estimate of δ's error is
  E = Σ SAFETY·le, each term carried forward by the step's growth factor of errors:
  1 unless the tight side is saturated, where ∂(dδ/du)/∂δ ≤ (dδ/du)·d ln(1 − e^{−μα1})/dδ
  (the slack side and the slipping parts do not expand errors, and the slack side's jump
  at its switch contracts them), so a step grows them by at most
  (1 − e^{−μα1'})/(1 − e^{−μα1}) — at most 2 in all, since δ/R < α0.  With the
  increments adding up to δ, E ≤ 2·SAFETY·SHARE·rtol·δ = rtol·δ.  Measured at rtol 1e-7
  over 4·10⁴ random drives of the documented range (``li``) and 10⁴ each (``continuous``,
  ``smooth``): true error ≤ 0.52·E (so SAFETY = 2 leaves about a factor 2) and ≤ 0.011·rtol.
  The ``smooth`` law, whose logistic weights can
  expand errors more, carries E by |∂x5/∂δ| of each step (the linearised step) and is
  checked against rtol at the end.
* **Steps inside the right side's radius of convergence.**  The embedded estimate is
  only trustworthy for steps well inside the distance to the nearest singularity of
  the right side; in regime 1 1/K is rational in F with poles at the roots of
  2RF/μ + L(F_p² − F²)/F_p (one near F = 0 when μL ≪ R, one just above F_p when
  μL ≫ R), in regime 2 at one negative F.  Steps are limited to ``KAPPA`` times the
  distance in u to these poles (the pole near 0 only where its weight (μL/2R)² exceeds
  ``tol``); for the smooth law also to ``KAPPA_SMOOTH`` times that to the poles of its
  logistic weights, s·z = ±iπ.
* **Reported estimate.**  E/δ rounded up to one significant digit (at most rtol): its
  lower digits are rounding noise and it jumps where a step decision changes, so it is
  reported as the piecewise constant bound it is (zero derivative).
* **Fixed maximum.**  The loop is ``until_done`` (nested CasADi loops of conditionals)
  of at most :func:`max_attempts` attempts; a point that has not reached U, or whose
  estimate exceeds rtol, gives NaN (callers report :class:`~ropemodel.errors.SolveError`).

The whole scheme is one CasADi Function of (F_T, mu, EA, R, L, alpha_0, F_p),
differentiable in every input, switch locations included (accept/reject decisions are
piecewise constant).  Outside the model: if δ reaches Rα0 the slack side unwraps
(α2 ≤ 0); the integrand is kept finite there (α2 is floored at 1e-9 rad), and callers
refuse the result (:func:`check_wrap`).
"""

from __future__ import annotations

import math
from functools import lru_cache

import casadi as ca
import numpy as np

from ropemodel.errors import InputError
from ropemodel.numerics.adaptive import B, E, ULPS, combine, dense, stages, until_done
from ropemodel.numerics.capstan_laws import LAWS, inverse_stiffness, smooth_weights
from ropemodel.papers import li_capstan as li

ARGS = ("F_T", "mu", "EA", "R", "L", "alpha_0", "F_p")
RTOL = 1e-7   # default relative error of δ to meet
STEPS = 16    # the first trial step is 1/STEPS of the range in u
SAFETY = 2.0  # factor on the summed local estimates (measured margin: module doc)
SHARE = 1.0 / (2.0 * SAFETY)  # local tolerance / rtol: SAFETY·SHARE·(growth ≤ 2) ≤ 1
KAPPA = 0.25  # largest step / distance to the nearest pole of the right side (regimes 1, 2)
KAPPA_SMOOTH = 0.1  # the same for the smooth law's logistic weights (their poles move with dδ/du)
GROW, BETA = 2.0, 0.08  # largest step growth; PI-controller exponent (Hairer's DOPRI5 uses 0.04 for h⁵)
NEWTON = 3    # Newton iterations on the interpolant, from the secant guess
INNER = 16    # attempts per inner loop of until_done
ALPHA_FLOOR = 1e-9  # [rad] floor of the wraps inside the integrand (outside the valid domain only)
LN2 = math.log(2.0)
#: interpolatory quadrature (order 6) on the stage nodes 0, 1/5, 3/10, 4/5, 8/9, 1: where 1/K does not
#: depend on δ (the tight side slipping, the slack side slipping or unloaded) its difference to the
#: 5th-order solution estimates that solution's own error, a second check beside le
Q6 = (25 / 288, 125 / 4464, 200 / 477, 25 / 36, -19683 / 52576, 0.0, 7 / 48)
STATE = ("u", "delta", "h", "err", "tight", "slack", "unloaded", "pending", "h_saved", "ratio_prev", "rejected",
         "attempts")
PARAMS = ("mu", "EA", "R", "L", "alpha_0", "F_p", "tol", "fixed", "U")  # U last: until_done's end


def max_attempts(rtol: float) -> int:
    """Loop length at ``rtol``: 4·rtol^(−1/4) + 96 attempts.  The most measured on 10⁴ random drives:
    77 (li) and 101 (smooth) of 321 at rtol 1e-7, 404 and 828 of 4096 at 1e-12."""
    return int(math.ceil(4.0 * rtol ** -0.25)) + 96


def _rate(law, sharpness, u, delta, flags, q):
    """dδ/du = F_p e^u/K [m] in the regime ``flags`` (crisp laws) or with the smooth law's weights."""
    mu, EA, R, L, a0, F_p = q[:6]
    x = ca.expm1(u)
    a1, a2 = a0 + delta / R, ca.fmax(a0 - delta / R, ALPHA_FLOOR)
    w = flags if law.crisp else smooth_weights(F_p * x, F_p, mu, a1, a2, sharpness)
    return F_p * ca.exp(u) * inverse_stiffness(x, mu, EA, R, L, a1, a2, w, law.name == "continuous")


def _switch(u, delta, q):
    """Tight and slack switching functions (≥ 0: saturated) at (u, δ) and their partial derivatives."""
    mu, R, a0 = q[0], q[2], q[4]
    e2 = ca.exp(-mu * ca.fmax(a0 - delta / R, ALPHA_FLOOR))
    return (u - mu * (a0 + delta / R), ca.expm1(u) + e2 - 1.0), ((1.0, -mu / R), (ca.exp(u), mu / R * e2))


def _locate(j, u, h, d0, d1, k, g0, g1, q):
    """Fraction θ ∈ [0, 1] of the step where switching function j crosses zero (Newton on the interpolant)."""
    den = g0 - g1
    theta = ca.fmin(ca.fmax(g0 / ca.if_else(den != 0, den, 1.0), 0.0), 1.0)
    for _ in range(NEWTON):
        y, dy = dense(theta, h, d0, d1, k)
        g, (gu, gd) = (v[j] for v in _switch(u + theta * h, y, q))
        slope = gu * h + gd * dy
        theta = ca.fmin(ca.fmax(theta - g / ca.if_else(slope != 0, slope, 1.0), 0.0), 1.0)
    return theta


def _pole_limit(law, sharpness, u, delta, f0, flags, q):
    """KAPPA × the distance in u to the nearest pole of the right side, else inf: in regime 1 the roots
    of 2Rx/μ + L(1 − x²), in regime 2 one x < 0; for the smooth law also the logistic weights' poles
    s·z = ±iπ (f0: dδ/du at the start)."""
    mu, EA, R, L, a0, F_p, tol = q[:7]
    ft, fs, fu = flags
    rho = mu * L / (2.0 * R)
    s = ca.sqrt(1.0 + 4.0 * rho * rho)
    near0 = ca.if_else(rho * rho > tol, u - ca.log1p(-2.0 * rho / (1.0 + s)), ca.inf)
    # the upper pole, x = (1 + s)/(2ρ) > 1: beyond u = 14 for ρ < 1e-6 (regime 1 ends at u = ln 2)
    regime1 = KAPPA * ca.fmin(near0, ca.log1p((1.0 + s) / (2.0 * ca.fmax(rho, 1e-6))) - u)
    if not law.crisp:
        (zt, zs), ((tu, td), (su, sd)) = _switch(u, delta, q)
        dist = ca.inf
        for z, dz in ((zt, tu + td * f0), (zs, su + sd * f0), (ca.expm1(u) - 1.0, ca.exp(u))):
            dist = ca.fmin(dist, ca.sqrt(z * z + (math.pi / sharpness) ** 2) / ca.fmax(ca.fabs(dz), 1e-300))
        return ca.fmin(KAPPA_SMOOTH * dist, ca.if_else(fu == 0, regime1, ca.inf))
    k_ss = li.slack_side_stiffness_saturated(mu, EA, R, L, ca.fmax(a0 - delta / R, ALPHA_FLOOR),
                                             law.name == "continuous")
    x_pole = -(L * k_ss + EA) / ((2.0 * R / mu + L) * k_ss + EA)
    regime2 = KAPPA * (u - ca.log1p(x_pole))
    slipping = ca.logic_and(ft == 0, fu == 0)
    return ca.if_else(slipping, ca.if_else(fs == 0, regime1, regime2), ca.inf)


def _controller(he, ratio, ok, z):
    """Next step after an attempt of length he with error ratio le/allowed (PI control, growth ≤ GROW)."""
    rprev, rejected = z[9], z[10]
    fac = 0.9 * ca.fmax(ratio, 1e-12) ** (-0.25 + 0.75 * BETA) * ca.if_else(ok, rprev ** BETA, 1.0)
    grow = ca.if_else(ca.logic_and(rejected, ok), 1.0, GROW)
    return ca.if_else(ratio <= 1e30, he * ca.fmin(grow, ca.fmax(0.2, fac)), 0.2 * he)


def _growth(law, delta, x5, q):
    """Factor by which the step carries earlier errors forward (module doc)."""
    mu, R, a0 = q[0], q[2], q[4]
    if not law.crisp:
        return ca.fabs(ca.jacobian(x5, delta))
    return ca.expm1(-mu * (a0 + x5 / R)) / ca.expm1(-mu * (a0 + delta / R))


def _corrected_switch(law, sharpness, u1, x5, fm, pend, flags, q):
    """δ at the end of a step redone to a switch, corrected for the residual g of the switching function:
    δ + (f⁺ − f⁻)·g/g' (g' = dg/du along the solution); and the new regime."""
    new = tuple(ca.if_else(pend == j + 1, 1 - flags[j], flags[j]) for j in range(2)) + (flags[2],)
    fp = _rate(law, sharpness, u1, x5, new, q)
    (gt, gs), ((tu, td), (su, sd)) = _switch(u1, x5, q)
    g = ca.if_else(pend == 1, gt, gs)
    slope = ca.if_else(pend == 1, tu + td * fm, su + sd * fm)
    steep = ca.fabs(slope) > 1e-300
    return x5 + ca.if_else(steep, (fp - fm) * g / ca.if_else(steep, slope, 1.0), 0.0), new


def _trial(law, sharpness, z, q):
    """One trial step from z in the frozen regime: its length he, whether it ends at U (last) or at
    F = F_p (clip), the stages k, the 5th-order result x5, the local estimate le and le/allowed."""
    u, d, h, fu = z[0], z[1], z[2], z[6]
    flags = (z[4], z[5], fu)
    tol, fixed, U = q[6], q[7], q[8]
    rate = lambda t, x, _: _rate(law, sharpness, t, x, flags, q)  # noqa: E731
    f0 = rate(u, d, None)
    h = ca.if_else(fixed, h, ca.fmin(h, _pole_limit(law, sharpness, u, d, f0, flags, q)))
    to_ln2 = ca.if_else(ca.logic_and(fu == 0, u < LN2), LN2 - u, ca.inf)
    last = ca.logic_and(h >= U - u, U - u <= to_ln2)
    clip = ca.logic_and(ca.logic_not(last), h >= to_ln2)
    he = ca.if_else(last, U - u, ca.if_else(clip, to_ln2, h))
    k = stages(rate, u, d, he, None, f0)
    x5 = d + combine(B, k, he)
    le = ca.fabs(combine(E, k, he))
    if law.crisp:  # a quadrature in u where δ does not enter 1/K: guard le against cancelling
        quadrature = ca.logic_and(flags[0] == 0, ca.logic_or(flags[1] == 0, fu == 1))
        le = ca.if_else(quadrature, ca.fmax(le, ca.fabs(combine(tuple(a - b for a, b in zip(Q6, B)), k, he))), le)
    ratio = le / ca.fmax(tol * ca.fabs(x5 - d) + ULPS * (ca.fabs(d) + ca.fabs(x5)), 1e-300)
    return h, he, last, clip, k, x5, le, ratio


def _crossing(law, z, q, he, k, x5, ok):
    """The fraction θ of an accepted step (not itself ending at a switch) where the tight or slack side
    first switches (2 if neither does), and which (1 tight, 2 slack)."""
    if not law.crisp:
        return ca.SX(2.0), ca.SX(0.0)
    u, d, ft, fs, fu, pend = z[0], z[1], z[4], z[5], z[6], z[7]
    (g0t, g0s), _ = _switch(u, d, q)
    (g1t, g1s), _ = _switch(u + he, x5, q)
    free = ca.logic_and(ok, pend == 0)
    cross_t = ca.logic_and(free, ft != (g1t >= 0))
    cross_s = ca.logic_and(ca.logic_and(free, fu == 0), fs != (g1s >= 0))
    th_t = ca.if_else(cross_t, _locate(0, u, he, d, x5, k, g0t, g1t, q), 2.0)
    th_s = ca.if_else(cross_s, _locate(1, u, he, d, x5, k, g0s, g1s, q), 2.0)
    return ca.fmin(th_t, th_s), ca.if_else(th_t <= th_s, 1.0, 2.0)


@lru_cache(maxsize=8)
def _body(variant: str, sharpness: float) -> ca.Function:
    """One attempted step: (z, p) → z' (state :data:`STATE`, parameters :data:`PARAMS`)."""
    law = LAWS[variant]
    z, p = ca.SX.sym("z", len(STATE)), ca.SX.sym("p", len(PARAMS))
    u, d, _, err, ft, fs, fu, pend, hsave, rprev = (z[i] for i in range(10))
    q = [p[i] for i in range(len(PARAMS))]
    h, he, last, clip, k, x5, le, ratio = _trial(law, sharpness, z, q)
    ok = ca.logic_or(ratio <= 1.0, q[7])
    h_next = ca.if_else(q[7], h, _controller(he, ratio, ok, z))
    first, which = _crossing(law, z, q, he, k, x5, ok)
    crossing = first < 2.0
    advance = ca.logic_and(ok, ca.logic_not(crossing))
    u_end = ca.if_else(last, q[8], ca.if_else(clip, LN2, u + he))
    x_sw, new = _corrected_switch(law, sharpness, u + he, x5, k[6], pend, (ft, fs, fu), q) if law.crisp \
        else (x5, (ft, fs, fu))
    grown = _growth(law, d, x5, q)
    if law.crisp:
        grown = ca.if_else(ft, grown, 1.0)
    h_adv = ca.if_else(pend > 0, ca.fmax(hsave, h_next),
                       ca.if_else(last, h, ca.if_else(clip, ca.fmax(h_next, h), h_next)))
    z_new = ca.vertcat(
        ca.if_else(advance, u_end, u),
        ca.if_else(advance, ca.if_else(pend > 0, x_sw, x5), d),
        ca.if_else(crossing, first * he, ca.if_else(advance, h_adv, h_next)),
        ca.if_else(advance, grown * err + SAFETY * le + ULPS * ca.fabs(x5), err),
        ca.if_else(advance, new[0], ft), ca.if_else(advance, new[1], fs),
        ca.if_else(ca.logic_and(advance, u_end >= LN2), 1.0, fu),
        ca.if_else(crossing, which, 0.0),
        ca.if_else(crossing, h_next, hsave),
        ca.if_else(ok, ca.fmax(ratio, 1e-4), rprev),
        ca.logic_not(ok), z[11] + 1.0)
    return ca.Function(f"capstan_attempt_{variant}", [z, p], [z_new], ["z", "p"], ["z_next"])


@lru_cache(maxsize=32)
def _loop(variant: str, sharpness: float, attempts: int) -> ca.Function:
    return until_done(_body(variant, sharpness), INNER, -(-attempts // INNER), f"capstan_loop_{variant}")


def _build(variant, sharpness, tol, fixed, steps, attempts, rtol):
    sym = [ca.MX.sym(a) for a in ARGS]
    F_T, mu, EA, R, L, a0, F_p = sym
    U = ca.log1p(F_T / F_p)
    z0 = ca.vertcat(0.0, 0.0, U / steps, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-4, 0.0, 0.0)
    zf = _loop(variant, float(sharpness), attempts)(z0, ca.vertcat(mu, EA, R, L, a0, F_p, tol, fixed, U))
    delta, err = zf[1], zf[3] / ca.fmax(ca.fabs(zf[1]), 1e-300)
    valid = ca.logic_and(zf[0] >= U, err <= rtol)
    return sym, ca.if_else(valid, delta, math.nan), ca.if_else(valid, _one_digit_up(err, rtol), math.nan), zf[11]


def _one_digit_up(err, rtol):
    """The estimate rounded up to one significant digit, at most rtol: an upper bound with the precision it
    has (its lower digits are rounding noise, ~1e-16 of δ over differences of ~1e-9 of it, and it jumps
    where a step decision changes), piecewise constant in the inputs (its derivative is 0)."""
    scale = 10.0 ** ca.floor(ca.log10(ca.fmax(err, 1e-300)))
    return ca.fmin(ca.ceil(err / scale) * scale, rtol)


@lru_cache(maxsize=32)
def rotation_function(variant: str = "li", steps: int = STEPS, sharpness: float = 30.0,
                      rtol: float = RTOL) -> ca.Function:
    """CasADi Function ``capstan_delta(F_T, mu, EA, R, L, alpha_0, F_p) -> (delta, error)``, error-controlled.

    Adaptive, event-located Dormand–Prince 5(4) in u = ln(1 + F/F_p) (module doc), first trial
    step U/``steps``, at most :func:`max_attempts` attempts.  ``error`` is the estimate E/δ of
    δ's relative error rounded up to one significant digit (at most ``rtol``; its lower digits
    are noise, so it is reported piecewise constant); where the loop does not finish or
    E/δ > rtol, both outputs are NaN (callers report :class:`~ropemodel.errors.SolveError`).

    variant: a key of :data:`ropemodel.numerics.capstan_laws.LAWS`; sharpness [-]: of the
    ``smooth`` law; rtol [-]: relative error of δ to meet.  Inputs in SI: F_T [N] ≥ 0, mu [-],
    EA [N], R [m], L [m], alpha_0 [rad], F_p [N].  Outputs: δ [m], the cable's displacement at the
    capstan rim (Δα = δ/R), and its estimated relative error [-].
    """
    sym, delta, err, _ = _build(variant, sharpness, SHARE * rtol, 0.0, steps, max_attempts(rtol), rtol)
    return ca.Function("capstan_delta", sym, [delta, err], list(ARGS), ["delta", "error"])


@lru_cache(maxsize=8)
def attempts_function(variant: str = "li", steps: int = STEPS, sharpness: float = 30.0,
                      rtol: float = RTOL) -> ca.Function:
    """The number of attempted steps of :func:`rotation_function` (a diagnostic for studies and tests)."""
    sym, _, _, n = _build(variant, sharpness, SHARE * rtol, 0.0, steps, max_attempts(rtol), rtol)
    return ca.Function("capstan_attempts", sym, [n], list(ARGS), ["attempts"])


@lru_cache(maxsize=32)
def fixed_step_function(variant: str, n: int, sharpness: float = 30.0) -> ca.Function:
    """δ(F_T, …) with n equal steps in u (no error control; switches located): for order checks."""
    sym, delta, _, _ = _build(variant, sharpness, ca.inf, 1.0, n, n + 16, ca.inf)
    return ca.Function(f"capstan_delta_fixed_{n}", sym, [delta], list(ARGS), ["delta"])


def rotation(F_T, mu, EA, R, L, alpha_0, F_p, variant="li", steps=STEPS, sharpness=30.0, rtol=RTOL,
             with_error=False):
    """δ [m] at load(s) F_T [N] (float or array); the other inputs SI floats.  Δα = δ/R [rad].

    With ``with_error``: (δ, estimated relative error).  NaN where ``rtol`` cannot be met.
    """
    fun = rotation_function(variant, steps, sharpness, rtol)
    F = np.atleast_1d(np.asarray(F_T, dtype=float))
    d, e = (np.asarray(v).ravel() for v in fun.map(F.size)(F.reshape(1, -1), mu, EA, R, L, alpha_0, F_p))
    if not np.ndim(F_T):
        d, e = float(d[0]), float(e[0])
    return (d, e) if with_error else d


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
    B_ = (c1 * r2 + c2) / (-L * (r2 - r1))
    F = np.asarray(F_T, dtype=float)
    return (c0 * F + A * np.log1p(-F / r1) + B_ * np.log1p(-F / r2)) / (2.0 * EA)


def unwrap_load(mu, EA, R, L, alpha_0, F_p, variant="li", steps=STEPS, sharpness=30.0, rtol=RTOL) -> float:
    """The load F_T [N] at which the rotation reaches α0 (slack side unwrapped, α2 = 0)."""
    from scipy.optimize import brentq

    def excess(F):
        d = rotation(F, mu, EA, R, L, alpha_0, F_p, variant, steps, sharpness, rtol)
        return d / R - alpha_0 if math.isfinite(d) else 1.0  # past the unwrap the integrand is not physical

    hi = max(F_p, 1.0)
    while excess(hi) < 0:
        hi *= 4.0
        if hi > 1e15:
            return math.inf
    return brentq(excess, 0.0, hi, xtol=1e-12 * hi, rtol=1e-12)


def check_wrap(F_T, delta, mu, EA, R, L, alpha_0, F_p, variant="li", steps=STEPS, sharpness=30.0,
               rtol=RTOL) -> None:
    """:class:`InputError` if the rotation δ/R at load F_T has unwrapped the slack side (α2 ≤ 0)."""
    if alpha_0 - delta / R > 0:
        return
    limit = unwrap_load(mu, EA, R, L, alpha_0, F_p, variant, steps, sharpness, rtol)
    raise InputError(
        f"F_T = {F_T:.6g} N rotates the capstan by {math.degrees(delta / R):.4g} deg, at least the initial "
        f"wrap alpha_0 = {math.degrees(alpha_0):.4g} deg: the slack side unwraps (alpha_2 <= 0) and the model "
        f"no longer applies; the largest load is F_T < {limit:.6g} N"
    )
