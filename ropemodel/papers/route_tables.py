"""The route step: a route of n straight segments reduced once to tables (O(n)), then each place of the load to a
few numbers read from them (O(log n) work, O(1) expression size).  ropemodel's extension of Krauze et al. (2025),
whose route is one straight incline (eq. (1)-(13)); docs/physics.md §4 derives the tension along a side.

Conventions as :mod:`ropemodel.papers.route`: segments i = 1…n listed from the drive (x = 0) to the return
sheave (x = L_u), lengths L_i [m], inclinations α_i [rad] (> 0 rising toward the drive), the winding rope's
resistance μ_i [-] per segment and the unwinding rope's μ_pl [-], the haulage's acceleration a_h [m/s²] in its
direction of travel.  ``way`` "up" is s = +1 (hauling up), "down" s = −1 (lowering).  A rise G [m] is per unit
rope weight: the tension there is F_end + q_l G.

Everything works on numpy arrays (floats) and on CasADi MX columns (the route's values as vectors of symbols);
the two give the same numbers to rounding.  The rises are the cumulative sum of the combined L_i g_i per
segment, in the order :func:`ropemodel.papers.route.tension_at_joints` adds them: on the 10 000-point profile of
``studies/route_scale.py`` they equal its loop bit for bit, where sums of L sin α and L μ cos α taken apart and
combined afterwards do not (3-6e-15 of the rises there).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ropemodel._math import fmin, if_else
from ropemodel.papers.route import G_N

#: the two directions of travel: name, s
WAYS = (("up", 1.0), ("down", -1.0))


def _symbolic(*items) -> bool:
    return any(isinstance(a, (ca.SX, ca.MX, ca.DM)) for a in items)


def _suffix_sums(v):
    """[Σ_{i>=1} v_i, Σ_{i>=2} v_i, …, v_n, 0]: sums toward the return sheave, added from its end."""
    if isinstance(v, np.ndarray):
        return np.concatenate([np.cumsum(v[::-1])[::-1], [0.0]])
    return ca.densify(ca.vertcat(_reversed(ca.cumsum(_reversed(v))), 0.0))


def _running_min(v):
    """[min(v_1), min(v_1, v_2), …, min(v_1…v_m)] of a column (numpy or MX, m >= 1)."""
    if isinstance(v, np.ndarray):
        return np.minimum.accumulate(v)
    a, b = ca.SX.sym("a"), ca.SX.sym("b")
    step = ca.Function("fmin", [a, b], [ca.fmin(a, b)]).mapaccum("running_min", v.numel())
    return ca.densify(step(v[0], v.T).T)


def _reversed(v):
    """v in reverse order (an MX column of one entry too, where CasADi's slice [::-1] refuses)."""
    return v[::-1] if isinstance(v, np.ndarray) else v[list(range(v.shape[0] - 1, -1, -1))]


def tables(L, alpha, mu, mu_pl, a_h):
    """The route's tables, once per route and acceleration a_h (a dict; numpy arrays, or MX columns where any
    argument is CasADi).  L, alpha, mu: one entry per segment (n >= 1); mu_pl, a_h: scalars.

    * ``ends`` [m], n: the joints' distances from the drive x_k = L_1 + … + L_k; ``L_u`` = x_n [m];
    * ``sin``, ``cos`` [-], n: sin α_i, cos α_i (eq. (1), (5), (7) on the load's segment);
    * ``sum_sin``, ``sum_mucos``, ``sum_cos`` [m]: Σ L_i sin α_i, Σ μ_i L_i cos α_i, Σ L_i cos α_i, the route
      sums per unit rope weight of eq. (2)/(6), (8)-(10) and (11) (times μ_pl);
    * per way (``up``: s = +1, ``down``: s = −1) [ropemodel's extension, docs/physics.md §4]:

      - ``g_<way>`` [-], n: the winding side's gradients g_i = sin α_i + s (μ_i cos α_i + a_h/g)
        (:func:`ropemodel.papers.route.rope_gradient`);
      - ``G_<way>`` [m], n + 1: its rises G_k = Σ_{i>k} L_i g_i, k = 0…n (G_n = 0, the return sheave; G_0 the
        drum, eq. (13) with one segment): the cumulative sum of L_i g_i from the return sheave;
      - ``P_<way>`` [m], n: P_k = min(G_1 … G_k), k = 1…n, the least rise from the drive's end (P_n includes
        the return sheave's G_n = 0);
      - ``Q_<way>`` [m], n − 1: Q_k = min(G_k … G_{n−1}), k = 1…n−1, the least rise of the inner joints from
        the return sheave's end (empty for one segment);
      - ``S_<way>`` [m]: the unwinding side's least rise between its ends, min(H_1 … H_{n−1}) with
        H_k = Σ_{i>k} L_i (sin α_i − s (μ_pl cos α_i + a_h/g)) (eq. (12) at the drum); for one segment, which
        has no joint between its ends, min(H_0, H_1) as
        :func:`ropemodel.papers.route.least_rope_tension` takes it.

    Examples
    --------
    Fig. 9 (Krauze et al. 2025): one 1150 m segment at 16°, μ = 0.05; hauled up in steady motion the winding
    rope rises q_l G_0 = 80 · 1150 (sin 16° + 0.05 cos 16°) = 29.7804 kN (eq. (2), (8)):

    >>> import math
    >>> t = tables([1150.0], [math.radians(16.0)], [0.05], 0.05, 0.0)
    >>> round(80.0 * float(t["G_up"][0]) / 1e3, 4)
    29.7804
    """
    if _symbolic(L, alpha, mu, mu_pl, a_h):
        L, alpha, mu = (ca.MX(ca.vertcat(*v)) if isinstance(v, (list, tuple)) else ca.MX(v) for v in (L, alpha, mu))
        sin, cos, total = ca.sin, ca.cos, ca.sum1
        least = ca.mmin
    else:
        L, alpha, mu = (np.asarray(v, dtype=float).ravel() for v in (L, alpha, mu))
        sin, cos, total, least = np.sin, np.cos, np.sum, np.min
    n = L.shape[0]
    s_a, c_a = sin(alpha), cos(alpha)
    ends = np.cumsum(L) if isinstance(L, np.ndarray) else ca.cumsum(L)
    out = {"ends": ends, "L_u": ends[n - 1], "sin": s_a, "cos": c_a,
           "sum_sin": total(L * s_a), "sum_mucos": total(mu * L * c_a), "sum_cos": total(L * c_a)}
    for way, s in WAYS:
        g = s_a + s * (mu * c_a + a_h / G_N)
        G = _suffix_sums(L * g)
        H = _suffix_sums(L * (s_a - s * (mu_pl * c_a + a_h / G_N)))
        out[f"g_{way}"], out[f"G_{way}"] = g, G
        out[f"P_{way}"] = _running_min(G[1:])
        out[f"Q_{way}"] = _reversed(_running_min(_reversed(G[1:n]))) if n > 1 else G[1:n]
        out[f"S_{way}"] = least(H[1:n]) if n > 1 else least(H)
    return out


def _joints_before(inner, x):
    """How many inner joints lie strictly before x [m] (the load's segment, 0-based: a load on a joint belongs
    to the segment nearer the drive); ``inner`` ascending, a numpy array with x numeric, else an MX column."""
    if isinstance(inner, np.ndarray):
        return np.searchsorted(inner, x, side="left")
    m = inner.numel()
    if m == 0:                                   # one segment: the load is on it (x is an MX column here)
        return ca.densify(ca.MX.zeros(x.shape))
    # count(inner >= x) = count(h <= −x) with h = −inner reversed, ascending (negation is exact: ties hold);
    # ca.low(h, v) is the i with h_i <= v < h_{i+1}, clamped to 0 … m − 2
    h, v = -_reversed(inner), -x
    at_or_beyond = ca.if_else(v < h[0], 0, ca.if_else(v >= h[m - 1], m, ca.low(h, v) + 1))
    return m - at_or_beyond


def at_places(table, x_m):
    """The route's numbers at the load's places x_m [m] (a number, a numpy array, or an MX column), from
    :func:`tables` (a dict: numpy arrays or MX entries alike).  A place beyond the route is at the return sheave
    (x = min(x_m, L_u)); its segment j is the one containing it, a joint belonging to the segment nearer the
    drive (as :func:`ropemodel.papers.route.at_position`).

    * ``j`` [-]: the load's segment, 0-based; ``x`` [m] the place on the route;
    * ``sin``, ``cos`` [-]: sin α_j, cos α_j (eq. (1), (5), (7) on the load's segment);
    * ``joints``: 1 where the route has a joint between its ends (n > 1), else 0 (then P, Q are inert);
      ``before``: 1 where an inner joint lies before the load (x_k < x), ``beyond``: 1 where one lies at or
      beyond it; ``inside0``: 1 where x > 0 (not at the drive), ``insideL``: 1 where x < L_u;
    * per way [m] (ropemodel's extension, docs/physics.md §4): ``P_<way>`` the least winding rise of the inner
      joints before the load, min(G_1 … G_j); ``Q_<way>`` that of the inner joints at or beyond it,
      min(G_{j+1} … G_{n−1}); ``B_<way>`` the rise beside the load G(x) = G_{j+1} + g_j (x_{j+1} − x).
      A set without joints reads its neighbour's entry: the flags say which hold.
    """
    if _symbolic(x_m) and isinstance(table["ends"], np.ndarray):
        table = {k: ca.MX(ca.DM(v)) for k, v in table.items()}
    ends, L_u = table["ends"], table["L_u"]
    n = ends.shape[0]
    x = fmin(x_m, L_u)
    j = _joints_before(ends[: n - 1], x)
    low, high = (np.maximum, np.minimum) if isinstance(ends, np.ndarray) else (ca.fmax, ca.fmin)
    out = {"j": j, "x": x, "sin": table["sin"][j], "cos": table["cos"][j], "joints": float(n > 1) + 0.0 * x,
           "before": j >= 1, "beyond": j <= n - 2, "inside0": x > 0.0, "insideL": x < L_u}
    lo, hi = low(j - 1, 0), high(j, max(n - 2, 0))
    for way, _ in WAYS:
        Q = table[f"Q_{way}"] if n > 1 else table[f"P_{way}"]
        out[f"P_{way}"] = table[f"P_{way}"][lo]
        out[f"Q_{way}"] = Q[hi]
        out[f"B_{way}"] = table[f"G_{way}"][j + 1] + table[f"g_{way}"][j] * (ends[j] - x)
    return out


def least_winding_tension(place, way, F_end, q_l, load):
    """The winding side's least tension between its ends [N] (:func:`ropemodel.papers.route.least_rope_tension`)
    from the numbers of :func:`at_places`: with F_end = F_nwl/2 [N], q_l >= 0 [N/m] and the load's pull J =
    ``load`` [N] (:func:`ropemodel.papers.route.load_pull`), the least of F_end + q_l P + J and F_end + q_l Q
    over the inner joints (before, beyond the load) and of F_end + q_l B (+ J before the load) beside it."""
    loaded, free = F_end + q_l * place[f"P_{way}"] + load, F_end + q_l * place[f"Q_{way}"]
    joints = fmin(if_else(place["before"], loaded, free), if_else(place["beyond"], free, loaded))
    beside = F_end + q_l * place[f"B_{way}"]
    sides = fmin(if_else(place["inside0"], beside + load, beside), if_else(place["insideL"], beside, beside + load))
    return if_else(place["joints"], fmin(joints, sides), sides)


def tables_function(n: int) -> ca.Function:
    """:func:`tables` of a route of ``n`` segments as a CasADi Function ``route_tables``: inputs ``L``, ``alpha``,
    ``mu`` (n each), ``mu_pl``, ``a_h``; outputs named as :func:`tables`' entries (built once per route shape,
    evaluated once per route's values and acceleration)."""
    ins = {"L": ca.MX.sym("L", n), "alpha": ca.MX.sym("alpha", n), "mu": ca.MX.sym("mu", n),
           "mu_pl": ca.MX.sym("mu_pl"), "a_h": ca.MX.sym("a_h")}
    out = tables(*ins.values())
    return ca.Function("route_tables", list(ins.values()), list(out.values()), list(ins), list(out))


def places_function(n: int, places: int) -> ca.Function:
    """:func:`at_places` for a route of ``n`` segments at ``places`` places as a CasADi Function ``route_places``:
    inputs the entries of :func:`tables`, named ``t_<entry>`` (the tables passed by reference), and ``x_m`` (a
    column of ``places``); outputs named as :func:`at_places`' entries, each a column of ``places``."""
    shapes = tables_function(n)
    ins = {k: ca.MX.sym("t_" + k, shapes.size_out(k)) for k in shapes.name_out()}
    x = ca.MX.sym("x_m", places)
    out = {k: ca.MX(v) for k, v in at_places(ins, x).items()}
    values = [ca.densify(ca.repmat(v, places, 1) if v.numel() == 1 else v) for v in out.values()]
    return ca.Function("route_places", [*ins.values(), x], values, ["t_" + k for k in ins] + ["x_m"], list(out))
