"""Where a winch's braking energy goes (effect ``braking``): back to the supply, or burnt.

A drive brakes whenever the load drives the drum (the drum's power P_drum < 0, four-quadrant
convention, :class:`ropemodel.effects.winch.DrivePower`): lowering a load on a slope steeper than its
resistances hold, and in the stop of every trip.  What reaches the motor, N_p = P_drum·η, goes

* ``regenerative`` (default): back to the supply, through a regenerative (four-quadrant, active
  front end) drive: a trip reports it as ``E_regen``, the energy returned;
* ``dissipative``: into a braking resistor (dynamic braking) of a drive that cannot regenerate:
  a trip reports it as ``E_dissipated``, the energy the resistor must take, and nothing returns.

Either way the motor carries the braking power (its largest, ``P_brake_max``, and the r.m.s. power
include it), and the energy drawn while motoring, ``E_trip``, is the same.  The default follows the
physics reference (docs/physics.md §4: the energy returned, "dissipated instead where the drive
cannot regenerate"); a scene whose drive has a braking resistor says ``braking = "dissipative"``,
and every trip output names where the energy went.  Neither variant builds an equation: the
choice is read by :mod:`ropemodel.trips` through the registry.
"""

from __future__ import annotations

from typing import ClassVar

from ropemodel.effects.base import Submodel, define_effect, register
from ropemodel.effects.winch import MODEL

define_effect(MODEL, "braking", "regenerative",
              "where a trip's braking energy goes: returned to the supply, or dissipated in a braking resistor")


class Braking(Submodel):
    """A destination of the braking energy: the key a trip reports it under and what that means."""

    #: the trip's summary key of the braking energy [J]
    energy_key: ClassVar[str] = ""
    #: where the braking energy goes, for text and reports
    destination: ClassVar[str] = ""


@register(MODEL, "braking", "regenerative")
class Regenerative(Braking):
    """The drive returns its braking power to the supply (regenerative, four-quadrant drive)."""

    description = "braking energy returned to the supply by a regenerative (four-quadrant) drive"
    energy_key = "E_regen"
    destination = "returned to the supply"


@register(MODEL, "braking", "dissipative")
class Dissipative(Braking):
    """The drive cannot regenerate: its braking power is burnt in a braking resistor."""

    description = "braking energy dissipated in a braking resistor (a drive that cannot regenerate)"
    energy_key = "E_dissipated"
    destination = "dissipated in the braking resistor"
