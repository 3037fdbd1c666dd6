"""A route of straight segments, and the haulage's inertia: ropemodel's extension of Krauze et al. (2025).

The paper treats the route as one straight incline (L_u, α_u, eq. (1)-(13)).  A real route is a list
of straight segments i = 1…n, listed from the drive (guiding sheave K_K, x = 0) toward the return
sheave K_ZN (x = L_u = Σ L_i), of inclination α_i and winding-rope resistance coefficient μ_i.
Each rope side spans the whole route; the load is at x_m, in segment j (the segment containing x_m;
a load on a joint belongs to the segment nearer the drive).  The paper's sums become (physics
reference ``docs/physics.md`` §4):

* rope weight along the route, each side: Σ q_l L_i sin α_i (eq. (2) and (6) for one segment);
* winding-rope resistance: Σ μ_i q_l L_i cos α_i (eq. (8)-(10)); unwinding: Σ μ_pl q_l L_i cos α_i (eq. (11));
* the load: G_ml = G_m sin α_j (eq. (1)), G_mo = G_m cos α_j (eq. (5)), T_m = μ_pm G_m cos α_j (eq. (7)).

One segment is the paper's case 1; two segments of equal inclination are its case 2 with point A
at their joint (the drive-side segment, of length L_ul, has μ_pl2, the other μ_pl1).

Inertia (not in the paper): while the haulage speeds up at a_h [m/s²] in its direction of travel
(negative while it slows down), the winding side (load and winding rope, mass (G_m + q_l L_u)/g)
needs m_C a_h more pull and the unwinding side (q_l L_u/g) m_S a_h less, with the sign of travel,
like the resistances of eq. (12)-(13): the rigid-body (inextensible rope) inertia of a ramp.

Tension along a rope side (not in the paper, which gives the forces at the drum only): each side runs
from the drum (x = 0) to the return sheave (x = L_u), where the tensioner holds it at F_nwl/2; toward the
drive its tension rises on segment i by q_l g_i per metre, g_i = sin α_i + σ (μ_i cos α_i + a_h/g), with
σ = +s on the winding side and −s on the unwinding side, and the winding side's load adds its pull
J = G_ml + s (T_m + G_m a_h/g) on its drive side (:func:`rope_tension`, :func:`least_rope_tension`;
the derivation and the sign conventions are in ``docs/physics.md`` §4).

Every function works on floats, numpy arrays and CasADi expressions; lists hold one entry per
segment.  Units: N, m, rad.
"""

from __future__ import annotations

import casadi as ca

from ropemodel._math import cos, fmax, fmin, if_else, sin
from ropemodel.papers import route_vector as rv

#: standard gravity [m/s²] (CGPM 1901)
G_N = 9.80665


def _symbolic(*items) -> bool:
    """Whether any of ``items`` (or of the entries of a list among them) is a CasADi expression."""
    return any(_symbolic(*a) if isinstance(a, (list, tuple)) else isinstance(a, (ca.SX, ca.MX, ca.DM)) for a in items)


def _vector(items):
    """A list with CasADi entries as one column (vector operations: a route of thousands of segments builds in a
    few operations, not thousands), or None for numbers (summed one by one, as written).

    The symbolic forms keep q_l (and F_end) outside the sums over the route: with the route's values known (the
    scene's, folded in) each sum is one number, and the model's size in the rope and the pretension, which
    sizing varies, no longer grows with the segments."""
    return rv.column(items) if _symbolic(*items) else None


def as_column(items):
    """A list of a route's values as one CasADi column where any is symbolic (a column passes through), else the
    list: what the functions here take per segment (a column of gradients builds in a few operations)."""
    if isinstance(items, (ca.SX, ca.MX)):
        return items
    column = _vector(items)
    return items if column is None else column


def _sum(column, start=0.0):
    """start + column[0] + column[1] + …, added in that order (as the loops over numbers add them)."""
    return start + ca.sum1(column) if column.numel() else start


def route_length(lengths):
    """Length of the route L_u = Σ L_i [m].  lengths [m] of the segments, each > 0."""
    column = _vector(lengths)
    if column is not None:
        return _sum(column)
    total = 0.0
    for length in lengths:
        total = total + length
    return total


