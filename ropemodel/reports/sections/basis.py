"""Sections "rope" (the rope's full designation) and "basis" (every normative number with its source and
status, the assumptions, the data still missing): :mod:`ropemodel.reports.filing`."""

from __future__ import annotations

from ropemodel.errors import RopeModelError
from ropemodel.reports import filing, page
from ropemodel.reports.registry import section

ROPE_ROWS = ("designation", "standard", "class", "core", "construction", "nominal diameter", "rope grade",
             "minimum breaking force", "wire finish", "lay", "maker", "test certificate")


def values(ctx) -> dict:
    """SI values at the point reported (the scene's parameters where the solve cannot be had)."""
    try:
        return ctx.result.values
    except RopeModelError:
        return ctx.scene.parameters


def _has_rope(ctx) -> bool:
    return filing.catalogue_rope(ctx.scene.built) is not None


@section("rope", "Rope", when=_has_rope)
def rope(ctx):
    d = filing.rope_designation(ctx.scene, values(ctx))
    rows = [[k, d[k] or "not given"] for k in ROPE_ROWS]
    html = page.table(["element", "value"], rows, kinds=["name", ""], cls="rope")
    html += page.fragment('<p class="note">Designation system: {{ d.system }} (status: {{ d.status }}; '
                          '{{ d.evidence }}) A "?" in the designation is an element not given: see "Data still '
                          'missing".</p>', d=d)
    return html


@section("basis", "Basis of the calculation")
def basis(ctx):
    scene = ctx.scene
    numbers = filing.normative_numbers(scene)
    html = page.fragment("<h3>Normative numbers</h3>")
    if numbers:
        html += page.table(["number", "value", "what it is", "source", "status"],
                           [[n["name"], n["value"], n["what"], n["source"], n["status"]] for n in numbers],
                           kinds=["name", "num", "", "", ""], cls="normative")
        html += page.fragment('<p class="note">Statuses: {{ s }}.</p>',
                              s="; ".join(f"{k}: {v}" for k, v in filing.STATUS_TEXT.items()))
    else:
        html += page.fragment("<p>This model uses no normative number.</p>")
    html += page.fragment("<h3>Assumptions</h3>") + _items(filing.assumptions(scene, ctx.reads), "assumptions")
    html += page.fragment("<h3>Data still missing</h3>")
    html += _items(filing.missing(scene, values(ctx)), "missing") or page.fragment("<p>None.</p>")
    return html


def _items(lines: list[str], cls: str):
    return page.fragment('<ol class="{{ c }}">{% for x in lines %}<li>{{ x }}</li>{% endfor %}</ol>', c=cls,
                         lines=lines) if lines else ""
