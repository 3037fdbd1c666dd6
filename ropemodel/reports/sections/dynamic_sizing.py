"""Section "dynamic sizing": a scene that sizes through its start-up and braking (``[numerics] sizing =
"dynamic"``): the dynamic design against the static one, each of the four manoeuvres simulated at the
recommended design with the load at every candidate place (the worst peaks, where the load governs each
manoeuvre and each check) and which instant of which manoeuvre fixes the design (:mod:`optimisation.dynamic`)."""

from __future__ import annotations

from ropemodel.reports import page
from ropemodel.reports.registry import section
from ropemodel.reports.sections.transient import every_parameter
from ropemodel.machines.base import declared_machine

INTRO = """<p>Every design check holds through {{ through }},
with the load anywhere on the route (the ends and the middle of every segment), not only at the static forces
(<code>ropemodel size --dynamic</code>); the recommended design verified by the hybrid simulator.
The recommended design against the static optimum (continuous optima; the static one is what the paper's
sizing gives):</p>"""


def sizes_dynamically(ctx) -> bool:
    return bool(ctx.sizing) and ctx.scene.numerics.get("sizing") == "dynamic"


@section("dynamic_sizing", "Dynamic sizing", when=sizes_dynamically, reads=every_parameter)
def dynamic_sizing(ctx):
    design = ctx.design
    q = design.scene.built.quantities
    text = declared_machine(design.scene).manoeuvres.TEXT
    html = page.fragment(INTRO, through=text["through"])
    if design.continuous and design.static:
        rows = [[k, page.show(q[k], design.continuous[k]), page.show(q[k], design.static[k]),
                 f"{100 * (design.continuous[k] / design.static[k] - 1):+.1f} %"] for k in design.continuous]
        html += page.table(["design variable", "dynamic optimum", "static optimum", "dynamic vs static"], rows,
                           kinds=["name", "num", "num", "num"], cls="dynamic-design")
    if not design.feasible:
        return html + page.verdict(False, "No design keeps every check through the manoeuvres.") + page.fragment(
            "<pre>{{ m }}</pre>", m=design.message)
    columns = declared_machine(design.scene).manoeuvres.PEAK_COLUMNS
    rows = [[m["manoeuvre"], m["where"], *(cell(m["peaks"]) for _, cell in columns), "ok" if m["ok"] else "FAILS"]
            for m in design.manoeuvres]
    html += page.fragment("<h3>{{ all }} at the recommended design (simulated; the worst of every place of the "
                          "load)</h3>", all=text["all"][:1].upper() + text["all"][1:])
    html += page.table(["manoeuvre", "governed with the load at", *(heading for heading, _ in columns), "checks"],
                       rows, kinds=["name", "", *("num" for _ in columns), ""], cls="manoeuvres")
    words = declared_machine(design.scene).words
    html += page.fragment("{% if m %}<p>{{ m }}.</p>{% endif %}",
                          m=words.mesh_text(design.mesh, design.scene.parameters))
    html += page.fragment("<h3>What fixes the design</h3><p>Active at the continuous optimum (a check at an instant "
                          "of a manoeuvre, or a static check):</p><ul>{% for a in active %}<li>{{ a }}</li>"
                          "{% endfor %}</ul>",
                          active=[words.readable(a, design.scene.parameters) for a in design.active_continuous])
    return html + _least_margins(design.manoeuvres, design.scene)


def _least_margins(manoeuvres, scene) -> str:
    """Each check's least margin through each manoeuvre (the simulator's history) in words: the force or
    take-up it judges and its limit there, the margin, the instant and the load's place
    (the machine's words, :class:`ropemodel.views.checks.Vocabulary`, as ``size --dynamic`` prints them), and the
    factors with their rules."""
    words = declared_machine(scene).words
    rows = [[m["manoeuvre"], r.check, r.value, r.limit, r.margin, r.t, r.where, "pass" if r.ok else "FAIL"]
            for m in manoeuvres for r in words.manoeuvre_rows(m, merged=False, parameters=scene.parameters)]
    return page.fragment("<h3>Checks through the manoeuvres</h3>") + page.table(
        ["manoeuvre", "check", "value", "limit", "margin", "at t", "with the load at", "verdict"], rows,
        kinds=["name", "", "num", "num", "num", "num", "", ""], cls="manoeuvre-checks") + page.fragment(
        "<p>Factors:</p><ul>{% for f in factors %}<li>{{ f }}</li>{% endfor %}</ul>", factors=words.factors(scene))
