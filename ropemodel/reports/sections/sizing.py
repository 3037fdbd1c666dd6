"""Section "sizing": the recommended rope, pretension and stroke, the active constraints, every check at
the recommended design; or, when no design exists, which checks conflict and by how much."""

from __future__ import annotations

from ropemodel.envelope import where_text
from ropemodel.reports import page
from ropemodel.reports.registry import section
from ropemodel.reports.sections.results import checks_html
from ropemodel.machines.base import declared_machine

INTRO = """<p>{{ objective }} (<code>ropemodel size</code>; catalogue diameter by {{ method }}).</p>"""
#: a declared sizing's introduction: what it minimises and what it enumerates
DECLARED = """<p>Minimised: {{ o.text }}, with every design check met (<code>ropemodel size</code>; catalogue size by
{{ method }}; {{ o.integer }} enumerated over {{ o.enumerated[0] }} to {{ o.enumerated[-1] }}, one continuous NLP
each, the lightest feasible kept): {{ "%.6g" % o.value }} kg at the design.</p>"""


def design_text(design) -> str:
    """``d = 38 mm, F_nwl = 43.6 kN, stroke = 4763 mm`` of a feasible design (its design variables)."""
    q = design.scene.built.quantities
    return ", ".join(f"{k} = {q[k].show(design.design[k])}" for k in design.continuous or design.design)


def reads(ctx) -> set[str]:
    """What the sizing is computed from (:func:`optimisation.problem.reads`)."""
    from optimisation.problem import reads as sizing_reads

    return sizing_reads(ctx.scene)[0]


@section("sizing", "Sizing", when=lambda ctx: ctx.sizing, reads=reads)
def sizing(ctx):
    design = ctx.design
    q = design.scene.built.quantities
    o = getattr(design, "objective", None)
    html = (page.fragment(DECLARED, method=design.method, o=o) if o else
            page.fragment(INTRO, method=design.method, objective=declared_machine(ctx.scene).sizing.INTRO))
    if design.continuous:
        rows = [[k, page.show(q[k], design.design[k]) if design.design else "-",
                 page.show(q[k], design.continuous[k]), q[k].description] for k in design.continuous]
        rows += [[k, page.show(q[k], x), "-", f"{q[k].description} (follows from the design)"]
                 for k, x in (design.design or {}).items() if k not in design.continuous]
        html += page.table(["design variable", "recommended (catalogue)", "continuous optimum", "meaning"], rows,
                           kinds=["name", "num", "num", ""], cls="design")
    if not design.feasible:
        html += page.verdict(False, "No design meets every check.")
        return html + page.fragment("<pre>{{ m }}</pre>", m=design.message)
    html += page.verdict(True, f"Design found: {design_text(design)}.")
    if not o:
        html += page.fragment("<p>{{ r }}; every check holds at the printed values.</p>",
                              r=declared_machine(ctx.scene).sizing.ROUNDED)
    html += page.fragment("<h3>Active constraints</h3><p>What fixes the design (at the recommended design):</p>"
                          "<ul>{% for a in active %}<li><code>{{ a }}</code></li>{% endfor %}</ul>",
                          active=design.active)
    extra = [[k, page.show(q[k], v), q[k].description + " (at its worst)"] for k, v in design.power.items()]
    extra += [[f"drive {kind}", page.show(q["N_p_up"], e["value"]),
               f"the drive's largest {kind} power: {where_text(e['where'], direction=True)}"]
              for kind, e in getattr(design, "drive", {}).items()]
    if design.least_drum is not None:
        extra.append(["D_min", page.show(q["D"], design.least_drum),
                      "no drum diameter given: the least drum, D_ratio_min d"])
    if extra:
        html += page.table(["quantity", "value", "meaning"], extra, kinds=["name", "num", ""])
    where = {k: where_text(w) for k, w in getattr(design, "governing", {}).items()}
    checks = checks_html({k: v for k, v in design.margins.items() if k in q}, q, design.scene,
                         where or None)   # static checks
    if checks:
        html += page.fragment("<h3>Checks at the recommended design</h3>") + checks
    return html + page.fragment('<p class="note">{{ m }}</p>', m=design.message)
