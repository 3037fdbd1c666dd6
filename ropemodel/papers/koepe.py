"""Koepe (friction) hoist, statics: the tensions either side of the wheel, their ratio and the anti-slip factor.

Standard mine-hoisting practice (de la Vergne 2003, ch. 14; Edwards 1992): no single paper; the geometry
and every assumption are stated here and in ``docs/physics.md`` §7, which also derives the dynamics
(:mod:`ropemodel.papers.koepe_slip`) and the lined wheel (:mod:`ropemodel.papers.koepe_lining`).

Two conveyances hang from n_head head ropes (mass per metre q_head each) over a friction wheel; n_tail tail
(balance) ropes (q_tail each) hang from the bottom of one conveyance, round a free loop, to the bottom of the
other.  The shaft is vertical.  Side L carries the loaded conveyance (m_conveyance + m_payload), side E the
other one (m_conveyance); the empty hoist is m_payload = 0.  Positions are depths below the upper position:
the loaded conveyance at y_L ∈ [0, H] (0 at the top of the wind, H, the winding distance, at the bottom), the
other at H − y_L.

* Head ropes: from the wheel's tangent point to the conveyance, H_head + depth (H_head, from the wheel to a
  conveyance at the upper position, the same on both sides).  The rope lying on the wheel is carried by the
  wheel and is no part of either side's static tension.
* Tail ropes: each side carries its tail ropes from the conveyance down to the bottom of the loop, at
  depth H + h_loop: H + h_loop − depth.  h_loop = (L_tail − H)/2 is the rope per side that never rises above
  a conveyance's lower position (L_tail: one tail rope's length); a free loop's turn is shared equally by the
  two sides (its vertical equilibrium), so h_loop counts half of it on each.  Default 0: the loop's rope
  raises both tensions alike, so 0 gives the largest ratio T_1/T_2 (conservative for slip; it understates
  T_1, for rope safety, by g n_tail q_tail h_loop).
* All n_head ropes share the side's tension equally (per rope T/n_head).

With these, each side's tension is linear in y_L, so T_L/T_E is monotone in y_L and T_1/T_2 =
max(T_L/T_E, T_E/T_L), like the tensions themselves, is worst at an end of the wind.  At rest the tensions do
not depend on the direction of travel; the direction enters through the manoeuvres
(:mod:`ropemodel.papers.koepe_slip`).

Units: masses [kg], masses per metre [kg/m], lengths and depths [m], tensions [N], angles [rad].  Every
function works on floats, numpy arrays and CasADi expressions, except those marked "floats only".
"""

from __future__ import annotations

from typing import NamedTuple

from ropemodel._math import fmax, fmin, if_else
from ropemodel.papers.route import G_N


def head_rope_length(H_head, depth):
    """Length of one head rope from the wheel's tangent point to a conveyance, L_h = H_head + y [m].

    H_head [m] head-rope length to a conveyance at its upper position, >= 0; depth y [m] of the conveyance
    below its upper position, 0 <= y <= H.  Standard practice (docs/physics.md §7).

    Examples
    --------
    >>> head_rope_length(56.7, 905.0)     # the loaded conveyance at the bottom of a 905 m wind
    961.7
    """
    return H_head + depth


def tail_rope_length(H, h_loop, depth):
    """Tail rope carried by one side, from the conveyance to the bottom of the loop, L_t = H + h_loop − y [m].

    H [m] winding distance, > 0; h_loop [m] = (L_tail − H)/2 >= 0, the rope per side below a conveyance's
    lower position (half the loop's turn included); depth y [m], 0 <= y <= H.  The two sides' L_t add up
    to L_tail = H + 2 h_loop at any position.  ropemodel's statement of the free loop (docs/physics.md §7).

    Examples
    --------
    >>> tail_rope_length(905.0, 5.0, 0.0), tail_rope_length(905.0, 5.0, 905.0)
    (910.0, 5.0)
    """
    return H + h_loop - depth


