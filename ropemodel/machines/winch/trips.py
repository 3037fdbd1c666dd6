"""What a winch's trip (:mod:`ropemodel.trips`) takes from the winch: its route's length and joints, the
tensioner's take-up along the trip (eq. (19)-(23): the stroke needed), and how to keep a slack rope taut.

The generic trip integrates the drum's and the drive's power exactly, piece by piece; the pieces' take-up is
the static model's ``dF_up``/``dF_down`` at the piece's middle (NaN without an elongation effect).
"""

from __future__ import annotations

import math

import numpy as np

from ropemodel.effects.winch_route import segment_lengths

#: summary keys a winch's trip adds → unit (the largest take-up over the trip: the stroke needed)
SUMMARY = {"stroke_needed": "m"}
#: the same keys as the report shows them: (label, unit shown, factor from SI)
ROWS = {"stroke_needed": ("tensioner stroke needed, eq. (23)", "mm", 1e3)}
#: the static model's outputs a trip reads, each with ``_up`` and ``_down``: the rope forces at the drum and the
#: tensioner's take-up
OUTPUTS = ("F_C", "F_S", "dF")


def length(v) -> float:
    """The route's length [m]: L_u, or the sum of its segments."""
    return v["L_u"] if "L_u" in v else sum(segment_lengths(v))


def joints(v) -> list[float]:
    """The distances of the route's joints from the drive [m] (none on a straight route)."""
    return list(np.cumsum(segment_lengths(v)))[:-1]


def take_up(out: dict, direction: str, n: int):
    """The tensioner's take-up ΔF [m] (eq. (23)) at each of ``n`` pieces; NaN without an elongation effect."""
    return out.get(f"dF_{direction}", np.full(n, np.nan))


def summary(take_ups) -> dict[str, float]:
    """The stroke needed: the largest take-up over the trip (none without an elongation effect)."""
    return {"stroke_needed": max(take_ups)} if all(math.isfinite(x) for x in take_ups) else {}


def lines(s: dict) -> list[str]:
    """The report's lines of the keys a winch adds."""
    if "stroke_needed" not in s:
        return []
    return [f"  stroke needed {s['stroke_needed'] * 1e3:.1f} mm (eq. (23), largest over the trip, ramps included)"]


def remedy(v, least: float) -> str:
    """The pretension that keeps every rope taut, ``least`` [N] being the least rope force of the trip."""
    return f"F_nwl > {(v['F_nwl'] - 2 * least) / 1e3:.6g} kN"
