"""Section "transient": the start-up or braking of a machine's scene (the winch's ``dynamics = "start"`` or
``"stop"``, the Koepe hoist's ``"braking"`` or ``"start"``), its summary and its histories as pictures.  Uses
only ``simulate(scene)``, ``.history``, ``.summary`` and ``.report()``, and what the machine's transient declares
(:class:`ropemodel.machines.base.Transient`: what it is, the figure, the variants shown elsewhere).

A winch's whole trip (``dynamics = "trip"``) is the "Trip" section's, computed exactly piece by piece: the
transient of a trip adds nothing to it, and its ratio of the largest force to the static force at the
trip's start is the change of segment, not a dynamic factor.  With an inextensible rope
(``rope_elasticity = "rigid"``) the transient has no elongation, so the tensioner never moves: the
section leaves the take-up out and says where the stroke is computed (eq. (23)).
"""

from __future__ import annotations

from ropemodel.effects import effects_of
from ropemodel.effects.transient.rope import RopeRigid
from ropemodel.machines.base import machine_of
from ropemodel.reports import figures, page
from ropemodel.reports.registry import section


def _variant(scene, effect: str) -> type:
    """The registered class of the scene's variant of ``effect``."""
    return effects_of(scene.model)[effect].variants[scene.effects[effect]]


def has_transient(ctx) -> bool:
    """A scene whose machine has a transient, with a start-up or a braking of it to simulate (not a variant
    another section shows: the winch's whole trip is the "Trip" section's)."""
    s = ctx.scene
    machine = machine_of(s)
    if machine is None or machine.transient is None or "dynamics" not in s.effects:
        return False
    profile = _variant(s, "dynamics")
    return issubclass(profile, machine.transient.profile) and not issubclass(profile, machine.transient.elsewhere)


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
    declared = machine_of(ctx.scene).transient
    text = sim.report()
    rigid = "rope_elasticity" in ctx.scene.effects and issubclass(_variant(ctx.scene, "rope_elasticity"), RopeRigid)
    if rigid:       # no take-up to report: the tensioner's own lines are left out
        tensioner = next(p for p in sim.system.parts if p.effect == "tensioner")
        dropped = set(tensioner.report(sim.summary))
        text = "\n".join(line for line in text.splitlines() if line not in dropped)
    html = page.fragment("<p>dynamics = \"{{ d }}\"{{ at }}{{ about }}. Summary:</p><pre>{{ r }}</pre>",
                         d=ctx.scene.effects["dynamics"], r=text, about=declared.about,
                         at=", at the recommended design" if ctx.at_design else "")
    if rigid:
        from ropemodel.reports.sections.trip import has_trip

        html += page.fragment(declared.rigid_note, r=ctx.scene.effects["rope_elasticity"],
                              trip=' and "Trip"' if has_trip(ctx) else "")
    return html + _figure(ctx.scene.name, sim.history, declared.figure)


def _figure(name: str, history, figure) -> str:
    """The history's columns the machine declares drawn against time, one panel per unit."""
    frame = history[[c for c in figure.columns if c in history.columns]] if figure.columns else history
    x = "t [s]" if "t [s]" in frame.columns else frame.columns[0]
    uri = figures.panels(frame, x, figure.units, title=f"{name}: histories")
    if not uri:
        return ""
    return page.fragment('<figure><img src="{{ u }}" alt="histories of the transient"><figcaption>{{ c }}; '
                         "{{ n }} output times.</figcaption></figure>", u=uri, c=figure.caption, n=len(frame))
