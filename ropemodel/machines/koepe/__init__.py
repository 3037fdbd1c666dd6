"""The Koepe friction hoist (``model = "koepe"``): its declaration for the generic drivers.

Its physics is in :mod:`ropemodel.effects.koepe` and the modules beside it (static states, wheel and braking
window, ropes, lining, checks, rules) and in :mod:`ropemodel.effects.koepe_transient` (the elastic transient).
Declared here: its checks in the model's order, its sizing (:mod:`.sizing`: the number and diameter of the head
ropes, the tail ropes' mass and the wheel, least suspended rope mass first), its transient (braking or start
with elastic head ropes: :class:`~ropemodel.machines.koepe.simulation.KoepeSimulation`) and its report
sections.
"""

from __future__ import annotations

from ropemodel.effects.koepe import MODEL
from ropemodel.effects.koepe_transient.profile import KoepeProfile
from ropemodel.machines.base import Figure, Machine, Transient, model_order, register
from ropemodel.machines.koepe.simulation import KoepeSimulation
from ropemodel.machines.koepe.sizing import KoepeSizing


def _scale(setup) -> tuple[float, float]:
    """The switching functions' scales: the largest rope speed [m/s] and the largest static tension [N]."""
    return max(float(setup.numbers["v_max"]), 1e-6), max(float(setup.numbers["T_max"]), 1.0)


def _length(system) -> float:
    """The least steady stretch of a head-rope element [m] (the states are lengths, speeds and energies; the
    stretch is the smallest length that matters)."""
    return float(system.setup.part("head_elasticity").mesh.e0.min())


def _numbers(values: dict) -> dict:
    return {k: float(v) for k, v in values.items()}


#: what the report draws of a braking or start: the tensions and the slip margin at the wheel [N], the speeds [m/s]
FIGURE = Figure(columns=("t [s]", "T_L [N]", "T_E [N]", "T_min [N]", "slip_margin [N]", "v_rope [m/s]",
                         "v_wheel [m/s]", "slip_speed [m/s]"),
                units=("N", "m/s"),
                caption="The tensions at the wheel, the least tension in the head ropes and the margin against slip "
                        "(kN); the speeds of the ropes and the wheel (m/s)")
#: the transient in words (the report's transient section)
ABOUT = ": the head ropes elastic, slip judged at every instant (docs/physics.md §7, elastic ropes)"


MACHINE = register(Machine(
    model=MODEL,
    title="Koepe friction hoist",
    checks=model_order,
    sizing=KoepeSizing(),
    transient=Transient(profile=KoepeProfile, result=KoepeSimulation, scale=_scale, length=_length,
                        numbers=_numbers, before_bind=True, about=ABOUT, figure=FIGURE),
    sections=("sizing", "transient"),
))