def rope_weight_along_route(q_l, lengths, inclinations):
    """Σ q_l L_i sin α_i [N]: weight along the route of one rope side (eq. (2), (6) for one segment).

    q_l [N/m] rope weight per metre; lengths [m]; inclinations α_i [rad], −π/2 < α_i < π/2.
    """
    L, a = _vector(lengths), _vector(inclinations)
    if L is not None and a is not None:
        return q_l * _sum(L * ca.sin(a))
    total = 0.0
    for length, alpha in zip(lengths, inclinations):
        total = total + q_l * length * sin(alpha)
    return total


def rope_resistance_along_route(q_l, lengths, inclinations, mus):
    """Σ μ_i q_l L_i cos α_i [N]: travel resistance of one rope side (eq. (8)-(11) for one segment).

    mus: resistance coefficient of the rope in each segment [-] (μ_pl for the unwinding rope).
    """
    L, a, m = _vector(lengths), _vector(inclinations), _vector(mus)
    if L is not None and a is not None and m is not None:
        return q_l * _sum(m * L * ca.cos(a))
    total = 0.0
    for length, alpha, mu in zip(lengths, inclinations, mus):
        total = total + mu * q_l * length * cos(alpha)
    return total


def _overlap(start, end, s0, s1):
    """Length of [start, end] ∩ [s0, s1] (0 if they do not meet)."""
    return fmax(fmin(end, s1) - fmax(start, s0), 0.0)


def rope_weight_between(q_l, lengths, inclinations, s0, s1):
    """q_l Σ ℓ_i sin α_i over the part ℓ_i of each segment between s0 and s1 [m] from the drive [N].

    With point A at L_ul (Krauze et al. 2025): [L_ul, L_u] gives G_l1 (eq. (3)), [0, L_ul] G_l2 (eq. (4)).
    """
    total, start = 0.0, 0.0
    for length, alpha in zip(lengths, inclinations):
        total = total + q_l * _overlap(start, start + length, s0, s1) * sin(alpha)
        start = start + length
    return total


def rope_resistance_between(q_l, lengths, inclinations, mus, s0, s1):
    """Σ μ_i q_l ℓ_i cos α_i over the part ℓ_i of each segment between s0 and s1 [m] from the drive [N].

    With point A at L_ul: [L_ul, L_u] gives T_l1 (eq. (8)), [0, L_ul] T_l2 (eq. (9)).
    """
    total, start = 0.0, 0.0
    for length, alpha, mu in zip(lengths, inclinations, mus):
        total = total + mu * q_l * _overlap(start, start + length, s0, s1) * cos(alpha)
        start = start + length
    return total


def at_position(x, lengths, values):
    """The value of the segment containing x [m] (from the drive): ``values[j]`` with
    L_1 + … + L_{j-1} < x <= L_1 + … + L_j; x <= L_1 gives the first, x beyond the route the last.

    Symbolic, as vectors: with c_j = [x <= L_1 + … + L_j] (c_n = 1), rising once along the route, the value is
    Σ_j values[j] (c_j − c_{j−1}): exactly one term is the value itself, the others add zeros."""
    if len(values) > 1 and _symbolic(x, *lengths, *values):
        v = rv.column(values)
        ends = rv.ends(lengths)[:-1]
        inside = ca.vertcat(ends >= x, 1.0)                       # c_1 … c_n
        first = inside - ca.vertcat(0.0, inside[:-1])             # 1 on the load's segment only
        return _sum(first * v)
    out = values[-1]
    ends, total = [], 0.0
    for length in lengths:
        total = total + length
        ends.append(total)
    for end, value in zip(reversed(ends[:-1]), reversed(values[:-1])):
        out = if_else(x <= end, value, out)
    return out


def load_weight_along_route(G_m, x, lengths, inclinations):
    """G_ml = G_m sin α_j [N], the load at x [m] in segment j (eq. (1) on the load's segment)."""
    return G_m * sin(at_position(x, lengths, inclinations))


def load_weight_normal_route(G_m, x, lengths, inclinations):
    """G_mo = G_m cos α_j [N] (eq. (5) on the load's segment)."""
    return G_m * cos(at_position(x, lengths, inclinations))


def load_resistance_route(mu_pm, G_m, x, lengths, inclinations):
    """T_m = μ_pm G_m cos α_j [N] (eq. (7) on the load's segment)."""
    return mu_pm * G_m * cos(at_position(x, lengths, inclinations))


