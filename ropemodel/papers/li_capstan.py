"""Equivalent stiffness of a preloaded capstan cable drive: Li, Liang, Dong, Qiu.

D. Li, L. Liang, K. Dong, H. Qiu, "Analysis and experimental determination of
cable-driven stiffness".  Equation numbers below are the paper's.

Symbols and units: load (tension change in the free span) F_T [N] = T/(2R) for a
load torque T [N·m]; preload F_p [N]; friction coefficient mu [-]; axial
stiffness EA [N]; wheel radius R [m]; free length L [m]; wrap angles alpha_1
(tight side), alpha_2 (slack side) [rad]; stiffnesses [N/m].

Every function works on floats, numpy arrays and CasADi symbols
(:mod:`ropemodel._math`).  The paper's slip-zone stiffnesses K_1 (eq. 12) and
K_2 (eq. 18) divide by F_T; the drive's stiffness never needs them: the
``*_side_stiffness_*`` functions are the series sums of eq. (24)-(25) written in
combined form, finite at F_T = 0.

Reading of eq. (26) (see docs/physics.md §5): K is the sum of a tight part and a slack
part, each switching on its own condition.  This completes the two cases the
four printed rows leave out (tight side saturated while the slack side is not;
F_T ≥ F_p while the tight side is not yet saturated).

Erratum kept as published: at the slack side's switch θ_s2 = α2 the published
saturated slack stiffness eq. (21) is e^{μα2} times the slip-zone value eq. (18),
so K jumps *up* where regime 1 becomes regime 2.  :func:`slack_side_stiffness`
reproduces that with ``continuous=False`` (the default, as published);
``continuous=True`` uses :func:`slack_saturated_stiffness_continuous`, derived by
continuing the slack slip zone's tension (F_p − F_T)e^{μθ} (eq. 16) over the
whole wrap, which meets eq. (18) at the switch.
"""

from __future__ import annotations

from ropemodel._math import expm1, fmax, fmin, if_else, log1p

# --- slip angles -----------------------------------------------------------------------------------


def tight_slip_angle(F_T, F_p, mu):
    """Slip angle of the tight side θ_s1 = ln((F_p + F_T)/F_p)/μ [rad].  Eq. (6).

    F_T [N] load, ≥ 0; F_p [N] preload, > 0; mu [-] friction coefficient, > 0.
    Valid while θ_s1 < α1; beyond, the slip zone is the whole wrap (eq. 13).
    """
    return log1p(F_T / F_p) / mu


def slack_slip_angle(F_T, F_p, mu):
    """Slip angle of the slack side θ_s2 = ln(F_p/(F_p − F_T))/μ [rad].  Eq. (16).

    F_T [N] load, 0 ≤ F_T < F_p (undefined at and beyond F_p); F_p [N]; mu [-].
    For a value safe everywhere use :func:`slack_slip_angle_limited`.
    """
    return -log1p(-F_T / F_p) / mu


def tight_slip_angle_limited(F_T, F_p, mu, alpha_1):
    """min(θ_s1, α1) [rad]: eq. (6) limited by the wrap as eq. (13) states.

    Evaluated as ln(1 + min(F_T/F_p, e^{μα1} − 1))/μ: finite for every F_T ≥ 0.
    alpha_1 [rad] tight-side wrap angle, > 0.
    """
    return log1p(fmin(F_T / F_p, expm1(mu * alpha_1))) / mu


