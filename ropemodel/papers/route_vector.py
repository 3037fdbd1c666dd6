"""The tension along a route's rope sides as vector operations (CasADi columns), for long routes: the sums and
minima over the segments in a few operations, with the rope's weight q_l and the tension F_end at the return
sheave outside them, so that where the route's values are known (the scene's, folded in) each is one number and
the model's size in q_l and F_end (what sizing varies) does not grow with the segments.  The functions of
:mod:`ropemodel.papers.route` call these on symbols; docs/physics.md §4 derives the forms.
"""

from __future__ import annotations

import threading

import casadi as ca


def _sum(column, start=0.0):
    """start + column[0] + column[1] + …, added in that order."""
    return start + ca.sum1(column) if column.numel() else start


#: the columns last made of a route's lists (and their cumulative sums), by the list's identity, each with its
#: list: a model's equations take the same segments' lists many times, and a column of 10 000 symbols costs
#: milliseconds each time it is made (the lists of a model's segments are made once: its submodel's ``profile``)
_MADE: dict[tuple[int, str], tuple] = {}
#: how many are kept
_KEEP = 16
_LOCK = threading.Lock()


def _made(items, kind: str, make):
    """``make()`` for the list ``items``, made once while it is among the last :data:`_KEEP` (by identity), where
    every entry is a CasADi expression (a list of numbers may be changed in place: made each time)."""
    if not all(isinstance(e, ca.SX) for e in items):
        return make()
    hit = _MADE.get((id(items), kind))
    if hit is None or hit[0] is not items:
        hit = (items, make())
        with _LOCK:
            if len(_MADE) >= _KEEP:
                _MADE.pop(next(iter(_MADE)), None)
            _MADE[(id(items), kind)] = hit
    return hit[1]


def column(items):
    """A CasADi column of ``items`` (a list or a column)."""
    if isinstance(items, (ca.SX, ca.MX, ca.DM)):
        return items
    return _made(items, "column", lambda: ca.vertcat(*items)) if isinstance(items, list) else ca.vertcat(*items)


def ends(lengths):
    """[x_1, …, x_n] (a CasADi column): the joints' distances from the drive, L_1 + … + L_k."""
    if isinstance(lengths, list):
        return _made(lengths, "ends", lambda: ca.cumsum(column(lengths)))
    return ca.cumsum(column(lengths))


def rises(lengths, gradients):
    """[G_0, …, G_n] (a CasADi column): G_k = Σ_{i>k} L_i g_i, the rise per unit rope weight from the return
    sheave to joint k (G_n = 0); the tension there is F_end + q_l G_k."""
    L, g = column(lengths), column(gradients)
    return ca.vertcat(ca.cumsum((L * g)[::-1])[::-1], 0.0)


def rise_at(x, lengths, gradients):
    """G(x) = Σ_i g_i ℓ_i(x) (a CasADi scalar): the rise per unit rope weight from the return sheave to x, ℓ_i(x)
    the part of segment i between x and the return sheave."""
    L, g, at = column(lengths), column(gradients), ends(lengths)
    L_u = at[-1]
    return _sum(g * ca.fmax(ca.fmin(at, L_u) - ca.fmax(at - L, x), 0.0))


def least_tension(F_end, q_l, lengths, gradients, x_m, load):
    """:func:`ropemodel.papers.route.least_rope_tension` between the side's ends (two segments or more) as vector
    operations, for q_l >= 0 (a rope's weight): the least over the joints is F_end + q_l min_k G_k
    (:func:`rises`), and on the loaded side the least of F_end + q_l P + J and F_end + q_l Q, with P, Q
    the least G_k of the joints before and beyond the load.  Rounding is monotone, so
    each equals the least of the terms of the loop to the last bit; the rope's weight and the pretension enter
    in a few operations whatever the number of joints (the route's minima fold into numbers where its values are
    known, as in sizing)."""
    inner = rises(lengths, gradients)[1:-1]          # G_1 … G_{n−1}, the joints between the ends
    if x_m is None:
        return F_end + q_l * ca.mmin(inner)
    joints = ends(lengths)
    L_u = joints[-1]
    x_m = ca.fmin(x_m, L_u)
    at = joints[:-1]                                   # x_1 … x_{n−1}
    top = ca.mmax(inner)                               # fills the joints not in a set: at least each of its own
    before, beyond = at < x_m, at >= x_m
    P = ca.mmin(ca.if_else(before, inner, top))
    Q = ca.mmin(ca.if_else(beyond, inner, top))
    loaded, free = F_end + q_l * P + load, F_end + q_l * Q
    # a set without joints takes the other's term (both are never empty: there is a joint between the ends)
    joints = ca.fmin(ca.if_else(before[0], loaded, free), ca.if_else(beyond[-1], free, loaded))
    beside = F_end + q_l * rise_at(x_m, lengths, gradients)        # the tension beside the load
    return ca.fmin(joints, ca.fmin(ca.if_else(x_m > 0.0, beside + load, beside),
                                   ca.if_else(x_m < L_u, beside, beside + load)))
