"""Section "equations": every equation used, numbered as in its paper, each followed by its numbers."""

from __future__ import annotations

from ropemodel.citations import CITATIONS
from ropemodel.reports import page
from ropemodel.reports.registry import section
from ropemodel.reports.sections.inputs import derived_note

GROUP = """<h3>{{ effect }} = "{{ variant }}": {{ description }}{% if refs %} [{{ refs }}]{% endif %}</h3>
{% for e in equations %}
<div class="eq"><span class="formula">{{ e.formula | typeset }}</span><span class="eqno">{{ e.label }}</span></div>
<div class="numbers"><span class="name">{{ e.defines }}</span> = {{ e.value }}{% if e.note %} ({{ e.note }}){% endif %}
{% if e.inputs %}&ensp;with {% for n, v in e.inputs %}
<span class="name">{{ n }}</span> = {{ v }}{{ ", " if not loop.last }}
{% endfor %}{% endif %}</div>
{% endfor %}"""

INTRO = """<p>Each equation as the paper numbers it (right), then its numbers{{ at }}: the quantity it defines, and
the values it is computed from. Names are the scene's (F_C_up: F<sub>C</sub> travelling up). References in
brackets are listed under "References".</p>"""


def reference_numbers(model) -> dict[str, int]:
    """Citation key → its number in the references list (the order of ``model.citations``)."""
    full = list(model.citations)
    return {k: full.index(text) + 1 for k, text in CITATIONS.items() if text in full}


def entries(model, values: dict, equations) -> list[dict]:
    """What the template shows of each equation: formula (or its source when it has none), label, numbers."""
    q = model.quantities
    out = []
    for eq in equations:
        names = [n for n in eq.names() if n != eq.defines]
        out.append({
            "formula": eq.formula or eq.source,
            "label": eq.source if eq.formula else "",
            "defines": eq.defines,
            "value": page.show(q[eq.defines], values.get(eq.defines)),
            "note": derived_note(model, eq.defines),
            "inputs": [(n, page.show(q[n], values.get(n))) for n in names],
        })
    return out


@section("equations", "Equations")
def equations(ctx):
    result = ctx.result
    model = result.model
    numbers = reference_numbers(model)
    html = page.fragment(INTRO, at=" at the recommended design" if ctx.at_design else "")
    for sm in model.submodels:
        eqs = [eq for eq in model.equations if model.defined_by[eq.defines] == sm.effect]
        if not eqs:
            continue
        refs = ", ".join(str(numbers[k]) for k in sm.citations if k in numbers)
        html += page.fragment(GROUP, effect=sm.effect, variant=sm.variant, description=sm.description, refs=refs,
                              equations=entries(model, result.values, eqs))
    return html
