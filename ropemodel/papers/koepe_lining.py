"""Koepe (friction) hoist on a Voigt-lined wheel: Hajduk (1992) eq. (19) on the wheel's arc.

Hajduk's lining (``docs/physics.md`` §3, :mod:`ropemodel.papers.hajduk1992`, reused here, not copied) holds,
on an arc α of a wheel of radius R turning at ω = v/R, at most the tension S given by

    ln(S/S_0) + S C(α) = μα,   C(α) = Q_R (1 − e^{−α/k_R}) + Q_T (1 − e^{−α/k_T}),   k = λ ω = λ v/R,

per rope, S_0 [N] the slack-side tension of one rope: the lining's creep during the time α R/v the rope
stays on the arc costs traction.  At rest (v = 0) the lining has fully crept (k = 0); as v → ∞ it has no
time to creep and the ratio is Euler–Eytelwein's.  On a Koepe wheel with n_head ropes sharing each side's
tension T equally, S_0 = T_2/n_head and S = T_1/n_head (docs/physics.md §7).

Assumptions, stated where they are used: the slack side is S_0, as for the winch's lined drum (§1); Hajduk's
S_0 is the tension where the rope meets the lining, so eq. (19) read this way holds as written while the
ropes run onto the wheel from the slack side; the ropes' inertia on the arc and their centrifugal force are
not in Hajduk's equilibrium and are left out here (:mod:`ropemodel.papers.koepe_slip` has them for a rigid
lining).

During a manoeuvre (:func:`ropemodel.papers.koepe_slip.manoeuvre_sides`) T_U = F_U + M_U a and
T_D = F_D − M_D a; the largest a before slip toward U solves eq. (19) with S = T_U/n, S_0 = T_D/n.  In
y = ln(T_D/F_D) the residual f(y) = ln(T_U/T_D) + κ T_U − μα (κ = C(α)/n_head) is strictly decreasing and
concave, so Newton's method started right of the root (:func:`voigt_slip_guess`) converges monotonically:
:func:`voigt_slip_acceleration` does so for floats and numpy arrays; a CasADi model poses
:func:`voigt_slip_residual` = 0 in y with that guess (a ``rootfinder``), and :func:`acceleration_from_log`
turns y into a.
"""

from __future__ import annotations

import numpy as np

from ropemodel._math import exp, fmax, fmin, log
from ropemodel.papers import hajduk1992 as hj

#: Newton steps allowed to the float solver: monotone from the guess, it needs at most 10 on 2e5 random cases
#: (tests/test_koepe_lining.py); the allowance keeps a margin and turns a failure into an error, not a number
MAX_NEWTON = 50
#: the last step taken is below this in y = ln(T_D/F_D): quadratic convergence leaves rounding only
STEP_TOL = 1e-12


def creep_parameter(lam, v, R):
    """k = λ ω = λ v/R [rad]: the angle the wheel turns in one retardation time.  Hajduk (1992), eq. (19).

    lam [s] retardation time of the lining, >= 0; v [m/s] rope speed, >= 0; R [m] wheel radius at the rope
    centre, > 0.  v = 0 (at rest) gives k = 0: the lining has fully crept.
    """
    return lam * v / R


def lining_compliance(alpha, R, v, Q_R, lambda_R, Q_T=0.0, lambda_T=0.0):
    """C(α) = Q_R (1 − e^{−α/k_R}) + Q_T (1 − e^{−α/k_T}) [1/N], the lining's compliance crept over the arc.

    Per rope; Hajduk (1992) eq. (19), generalised to λ_R ≠ λ_T (docs/physics.md §3), with k = λ v/R.
    alpha [rad] > 0; R [m] > 0; v [m/s] >= 0; Q_R, Q_T [1/N] >= 0
    (:func:`ropemodel.papers.hajduk1992.radial_compliance`, ``tangential_compliance``); lambda_R, lambda_T [s]
    >= 0.

    Examples
    --------
    At rest the lining has fully crept: C = Q_R + Q_T.

    >>> lining_compliance(3.14, 2.25, 0.0, 2e-9, 0.5, 1e-9, 0.2) == 2e-9 + 1e-9
    True
    """
    return hj.lining_term(1.0, alpha, Q_R, creep_parameter(lambda_R, v, R), Q_T, creep_parameter(lambda_T, v, R))


