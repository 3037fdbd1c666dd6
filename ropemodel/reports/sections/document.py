"""Section "document": the document's number and revision, the sign-off block and the revision history.

They come from the scene's ``[report]`` table (:mod:`ropemodel.scene_report`); the block is always there, its
names and dates left blank where the scene gives none, to be signed by hand.  The printed page carries the
document and revision in its running header (:func:`running_header`).
"""

from __future__ import annotations

from ropemodel.reports import page
from ropemodel.reports.registry import section
from ropemodel.scene_report import ROLES, Filing

HEAD = """<dl class="head">
<dt>document</dt><dd>{{ f.document or "no document number (give [report] document)" }}</dd>
{% if f.project %}<dt>project</dt><dd>{{ f.project }}</dd>{% endif %}
<dt>revision</dt><dd>{{ f.revision or "no revision (give [report] revision)" }}</dd>
<dt>calculated</dt><dd>{{ date }}, ropemodel {{ version }}</dd>
</dl>"""

ROLE_TEXT = {"prepared": "Prepared by", "checked": "Checked by", "approved": "Approved by"}


def filing(ctx) -> Filing:
    """The scene's ``[report]``, or an empty one (every field to be filled by hand)."""
    return ctx.scene.filing or Filing()


def title(ctx) -> str:
    """The page's title: ``[report] title``, else "Design report: <scene name>"."""
    return filing(ctx).title or f"Design report: {ctx.scene.name}"


def running_header(ctx) -> tuple[str, str, str]:
    """(header left, header right, footer left) of each printed page."""
    f = filing(ctx)
    left = " · ".join(x for x in (f.document, f"revision {f.revision}" if f.revision else "") if x)
    digest = ctx.scene.digest
    foot = f"scene {ctx.scene.source or ctx.scene.name}" + (f", SHA-256 {digest[:16]}…" if digest else "")
    return left or "design report (no document number)", title(ctx), foot


def signoff_rows(f: Filing) -> list[list[str]]:
    """One row per role: role, name, date, signature (blank, signed by hand)."""
    by_role = {s.role: s for s in f.signatures}
    return [[ROLE_TEXT[r], by_role[r].name or "", str(by_role[r].date or ""), ""] for r in ROLES]


@section("document", "Document")
def document(ctx):
    from ropemodel.reports.sections.scene import stamp, version

    f = filing(ctx)
    html = page.fragment(HEAD, f=f, date=stamp(ctx), version=version())
    html += page.fragment("<h3>Sign-off</h3>")
    html += page.table(["", "name", "date", "signature"], signoff_rows(f), cls="signoff")
    html += page.fragment("<h3>Revision history</h3>")
    if f.history:
        html += page.table(["revision", "date", "description", "by"],
                           [[r.revision, str(r.date), r.description, r.by] for r in f.history], cls="history")
    else:
        html += page.fragment('<p class="note">No revision history given ([[report.history]] in the scene).</p>')
    return html
