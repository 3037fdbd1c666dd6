"""The rope haulage winch (``model = "winch"``, Krauze et al. 2025): its declaration for the generic drivers.

Its physics is in :mod:`ropemodel.effects` (``winch*`` modules, the transient's :mod:`ropemodel.effects.transient`).
Declared here: its checks in report order (:mod:`ropemodel.effects.winch_checks`), its sizing
(:mod:`.sizing`: d, F_nwl and stroke, least rope mass first), the four manoeuvres of dynamic sizing
(:mod:`.manoeuvres`) with its checks in words (:mod:`.words`), its transient (start-up, braking or a whole trip),
what its trips take from it (:mod:`.trips`) and its report sections.  :mod:`.scenes` makes random sizing scenes
for the studies.
"""

from __future__ import annotations

from ropemodel.effects.transient.base import MODEL
from ropemodel.effects.transient.profile import Profile, Trip
from ropemodel.effects.winch_checks import CHECKS, margin_names
from ropemodel.effects.winch_rope import RopeCatalogue
from ropemodel.machines.base import Machine, Transient, register
from ropemodel.machines.winch import manoeuvres, sizing, trips
from ropemodel.machines.winch.words import WORDS


def _scale(setup) -> tuple[float, float]:
    """The switching functions' scales: the drive's speed [m/s] and the winding rope's static force of the
    transient's direction [N]."""
    return max(float(setup.numbers["v_pj"]), 1e-6), max(abs(float(setup.numbers[f"F_C_{setup.travel}"])), 1.0)


def _length(system) -> float:
    """The rope's static stretch over the route, L_u q_lw f_scale [m]: the length the states are measured in."""
    nums = system.setup.numbers
    return nums["L_u"] * nums["q_lw"] * system.setup.f_scale


#: the report's note on a transient with an inextensible rope (``rope_elasticity = "rigid"``)
RIGID = ('<p class="note">rope_elasticity = "{{ r }}": an inextensible rope has no elongation, so the tensioner '
         "does not move in this transient and the take-up is not shown; the stroke the rope needs is eq. (23)'s "
         '(under "Results"{{ trip }}). The dynamic factor is the rigid-body inertia of the ramp alone (no rope '
         "oscillation).</p>")


MACHINE = register(Machine(
    model=MODEL,
    title="rope haulage winch",
    checks=margin_names,
    sizing=sizing,
    manoeuvres=manoeuvres,
    transient=Transient(profile=Profile, result=None, scale=_scale, length=_length, rigid_note=RIGID,
                        elsewhere=(Trip,)),
    trips=trips,
    sections=("sizing", "transient", "trip", "dynamic_sizing"),
    ropes=(RopeCatalogue,),
    check_text={base: text for base, text, _ in CHECKS},
    words=WORDS,
))
