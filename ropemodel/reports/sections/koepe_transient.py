"""Section "koepe_transient": the braking or start of a Koepe hoist with elastic head ropes (``dynamics =
"braking"`` or ``"start"``, :func:`ropemodel.dynamics.simulate`): its summary and its histories as pictures."""

from __future__ import annotations

from ropemodel.effects import effects_of
from ropemodel.effects.koepe_transient.profile import KoepeProfile
from ropemodel.reports import figures, page
from ropemodel.reports.registry import section
from ropemodel.reports.sections.transient import every_parameter

#: the history's columns drawn: tensions and margin at the wheel [N], speeds [m/s]
COLUMNS = ("t [s]", "T_L [N]", "T_E [N]", "T_min [N]", "slip_margin [N]", "v_rope [m/s]", "v_wheel [m/s]",
           "slip_speed [m/s]")


def has_koepe_transient(ctx) -> bool:
    """A Koepe scene with a braking or a start to simulate."""
    s = ctx.scene
    if "dynamics" not in s.effects:
        return False
    return issubclass(effects_of(s.model)["dynamics"].variants[s.effects["dynamics"]], KoepeProfile)


@section("koepe_transient", "Transient with elastic ropes", when=has_koepe_transient, reads=every_parameter)
def koepe_transient(ctx):
    sim = ctx.simulation
    html = page.fragment("<p>dynamics = \"{{ d }}\"{{ at }}: the head ropes elastic, slip judged at every instant "
                         "(docs/physics.md §7, elastic ropes). Summary:</p><pre>{{ r }}</pre>",
                         d=ctx.scene.effects["dynamics"], r=sim.report(),
                         at=", at the recommended design" if ctx.at_design else "")
    frame = sim.history[[c for c in COLUMNS if c in sim.history.columns]]
    uri = figures.panels(frame, "t [s]", ("N", "m/s"), title=f"{ctx.scene.name}: histories")
    if uri:
        html += page.fragment('<figure><img src="{{ u }}" alt="histories of the Koepe transient"><figcaption>The '
                              "tensions at the wheel, the least tension in the head ropes and the margin against "
                              "slip (kN); the speeds of the ropes and the wheel (m/s); {{ n }} output times."
                              "</figcaption></figure>", u=uri, n=len(frame))
    return html
