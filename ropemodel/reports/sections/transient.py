"""Section "transient": the start-up or braking of a winch scene (``dynamics`` not ``"none"``), its summary
and its histories as pictures.  Uses only ``simulate(scene)``, ``.history``, ``.summary`` and ``.report()``."""

from __future__ import annotations

from ropemodel.reports import figures, page
from ropemodel.reports.registry import section

#: units of the history's columns drawn, one panel each: forces, speeds, lengths
UNITS = ("N", "m/s", "m")


def has_transient(ctx) -> bool:
    return ctx.scene.effects.get("dynamics", "none") != "none"


@section("transient", "Transient", when=has_transient)
def transient(ctx):
    sim = ctx.simulation
    history = sim.history
    x = "t [s]" if "t [s]" in history.columns else history.columns[0]
    html = page.fragment("<p>dynamics = \"{{ d }}\"{{ at }}. Summary:</p><pre>{{ r }}</pre>",
                         d=ctx.scene.effects["dynamics"], r=sim.report(),
                         at=", at the recommended design" if ctx.at_design else "")
    uri = figures.panels(history, x, UNITS, title=f"{ctx.scene.name}: histories")
    if uri:
        html += page.fragment('<figure><img src="{{ u }}" alt="histories of the transient"><figcaption>Forces (kN), '
                              "speeds (m/s) and lengths (m) against time; {{ n }} output times.</figcaption></figure>",
                              u=uri, n=len(history))
    return html
