"""Direction of the transient and where the load is (effect ``travel``).

``up`` (default): the load is hauled up the incline (Krauze et al. 2025, upward column); ``down``:
the load is lowered.  ``x_m`` is the load's distance from the drive along the winding rope,
0 ≤ x_m ≤ L_u.  Not given, the load is at the start of a trip in the chosen direction: upward
travel starts with the load at the return sheave's end of the route (x_m = L_u), downward travel
with the load at the drive (x_m = 0, where the winding rope meets the drum).  The summary says which
position was used and whether it was given.
"""

from __future__ import annotations

import math

from ropemodel.effects import domains as dom
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.transient.base import MODEL, TransientSubmodel
from ropemodel.quantity import Quantity

define_effect(MODEL, "travel", "up", "direction of travel of the simulated transient (up: load hauled up)")

X_M = Quantity("x_m", "m", "distance of the load from the drive along the winding rope", "m", **dom.ROUTE_POSITION,
               unlimited=True, unlimited_text="anywhere", default=math.inf, guess=1000.0,
               default_note="not given: anywhere on the route, each result at its worst place (run, solve, size, "
                            "sweep, sensitivity, report); a transient (simulate) starts at the start of a trip in "
                            "its direction (upward: the load at the return sheave, x_m = L_u; downward: at the "
                            "drive, x_m = 0)")


def beyond_route(values) -> list[str]:
    """The rule 0 <= x_m <= L_u (x_m given, L_u a parameter): one message, or none."""
    x, L = values.get("x_m"), values.get("L_u")
    if x is not None and L is not None and math.isfinite(x) and x > L:
        return [f"x_m = {x:g} m is beyond the return sheave at L_u = {L:g} m: the load must be on the route, "
                f"0 <= x_m <= L_u (leave x_m out for every place on the route)"]
    return []


class Travel(TransientSubmodel):
    """Direction ``sign`` (+1 up, −1 down) and the load's start position."""

    citations = ("krauze2025",)
    quantities = (X_M,)
    order = 0
    structural = ("x_m", "L_u")
    sign = +1
    start_text = ""

    def start(self, L_u: float) -> float:
        raise NotImplementedError

    def rules(self, values):
        return beyond_route(values)

    def bind(self, setup):
        super().bind(setup)
        setup.direction, setup.travel = self.sign, self.variant
        x = setup.numbers.get("x_m", math.inf)
        self.x_m_given = math.isfinite(x)
        self.x_m = x if self.x_m_given else self.start(float(setup.numbers["L_u"]))
        setup.numbers["x_m"] = setup.values["x_m"] = self.x_m

    def summary(self, run):
        return {"direction": self.variant, "x_m": self.x_m,
                "x_m_source": "given" if self.x_m_given else f"default: {self.start_text}"}

    def report(self, summary):
        return [f"  load at x_m = {summary['x_m']:.6g} m from the drive ({summary['x_m_source']})"]


@register(MODEL, "travel", "up")
class TravelUp(Travel):
    """The transient hauls the load up the incline (Krauze et al. 2025, upward column)."""

    description = "load hauled up"
    start_text = "the start of an upward trip, the load at the return sheave (x_m = L_u)"

    def start(self, L_u):
        return L_u


@register(MODEL, "travel", "down")
class TravelDown(Travel):
    """The transient lowers the load (Krauze et al. 2025, downward column)."""

    description = "load lowered"
    sign = -1
    start_text = "the start of a downward trip, the load at the drive (x_m = 0)"

    def start(self, L_u):
        return 0.0
