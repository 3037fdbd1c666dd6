"""The Koepe hoist's side of the rule sets: its suspended length, and which parameter each rule sets.

The head ropes are driven by friction on the wheel (rope kind ``friction-drum``, the wheel a
``friction-drum``); the tail ropes are ``tail`` ropes.  A rule set for machine ``koepe`` may set:

=============================  ====================  ====================================  =====================
governs                        parameter             checks                                context
=============================  ====================  ====================================  =====================
rope_safety                    ``n_safety_head``     head_safety_margin                    rope = friction-drum
rope_safety                    ``n_safety_tail``     tail_safety_margin                    rope = tail
drum_ratio                     ``D_ratio_min``       wheel_margin (D ≥ D_ratio_min d)       drum = friction-drum
least_drum                     ``D_min``             wheel_size_margin (D ≥ D_min)          drum = friction-drum
emergency_deceleration_min     ``a_brake_min``       brake_margin_hoist, brake_margin_lower  —
=============================  ====================  ====================================  =====================

**The suspended length** (engineering judgement: the rules read call it the "maximum suspended rope length",
30 CFR § 57.19021, without saying it for a friction hoist): the head rope from the wheel's tangent point to a
conveyance at its lower position, ``H_head + H``, the longest head rope whose weight a rope carries.  The
rope lying on the wheel and the tail ropes below are not counted; a rule that counts them has a shorter
factor for a longer length: override the factor in ``[rules]`` with the reason.
"""

from __future__ import annotations

from ropemodel.effects.koepe import MODEL
from ropemodel.effects.rulebinding import Binding, Length, bind_rules

SUSPENDED = ("the head rope from the wheel's tangent point to a conveyance at its lower position, H_head + H: the "
             "longest head rope whose weight a rope carries, taken as the rule's \"maximum suspended rope length\"")
BRAKE = ("brake_margin_hoist", "brake_margin_lower")


def suspended_inputs(names) -> tuple[str, ...]:
    """The parameters the suspended length is read from, ``H_head`` and ``H``; none while ``names`` lacks either
    (a value left out or refused: the rule's value waits, the scene's problems name it)."""
    both = ("H_head", "H")
    return both if set(both) <= set(names) else ()


def suspended_length(values):
    """H_head + H [m] (floats, numpy arrays or CasADi symbols)."""
    return values["H_head"] + values["H"]


bind_rules(
    MODEL, "koepe",
    lengths=(Length("suspended", suspended_length, suspended_inputs, SUSPENDED, "engineering judgement"),),
    bindings=(
        Binding("rope_safety", "n_safety_head", ("head_safety_margin",), {"rope": "friction-drum"}),
        Binding("rope_safety", "n_safety_tail", ("tail_safety_margin",), {"rope": "tail"}),
        Binding("drum_ratio", "D_ratio_min", ("wheel_margin",), {"drum": "friction-drum"}),
        Binding("least_drum", "D_min", ("wheel_size_margin",), {"drum": "friction-drum"}),
        Binding("emergency_deceleration_min", "a_brake_min", BRAKE),
    ),
)
