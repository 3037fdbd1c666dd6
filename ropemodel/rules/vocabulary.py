"""The words rule sets are written in: what a rule governs, the machines, the kinds of rope and drum, the
statuses of a rule's text.

A rule says what it governs in the world (``rope_safety`` of a ``friction-drum`` rope), not in a model's
symbols; each model binds those words to its parameters (:mod:`ropemodel.effects.rulebinding`), so one
rule set serves every machine it is written for.
"""

from __future__ import annotations

#: governs → (SI unit of the value, what it is)
GOVERNS: dict[str, tuple[str, str]] = {
    "rope_safety": ("1", "least rope safety factor: the rope's minimum breaking force over its static force"),
    "drum_ratio": ("1", "least ratio of drum (or sheave) diameter to rope diameter, D/d"),
    "least_drum": ("m", "least drum (or sheave) diameter"),
    "slip_safety": ("1", "least safety factor against slip of the rope on its friction drum"),
    "least_tension": ("N", "least tension allowed in any rope"),
    "dynamic_allowance": ("1", "least allowance on the static loads for the dynamic loads of starting, slowing "
                               "and braking (0.1: +10 %)"),
    "drum_load_slack_side": ("1", "fraction of the rope's breaking force taken on the slack side when a "
                                  "friction drum, its shaft and bearings are sized with the full breaking force "
                                  "on the tight side"),
    "connector_safety": ("1", "least safety factor of connecting devices (couplings, pins, shackles)"),
    "termination_efficiency": ("1", "least strength of a rope's load-end attachment, as a fraction of the rope's"),
    "lining_friction": ("1", "least coefficient of friction of the drum lining against the rope"),
    "emergency_deceleration_min": ("m/s^2", "least deceleration of an emergency stop (the safety brake)"),
}

#: machine → what it is (a rule set names the machines it is written for)
MACHINES: dict[str, str] = {
    "winch": "endless-rope haulage on an incline: a friction drum, a return sheave and a tensioner "
             "(ropemodel model 'winch', Krauze et al. 2025)",
    "koepe": "friction (Koepe) hoist in a shaft: head ropes over a friction wheel, optional tail ropes "
             "(ropemodel model 'koepe')",
    "drum-hoist": "winding-drum hoist in a shaft or slope (not a ropemodel model)",
}

#: context key → value → meaning; a rule's ``where`` may name these (a model's binding gives them)
CONTEXT: dict[str, dict[str, str]] = {
    "rope": {"winding-drum": "a rope wound on a drum (drum hoist)",
             "friction-drum": "a rope driven by friction on a drum or wheel (Koepe head ropes, an endless "
                              "haulage rope)",
             "hand-pulled": "a winch's pulling rope pulled out by hand at each load cycle (forestry, vehicle and "
                            "cable-pulling winches)",
             "tail": "a tail (balance) rope", "guide": "a guide rope", "connector": "a connecting device"},
    "drum": {"friction-drum": "a friction drum or wheel with a lining (Koepe wheel, haulage drive drum)",
             "winding-drum": "a drum the rope is wound on", "v-groove-sheave": "a traction sheave with V grooves",
             "head-sheave": "a head (deflection) sheave"},
}

#: status → meaning (a rule's status is never better than what was read)
STATUSES: dict[str, str] = {
    "confirmed": "the text was read; its clause and source are cited",
    "to verify": "known from a secondary source only (a summary, a state rule quoting it, the issue); read the "
                 "text before filing",
    "engineering judgement": "no text: a choice ropemodel makes, with its reason",
}

#: units a rule's length may be written in (the unit the source writes it in)
LENGTH_UNITS = ("m", "ft")
