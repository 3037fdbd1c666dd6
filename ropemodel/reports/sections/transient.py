"""Section "transient": the start-up or braking of a winch scene (``dynamics = "start"`` or ``"stop"``), its
summary and its histories as pictures.  Uses only ``simulate(scene)``, ``.history``, ``.summary`` and
``.report()``.

A whole trip (``dynamics = "trip"``) is the "Trip" section's, computed exactly piece by piece: the
transient of a trip adds nothing to it, and its ratio of the largest force to the static force at the
trip's start is the change of segment, not a dynamic factor.  With an inextensible rope
(``rope_elasticity = "rigid"``) the transient has no elongation, so the tensioner never moves: the
section leaves the take-up out and says where the stroke is computed (eq. (23)).
"""

from __future__ import annotations

from ropemodel.effects import effects_of
from ropemodel.effects.transient.profile import Profile, Trip
from ropemodel.effects.transient.rope import RopeRigid
from ropemodel.machines.base import declared_machine
from ropemodel.reports import figures, page
from ropemodel.reports.registry import section

#: units of the history's columns drawn, one panel each: forces, speeds, lengths
UNITS = ("N", "m/s", "m")


def _variant(scene, effect: str) -> type:
    """The registered class of the scene's variant of ``effect``."""
    return effects_of(scene.model)[effect].variants[scene.effects[effect]]


def has_transient(ctx) -> bool:
    """A winch scene with a start-up or a braking to simulate (a whole trip is the "Trip" section's)."""
    s = ctx.scene
    if "dynamics" not in s.effects:
        return False
    profile = _variant(s, "dynamics")
    return issubclass(profile, Profile) and not issubclass(profile, Trip)


def every_parameter(ctx) -> set[str]:
    """A transient's system of parts reads every parameter of the scene."""
    return set(ctx.scene.parameters)


def simulated(ctx) -> set[str]:
    """What a simulation of the scene reads: every parameter but those of its transient variants that only
    dynamic sizing reads (``sizing_only``: the dynamic slip factor, the mesh tolerance)."""
    s = ctx.scene
    return set(s.parameters) - {n for e in s.effects for n in getattr(_variant(s, e), "sizing_only", ())}


@section("transient", "Transient", when=has_transient, reads=simulated)
def transient(ctx):
    sim = ctx.simulation
    history = sim.history
    text = sim.report()
    rigid = issubclass(_variant(ctx.scene, "rope_elasticity"), RopeRigid)
    if rigid:       # no take-up to report: the tensioner's own lines are left out
        tensioner = next(p for p in sim.system.parts if p.effect == "tensioner")
        dropped = set(tensioner.report(sim.summary))
        text = "\n".join(line for line in text.splitlines() if line not in dropped)
    x = "t [s]" if "t [s]" in history.columns else history.columns[0]
    html = page.fragment("<p>dynamics = \"{{ d }}\"{{ at }}. Summary:</p><pre>{{ r }}</pre>",
                         d=ctx.scene.effects["dynamics"], r=text,
                         at=", at the recommended design" if ctx.at_design else "")
    if rigid:
        from ropemodel.reports.sections.trip import has_trip

        html += page.fragment(declared_machine(ctx.scene).transient.rigid_note, r=ctx.scene.effects["rope_elasticity"],
                              trip=' and "Trip"' if has_trip(ctx) else "")
    uri = figures.panels(history, x, UNITS, title=f"{ctx.scene.name}: histories")
    if uri:
        html += page.fragment('<figure><img src="{{ u }}" alt="histories of the transient"><figcaption>Forces (kN), '
                              "speeds (m/s) and lengths (m) against time; {{ n }} output times.</figcaption></figure>",
                              u=uri, n=len(history))
    return html
