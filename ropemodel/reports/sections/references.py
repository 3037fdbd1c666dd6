"""Section "references": the papers behind the results (the citations of every submodel used)."""

from __future__ import annotations

from ropemodel.reports import page
from ropemodel.reports.registry import section


@section("references", "References")
def references(ctx):
    cited = ctx.scene.built.citations
    return page.fragment('<ol>{% for c in cited %}<li id="ref-{{ loop.index }}">{{ c }}</li>{% endfor %}</ol>',
                         cited=cited)