def rope_gradient(inclination, mu, sign, a_h=0.0, g=G_N):
    """g_i = sin α_i + σ (μ_i cos α_i + a_h/g) [-]: how fast a rope side's tension rises toward the drive on a
    segment, per metre and per unit rope weight (docs/physics.md §4; not in Krauze et al. 2025).

    inclination α_i [rad] (> 0: rising toward the drive); mu μ_i [-] the side's resistance coefficient there
    (μ_i of the winding rope, μ_pl of the unwinding one); sign σ = +s on the winding side and −s on the
    unwinding side (s = +1 hauling up, −1 lowering); a_h [m/s²] the haulage's acceleration in its direction of
    travel (rigid rope; 0 in steady motion).  The sum of q_l L_i g_i over the route is the paper's
    G_ls ∓ T_ls (unwinding) or G_l ± T_l (winding), eq. (12)-(13), plus the rope's inertia.

    Examples
    --------
    The Fig. 9 incline (16°, μ_pl = 0.05) hauled up: the unwinding rope's tension rises toward the drum by
    q_l (sin 16° − 0.05 cos 16°) per metre, so over 1150 m at 80 N/m it gains G_ls − T_ls = 25.3586 −
    4.4218 kN (eq. (6), (11)):

    >>> import math
    >>> round(80.0 * 1150.0 * rope_gradient(math.radians(16.0), 0.05, -1.0) / 1e3, 4)
    20.9368
    """
    return sin(inclination) + sign * (mu * cos(inclination) + a_h / g)


def load_pull(G_ml, T_m, G_m, sign, a_h=0.0, g=G_N):
    """J = G_ml + s (T_m + G_m a_h/g) [N]: how much more the winding rope pulls on the drive side of the load
    than beyond it (eq. (1), (7) on the load's segment, plus its inertia; s = +1 hauling up, −1 lowering).
    Negative when lowering on a slope gentler than the load's resistance (or while a lowering speeds up):
    the rope beyond the load then pulls it down the route."""
    return G_ml + sign * (T_m + G_m * a_h / g)


def tension_at_joints(F_end, q_l, lengths, gradients):
    """[T_0, T_1, …, T_n] [N]: a rope side's tension at the joints x_0 = 0 (the drum), x_k = L_1 + … + L_k,
    x_n = L_u (the return sheave, where it is F_end = F_nwl/2), without a load on the side:
    T_{k−1} = T_k + q_l L_k g_k (:func:`rope_gradient`), docs/physics.md §4.

    Examples
    --------
    Fig. 9 hauled up, the unwinding rope: 10 kN at the return sheave, F_S_up = 30.9368 kN at the drum
    (eq. (12)):

    >>> import math
    >>> g = rope_gradient(math.radians(16.0), 0.05, -1.0)
    >>> [round(t / 1e3, 4) for t in tension_at_joints(10e3, 80.0, [1150.0], [g])]
    [30.9368, 10.0]
    """
    if _symbolic(F_end, q_l, *lengths, gradients):
        rise = rv.rises(lengths, gradients)
        return [F_end + q_l * rise[k] for k in range(rise.numel())]
    out = [F_end]
    for length, gradient in zip(reversed(list(lengths)), reversed(list(gradients))):
        out.append(out[-1] + q_l * length * gradient)
    return out[::-1]