def voigt_traction_ratio(T_2, n_head, mu, alpha, R, v, Q_R, lambda_R, Q_T=0.0, lambda_T=0.0):
    """Traction limit T_1/T_2 of the Voigt-lined wheel for the slack-side tension T_2 [-].  Hajduk (1992), eq. (19).

    ln s + s (T_2/n_head) C(α) = μα, s = T_1/T_2, solved by
    :func:`ropemodel.papers.hajduk1992.tension_ratio_anisotropic` with q = Q T_2/n_head and k = λ v/R.
    T_2 [N] > 0 total over the n_head ropes; mu [-] > 0; alpha [rad] > 0; R [m]; v [m/s] >= 0 (0: at rest,
    fully crept); Q_R, Q_T [1/N] per rope; lambda_R, lambda_T [s].
    Q = 0 gives Euler–Eytelwein, e^{μα} (eq. (8)).  S_0 = T_2/n_head (docs/physics.md §7).

    Examples
    --------
    Hajduk's Fig. 5 setting (μ = 0.2, q = Q S_0 = 0.1, λω = 0.01π, α = π; docs/physics.md §3: 1.597677) on a
    wheel: 4 ropes of 100 kN each (T_2 = 400 kN), Q = 1e-6 /N, R = 2 m, v = 2π cm/s, λ = 1 s:

    >>> import math
    >>> round(voigt_traction_ratio(400e3, 4, 0.2, math.pi, 2.0, 0.02 * math.pi, 1e-6, 1.0), 6)
    1.597677
    """
    per_rope = T_2 / n_head
    return hj.tension_ratio_anisotropic(mu, alpha, Q_R * per_rope, creep_parameter(lambda_R, v, R),
                                        Q_T * per_rope, creep_parameter(lambda_T, v, R))


def _tensions(y, F_up, F_down, M_up, M_down):
    """(T_U, T_D) [N] at y = ln(T_D/F_D): T_D = F_D e^y, T_U = F_U + M_U (F_D − T_D)/M_D."""
    T_D = F_down * exp(y)
    return F_up + M_up * (F_down - T_D) / M_down, T_D


def acceleration_from_log(y, F_down, M_down):
    """a = (F_D − T_D)/M_D [m/s²] with T_D = F_D e^y: the upward acceleration of side U at y = ln(T_D/F_D)."""
    return (F_down - F_down * exp(y)) / M_down


def voigt_slip_residual(y, F_up, F_down, M_up, M_down, n_head, mu, alpha, C):
    """f(y) = ln(T_U/T_D) + (T_U/n_head) C − μα [-], zero at the slip limit.  Hajduk (1992), eq. (19).

    Eq. (19) with S = T_U/n_head and S_0 = T_D/n_head (via :func:`ropemodel.papers.hajduk1992.tension_ratio_residual`),
    in y = ln(T_D/F_D), T_U = F_U + M_U (F_D − T_D)/M_D.  Strictly decreasing and concave in y on its domain
    T_U > 0 (docs/physics.md §7).  F_up, F_down [N] > 0; M_up, M_down [kg] > 0; C [1/N] from
    :func:`lining_compliance`; mu [-] > 0; alpha [rad] > 0.
    """
    T_U, T_D = _tensions(y, F_up, F_down, M_up, M_down)
    return hj.tension_ratio_residual(T_U / T_D, mu, alpha, C * T_D / n_head, 0.0)


