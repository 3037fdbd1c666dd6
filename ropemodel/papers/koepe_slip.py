"""Koepe (friction) hoist, rigid dynamics: the largest acceleration and deceleration before the ropes slip.

ropemodel's derivation (``docs/physics.md`` §7), generalising the standard rigid relations of MODELS.md §5
(each side's mass T/g, nothing else moving) to what really moves: each side's moving mass M (its conveyance,
payload and ropes, and whatever turns with it, e.g. a deflection sheave: :func:`ropemodel.papers.koepe.side_mass`),
the head ropes lying on the wheel, and the centrifugal force of the ropes on the arc.

The ropes are inextensible and stick to the wheel.  Side U is accelerated upward at a [m/s²] while side D
goes down at a; F_U, F_D [N] are the sides' tensions at the wheel with a = 0 (their static tensions, plus or
minus the shaft resistance); M_U, M_D [kg] their moving masses.  Newton's law on each side:

    T_U = F_U + M_U a,      T_D = F_D − M_D a.

On the arc (wrap α, friction μ, radius R), a rope element of mass q R dθ (q = n_head q_head [kg/m]) moving at
speed v and accelerating at a_θ toward the high side, at the onset of slip toward the high side:

    dT/dθ = μ (T − q v²) + q R a_θ,   so   T_1 − q v² + q R a_θ/μ = (T_2 − q v² + q R a_θ/μ) e^{μα}.

With T_1 = T_U, T_2 = T_D and a_θ = −a (the ropes run from U over the wheel to D) the largest a is

    a_slip = (e^{μα} F_D − F_U − (e^{μα} − 1) q v²) / (M_U + e^{μα} M_D + q R (e^{μα} − 1)/μ),

:func:`slip_acceleration`.  The rope on the wheel acts as a mass q R (e^{μα} − 1)/μ (→ q R α, all of it, as
μα → 0); the wheel's own inertia does not enter (it changes the torque, not the tensions).  With q = 0 it is
MODELS.md §5's a/g = (e^{μα} T_2 − T_1)/(e^{μα} T_2 + T_1) for M = T/g; as μ → 0 it is the free (Atwood)
acceleration of the two sides, the wheel transmitting nothing.

The four manoeuvres (:func:`manoeuvre_sides`; "hoist" moves the loaded conveyance up) map the loaded side L
and the other side E onto U and D, with the shaft resistance F_r [N] (guides, air; standard practice lumps it
on the loaded conveyance) against the loaded conveyance's velocity.  Each result is the largest magnitude
[m/s²] the manoeuvre can have without slip; a negative value means the manoeuvre slips even at a = 0.

Every function works on floats, numpy arrays and CasADi expressions, except those marked "floats only".
"""

from __future__ import annotations

from typing import NamedTuple

from ropemodel._math import exp, expm1, fmax, fmin, if_else

#: below this μα the ratio (e^x − 1)/x is its Taylor series (the next term, x⁴/120, is below 1e-18)
_SERIES = 1e-4

#: the four manoeuvres, "hoist" moving the loaded conveyance up
MANOEUVRES = ("hoist_accel", "hoist_decel", "lower_accel", "lower_decel")


def _expm1_ratio(x):
    """(e^x − 1)/x for x >= 0, 1 at x = 0; both branches finite everywhere."""
    xs = fmax(x, _SERIES)
    return if_else(x < _SERIES, 1.0 + x / 2.0 + x * x / 6.0 + x * x * x / 24.0, expm1(xs) / xs)


def effective_arc_mass(q_arc, R, mu, alpha):
    """Mass the head ropes lying on the wheel add to the slip condition, q R (e^{μα} − 1)/μ [kg].

    q_arc = n_head q_head [kg/m] >= 0; R [m] wheel radius at the rope centre; mu [-] >= 0; alpha [rad] > 0.
    Tends to q R α, the whole arc's rope, as μα → 0.  ropemodel's derivation (docs/physics.md §7).

    Examples
    --------
    >>> import math
    >>> round(effective_arc_mass(4 * 8.6, 2.25, 0.25, math.pi), 1)     # the arc itself holds 243.2 kg
    369.4
    """
    return q_arc * R * alpha * _expm1_ratio(mu * alpha)


def centrifugal_tension(q_arc, v):
    """Centrifugal tension of the ropes on the arc, q v² [N]: it lifts them off the lining.

    q_arc = n_head q_head [kg/m]; v [m/s] rope speed.  Belt-drive theory (not in the seeds).

    Examples
    --------
    >>> round(centrifugal_tension(4 * 8.6, 12.0), 1)
    4953.6
    """
    return q_arc * v * v


def side_tension_dynamic(F, M, a):
    """Tension of a side at the wheel while it accelerates upward at a, T = F + M a [N] (Newton's law).

    F [N] the side's tension at a = 0; M [kg] its moving mass; a [m/s²], negative for a side going down
    faster or rising slower.
    """
    return F + M * a