def slack_slip_angle_limited(F_T, F_p, mu, alpha_2):
    """min(θ_s2, α2) [rad]: eq. (16) limited by the wrap as eq. (19) states.

    Where F_T ≥ F_p(1 − e^{−μα2}) — in particular at and beyond F_T = F_p, where eq. (16)
    has no value — the slip zone fills the slack wrap and the result is θ = α2 itself
    (not eq. 16 at the switch load: with a long, grippy wrap 1 − e^{−μα2} rounds to 1
    and ln(1 − 1) would be −∞).  Below, −ln(1 − F_T/F_p)/μ with F_T/F_p < 1.  Every branch
    is finite with finite derivatives.  alpha_2 [rad] slack-side wrap angle, > 0.
    """
    x = F_T / F_p
    saturated = x >= -expm1(-mu * alpha_2)
    slipping = -log1p(-if_else(saturated, 0.0 * x, x)) / mu  # argument < 1 where it is selected
    return if_else(saturated, alpha_2 + 0.0 * x, slipping)


def tight_switch_load(F_p, mu, alpha_1):
    """Load at which the tight side's slip zone reaches its wrap, F_p(e^{μα1} − 1) [N].

    Eq. (6) with eq. (13), θ_s1 = α1.  F_p [N]; mu [-]; alpha_1 [rad].
    """
    return F_p * expm1(mu * alpha_1)


def slack_switch_load(F_p, mu, alpha_2):
    """Load at which the slack side's slip zone reaches its wrap, F_p(1 − e^{−μα2}) [N].

    Eq. (16) with eq. (19), θ_s2 = α2.  F_p [N]; mu [-]; alpha_2 [rad].
    """
    return -F_p * expm1(-mu * alpha_2)


# --- parts of the stiffness (as published) ---------------------------------------------------------


def free_length_stiffness(EA, L):
    """Stiffness of the free span K_0 = EA/L [N/m].  Eq. (22).  EA [N] > 0; L [m] > 0."""
    return EA / L


def tight_slip_zone_stiffness(F_T, F_p, mu, EA, R):
    """Stiffness of the tight side's slip zone K_1 = μEA(F_p + F_T)/(R F_T) [N/m].  Eq. (12).

    Diverges at F_T = 0 (F_T [N] > 0 here); the drive's stiffness uses the
    combined form :func:`tight_side_stiffness_slipping` instead.
    """
    return mu * EA * (F_p + F_T) / (R * F_T)


def slack_slip_zone_stiffness(F_T, F_p, mu, EA, R):
    """Stiffness of the slack side's slip zone K_2 = μEA(F_p − F_T)/(R F_T) [N/m].  Eq. (18).

    0 < F_T < F_p; use :func:`slack_side_stiffness_slipping` in the drive.
    """
    return mu * EA * (F_p - F_T) / (R * F_T)


def tight_saturated_stiffness(mu, EA, R, alpha_1):
    """Tight side's wrap stiffness once θ_s1 = α1, K_1 = μEA/(R(1 − e^{−μα1})) [N/m].  Eq. (15).

    mu [-] > 0; EA [N] > 0; R [m] > 0; alpha_1 [rad] > 0 tight-side wrap.
    """
    return mu * EA / (R * -expm1(-mu * alpha_1))


def slack_saturated_stiffness(mu, EA, R, alpha_2):
    """Slack side's wrap stiffness once θ_s2 = α2, K_2 = μEA/(R(1 − e^{−μα2})) [N/m].  Eq. (21).

    As published.  It is e^{μα2} times eq. (18) at the switch, so the slack side's
    stiffness jumps up there; see :func:`slack_saturated_stiffness_continuous`.
    mu [-] > 0; EA [N] > 0; R [m] > 0; alpha_2 [rad] > 0 slack-side wrap.
    """
    return mu * EA / (R * -expm1(-mu * alpha_2))


def slack_saturated_stiffness_continuous(mu, EA, R, alpha_2):
    """Continuous alternative to eq. (21): μEA/(R(e^{μα2} − 1)) [N/m].  Not in the paper.

    Derivation: once θ_s2 = α2 the whole slack wrap slips with tension
    (F_p − F_T)e^{μθ} (eq. 16 continued), so the wrap shortens by
    δ2 = (R/EA)[F_p α2 − (F_p − F_T)(e^{μα2} − 1)/μ] and dF_T/dδ2 = μEA/(R(e^{μα2} − 1)),
    which equals eq. (18) at the switch F_T = F_p(1 − e^{−μα2}).
    mu [-] > 0; EA [N] > 0; R [m] > 0; alpha_2 [rad] > 0.
    """
    return mu * EA / (R * expm1(mu * alpha_2))


