"""The places of the load that can govern, found without the model: a route of n segments in O(n log n).

:func:`ropemodel.envelope.cases.load_cases` lists n + 1 places per manoeuvre, and an NLP that checks every
output at every one of them grows as O(n²) (each case is a copy of a model whose size grows with n).  The
place enters the winch's equations in two ways only (docs/physics.md §4, "Where the load governs"):

* the forces at the drum, the powers and every margin made of them depend on the place only through the
  load's pull J_p = G_m (sin α_j + s (μ_pm cos α_j + a/g)) on its segment j, and each grows with J_p: their
  worst is at the place of the largest or the least J_p, per direction s and acceleration a;
* the least tension of the winding rope between its ends
  (:func:`ropemodel.papers.route.least_rope_tension`, ``between=True``) with the load at the end x_p of its
  segment is F_nwl/2 + min(J_p + q_l A_p, q_l B_p), with G_k = Σ_{i>k}
  L_i g_i the rise of the unloaded side from the return sheave to joint k (g_i :func:`rope_gradient`),
  A_p = min_{1<=k<=p} G_k and B_p = min_{p<=k<n} G_k (G_k from the route's sums,
  :func:`ropemodel.papers.route_numbers.rises`, and A_p their running minimum).  B_p is least at the
  drive (p = 0) whatever q_l; the least of J_p + q_l A_p over p, for any q_l > 0, is at a vertex of the lower
  convex hull of the points (A_p, J_p) between the least A and the least J (a supporting line of slope −q_l).
  The least over the whole side adds the drum's force (the case above) and F_nwl/2 (the same at every place).

The places kept (for every direction and manoeuvre of the cases) are these, and the route's two ends.  None
of them depends on q_l or F_nwl, so the pruned list holds for every rope and pretension a sizing tries; it
does depend on G_m, μ_pm, the route and the resistances, so a sweep that varies those must not prune.  A
scene whose effects read the place otherwise (the as-built elongation: the load's pull times x_m) is not
pruned (:func:`prunable`).  ``run`` and ``size`` evaluate the kept places only: at n places the whole model,
whose size grows with n, would cost O(n²).
"""

from __future__ import annotations

import numpy as np

from ropemodel.effects.route_arrays import RouteArrays
from ropemodel.envelope.cases import LoadCase
from ropemodel.papers import route_numbers as rn
from ropemodel.papers.route import G_N

#: below this many places, every place is kept (nothing to gain)
MIN_PLACES = 8


def governing_places(params, accelerations, weights=(0.0, np.inf)) -> set[int]:
    """Joints (0 = the drive, k = the end of segment k) where the load can govern, for each acceleration a
    [m/s²] in ``accelerations`` and both directions (see the module docstring), for every rope weight q_l in
    ``weights`` [N/m] (low, high; default every q_l > 0).  ``params``: SI floats."""
    segments = RouteArrays.from_values(params)
    n = segments.n
    seg = np.concatenate([[0], np.arange(n)])          # the load's segment at each place (0-based)
    keep = {0, n}
    sums = rn.route_sums(segments.L, segments.alpha, segments.mu_w, segments.own_mu)
    for a in accelerations:
        for _, s in rn.WAYS:
            J = params["G_m"] * (sums["sin"] + s * (params["mu_pm"] * sums["cos"] + a / G_N))[seg]
            keep |= {int(np.argmax(J)), int(np.argmin(J))}
            G = rn.rises(sums, s, a, params["mu_pl"])[0]
            A = np.concatenate([[np.inf], np.minimum.accumulate(G[1:])])  # A_0 = ∞: no loaded term at the drive
            keep |= _hull_toward_least(A, J, *weights)
    return keep


def _hull_toward_least(A: np.ndarray, J: np.ndarray, low: float = 0.0, high: float = np.inf) -> set[int]:
    """Indices p minimising J_p + q A_p for some q in [low, high], q > 0: vertices of the lower convex hull of the
    points (A_p, J_p) (Andrew's monotone chain).  Vertex k of the hull, in order of A, is least for the q between
    minus the slopes of its edges, −s_k <= q <= −s_{k−1} (s_{−1} = −∞ toward the least A, s_last = +∞)."""
    idx = [int(i) for i in np.lexsort((J, A)) if np.isfinite(A[i])]
    hull: list[int] = []
    for i in idx:
        while len(hull) >= 2 and _cross(A, J, hull[-2], hull[-1], i) <= 0.0:
            hull.pop()
        hull.append(i)
    slopes = [_slope(A, J, a, b) for a, b in zip(hull, hull[1:])]
    out = set()
    for k, i in enumerate(hull):
        most = -slopes[k - 1] if k else np.inf                      # the largest q it is least for
        least = -slopes[k] if k < len(slopes) else -np.inf          # the smallest
        if most > 0.0 and most >= low and least <= high:
            out.add(i)
    return out


def _slope(A, J, a: int, b: int) -> float:
    """The slope of the hull's edge from a to b (A[b] >= A[a]); +∞ where it is vertical."""
    dA = float(A[b] - A[a])
    return float(J[b] - J[a]) / dA if dA > 0.0 else np.inf


def _cross(x, y, o, a, b) -> float:
    return float((x[a] - x[o]) * (y[b] - y[o]) - (y[a] - y[o]) * (x[b] - x[o]))


def prunable(model) -> bool:
    """Whether every submodel of ``model`` reads the load's place only through its pull and the least tension
    (:attr:`ropemodel.effects.base.Submodel.place_through_pull`): only then do the kept places hold every
    worst case."""
    return all(sm.place_through_pull for sm in model.submodels)


def prune(cases: list[LoadCase], params, model, weights=(0.0, np.inf)) -> list[LoadCase]:
    """``cases`` at the places that can govern only (:func:`governing_places`, for every rope weight q_l in
    ``weights`` [N/m]); ``cases`` as they are when the place is pinned, there are few places, or a submodel of
    ``model`` reads the place otherwise (:func:`prunable`)."""
    places = {c.joint for c in cases}
    if None in places or len(places) < MIN_PLACES or not prunable(model):
        return cases
    one_per_manoeuvre = {c.manoeuvre: c for c in cases}.values()
    accelerations = {float(c.values(params).get("a_h", params.get("a_h", 0.0))) for c in one_per_manoeuvre}
    keep = governing_places(params, sorted(accelerations), weights)
    return [c for c in cases if c.joint in keep]
