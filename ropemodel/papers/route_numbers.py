"""A route of n straight segments reduced, for each load case, to a few numbers that enter the model's equations
linearly in μ_pl, a_h, x_m and L_ul: ropemodel's extension of Krauze et al. (2025), whose route is one straight
incline (eq. (1)-(13)); docs/physics.md §4 derives the tension along a rope side.

Conventions as :mod:`ropemodel.papers.route`: segments i = 1…n from the drive (x = 0) to the return sheave
(x = L_u), lengths L_i [m], inclinations α_i [rad], the winding rope's coefficient μ_i [-] of the segments that
give their own (``own``), μ_pl [-] on the others.  Numbers only (numpy).

The rise of the winding side from the return sheave to joint k, per unit rope weight, is
G_k = A_k + s (M_k + μ_pl C'_k) + s (a_h/g) X_k with the suffix sums (over i > k)

* A_k = Σ L_i sin α_i, M_k = Σ_own μ_i L_i cos α_i, C'_k = Σ_plain L_i cos α_i, C_k = Σ L_i cos α_i,
  X_k = Σ L_i = L_u − x_k;

and that of the unwinding side H_k = A_k − s μ_pl C_k − s (a_h/g) X_k (s = +1 hauling up, −1 lowering).  A least
tension over joints is F_end + q_l min_k G_k: the index of the least is found here at the case's numbers and its
coefficients (A_k, M_k, C'_k, X_k) are handed to the model, which forms the least rise in its own symbols, so its
value and its derivatives in μ_pl, a_h (and what they are made of) are those of the loop's away from ties.
"""

from __future__ import annotations

import numpy as np

from ropemodel.papers.route import G_N

#: the two directions of travel: name, s
WAYS = (("up", 1.0), ("down", -1.0))
#: the coefficients of a winding rise (A, M, C', X) and of an unwinding rise (A, C, X)
WINDING = ("A", "mo", "cp", "X")
UNWINDING = ("A", "C", "X")


def _suffix(v: np.ndarray) -> np.ndarray:
    """[Σ_{i>=1} v_i, …, v_n, 0]: sums toward the return sheave, k = 0…n."""
    return np.concatenate([np.cumsum(v[::-1])[::-1], [0.0]])


def route_sums(L, alpha, mu, own) -> dict:
    """The route's suffix sums at every joint k = 0…n (``A``, ``mo``, ``cp``, ``C``, ``X``, each n + 1), the
    joints' distances ``ends`` (n) from the drive, ``sin``, ``cos``, ``mo_i`` = μ_i cos α_i on the segments that
    give μ_i (else 0) and ``cp_i`` = cos α_i on the others (else 0).  Once per route."""
    L, alpha, mu = (np.asarray(v, dtype=float).ravel() for v in (L, alpha, mu))
    own = np.asarray(own, dtype=bool).ravel()
    s, c = np.sin(alpha), np.cos(alpha)
    mo_i, cp_i = np.where(own, mu * c, 0.0), np.where(own, 0.0, c)
    return {"ends": np.cumsum(L), "sin": s, "cos": c, "mo_i": mo_i, "cp_i": cp_i, "A": _suffix(L * s),
            "mo": _suffix(L * mo_i), "cp": _suffix(L * cp_i), "C": _suffix(L * c), "X": _suffix(L)}


def rises(sums: dict, s: float, a_h: float, mu_pl: float) -> tuple[np.ndarray, np.ndarray]:
    """The winding and the unwinding side's rises G_k, H_k [m] at every joint k = 0…n (n + 1 each; 0 at the return
    sheave), from :func:`route_sums`, for the direction s (+1 hauling up, −1 lowering), a_h [m/s²] and μ_pl [-]:
    the tension at joint k is F_end + q_l G_k (without the load) and F_end + q_l H_k."""
    G = sums["A"] + s * (sums["mo"] + mu_pl * sums["cp"]) + s * (a_h / G_N) * sums["X"]
    H = sums["A"] - s * mu_pl * sums["C"] - s * (a_h / G_N) * sums["X"]
    return G, H


def _running_arg(v: np.ndarray) -> np.ndarray:
    """For each k, an index i <= k with v_i = min(v_0 … v_k) (numpy, len(v) >= 1)."""
    least = np.minimum.accumulate(v)
    return np.maximum.accumulate(np.where(v == least, np.arange(v.size), 0))