def series_stiffness(K_a, K_0, K_b):
    """Three springs in series, 1/(1/K_a + 1/K_0 + 1/K_b) [N/m].  Eq. (24) and (25)."""
    return 1.0 / (1.0 / K_a + 1.0 / K_0 + 1.0 / K_b)


# --- the sides of the drive in combined form (eq. 24-26) ------------------------------------------


def tight_side_stiffness_slipping(F_T, F_p, mu, EA, R, L):
    """K_ti while θ_s1 < α1: μEA(F_p+F_T)/(2RF_T + μL(F_p+F_T)) [N/m].  Eq. (24) with (12), (22); eq. (26).

    The series sum of K_1, K_0, K_1' written without 1/F_T: equals EA/L at F_T = 0.
    F_T [N] ≥ 0; F_p [N] > 0; mu [-] > 0; EA [N] > 0; R [m] > 0; L [m] ≥ 0 (L > 0 if F_T = 0).
    """
    s = F_p + F_T
    return mu * EA * s / (2.0 * R * F_T + mu * L * s)


def tight_side_stiffness_saturated(mu, EA, R, L, alpha_1):
    """K_ti once θ_s1 ≥ α1: μEA/(2R(1 − e^{−μα1}) + μL) [N/m].  Eq. (24) with (15), (22); eq. (26).

    mu [-] > 0; EA [N] > 0; R [m] > 0; L [m] ≥ 0; alpha_1 [rad] > 0.
    """
    return mu * EA / (-2.0 * R * expm1(-mu * alpha_1) + mu * L)


def slack_side_stiffness_slipping(F_T, F_p, mu, EA, R, L):
    """K_sl while θ_s2 < α2: μEA(F_p−F_T)/(2RF_T + μL(F_p−F_T)) [N/m].  Eq. (25) with (18), (22); eq. (26).

    Evaluated with max(F_p − F_T, 0), so it is 0 (not negative or infinite) for F_T ≥ F_p.
    F_T [N] ≥ 0; F_p [N] > 0; mu [-] > 0; EA [N] > 0; R [m] > 0; L [m] ≥ 0 (> 0 if F_T = 0).
    """
    q = fmax(F_p - F_T, 0.0)
    return mu * EA * q / (2.0 * R * F_T + mu * L * q)


def slack_side_stiffness_saturated(mu, EA, R, L, alpha_2, continuous=False):
    """K_sl once θ_s2 ≥ α2 and F_T < F_p [N/m].  Eq. (25) with (21), (22); eq. (26).

    As published (``continuous=False``): μEA/(2R(1 − e^{−μα2}) + μL), which jumps
    up from :func:`slack_side_stiffness_slipping` at the switch.  ``continuous=True``:
    μEA/(2R(e^{μα2} − 1) + μL) (:func:`slack_saturated_stiffness_continuous`), no jump.
    mu [-] > 0; EA [N] > 0; R [m] > 0; L [m] ≥ 0; alpha_2 [rad] > 0.
    """
    wrap = expm1(mu * alpha_2) if continuous else -expm1(-mu * alpha_2)
    return mu * EA / (2.0 * R * wrap + mu * L)


def tight_side_stiffness(F_T, F_p, mu, EA, R, L, alpha_1):
    """Tight part of eq. (26), K_ti [N/m]: slipping form while F_T < F_p(e^{μα1} − 1), else saturated.

    Continuous at the switch.  Both branches are finite for F_T ≥ 0 (L > 0 if F_T = 0).
    F_T [N]; F_p [N]; mu [-]; EA [N]; R [m]; L [m]; alpha_1 [rad] (ranges as in :func:`drive_stiffness`).
    """
    tight_sat = F_T >= tight_switch_load(F_p, mu, alpha_1)
    return if_else(tight_sat, tight_side_stiffness_saturated(mu, EA, R, L, alpha_1),
                   tight_side_stiffness_slipping(F_T, F_p, mu, EA, R, L))