def side_static_tension(m, n_head, q_head, L_head, n_tail, q_tail, L_tail, g=G_N):
    """Static tension of one side at the wheel, T = g (m + n_head q_head L_h + n_tail q_tail L_t) [N].

    m [kg] the conveyance with what it carries; n_head, n_tail [-] numbers of head and tail ropes (n_tail = 0:
    none); q_head, q_tail [kg/m] mass per metre of one rope; L_head, L_tail [m] from
    :func:`head_rope_length` and :func:`tail_rope_length`; g [m/s²].  The total over the n_head ropes.
    Standard practice (de la Vergne 2003, ch. 14; docs/physics.md §7).

    Examples
    --------
    The empty side of the issue's example with its conveyance at the top (29.6 t; 4 head ropes of
    8.6 kg/m over 56.7 m; 2 tail ropes of 15.5 kg/m over 905 m), in kN:

    >>> round(side_static_tension(29.6e3, 4, 8.6, 56.7, 2, 15.5, 905.0) / 1e3, 3)
    584.53
    """
    return g * (m + n_head * q_head * L_head + n_tail * q_tail * L_tail)


def side_tensions(y_L, m_conveyance, m_payload, H, H_head, n_head, q_head, n_tail=0, q_tail=0.0, h_loop=0.0,
                  g=G_N):
    """Static tensions (T_L, T_E) [N] of the loaded side and the other, the loaded conveyance at depth y_L.

    T_L = g [m_conveyance + m_payload + n_head q_head (H_head + y_L) + n_tail q_tail (H + h_loop − y_L)]
    T_E = g [m_conveyance + n_head q_head (H_head + H − y_L) + n_tail q_tail (h_loop + y_L)]

    y_L [m], 0 (loaded conveyance at the top) <= y_L <= H (at the bottom); m_conveyance, m_payload [kg] >= 0
    (m_payload = 0: the empty hoist); H [m] winding distance > 0; H_head [m] >= 0; n_head >= 1; q_head, q_tail
    [kg/m] >= 0; n_tail >= 0; h_loop [m] >= 0; g [m/s²].  Standard practice (docs/physics.md §7).

    Examples
    --------
    The issue's example (H = 905 m, H_head = 56.7 m, 29.6 t + 22 t, 4 × 8.6 kg/m, 2 × 15.5 kg/m), loaded
    conveyance at the bottom, in kN:

    >>> T_L, T_E = side_tensions(905.0, 29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5)
    >>> round(T_L / 1e3, 3), round(T_E / 1e3, 3)
    (830.451, 584.53)
    """
    depth_E = H - y_L
    T_L = side_static_tension(m_conveyance + m_payload, n_head, q_head, head_rope_length(H_head, y_L),
                              n_tail, q_tail, tail_rope_length(H, h_loop, y_L), g)
    T_E = side_static_tension(m_conveyance, n_head, q_head, head_rope_length(H_head, depth_E),
                              n_tail, q_tail, tail_rope_length(H, h_loop, depth_E), g)
    return T_L, T_E


def side_mass(T_static, m_extra=0.0, g=G_N):
    """Mass moving with one side, M = T/g + m_extra [kg].

    Everything a side's static tension T [N] carries moves with it (conveyance, payload, its head ropes, its
    tail ropes: a free loop's turn is shared like its weight); m_extra [kg] >= 0 adds what moves with the
    side without hanging from it: a deflection sheave on that side (:func:`sheave_equivalent_mass`).
    ropemodel's statement (docs/physics.md §7); MODELS.md §5 takes M = T/g.

    Examples
    --------
    >>> round(side_mass(830451.0, 2000.0))
    86682
    """
    return T_static / g + m_extra


def sheave_equivalent_mass(J, r):
    """Mass equivalent to a sheave's rotation, J/r² [kg], for a rope running over it without slip.

    J [kg m²] moment of inertia of the sheave about its axle, >= 0; r [m] its radius at the rope centre, > 0.
    Bearing friction is left out.  Rigid-body mechanics: the torque J a/r that accelerates the sheave is a
    tension difference (J/r²) a across it (docs/physics.md §7).

    Examples
    --------
    >>> sheave_equivalent_mass(9000.0, 1.5)
    4000.0
    """
    return J / r**2


