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

Every function works on floats, numpy arrays and CasADi expressions; lists hold one entry per
segment.  Units: N, m, rad.
"""

from __future__ import annotations

from ropemodel._math import cos, if_else, sin

#: standard gravity [m/s²] (CGPM 1901)
G_N = 9.80665


def route_length(lengths):
    """Length of the route L_u = Σ L_i [m].  lengths [m] of the segments, each > 0."""
    total = 0.0
    for length in lengths:
        total = total + length
    return total


def rope_weight_along_route(q_l, lengths, inclinations):
    """Σ q_l L_i sin α_i [N]: weight along the route of one rope side (eq. (2), (6) for one segment).

    q_l [N/m] rope weight per metre; lengths [m]; inclinations α_i [rad], −π/2 < α_i < π/2.
    """
    total = 0.0
    for length, alpha in zip(lengths, inclinations):
        total = total + q_l * length * sin(alpha)
    return total


def rope_resistance_along_route(q_l, lengths, inclinations, mus):
    """Σ μ_i q_l L_i cos α_i [N]: travel resistance of one rope side (eq. (8)-(11) for one segment).

    mus: resistance coefficient of the rope in each segment [-] (μ_pl for the unwinding rope).
    """
    total = 0.0
    for length, alpha, mu in zip(lengths, inclinations, mus):
        total = total + mu * q_l * length * cos(alpha)
    return total


def _overlap(start, end, s0, s1):
    """Length of [start, end] ∩ [s0, s1] (0 if they do not meet)."""
    from ropemodel._math import fmax, fmin

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
    L_1 + … + L_{j-1} < x <= L_1 + … + L_j; x <= L_1 gives the first, x beyond the route the last."""
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
