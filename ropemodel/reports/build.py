"""Build the page of a report: every section that applies, in order; a section that cannot be
computed shows why, and is listed in :attr:`Report.incomplete`."""

from __future__ import annotations

from dataclasses import dataclass, field

from ropemodel.errors import RopeModelError, require
from ropemodel.reports import page
from ropemodel.reports.context import Context
from ropemodel.reports.registry import declared, sections
from ropemodel.reports.sections.document import running_header, title
from ropemodel.reports.sections.scene import stamp, version
from ropemodel.scene import SceneLike


@dataclass
class Report:
    """A built report: the page (HTML text), the sections shown, those that could not be computed."""

    html: str
    shown: list[str] = field(default_factory=list)
    #: (section name, why it could not be computed)
    incomplete: list[tuple[str, str]] = field(default_factory=list)
    #: the conclusions, one line each (checks, sizing)
    verdicts: list[str] = field(default_factory=list)


def requirements() -> None:
    """:class:`~ropemodel.errors.InputError` naming the ``report`` extra if Jinja2 or matplotlib is missing."""
    require("jinja2", "report")
    require("matplotlib", "report")


def report(scene: SceneLike, values: dict | None = None, method: str | None = None) -> Report:
    """The design report of a scene: one self-contained HTML page (``ropemodel report``).

    Parameters
    ----------
    scene : Scene or str or Path
        A loaded scene, a scene TOML file or the name of a built-in scene (``"example"``: Krauze et al.
        2025, Fig. 9).  A sizing scene (a winch with a catalogue rope) is sized, and the page reports
        the design.
    values : dict, optional
        Parameters that replace or complete the file's, ``{name: value}`` (SI floats, strings with
        units, pint Quantities), checked with the file's.
    method : {"next-size-up", "bonmin"}, optional
        Sizing scenes: how to pick the catalogue diameter.

    Returns
    -------
    Report
        ``html`` (the page: styles inline, pictures as SVG data URIs, no network resource),
        ``shown`` (the sections on it), ``incomplete`` (sections that could not be computed, and
        why; the page says so in their place) and ``verdicts`` (the checks and the sizing, one line
        each).  Write it with ``Path("report.html").write_text(r.html, encoding="utf-8")``; the PDF:
        ``ropemodel report SCENE --pdf report.pdf`` (headless Chromium).

    Raises
    ------
    InputError
        Every problem of the scene and of ``values`` at once; the ``report`` extra (Jinja2,
        matplotlib) missing.

    Examples
    --------
    >>> import ropemodel as rm
    >>> r = rm.report("example")
    >>> "190.949" in r.html and r.incomplete == []       # F_C_up of Fig. 9, kN
    True
    >>> r.shown[:5]
    ['document', 'scene', 'inputs', 'basis', 'equations']
    """
    from ropemodel.reports.context import load

    requirements()
    return build(load(scene, values, origin="values", method=method))


def build(ctx: Context) -> Report:
    """The report of ``ctx`` (see :func:`ropemodel.reports.context.load`)."""
    requirements()
    report, parts = Report(""), []
    for s in sections():
        try:
            if not (declared(s.name, ctx.scene) and s.applies(ctx)):
                continue
            html = page.markup(s.render(ctx))   # a section's HTML is kept as it is (it escapes what it quotes)
        except RopeModelError as exc:
            report.incomplete.append((s.name, str(exc)))
            html = page.error(f"Not computed: {exc}")
        parts.append((s.name, s.title, html))
        report.shown.append(s.name)
    report.html = page.page(title(ctx), version(), stamp(ctx), parts, running_header(ctx))
    report.verdicts = verdicts(ctx)
    return report


def verdicts(ctx: Context) -> list[str]:
    """The report's conclusions in one line each: the checks, the sizing (what was computed)."""
    from ropemodel.reports.sections.results import margins_of
    from ropemodel.reports.sections.sizing import design_text

    out = []
    try:
        values = ctx.result.values
        names = margins_of(ctx.result.outputs, ctx.scene)
    except RopeModelError:
        names = []
    if names:
        failed = [n for n in names if values[n] < 0]
        where = "at the recommended design" if ctx.at_design else "at the scene's values"
        out.append(f"checks {where}: " + (f"{len(failed)} of {len(names)} FAIL ({', '.join(failed)})" if failed
                                          else f"all {len(names)} pass"))
    if ctx.sizing:
        try:
            design = ctx.design
            out.append(f"sizing: design {design_text(design)}, every check met" if design.feasible
                       else "sizing: no design meets every check")
        except RopeModelError:
            pass
    return out