def slip_acceleration(F_up, F_down, M_up, M_down, mu, alpha, q_arc=0.0, R=0.0, v=0.0):
    """Largest upward acceleration of side U before the ropes slip toward it [m/s²].

    a = (e^{μα} F_D − F_U − (e^{μα} − 1) q v²) / (M_U + e^{μα} M_D + q R (e^{μα} − 1)/μ)

    F_up, F_down [N] > 0 the sides' tensions at a = 0; M_up, M_down [kg] > 0 their moving masses; mu [-] >= 0;
    alpha [rad] > 0; q_arc = n_head q_head [kg/m] >= 0 (0: the rope on the wheel and the centrifugal term left
    out, as MODELS.md §5); R [m] wheel radius at the rope centre; v [m/s] rope speed at the instant.  Valid
    while both tensions exceed q v² (the ropes press on the lining).  Rigid lining (Euler–Eytelwein) and
    inextensible ropes; ropemodel's derivation (docs/physics.md §7).

    Examples
    --------
    MODELS.md §5 (M = T/g, q = 0) for T_1 = 830.451 kN, T_2 = 584.530 kN, μ = 0.25 over 180°:

    >>> import math
    >>> g = 9.80665
    >>> round(slip_acceleration(830451.0, 584530.0, 830451.0 / g, 584530.0 / g, 0.25, math.pi), 4)
    2.0964
    """
    E = exp(mu * alpha)
    numerator = E * F_down - F_up - (E - 1.0) * centrifugal_tension(q_arc, v)
    return numerator / (M_up + E * M_down + effective_arc_mass(q_arc, R, mu, alpha))


def manoeuvre_sides(T_L, T_E, M_L, M_E, F_r=0.0):
    """(F_U, F_D, M_U, M_D) of each manoeuvre, keyed by :data:`MANOEUVRES` [N, N, kg, kg].

    T_L, T_E [N] static tensions of the loaded side and the other; M_L, M_E [kg] their moving masses; F_r [N]
    >= 0 shaft resistance on the loaded conveyance, against its velocity (adds to T_L while hoisting).

    * hoist_accel: L rising faster: U = L, D = E;   * hoist_decel: L rising slower: U = E, D = L;
    * lower_accel: L sinking faster: U = E, D = L;  * lower_decel: L sinking slower: U = L, D = E.
    """
    up, down = T_L + F_r, T_L - F_r
    return {"hoist_accel": (up, T_E, M_L, M_E), "hoist_decel": (T_E, up, M_E, M_L),
            "lower_accel": (T_E, down, M_E, M_L), "lower_decel": (down, T_E, M_L, M_E)}


def a_slip_hoist_accel(T_L, T_E, M_L, M_E, mu, alpha, q_arc=0.0, R=0.0, v=0.0, F_r=0.0):
    """Largest acceleration while hoisting (loaded conveyance rising faster) before slip [m/s²].

    a = (e^{μα} T_E − T_L − F_r − (e^{μα} − 1) q v²) / (M_L + e^{μα} M_E + q R (e^{μα} − 1)/μ)

    Arguments as :func:`slip_acceleration` and :func:`manoeuvre_sides`.  docs/physics.md §7.

    Examples
    --------
    The issue's example, loaded conveyance at the bottom, M = T/g:

    >>> import math
    >>> g = 9.80665
    >>> round(a_slip_hoist_accel(830451.0, 584530.0, 830451.0 / g, 584530.0 / g, 0.25, math.pi), 4)
    2.0964
    """
    return slip_acceleration(*manoeuvre_sides(T_L, T_E, M_L, M_E, F_r)["hoist_accel"], mu, alpha, q_arc, R, v)


def a_slip_hoist_decel(T_L, T_E, M_L, M_E, mu, alpha, q_arc=0.0, R=0.0, v=0.0, F_r=0.0):
    """Largest deceleration while hoisting (loaded conveyance rising slower) before slip [m/s²].

    d = (e^{μα} (T_L + F_r) − T_E − (e^{μα} − 1) q v²) / (e^{μα} M_L + M_E + q R (e^{μα} − 1)/μ)

    Arguments as :func:`slip_acceleration` and :func:`manoeuvre_sides`.  docs/physics.md §7.

    Examples
    --------
    The issue's example, loaded conveyance at the top (T_L = 800.276 kN, T_E = 614.705 kN), M = T/g:

    >>> import math
    >>> g = 9.80665
    >>> round(a_slip_hoist_decel(800276.0, 614705.0, 800276.0 / g, 614705.0 / g, 0.25, math.pi), 4)
    4.7194
    """
    return slip_acceleration(*manoeuvre_sides(T_L, T_E, M_L, M_E, F_r)["hoist_decel"], mu, alpha, q_arc, R, v)