def voigt_slip_guess(F_up, F_down, M_up, M_down, n_head, mu, alpha, C):
    """Start y_0 = ln(T_D/F_D) right of the root of :func:`voigt_slip_residual`, where Newton converges monotonically.

    T_U,0 = min(T_free, μα n_head/C), T_free = (M_D F_U + M_U F_D)/(M_U + M_D) the tension of both sides when
    they move freely: there T_U <= T_D and (T_U/n_head) C <= μα, so f(y_0) <= 0 (docs/physics.md §7).
    """
    T_free = (M_down * F_up + M_up * F_down) / (M_up + M_down)
    T_U = fmin(T_free, mu * alpha * n_head / fmax(C, 1e-300))
    T_U = fmax(T_U, 1e-12 * T_free)   # μα → 0 would put the start on the edge of the domain
    return log((F_down + M_down * (F_up - T_U) / M_up) / F_down)


def voigt_newton_step(y, F_up, F_down, M_up, M_down, n_head, mu, alpha, C):
    """Newton's step −f/f' for :func:`voigt_slip_residual` (f' = −(M_U/M_D)(T_D/T_U)(1 + κ T_U) − 1, κ = C/n).

    From :func:`voigt_slip_guess` the steps are monotone (docs/physics.md §7); floats, numpy arrays and CasADi
    expressions alike (a model may unroll them)."""
    T_U, T_D = _tensions(y, F_up, F_down, M_up, M_down)
    kappa = C / n_head
    slope = -(M_up / M_down) * T_D * (1.0 / T_U + kappa) - 1.0
    return -voigt_slip_residual(y, F_up, F_down, M_up, M_down, n_head, mu, alpha, C) / slope


def voigt_slip_acceleration(F_up, F_down, M_up, M_down, n_head, mu, alpha, R, v, Q_R, lambda_R, Q_T=0.0,
                            lambda_T=0.0):
    """Largest upward acceleration of side U before the ropes slip toward it on a Voigt lining [m/s²].

    Solves ln(T_U/T_D) + (T_U/n_head) C(α) = μα (Hajduk 1992, eq. (19), S_0 = T_D/n_head) with T_U = F_U + M_U a,
    T_D = F_D − M_D a, by Newton's method in y = ln(T_D/F_D) from :func:`voigt_slip_guess` until a step is
    below 1e-12 (the error left is then rounding).  Floats and numpy arrays (a CasADi model poses
    :func:`voigt_slip_residual` instead).  Arguments as :func:`ropemodel.papers.koepe_slip.slip_acceleration`
    and :func:`voigt_traction_ratio`; v [m/s] the rope speed at the instant.  Never above the rigid lining's
    limit (the lining only costs traction).

    Examples
    --------
    The issue's example, loaded conveyance at the bottom, hoisting from rest, a realistic lining (Q = 2e-9 /N per
    rope): the rigid wheel's 2.0964 m/s² less what the crept lining takes:

    >>> import math
    >>> g = 9.80665
    >>> round(voigt_slip_acceleration(830451.0, 584530.0, 830451.0 / g, 584530.0 / g, 4, 0.25, math.pi,
    ...                               2.25, 0.0, 2e-9, 0.5), 4)
    2.094
    """
    C = lining_compliance(alpha, R, v, Q_R, lambda_R, Q_T, lambda_T)
    args = (F_up, F_down, M_up, M_down, n_head, mu, alpha, C)
    y = np.asarray(voigt_slip_guess(*args), dtype=float)
    for _ in range(MAX_NEWTON):
        step = np.asarray(voigt_newton_step(y, *args), dtype=float)
        y = y + step
        if np.all(np.abs(step) <= STEP_TOL * np.maximum(1.0, np.abs(y))):
            return _as_float(acceleration_from_log(y, F_down, M_down))
    raise ArithmeticError(f"the Voigt slip limit did not converge in {MAX_NEWTON} Newton steps")


def _as_float(x):
    """A Python float for a 0-d result, the array otherwise."""
    return float(x) if np.ndim(x) == 0 else x