def arc_rope_mass(n_head, q_head, R, alpha):
    """Mass of the head ropes lying on the wheel, n_head q_head R α [kg].

    n_head [-]; q_head [kg/m]; R [m] wheel radius at the rope centre (D/2), > 0; alpha [rad] wrap, > 0.
    It enters the dynamics (:func:`ropemodel.papers.koepe_slip.effective_arc_mass`), not the static tensions.

    Examples
    --------
    >>> import math
    >>> round(arc_rope_mass(4, 8.6, 2.25, math.pi), 1)
    243.2
    """
    return n_head * q_head * R * alpha


def high_low(T_a, T_b):
    """(T_1, T_2) = (max, min) of the two sides' tensions [N].  Not smooth where T_a = T_b; IPOPT wants
    :func:`traction_margins`, one per side."""
    return fmax(T_a, T_b), fmin(T_a, T_b)


def static_ratio(T_a, T_b):
    """Static tension ratio T_1/T_2 >= 1 [-], high over low, of the two sides' tensions T_a, T_b [N] > 0.

    Standard practice (de la Vergne 2003, ch. 14).  No slip at rest while T_1/T_2 <= the traction limit
    (e^{μα}, :func:`ropemodel.papers.friction.euler_eytelwein_ratio`, on a rigid lining).

    Examples
    --------
    >>> round(static_ratio(830451.0, 584530.0), 4)
    1.4207
    """
    T_1, T_2 = high_low(T_a, T_b)
    return T_1 / T_2


def traction_margins(T_L, T_E, ratio):
    """Margins against static slip, one per side: (ratio T_E − T_L, ratio T_L − T_E) [N], both >= 0 for no slip.

    The first fails when the loaded side pulls the ropes over the wheel, the second when the other side
    does.  Smooth (no max/min), for sizing.  ratio [-] the traction limit, e.g. e^{μα}.  Euler–Eytelwein
    written multiplied out.

    Examples
    --------
    >>> [round(m) for m in traction_margins(830451.0, 584530.0, 2.0)]
    [338609, 1076372]
    """
    return ratio * T_E - T_L, ratio * T_L - T_E


def anti_slip_factor(T_1, T_2, ratio):
    """Anti-slip factor σ = (ratio − 1) T_2/(T_1 − T_2) [-] of Chinese friction-hoist practice.

    The friction the arc can still give, (ratio − 1) T_2, over what the tension difference T_1 − T_2 [N]
    takes; σ = 1 at the onset of slip, σ > 1 safe, σ = inf when T_1 = T_2.  ratio [-] the traction limit
    (e^{μα} on a rigid lining; :func:`ropemodel.papers.koepe_lining.voigt_traction_ratio` on a Voigt lining).
    With static tensions it is the static factor, with the tensions of a manoeuvre the dynamic one.
    Source: Chinese design practice for multi-rope friction hoists (key ``antislip_cn``; MODELS.md §5).

    Examples
    --------
    The issue's example, loaded conveyance at the bottom, μ = 0.25 over 180°:

    >>> import math
    >>> round(anti_slip_factor(830451.0, 584530.0, math.exp(0.25 * math.pi)), 3)
    2.836
    """
    difference = T_1 - T_2
    safe = if_else(difference > 0, difference, 1.0 + 0.0 * difference)
    return if_else(difference > 0, (ratio - 1.0) * T_2 / safe, float("inf") + 0.0 * difference)


def anti_slip_margin(T_1, T_2, ratio, sigma_min):
    """σ >= σ_min multiplied out, (ratio − 1) T_2 − σ_min (T_1 − T_2) [N], >= 0 passes.

    Smooth and without a pole at T_1 = T_2, for sizing; same sign as σ − σ_min while T_1 > T_2.
    sigma_min [-] the factor a rule set requires.  See :func:`anti_slip_factor`.

    Examples
    --------
    >>> import math
    >>> round(anti_slip_margin(830451.0, 584530.0, math.exp(0.25 * math.pi), 1.75) / 1e3, 1)
    267.1
    """
    return (ratio - 1.0) * T_2 - sigma_min * (T_1 - T_2)


