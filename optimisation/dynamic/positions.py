"""Where the load is when a manoeuvre happens: the candidate positions along the route.

A winch starts and stops with the load anywhere on its route, not only at the ends of a trip: a
restart after a stop on the steepest segment is often the hardest start.  The transient freezes the
spans over a manoeuvre (:mod:`ropemodel.effects.transient.chain`), so a position is a place x_m [m from
the drive] and the segment whose inclination the load has there.  The candidates
(:func:`candidates`) are, on every segment, its end nearer the drive, its middle and its far end:

* the natural ends of a trip, x_m = 0 (at the drive) and x_m = L_u (at the return sheave), are the first
  segment's near end and the last one's far end;
* a joint is taken from both sides: the load on the drive-side segment at the joint itself (where the
  route puts a load on a joint, :func:`ropemodel.papers.route.at_position`) and the load on the far
  segment :data:`JOINT_STEP` beyond it;
* the middle, where the spans to the drive and to the return sheave are between their extremes.

The peak forces of a manoeuvre change with x_m within a segment through the spans' stiffness (the
span from the drive to the load is EA/x_m stiff) and jump at a joint with the load's inclination; the
three places per segment bound the first and catch the second.  A straight route is one segment.  A
scene that gives ``x_m`` pins every manoeuvre there (the designer's own question).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: how far beyond a joint [m] the load is put to be on the far segment (a load on a joint belongs to the
#: segment nearer the drive); 1 mm changes the spans by a part in 10^5 of a route of 100 m or more
JOINT_STEP = 1e-3


@dataclass(frozen=True)
class Position:
    """A place of the load: ``x_m`` [m from the drive], its ``segment`` (1 = at the drive) and ``text``
    (which place it is, for the output)."""

    x_m: float
    segment: int
    text: str

    @property
    def shown(self) -> str:
        """x_m [m] to the millimetre (a place beyond a joint differs from it by :data:`JOINT_STEP`)."""
        return f"{self.x_m:.3f}".rstrip("0").rstrip(".")

    @property
    def where(self) -> str:
        return f"x_m = {self.shown} m ({self.text})"


def segment_lengths(scene) -> list[float]:
    """The route's segment lengths [m] from the drive: ``L_1, L_2, …`` of a route of segments, else ``[L_u]``."""
    v = scene.parameters
    lengths = [float(v[f"L_{i}"]) for i in range(1, len(v) + 2) if f"L_{i}" in v]
    return lengths or [float(v["L_u"])]


def candidates(scene) -> list[Position]:
    """The candidate positions of ``scene``'s load, from the drive outwards (a given ``x_m``: that one)."""
    x_given = scene.parameters.get("x_m", math.inf)
    lengths = segment_lengths(scene)
    if math.isfinite(x_given):
        return [Position(float(x_given), _segment_of(float(x_given), lengths), "given")]
    n, out, start = len(lengths), [], 0.0
    for j, length in enumerate(lengths, start=1):
        end = start + length            # summed as the route sums its ends: a joint is exactly on it
        name = "the route" if n == 1 else f"segment {j}"
        if j == 1:
            out.append(Position(0.0, 1, f"at the drive, on {name}"))
        else:
            out.append(Position(start + JOINT_STEP, j, f"segment {j} at its joint with segment {j - 1}"))
        out.append(Position(start + length / 2, j, f"middle of {name}"))
        if j == n:
            out.append(Position(end, j, f"at the return sheave, on {name}"))
        else:
            out.append(Position(end, j, f"segment {j} at its joint with segment {j + 1}"))
        start = end
    return out


def _segment_of(x: float, lengths) -> int:
    """The segment a load at x belongs to (a joint: the one nearer the drive)."""
    end = 0.0
    for j, length in enumerate(lengths, start=1):
        end += length
        if x <= end:
            return j
    return len(lengths)