def a_slip_lower_accel(T_L, T_E, M_L, M_E, mu, alpha, q_arc=0.0, R=0.0, v=0.0, F_r=0.0):
    """Largest acceleration while lowering (loaded conveyance sinking faster) before slip [m/s²].

    a = (e^{μα} (T_L − F_r) − T_E − (e^{μα} − 1) q v²) / (e^{μα} M_L + M_E + q R (e^{μα} − 1)/μ)

    Without shaft resistance it equals :func:`a_slip_hoist_decel`.  docs/physics.md §7.

    Examples
    --------
    The issue's example, loaded conveyance at the top, 5 kN of shaft resistance holding the sinking load back:

    >>> import math
    >>> g = 9.80665
    >>> round(a_slip_lower_accel(800276.0, 614705.0, 800276.0 / g, 614705.0 / g, 0.25, math.pi, F_r=5e3), 4)
    4.674
    """
    return slip_acceleration(*manoeuvre_sides(T_L, T_E, M_L, M_E, F_r)["lower_accel"], mu, alpha, q_arc, R, v)


def a_slip_lower_decel(T_L, T_E, M_L, M_E, mu, alpha, q_arc=0.0, R=0.0, v=0.0, F_r=0.0):
    """Largest deceleration while lowering (loaded conveyance sinking slower) before slip [m/s²].

    d = (e^{μα} T_E − T_L + F_r − (e^{μα} − 1) q v²) / (M_L + e^{μα} M_E + q R (e^{μα} − 1)/μ)

    Without shaft resistance it equals :func:`a_slip_hoist_accel`: the loaded side, heavier, pulls the ropes
    over the wheel.  docs/physics.md §7.

    Examples
    --------
    The issue's example, loaded conveyance at the bottom, with the ropes on the wheel at 12 m/s:

    >>> import math
    >>> g = 9.80665
    >>> round(a_slip_lower_decel(830451.0, 584530.0, 830451.0 / g, 584530.0 / g, 0.25, math.pi,
    ...                          q_arc=4 * 8.6, R=2.25, v=12.0), 4)
    2.0654
    """
    return slip_acceleration(*manoeuvre_sides(T_L, T_E, M_L, M_E, F_r)["lower_decel"], mu, alpha, q_arc, R, v)


def coasting_deceleration(T_L, T_E, M_total, direction, F_r=0.0):
    """Deceleration with neither drive nor brake, d = (s (T_L − T_E) + F_r)/M_total [m/s²].

    s = +1 hoisting, −1 lowering; T_L, T_E [N] static tensions; F_r [N] >= 0 shaft resistance; M_total [kg]
    everything that moves: both sides, the rope on the wheel, the wheel, drive and brake discs referred to the
    rope (J/R²).  The brake only adds to it (its torque opposes the motion), so a brake cannot decelerate
    less than this: the floor of the braking window.  Rigid-body mechanics (docs/physics.md §7).

    Examples
    --------
    >>> round(coasting_deceleration(830451.0, 584530.0, 180000.0, +1), 3)
    1.366
    """
    return (direction * (T_L - T_E) + F_r) / M_total


def braking_window(d_slip, d_min, d_max=float("inf"), d_free=-float("inf")):
    """Admissible brake decelerations [low, high] [m/s²]: low = max(d_min, d_free), high = min(d_slip, d_max).

    d_slip [m/s²] the slip limit of the direction (:func:`a_slip_hoist_decel` or :func:`a_slip_lower_decel`);
    d_min, d_max [m/s²] the least and largest deceleration the rule set allows for an emergency stop; d_free
    [m/s²] :func:`coasting_deceleration`.  Empty when low > high: see :func:`braking_window_verdict`.

    Examples
    --------
    >>> braking_window(2.07, 1.5, 5.0)
    (1.5, 2.07)
    """
    return fmax(d_min, d_free), fmin(d_slip, d_max)


class BrakingWindow(NamedTuple):
    """The brake's admissible deceleration in one direction [m/s²]: the interval, what bounds it, and a message
    naming the conflict when it is empty ("" otherwise)."""

    direction: str
    low: float
    high: float
    low_by: str
    high_by: str
    admissible: bool
    message: str


def braking_window_verdict(direction: str, d_slip: float, d_min: float, d_max: float = float("inf"),
                           d_free: float = -float("inf")) -> BrakingWindow:
    """The braking window of one direction ("hoisting" or "lowering"), or the conflict named.  Floats only.

    Arguments as :func:`braking_window`.

    Examples
    --------
    >>> verdict = braking_window_verdict("lowering", 1.2, 1.5)
    >>> verdict.admissible, verdict.low_by, verdict.high_by
    (False, "the rule's least deceleration", 'the slip limit (a_slip_lower_decel)')
    >>> verdict.message[:46]
    'lowering: no admissible brake deceleration: th'
    """
    slip = f"the slip limit (a_slip_{'hoist' if direction == 'hoisting' else 'lower'}_decel)"
    lows = [("the rule's least deceleration", float(d_min)), ("the deceleration without brake", float(d_free))]
    highs = [(slip, float(d_slip)), ("the rule's largest deceleration", float(d_max))]
    low_by, low = max(lows, key=lambda item: item[1])
    high_by, high = min(highs, key=lambda item: item[1])
    admissible = low <= high
    message = "" if admissible else (f"{direction}: no admissible brake deceleration: {low_by} {low:.4g} m/s² "
                                     f"exceeds {high_by} {high:.4g} m/s²")
    return BrakingWindow(direction, low, high, low_by, high_by, admissible, message)