class StaticCase(NamedTuple):
    """One static case: its name, the loaded conveyance's depth y_L [m] and payload [kg], the tensions [N],
    which side is high ("loaded" or "other"), T_1/T_2 [-]."""

    name: str
    y_L: float
    m_payload: float
    T_L: float
    T_E: float
    T_1: float
    T_2: float
    high_side: str
    ratio: float


def static_cases(m_conveyance, m_payload, H, H_head, n_head, q_head, n_tail=0, q_tail=0.0, h_loop=0.0,
                 g=G_N) -> list[StaticCase]:
    """The static cases at the ends of the wind: loaded at the bottom, loaded at the top, empty.  Floats only.

    The tensions are linear in the position, so these hold the largest T_1 and the largest T_1/T_2 over
    the wind (docs/physics.md §7).  The empty hoist's two end positions mirror each other; one is listed.
    Arguments as :func:`side_tensions`.

    Examples
    --------
    >>> [(c.name, round(c.ratio, 4)) for c in static_cases(29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5)]
    [('loaded at the bottom', 1.4207), ('loaded at the top', 1.3019), ('empty', 1.0516)]
    """
    cases = []
    for name, y_L, payload in (("loaded at the bottom", H, m_payload), ("loaded at the top", 0.0, m_payload),
                               ("empty", H, 0.0)):
        T_L, T_E = (float(t) for t in side_tensions(y_L, m_conveyance, payload, H, H_head, n_head, q_head,
                                                    n_tail, q_tail, h_loop, g))
        high = "loaded" if T_L >= T_E else "other"
        cases.append(StaticCase(name, float(y_L), float(payload), T_L, T_E, max(T_L, T_E), min(T_L, T_E),
                                high, max(T_L, T_E) / min(T_L, T_E)))
    return cases


class StaticSlip(NamedTuple):
    """Verdict on slip at rest: the worst case, its ratio against the traction limit, and a message naming the
    numbers when it slips ("" when it holds)."""

    case: StaticCase
    limit: float
    slips: bool
    message: str


def slip_at_rest(cases: list[StaticCase], limit) -> StaticSlip:
    """Does the hoist slip at rest?  The case of largest T_1/T_2 against the traction limit.  Floats only.

    ``limit`` [-]: e^{μα} on a rigid lining, or a function of T_2 (e.g. a Voigt lining's ratio at rest,
    :func:`ropemodel.papers.koepe_lining.voigt_traction_ratio` with v = 0), evaluated for each case.
    A hoist that slips at rest has no answer to any design question; the message says why, with the numbers.

    Examples
    --------
    No tail ropes, 1000 m wind, 20 t conveyances, 15 t payload, 4 × 8.6 kg/m head ropes, μ = 0.25 over 180°:

    >>> import math
    >>> verdict = slip_at_rest(static_cases(20e3, 15e3, 1000.0, 50.0, 4, 8.6), math.exp(0.25 * math.pi))
    >>> verdict.slips, round(verdict.case.ratio, 3)
    (True, 3.274)
    """
    worst, worst_limit, worst_excess = cases[0], 0.0, -float("inf")
    for case in cases:
        lim = float(limit(case.T_2)) if callable(limit) else float(limit)
        if case.ratio / lim - 1.0 > worst_excess:
            worst, worst_limit, worst_excess = case, lim, case.ratio / lim - 1.0
    slips = worst_excess > 0.0
    message = ""
    if slips:
        message = (f"the ropes slip on the wheel at rest ({worst.name}): T_1/T_2 = {worst.ratio:.4g} exceeds the "
                   f"traction limit {worst_limit:.4g} (T_1 = {worst.T_1 / 1e3:.4g} kN on the {worst.high_side} "
                   f"side, T_2 = {worst.T_2 / 1e3:.4g} kN); heavier tail ropes, a larger wrap or friction, or a "
                   f"lighter payload")
    return StaticSlip(worst, worst_limit, slips, message)
