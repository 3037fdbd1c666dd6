"""The head ropes of a Koepe hoist cut into Kelvin–Voigt elements, in the steady state the transient starts from.

Floats only (numpy): the mesh is the transient's structure.  Sides: row 0 is side L (the loaded conveyance), row 1
side E (the other); depths are positive downward from the wheel's tangent points; x is the rope run over the
wheel from side L to side E [m] (x > 0: the loaded conveyance rises).  The model (docs/physics.md §7, elastic
ropes):

* each side's n_head ropes are one span of axial stiffness n_head·EA_head, from the tangent point to the
  conveyance, H_head + y long (:func:`ropemodel.papers.koepe.head_rope_length`), cut into N elements;
* the top element is ``2·reel`` longer than the others so that rope may run over the wheel: its unstretched
  length is top ∓ x (the upper sign for side L), the others keep theirs.  Of the top element's rope, top/2 is
  lumped on node 1 and the rest, a column of top ∓ x − top/2, hangs from the tangent point and moves with the
  rope on the wheel, so that every node's mass is constant (the column used up is an error);
* the rope's mass q = n_head q_head per metre, lumped half of each element on each end; node N is the conveyance;
* the elongations e0 balance the weights below each element in steady motion at speed v0, with the tail loop's
  pull ρ (g ℓ_t + v0²) (ρ = n_tail q_tail; :mod:`.ropes`) and the shaft resistance on the loaded conveyance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ropemodel.errors import InputError
from ropemodel.papers.route import G_N

#: side L shortens as x grows, side E lengthens
SGN = (-1.0, 1.0)


@dataclass(frozen=True)
class KoepeMesh:
    """The elements [SI]: per side the top element's initial length ``top``, the others' ``delta``, every length
    ``lengths`` (2 × N), node masses ``m`` (node N the conveyance), steady elongations ``e0`` and depths ``z0``;
    the tail loop's length ``L_t`` and mass per metre ``rho``; the head ropes' q and n·EA; ``reel``."""

    N: int
    top: np.ndarray
    delta: np.ndarray
    lengths: np.ndarray
    m: np.ndarray
    e0: np.ndarray
    z0: np.ndarray
    L_t: float
    rho: float
    q: float
    nEA: float
    reel: float

    def column(self, side: int, x):
        """Length [m] of the column hanging from the tangent point of ``side`` after a run x: top ∓ x − top/2."""
        return self.top[side] / 2 + SGN[side] * x


def spans(p: dict, y_L: float) -> np.ndarray:
    """The head-rope spans (L, E) [m] with the loaded conveyance at depth y_L: H_head + y."""
    return np.array([p["H_head"] + y_L, p["H_head"] + p["H"] - y_L])


def fits(span: float, reel: float, N: int) -> bool:
    """Whether a span leaves rope for its N − 1 lower elements after a top element 2·reel longer (a span of one
    element always fits: its column is checked during the run)."""
    return N == 1 or span / N + 2 * reel < span


def element_lengths(p: dict, y_L: float, N: int, reel: float, grows: int = -1):
    """(top, delta, lengths): the top element span/N + 2·reel (at most the span), the others sharing the rest.

    The span that lengthens in the manoeuvre (``grows``: 0 side L, 1 side E, −1 neither) keeps a top element of
    span/N where 2·reel more does not fit: its column only grows (span/(2N) is left for a run back)."""
    sp = spans(p, y_L)
    reels = np.array([0.0 if k == grows and not fits(s, reel, N) else reel for k, s in enumerate(sp)])
    bad = [f"the {side} head-rope span ({s:.4g} m) is too short for {N} elements and {reel:.4g} m of rope run over "
           f"the wheel (the nominal manoeuvre's run and a margin): start the conveyance further from the end of the "
           f"wind (y_start), shorten t_end, brake harder, or fewer [numerics] segments"
           for side, s, r in zip(("loaded side's", "other side's"), sp, reels) if not fits(s, r, N)]
    if bad:
        raise InputError(problems=bad)
    top = np.minimum(sp / N + 2 * reels, sp)
    delta = (sp - top) / max(N - 1, 1)
    lengths = np.hstack([top[:, None], np.repeat(delta[:, None], N - 1, axis=1)])
    return top, delta, lengths


def build_mesh(p: dict, y_L: float, v0: float, reel: float, N: int, resistance: float = 0.0,
               grows: int = -1) -> KoepeMesh:
    """The mesh in steady motion at v0 [m/s] (+: hoisting) with the loaded conveyance at depth y_L [m].

    p: SI floats H, H_head, m_conveyance, m_payload, n_head, q_head, EA_head, n_tail, q_tail, h_loop;
    resistance [N]: the shaft resistance's force on the loaded conveyance in that motion, + downward (it pulls
    against a rising conveyance).  The tail loop's side lengths depend on the stretched depths, so the steady
    elongations are iterated to a fixed point (a contraction of ratio ρ g/k: converged to 1e-13 of the depth).
    """
    top, delta, lengths = element_lengths(p, y_L, N, reel, grows)
    q, nEA = p["n_head"] * p["q_head"], p["n_head"] * p["EA_head"]
    m = q * (lengths + np.hstack([lengths[:, 1:], np.zeros((2, 1))])) / 2
    m[:, -1] += p["m_conveyance"]
    m[0, -1] += p["m_payload"]
    rho, L_t = p["n_tail"] * p["q_tail"], p["H"] + 2 * p["h_loop"]
    k = nEA / lengths
    z_N = spans(p, y_L)
    below = np.cumsum((m * G_N)[:, ::-1], axis=1)[:, ::-1]
    below[0] += resistance
    for _ in range(100):
        l_t = (z_N[::-1] - z_N + L_t) / 2
        F = below + (rho * (G_N * l_t + v0 ** 2))[:, None]
        e0 = F / k
        z0 = np.cumsum(lengths + e0, axis=1)
        if np.allclose(z0[:, -1], z_N, rtol=0.0, atol=1e-13 * z_N.max()):
            break
        z_N = z0[:, -1]
    return KoepeMesh(N, top, delta, lengths, m, e0, z0, float(L_t), float(rho), float(q), float(nEA), float(reel))


def reel_for(travel: float) -> float:
    """Rope the mesh lets run over the wheel for a manoeuvre that nominally runs ``travel`` [m]: 5 % and 0.5 m
    more, for the ropes' stretch and a slip (the run beyond it stops the simulation with an error)."""
    return 1.05 * abs(travel) + 0.5


def least_span(reel: float, N: int) -> float:
    """The shortest span [m] that :func:`fits` a top element 2·reel longer, with its lower elements at least
    1 m long (so that the stiffest element stays within a factor of span/N of the others)."""
    if N == 1:
        return 2 * reel + 1.0
    return (2 * reel + (N - 1)) * N / (N - 1)
