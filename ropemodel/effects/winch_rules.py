"""The winch's side of the rule sets: its suspended length, and which parameter each rule sets.

The winch is an endless-rope haulage: its rope is driven by friction on the drive drum (rope kind
``friction-drum``) and runs the whole route to the return sheave.  A rule set for machine ``winch`` may
set:

=================  ==============  =======================================  ===========================
governs            parameter       checks                                   context
=================  ==============  =======================================  ===========================
rope_safety        ``n_rope``      safety_margin (F_min/F_C ≥ n_rope)       rope = friction-drum
                                   (and safety_margin_S of the transients)
drum_ratio         ``D_ratio_min`` drum_margin (D ≥ D_ratio_min d)          drum = friction-drum
slip_safety        ``n_slip``      slip_margin (lining effect)              drum = friction-drum
least_tension      ``F_S_min``     slack_margin, taut_margin,                —
                                   route_margin (along the route),
                                   sheave_margin (at the return sheave)
=================  ==============  =======================================  ===========================

**The suspended length** (engineering judgement; no rule cited defines it for an endless haulage).
Hoisting rules write a factor as a formula in the "maximum suspended rope length" (30 CFR § 57.19021:
"L equals the maximum suspended rope length in feet"): the rope between the drum or head sheave and the
conveyance at its farthest position, whose own weight the rope carries.  On an incline that rope lies
along the route, so ropemodel takes the route's length from the drive to the return sheave, ``L_u``
(on a route of segments, the sum of their lengths): the winding rope's length when the load is at the
far end.  The other reading, the vertical lift L_u sin α_u, is shorter; a factor that falls with length
(7.0 − 0.0005 L) is then higher.  Ask the authority which it accepts; override ``n_rope`` in
``[rules]`` (with the reason) if it is the vertical lift.
"""

from __future__ import annotations

import re

from ropemodel.effects.rulebinding import Binding, Length, bind_rules
from ropemodel.effects.winch import MODEL

_SEGMENT = re.compile(r"^L_(\d+)$")
SUSPENDED = ("the route's length from the drive to the return sheave, L_u (on a route of segments, the sum of "
             "their lengths): the winding rope's length with the load at the far end, taken as the rule's "
             "\"suspended length\"; the vertical lift L_u sin α_u is the other reading")


def _segments(names) -> tuple[str, ...]:
    found = sorted((int(m[1]), k) for k in names for m in [_SEGMENT.match(k)] if m)
    return tuple(k for _, k in found)


def route_inputs(names) -> tuple[str, ...]:
    """The parameters the route's length is read from: ``L_u``, or the segments' ``L_1``, ``L_2``, …"""
    return ("L_u",) if "L_u" in names else _segments(names)


def route_length(values):
    """The route's length [m] (floats, numpy arrays or CasADi symbols)."""
    names = route_inputs(values)
    total = values[names[0]]
    for k in names[1:]:
        total = total + values[k]
    return total


bind_rules(
    MODEL, "winch",
    lengths=(Length("suspended", route_length, route_inputs, SUSPENDED, "engineering judgement"),),
    bindings=(
        Binding("rope_safety", "n_rope", ("safety_margin", "safety_margin_S"), {"rope": "friction-drum"}),
        Binding("drum_ratio", "D_ratio_min", ("drum_margin",), {"drum": "friction-drum"}),
        Binding("slip_safety", "n_slip", ("slip_margin",), {"drum": "friction-drum"}),
        Binding("least_tension", "F_S_min", ("slack_margin", "taut_margin", "route_margin", "sheave_margin")),
    ),
)
