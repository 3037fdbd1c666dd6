"""Section "inputs": every parameter with its unit and where it came from; what the rope catalogue
derived; the defaults used and why; unused parameters; warnings."""

from __future__ import annotations

from ropemodel.errors import RopeModelError
from ropemodel.machines import machine_of
from ropemodel.reports import page
from ropemodel.reports.registry import section

#: scene.origin → what the report says
ORIGIN = {"scene": "scene file", "default": "default (see below)", "--set": "--set on the command line",
          "route": "[[route]] segment", "api": "Python API", "sizing": "chosen by the sizing",
          "rules": "rule set (see \"Rules\")", "rules override": "override in [rules] (see \"Rules\")"}
CATALOGUE = "derived from the rope catalogue"


def origin(scene, name: str) -> str:
    where = scene.origin.get(name, "")
    return ORIGIN.get(where, where or "-")


def catalogue_rope(model):
    """The catalogue rope submodel of ``model`` (an EN 12385-4 construction: its machine's ``ropes``), or None."""
    ropes = getattr(machine_of(model.name), "ropes", ())
    return next((sm for sm in model.submodels if isinstance(sm, ropes)), None)


def derived(model) -> list[str]:
    """Outputs of ``model`` derived from the rope catalogue (q_l, q_lw, F_min, ...), in model order."""
    rope = catalogue_rope(model)
    if rope is None:
        return []
    return [n for n in model.outputs if model.defined_by[n] == rope.effect]


def derived_note(model, name: str) -> str:
    """``"derived from the rope catalogue (rope = ...)"`` for such an output, else ``""``."""
    rope = catalogue_rope(model)
    if rope is None or name not in derived(model):
        return ""
    return f"{CATALOGUE} (rope = \"{rope.variant}\")"


@section("inputs", "Inputs")
def inputs(ctx):
    s, q = ctx.scene, ctx.quantities
    try:
        point = ctx.point      # a sizing scene's design variables, once chosen, are inputs of the rest
    except RopeModelError:
        point = s
    rows = [[n, page.show(q[n], point.parameters[n]), q[n].description, origin(point, n)]
            for n in s.built.parameters if n in point.parameters]
    html = page.table(["parameter", "value", "meaning", "from"], rows, kinds=["name", "num", "", ""], cls="inputs")
    left = [n for n in s.absent if n not in point.parameters]
    if left:
        html += page.fragment('<p class="note">Left to the sizing, which found no design (see "Sizing"): '
                              "{{ names }}.</p>", names=", ".join(left))
    html += _derived(ctx)
    html += _defaults(s)
    if s.unused:
        html += page.fragment("<h3>Unused parameters</h3><p>Given, but not used by the chosen effects:</p>")
        html += page.table(["parameter", "used by"], [[n, by] for n, by in s.unused.items()], kinds=["name", ""],
                           cls="unused")
    if s.checks:
        html += page.fragment("<h3>Computed quantities given as checks</h3><p>Each agrees with the value the "
                              "scene computes, to the digits typed (verified when the scene was read).</p>")
        html += page.table(["quantity", "as typed"], [[n, c.text] for n, c in s.checks.items()], kinds=["name", ""])
    html += page.fragment("<h3>Warnings</h3>{% if w %}<ul>{% for x in w %}<li>{{ x }}</li>{% endfor %}</ul>"
                          "{% else %}<p>None.</p>{% endif %}", w=list(s.warnings))
    return html


def _derived(ctx):
    model = ctx.scene.built
    names = derived(model)
    if not names:
        return ""
    rope = catalogue_rope(model)
    try:
        values = ctx.result.values
    except RopeModelError:
        values = {}
    q = ctx.quantities
    rows = [[page.escape(n), page.show(q[n], values.get(n)), q[n].description, CATALOGUE] for n in names]
    html = page.fragment("<h3>Derived from the rope catalogue</h3><p>rope = \"{{ v }}\": {{ d }}. These are "
                         "computed from the diameter d and the construction's factors, not measured on the installed "
                         "rope; the unit elongation q_lw in particular follows from the assumed modulus rope_E "
                         "(q_lw = L_u / (E C d²)){{ at }}.</p>", v=rope.variant, d=rope.description,
                         at=" (at the recommended design)" if ctx.at_design else "")
    return html + page.table(["quantity", "value", "meaning", "from"], rows, kinds=["name", "num", "", ""],
                             cls="derived")


def _defaults(scene):
    if not scene.defaults:
        return page.fragment("<h3>Defaults used</h3><p>None: the scene gives every parameter.</p>")
    q = scene.built.quantities
    rows = [[page.escape(n), page.show(q[n], scene.parameters[n]), why] for n, why in scene.defaults.items()
            if n in scene.parameters]
    return page.fragment("<h3>Defaults used</h3>") + page.table(["parameter", "value", "why this value"], rows,
                                                               kinds=["name", "num", ""], cls="defaults")