def places(sums: dict, x_m, a_h: float, mu_pl: float) -> dict:
    """The numbers at the load's places ``x_m`` [m] (an array) for one acceleration a_h [m/s²] and μ_pl [-]:

    * ``j`` the load's segment (0-based; a place on a joint belongs to the segment nearer the drive, beyond the
      route: the last), ``sin_j``, ``cos_j``, ``mo_j``, ``cp_j`` its sin α_j, cos α_j and coefficients;
    * ``B_A``, ``B_mo``, ``B_cp`` [m]: the winding rise beside the load at x is (B_A − sin_j x) + s ((B_mo −
      mo_j x) + μ_pl (B_cp − cp_j x)) + s (a_h/g)(L_u − x): A_{j+1} + sin_j x_{j+1} and the like;
    * ``before``, ``beyond``: 1 where an inner joint lies before the load, at or beyond it;
    * per way: ``P_<c>_<way>``, ``Q_<c>_<way>`` (c in :data:`WINDING`) the coefficients of the least winding rise
      of the inner joints before the load (G_1 … G_j) and at or beyond it (G_{j+1} … G_{n−1}); ``S_<c>_<way>`` (c
      in :data:`UNWINDING`) those of the unwinding side's least between its ends (H_1 … H_{n−1}; one segment:
      H_0, H_1), and ``kP_<way>``, ``kQ_<way>``, ``kS_<way>`` the joints they are at.  A set without joints reads
      a neighbour's entry: the flags say which hold."""
    ends = sums["ends"]
    n = ends.size
    x = np.minimum(np.asarray(x_m, dtype=float), ends[-1])
    j = np.searchsorted(ends[: n - 1], x, side="left")
    nxt = j + 1
    out = {"j": j, "sin_j": sums["sin"][j], "cos_j": sums["cos"][j], "mo_j": sums["mo_i"][j],
           "cp_j": sums["cp_i"][j], "B_A": sums["A"][nxt] + sums["sin"][j] * ends[j],
           "B_mo": sums["mo"][nxt] + sums["mo_i"][j] * ends[j], "B_cp": sums["cp"][nxt] + sums["cp_i"][j] * ends[j],
           "before": (j >= 1).astype(float), "beyond": (j <= n - 2).astype(float)}
    lo, hi = np.maximum(j - 1, 0), np.minimum(j, max(n - 2, 0))
    k = np.arange(n + 1)
    for way, s in WAYS:
        G, H = rises(sums, s, a_h, mu_pl)
        at_P = k[1:][_running_arg(G[1:])][lo]          # G_1 … G_{max(j, 1)}
        if n > 1:                                        # G_{j+1} … G_{n−1}, from the return sheave's end
            inner = k[1:n]
            at_Q = inner[::-1][_running_arg(G[1:n][::-1])][::-1][hi]
        else:
            at_Q = at_P
        span = k[1:n] if n > 1 else k
        at_S = span[int(np.argmin(H[span]))]
        out[f"kP_{way}"], out[f"kQ_{way}"], out[f"kS_{way}"] = at_P, at_Q, np.full(x.shape, at_S)
        for c in WINDING:
            out[f"P_{c}_{way}"], out[f"Q_{c}_{way}"] = sums[c][at_P], sums[c][at_Q]
        for c in UNWINDING:
            out[f"S_{c}_{way}"] = np.full(x.shape, sums[c][at_S])
    return out


def split_at(sums: dict, at: float) -> dict:
    """Point A at ``at`` [m] from the drive (Krauze et al. 2025, L_ul): the route's sums over [0, A] are
    ``A_sin0`` + ``A_sin1`` A, ``A_mo0`` + ``A_mo1`` A and ``A_cp0`` + ``A_cp1`` A (Σ ℓ_i sin α_i, Σ_own μ_i ℓ_i
    cos α_i, Σ_plain ℓ_i cos α_i over the part ℓ_i of each segment before A; eq. (4), (9) on a route), linear in
    A on A's segment (a point on a joint: the segment nearer the drive)."""
    ends = sums["ends"]
    n = ends.size
    j = int(np.searchsorted(ends[: n - 1], min(float(at), float(ends[-1])), side="left"))
    start = float(ends[j - 1]) if j else 0.0
    out = {"jA": j}
    for key, per in (("sin", "sin"), ("mo", "mo_i"), ("cp", "cp_i")):
        whole = "A" if key == "sin" else key
        before = sums[whole][0] - sums[whole][j]        # the segments wholly before A's
        out[f"A_{key}0"], out[f"A_{key}1"] = before - sums[per][j] * start, sums[per][j]
    return out


def through(L, alpha, mu, own, at: dict, split: int | None = None) -> dict:
    """The numbers of :func:`places` (and of :func:`split_at`, at A's segment ``split``) at one place as CasADi
    expressions of the segments' values ``L``, ``alpha``, ``mu`` (columns), at the indices ``at`` (that place's
    entry of :func:`places`: its segment ``j`` and least joints ``k*``) chosen at their values: equal to the
    numbers there, and their derivatives in the segments' values are those of the loops while the indices hold
    (a sensitivity in a segment's value)."""
    import casadi as ca

    own, zero = ca.DM(np.asarray(own, dtype=float)), type(L)(0.0)     # SX or MX, as the segments' values
    s, c = ca.sin(alpha), ca.cos(alpha)
    per = {"A": L * s, "mo": L * (own * mu * c), "cp": L * ((1.0 - own) * c), "C": L * c, "X": L}
    n = L.shape[0]

    def total(v):
        return ca.sum1(v) if v.numel() else zero

    def suffix(key: str, k: int):
        return total(per[key][k:]) if k < n else zero

    j = int(at["j"])
    end_j = ca.sum1(L[: j + 1])
    mo_j, cp_j = own[j] * mu[j] * c[j], (1.0 - own[j]) * c[j]
    out = {"sin_j": s[j], "cos_j": c[j], "mo_j": mo_j, "cp_j": cp_j, "B_A": suffix("A", j + 1) + s[j] * end_j,
           "B_mo": suffix("mo", j + 1) + mo_j * end_j, "B_cp": suffix("cp", j + 1) + cp_j * end_j,
           "before": zero + float(at["before"]), "beyond": zero + float(at["beyond"])}
    for way, _ in WAYS:
        for c_ in WINDING:
            out[f"P_{c_}_{way}"] = suffix(c_, int(at[f"kP_{way}"]))
            out[f"Q_{c_}_{way}"] = suffix(c_, int(at[f"kQ_{way}"]))
        for c_ in UNWINDING:
            out[f"S_{c_}_{way}"] = suffix(c_, int(at[f"kS_{way}"]))
    if split is not None:
        start = total(L[:split])
        for key, field in (("sin", s), ("mo", own * mu * c), ("cp", (1.0 - own) * c)):
            whole = "A" if key == "sin" else key
            out[f"A_{key}0"] = total(per[whole][:split]) - field[split] * start
            out[f"A_{key}1"] = field[split]
    return out