def rope_tension(x, F_end, q_l, lengths, gradients, x_m=None, load=0.0):
    """T(x) [N]: a rope side's tension at x [m] from the drive, 0 <= x <= L_u (docs/physics.md §4)::

        T(x) = F_end + q_l Σ_i g_i ℓ_i(x) + J [x < x_m]

    with ℓ_i(x) the part of segment i between x and the return sheave, F_end = F_nwl/2 the tension there,
    g_i the side's gradients (:func:`rope_gradient`) and, on the winding side, the load at x_m [m] with its
    pull J = ``load`` (:func:`load_pull`) on its drive side.  At x = x_m this is the tension just beyond
    the load (on its return-sheave side); just before it the tension is T(x_m) + J.

    Examples
    --------
    Fig. 9 hauled up, the winding rope (μ_pl = 0.05) with the load at 800 m: 10 kN at the return sheave and
    F_C_up = 190.949 kN at the drum (eq. (13)); just beyond the load, 10 kN and the 350 m of rope beyond it,
    10 + 0.08·350·(sin 16° + 0.05 cos 16°) = 19.064 kN:

    >>> import math
    >>> a = math.radians(16.0)
    >>> g, J = rope_gradient(a, 0.05, 1.0), load_pull(467e3 * math.sin(a), 0.05 * 467e3 * math.cos(a), 467e3, 1.0)
    >>> [round(rope_tension(x, 10e3, 80.0, [1150.0], [g], 800.0, J) / 1e3, 3) for x in (0.0, 800.0, 1150.0)]
    [190.949, 19.064, 10.0]
    """
    L_u = route_length(lengths)
    if _symbolic(x, F_end, q_l, *lengths, gradients):
        total = F_end + q_l * rv.rise_at(x, lengths, gradients)
        return total if x_m is None else total + if_else(x < x_m, load, 0.0)
    total, start = F_end, 0.0
    for length, gradient in zip(lengths, gradients):
        total = total + q_l * gradient * _overlap(start, start + length, x, L_u)
        start = start + length
    return total if x_m is None else total + if_else(x < x_m, load, 0.0)


def least_rope_tension(F_end, q_l, lengths, gradients, x_m=None, load=0.0, between=False):
    """The least tension [N] of a rope side along the whole route, from the drum to the return sheave, both
    included (docs/physics.md §4); ``between=True``: between its ends only, at the route's joints and beside the
    load (what the route's own check holds: the drum's force, eq. (12)-(13), and the return sheave's F_end =
    F_nwl/2 have checks of their own).

    The tension (:func:`rope_tension`) is linear on each segment and continuous but at the load, so the side's
    least value is at the drum, at a joint x_k (where the gradient changes from falling to rising toward the
    drive), beside the load, or at the return sheave::

        min( T_0 + J,  min_{0 < k < n} (T_k + J [x_k < x_m]),  T(x_m) + J,  T(x_m),  F_end )

    with T_k the tension at the joints without the load (:func:`tension_at_joints`), T_0 + J the drum's force,
    T(x_m) + J and T(x_m) just before and beyond the load.  Between the ends the first and the last are left
    out, and so is the load's side at an end.  The whole side's least does not depend on where the route is cut;
    the least between the ends does, near an end where the side is least (it approaches the end's value).  A
    load beyond the route is at the return sheave.  Arguments as :func:`rope_tension`; ``x_m=None``: a side
    without a load.  One segment without a load has nothing between its ends: its least there is its ends'.

    Examples
    --------
    A dip: from the drive 300 m down at 5°, then 300 m up at 2° to the return sheave (α = 5°, −2°); the
    unwinding rope of a haulage hauling up (μ_pl = 0.05, q_l = 80 N/m, 10 kN at the return sheave) is
    least at the bottom of the dip, below both ends:

    >>> import math
    >>> g = [rope_gradient(math.radians(a), 0.05, -1.0) for a in (5.0, -2.0)]
    >>> [round(t / 1e3, 4) for t in tension_at_joints(10e3, 80.0, [300.0, 300.0], g)]
    [8.8594, 7.9631, 10.0]
    >>> round(least_rope_tension(10e3, 80.0, [300.0, 300.0], g) / 1e3, 4)
    7.9631

    Hauled up a straight 16° incline (Fig. 9), the unwinding rope is least at the return sheave, 10 kN; between
    its ends, a joint 10 m before the sheave is its least (the route cut there: the closer the cut, the lower):

    >>> g = rope_gradient(math.radians(16.0), 0.05, -1.0)
    >>> [round(least_rope_tension(10e3, 80.0, [1140.0, 10.0], [g, g], between=b) / 1e3, 4) for b in (False, True)]
    [10.0, 10.1821]
    """
    inside = _between(F_end, q_l, lengths, gradients, x_m, load)
    if between:
        return inside
    return fmin(inside, with_ends(F_end, q_l, lengths, gradients, load))


