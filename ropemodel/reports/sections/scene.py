"""Section "scene": what was calculated, from which file (and its SHA-256), by which version, when."""

from __future__ import annotations

from ropemodel.machines.base import declared_machine
from ropemodel.reports import page
from ropemodel.reports.registry import section

HEAD = """<dl class="head">
<dt>scene</dt><dd>{{ scene.name }}</dd>
{% if description %}<dt>description</dt><dd>{{ description }}</dd>{% endif %}
<dt>model</dt><dd>{{ scene.model }}</dd>
<dt>source file</dt><dd>{{ scene.source or "built in Python (no file)" }}</dd>
<dt>SHA-256 of the file</dt><dd><code>{{ scene.digest or "none (no file)" }}</code></dd>
<dt>ropemodel version</dt><dd>{{ version }}</dd>
<dt>date</dt><dd>{{ date }}</dd>
{% if ctx.sizing %}<dt>sizing</dt><dd>yes: {{ sized }}; design
checks switched on</dd>{% endif %}
</dl>"""


def version() -> str:
    from ropemodel import __version__

    return __version__


def stamp(ctx) -> str:
    """The report's date and time (UTC), as the page shows it."""
    return ctx.created.strftime("%Y-%m-%d %H:%M UTC")


@section("scene", "Scene")
def scene(ctx):
    s = ctx.scene
    description = s.raw.get("scene", {}).get("description", "") if isinstance(s.raw.get("scene"), dict) else ""
    sized = page.fragment(declared_machine(s).sizing.SCENE_TEXT, scene=s) if ctx.sizing else ""
    html = page.fragment(HEAD, scene=s, description=description, version=version(), date=stamp(ctx), ctx=ctx,
                         sized=sized)
    html += page.fragment("<h3>Effects (the submodels chosen)</h3>")
    built = s.built.built_effects
    rows = [[sm.effect, sm.variant, sm.description] for sm in s.built.submodels if sm.effect in built]
    html += page.table(["effect", "variant", "what it models"], rows, kinds=["name", "name", ""], cls="effects")
    idle = [f"{e} = \"{v}\"" for e, v in s.effects.items() if e not in built]
    if idle:
        html += page.fragment('<p class="note">Also chosen, building no equation of the static model: {{ i }}.</p>',
                              i=", ".join(idle))
    if s.numerics:
        html += page.fragment("<h3>Numerics</h3>")
        html += page.table(["option", "value"], [[k, repr(v)] for k, v in s.numerics.items()], kinds=["name", ""],
                           cls="numerics")
    return html
