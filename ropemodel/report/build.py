"""Build the page of a report: every section that applies, in order; a section that cannot be
computed shows why, and is listed in :attr:`Report.incomplete`."""

from __future__ import annotations

from dataclasses import dataclass, field

from ropemodel.errors import RopeModelError, require
from ropemodel.report import page
from ropemodel.report.context import Context
from ropemodel.report.registry import sections
from ropemodel.report.sections.scene import stamp, version


@dataclass
class Report:
    """A built report: the page (HTML text), the sections shown, those that could not be computed."""

    html: str
    shown: list[str] = field(default_factory=list)
    #: (section name, why it could not be computed)
    incomplete: list[tuple[str, str]] = field(default_factory=list)


def requirements() -> None:
    """:class:`~ropemodel.errors.InputError` naming the ``report`` extra if Jinja2 or matplotlib is missing."""
    require("jinja2", "report")
    require("matplotlib", "report")


def build(ctx: Context) -> Report:
    """The report of ``ctx`` (see :func:`ropemodel.report.context.load`)."""
    requirements()
    report, parts = Report(""), []
    for s in sections():
        try:
            if not s.applies(ctx):
                continue
            html = page.markup(s.render(ctx))   # a section's HTML is kept as it is (it escapes what it quotes)
        except RopeModelError as exc:
            report.incomplete.append((s.name, str(exc)))
            html = page.error(f"Not computed: {exc}")
        parts.append((s.name, s.title, html))
        report.shown.append(s.name)
    report.html = page.page(f"Design report: {ctx.scene.name}", version(), stamp(ctx), parts)
    return report