def with_ends(F_end, q_l, lengths, gradients, load=0.0):
    """The lesser of a rope side's tensions at its ends [N]: at the drum F_end + q_l Σ L_i g_i + J (the drum's
    force, eq. (12)-(13); J = ``load`` the load's pull on the winding side, 0 on the unwinding one) and at the
    return sheave F_end (docs/physics.md §4)."""
    if _symbolic(*lengths, gradients):
        rise = _sum(rv.column(lengths) * rv.column(gradients))
    else:
        rise = 0.0
        for length, gradient in zip(reversed(list(lengths)), reversed(list(gradients))):
            rise = rise + length * gradient
    return F_end + fmin(q_l * rise + load, 0.0)


def _between(F_end, q_l, lengths, gradients, x_m, load):
    """:func:`least_rope_tension` between the side's ends."""
    if len(lengths) > 1 and _symbolic(F_end, q_l, x_m, load, *lengths, gradients):
        return rv.least_tension(F_end, q_l, lengths, gradients, x_m, load)
    joints = tension_at_joints(F_end, q_l, lengths, gradients)
    L_u = route_length(lengths)
    if x_m is not None:
        x_m = fmin(x_m, L_u)
    at, out = 0.0, None
    for k in range(1, len(joints) - 1):
        at = at + lengths[k - 1]
        here = joints[k] if x_m is None else joints[k] + if_else(at < x_m, load, 0.0)
        out = here if out is None else fmin(out, here)
    if x_m is not None:
        beside = rope_tension(x_m, F_end, q_l, lengths, gradients)
        before = if_else(x_m > 0.0, beside + load, beside)           # at the drive: the drum's force
        after = if_else(x_m < L_u, beside, beside + load)            # at the return sheave: F_end
        out = fmin(before, after) if out is None else fmin(out, fmin(before, after))
    return fmin(joints[0], joints[-1]) if out is None else out


def winding_side_mass(G_m, q_l, L_u, g=G_N):
    """Mass moving with the winding side, (G_m + q_l L_u)/g [kg]: the load and the winding rope."""
    return (G_m + q_l * L_u) / g


def unwinding_side_mass(q_l, L_u, g=G_N):
    """Mass of the unwinding rope, q_l L_u/g [kg]."""
    return q_l * L_u / g


# --- kinematics of a trip with linear ramps (docs/physics.md §4) ------------------------------------


def trip_phases(length: float, v_pj: float, t_ramp: float) -> list[tuple[float, float, float, float]]:
    """Phases (t0, t1, v0, a) of a trip over ``length`` [m]: ramp to v_pj [m/s] in t_ramp [s], run, ramp down.

    A route shorter than v_pj·t_ramp never reaches full speed: up and down at the same acceleration
    v_pj/t_ramp (a triangle).  Floats only.

    Examples
    --------
    >>> trip_phases(1150.0, 2.5, 5.0)      # 5 s up, 455 s at 2.5 m/s, 5 s down
    [(0.0, 5.0, 0.0, 0.5), (5.0, 460.0, 2.5, 0.0), (460.0, 465.0, 2.5, -0.5)]
    """
    a = v_pj / t_ramp
    if length <= v_pj * t_ramp:
        t_half = (length / a) ** 0.5
        return [(0.0, t_half, 0.0, a), (t_half, 2.0 * t_half, a * t_half, -a)]
    cruise = (length - v_pj * t_ramp) / v_pj
    return [(0.0, t_ramp, 0.0, a), (t_ramp, t_ramp + cruise, v_pj, 0.0),
            (t_ramp + cruise, 2.0 * t_ramp + cruise, v_pj, -a)]


def distance_travelled(phases, t: float) -> float:
    """Distance [m] travelled by time t [s] along ``phases`` (:func:`trip_phases`)."""
    s = 0.0
    for t0, t1, v0, a in phases:
        dt = min(max(t - t0, 0.0), t1 - t0)
        s += v0 * dt + 0.5 * a * dt * dt
    return s


def time_at_distance(phases, distance: float) -> float:
    """The time [s] at which ``distance`` [m] has been travelled (the distance only grows)."""
    s = 0.0
    for t0, t1, v0, a in phases:
        step = v0 * (t1 - t0) + 0.5 * a * (t1 - t0) ** 2
        if s + step >= distance:
            d = distance - s
            if a == 0.0:
                return t0 + d / v0
            root = max(v0 * v0 + 2.0 * a * d, 0.0) ** 0.5
            return t0 + (root - v0) / a
        s += step
    return phases[-1][1]
