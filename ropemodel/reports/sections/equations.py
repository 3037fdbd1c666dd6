"""Section "equations": every equation used, numbered as in its paper, each followed by its numbers.

Each formula is printed from the expression the model computes (:mod:`ropemodel.core.formulas`), the
same entry the calculation sheet writes (:mod:`ropemodel.reports.sheet`): the page cannot show one
formula and compute another.
"""

from __future__ import annotations

from ropemodel.citations import CITATIONS
from ropemodel.core.formulas import shown
from ropemodel.reports import page
from ropemodel.reports.registry import section
from ropemodel.reports.sections.inputs import derived_note
from ropemodel.reports.sheet import groups

GROUP = """<h3>{{ effect }} = "{{ variant }}": {{ description }}{% if refs %} [{{ refs }}]{% endif %}</h3>
{% for e in equations %}
<div class="eq"><span class="formula">{% if e.formula %}{{ e.formula | formula }}{% else %}{{ e.symbol | typeset }}:
{{ e.source }}{% endif %}</span><span class="eqno">{{ e.label }}</span></div>
{% if e.method %}<div class="numbers method">{{ e.method }}</div>{% endif %}
<div class="numbers"><span class="name">{{ e.defines }}</span> = {{ e.value }}{% if e.note %} ({{ e.note }}){% endif %}
{% if e.inputs %}&ensp;with {% for n, v in e.inputs %}
<span class="name">{{ n }}</span> = {{ v }}{{ ", " if not loop.last }}
{% endfor %}{% endif %}</div>
{% endfor %}"""

INTRO = """<p>Each equation as the paper numbers it (right), printed from the expression ropemodel computes, then
its numbers{{ at }}: the quantity it defines, and the values it is computed from. Names are the scene's
(F_C_up: F<sub>C,up</sub>, travelling up). Where a value is the root of an equation or an integral, the
equation it solves is shown with the method and its tolerance. The same equations, with a Python expression
that recomputes each, are the calculation sheet: <code>ropemodel report SCENE --format json</code>.
References in brackets are listed under "References".</p>"""

KIND = {"closed": "", "implicit": "solved by ", "numerical": "computed by "}


def reference_numbers(model) -> dict[str, int]:
    """Citation key → its number in the references list (the order of ``model.citations``)."""
    full = list(model.citations)
    return {k: full.index(text) + 1 for k, text in CITATIONS.items() if text in full}


def entries(model, values: dict, equations) -> list[dict]:
    """What the template shows of each equation: formula, label (its source), method, numbers."""
    q = model.quantities
    out = []
    for eq in equations:
        s = shown(model, eq)
        method = s.method if s.kind != "closed" else ""
        out.append({
            "formula": s.formula,
            "label": eq.source if s.formula else "",
            "source": eq.source,
            "symbol": q[eq.defines].typeset,
            "method": f"{KIND[s.kind]}{method}" if method else "",
            "defines": eq.defines,
            "value": page.show(q[eq.defines], values.get(eq.defines)),
            "note": derived_note(model, eq.defines),
            "inputs": [(n, page.show(q[n], values.get(n))) for n in s.inputs],
        })
    return out


@section("equations", "Equations")
def equations(ctx):
    result = ctx.result
    model = result.model
    numbers = reference_numbers(model)
    html = page.fragment(INTRO, at=" at the recommended design" if ctx.at_design else "")
    for sm, eqs in groups(model):
        refs = ", ".join(str(numbers[k]) for k in sm.citations if k in numbers)
        html += page.fragment(GROUP, effect=sm.effect, variant=sm.variant, description=sm.description, refs=refs,
                              equations=entries(model, result.values, eqs))
    return html