def slack_side_stiffness(F_T, F_p, mu, EA, R, L, alpha_2, continuous=False):
    """Slack part of eq. (26), K_sl [N/m]: 0 for F_T ≥ F_p (slack side unloaded); slipping form while
    F_T < F_p(1 − e^{−μα2}); else saturated (published eq. 21, or the continuous alternative).

    F_T [N]; F_p [N]; mu [-]; EA [N]; R [m]; L [m]; alpha_2 [rad] (ranges as in :func:`drive_stiffness`);
    continuous: use :func:`slack_saturated_stiffness_continuous` for the saturated side.
    """
    slack_sat = F_T >= slack_switch_load(F_p, mu, alpha_2)
    inner = if_else(slack_sat, slack_side_stiffness_saturated(mu, EA, R, L, alpha_2, continuous),
                    slack_side_stiffness_slipping(F_T, F_p, mu, EA, R, L))
    return if_else(F_T >= F_p, 0.0 * inner, inner)


def drive_stiffness(F_T, F_p, mu, EA, R, L, alpha_1, alpha_2, continuous=False):
    """Equivalent stiffness of the drive K = K_ti + K_sl [N/m].  Eq. (23), (26) in the tight + slack reading.

    F_T [N] ≥ 0; F_p [N] > 0; mu [-] > 0; EA [N] > 0; R [m] > 0; L [m] ≥ 0 (> 0 at F_T = 0);
    alpha_1, alpha_2 [rad] > 0 the wraps at this load.  K(0) = 2EA/L.

    Examples
    --------
    The experiment of the paper (μ = 0.25, EA = 50 kN, R = 75 mm, L = 360 mm, wraps 64°): unloaded,
    both free spans in parallel, 2EA/L; fully saturated (regime 3 of eq. (26)) at F_T = F_p − 1 N:

    >>> import math
    >>> a = math.radians(64)
    >>> round(drive_stiffness(0.0, 60.0, 0.25, 5e4, 0.075, 0.36, a, a), 2)
    277777.78
    >>> k3 = 2 * 0.25 * 5e4 / (2 * 0.075 * (1 - math.exp(-0.25 * a)) + 0.25 * 0.36)
    >>> math.isclose(drive_stiffness(59.0, 60.0, 0.25, 5e4, 0.075, 0.36, a, a), k3, rel_tol=1e-14)
    True
    """
    return (tight_side_stiffness(F_T, F_p, mu, EA, R, L, alpha_1)
            + slack_side_stiffness(F_T, F_p, mu, EA, R, L, alpha_2, continuous))


# --- identification from tests (section 4) --------------------------------------------------------


def friction_coefficient_from_test(F_T, F_p, alpha):
    """μ = ln((F_p + F_T)/F_p)/α [-] from a capstan friction test.  Eq. (27).

    F_T [N] measured tension rise; F_p [N] preload; alpha [rad] wrap angle.
    """
    return log1p(F_T / F_p) / alpha


def axial_stiffness_from_test(F, L, dL):
    """EA = F L/ΔL [N] from a tensile test (section 4).  F [N]; L [m] sample length; dL [m] elongation."""
    return F * L / dL


def wrap_angles(alpha_0, delta, R):
    """Wraps after a rotation δ/R: α1 = α0 + δ/R, α2 = α0 − δ/R [rad].  Eq. (13), (19).

    alpha_0 [rad] initial wrap; delta [m] cable displacement at the capstan's rim; R [m].
    """
    d = delta / R
    return alpha_0 + d, alpha_0 - d
