"""An S-curve speed ramp with a jerk limit (``ramp = "scurve"``).

The acceleration rises at the jerk limit J from 0 to a_max, stays there, and falls at J back to 0,
reaching v_pj in t_ramp: a_max (t_ramp − t_j) = v_pj with t_j = a_max/J, so in s = t/t_ramp the jerk
phases last s_j = t_j/t_ramp with s_j (1 − s_j) = v_pj/(J t_ramp²).  That needs J ≥ 4 v_pj/t_ramp²
(s_j = ½: a triangle of acceleration).  Not in Krauze et al. (2025); the usual shape of a
jerk-limited drive (e.g. lifts and hoists).
"""

from __future__ import annotations

from ropemodel._math import sqrt
from ropemodel.effects import domains as dom
from ropemodel.effects.base import register
from ropemodel.effects.transient.base import MODEL
from ropemodel.effects.transient.ramp import Piece, RampShape
from ropemodel.quantity import Quantity

JERK = Quantity("jerk_max", "m/s^3", "largest jerk of the S-curve speed ramp", "m/s^3", positive=True, guess=1.0,
                **dom.domain(1e-3, 1e4, "1e-3 to 10^4 m/s^3: lifts ride at about 1 m/s^3"))


@register(MODEL, "ramp", "scurve")
class SCurveRamp(RampShape):
    """S-curve speed ramp: acceleration a trapezoid with slopes ±jerk_max, zero at both ends."""

    description = "S-curve speed ramp with a jerk limit (acceleration a trapezoid)"
    quantities = (JERK,)
    gathered = False                  # jerk_max is required, and only by this variant

    def rules(self, values):
        v, T, J = values.get("v_pj"), values.get("t_ramp"), values.get("jerk_max")
        if None not in (v, T, J) and J * T**2 < 4 * v:
            return [f"jerk_max = {J:g} m/s^3 cannot reach v_pj = {v:g} m/s in t_ramp = {T:g} s: the S-curve "
                    f"needs jerk_max >= 4 v_pj/t_ramp^2 = {4 * v / T**2:g} m/s^3"]
        return []

    def pieces(self, values):
        c = values["v_pj"] / (values["jerk_max"] * values["t_ramp"] ** 2)
        sj = (1 - sqrt(1 - 4 * c)) / 2            # jerk phases: s_j (1 − s_j) = c
        A = 1 / (1 - sj)                          # f' in the middle: the area under f' is 1
        return [Piece(0.0, sj, lambda s: A * s**2 / (2 * sj), lambda s: A * s / sj),
                Piece(sj, 1 - sj, lambda s: A * (s - sj / 2), lambda s: A + 0 * s),
                Piece(1 - sj, 1.0, lambda s: 1 - A * (1 - s) ** 2 / (2 * sj), lambda s: A * (1 - s) / sj)]
