"""``ropemodel report SCENE [--set NAME=VALUE ...] [-o report.html] [--pdf report.pdf]``: a design report.

One self-contained HTML page (no network resource: styles inline, pictures as data URIs) with the
scene and its file's SHA-256, the inputs and where each came from, the equations with their
numbers, the results, every design check, the sizing, the transient, what matters most and the
references (:mod:`ropemodel.reports`).  ``--pdf``: the page printed by headless Chromium.
``--format json -o calc.json``: the calculation sheet instead of the page, every equation with a
Python expression that recomputes it (:mod:`ropemodel.reports.sheet`).

Outputs are checked before any work, locked while written, written under a temporary name and
renamed into place.  Exit 0: written; 1: written, but a section could not be computed (named on
stderr and in the page), or a file could not be written; 2: bad input (the scene's own list of
problems, an output that cannot be written, Chromium missing for --pdf, the ``report`` extra missing).
"""

from __future__ import annotations

import tempfile
from contextlib import ExitStack
from pathlib import Path

from ropemodel.cli._common import assignments, warn
from ropemodel.errors import InputError
from ropemodel.progress import status

NAME = "report"
HELP = "write a design report of a scene: a self-contained HTML page (-o) and/or its PDF (--pdf, headless Chromium)"
HTML = (".html", ".htm")
PDF = (".pdf",)
JSON = (".json",)


def add_arguments(parser) -> None:
    parser.add_argument("scene", help="scene TOML file, or the name of a built-in scene ('example' for Fig. 9)")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a parameter; a dimensional VALUE carries its unit, e.g. alpha_u=20deg")
    parser.add_argument("-o", "--output", metavar="FILE", help="write the report as one HTML page (FILE.html), or "
                        "with --format json the calculation sheet (FILE.json)")
    parser.add_argument("--format", choices=("html", "json"), default="html",
                        help="what -o writes: the page (html, default) or the calculation sheet (json: every "
                        "equation with its inputs, value and a Python expression that recomputes it)")
    parser.add_argument("--pdf", metavar="FILE.pdf", help="write the report as PDF (printed by headless Chromium)")
    parser.add_argument("--discrete", choices=("next-size-up", "bonmin"), default=None,
                        help="sizing scenes: how to pick the catalogue diameter (default: next-size-up)")


def _outputs(args) -> tuple[Path | None, Path | None]:
    from ropemodel.sweeps.files import check_output

    if not args.output and not args.pdf:
        raise InputError("nothing to write: give -o FILE.html and/or --pdf FILE.pdf (or --format json -o FILE.json)")
    if args.format == "json" and not args.output:
        raise InputError("--format json writes the calculation sheet to -o FILE.json: give -o")
    html = check_output(args.output, JSON if args.format == "json" else HTML) if args.output else None
    pdf = check_output(args.pdf, PDF) if args.pdf else None
    if html is not None and pdf is not None and html.resolve() == pdf.resolve():
        raise InputError(f"-o and --pdf name the same file {html}")
    return html, pdf


def _sheet_text(ctx) -> str:
    """The calculation sheet as JSON text (standard JSON: no NaN, no Infinity)."""
    import json

    from ropemodel.reports.sheet import sheet

    return json.dumps(sheet(ctx), indent=1, ensure_ascii=False, allow_nan=False) + "\n"


def _write_text(path: Path, text: str) -> None:
    from ropemodel.sweeps.files import write_atomic

    def write(tmp):
        tmp.write_text(text, encoding="utf-8")

    def check(tmp):
        if tmp.read_text(encoding="utf-8") != text:
            raise OSError("the file written does not read back as written")

    write_atomic(path, write, check)


def _write_pdf(path: Path, text: str, exe: str | None) -> None:
    from ropemodel.reports.browser import print_pdf
    from ropemodel.sweeps.files import write_atomic

    def check(tmp):
        data = tmp.read_bytes()
        if not data.startswith(b"%PDF-") or b"%%EOF" not in data[-1024:]:
            raise OSError("Chromium's PDF is not a complete PDF file")

    with tempfile.TemporaryDirectory(prefix="ropemodel-report-") as d:
        page = Path(d) / "report.html"
        page.write_text(text, encoding="utf-8")
        write_atomic(path, lambda tmp: print_pdf(page, tmp, exe), check)


def _make(ctx, sheet: bool, page: bool):
    """(text for -o, the page for --pdf or None, the verdicts, the sections not computed)."""
    from ropemodel.reports import build
    from ropemodel.reports.build import verdicts

    with status(f"report of {ctx.scene.name}: computing and drawing"):
        if not page:        # the sheet alone: the page's sections are not drawn
            return _sheet_text(ctx), None, verdicts(ctx), []
        report = build(ctx)
        text = _sheet_text(ctx) if sheet else report.html
    return text, report.html, report.verdicts, report.incomplete


def main(args) -> int:
    from ropemodel.reports import load
    from ropemodel.reports.browser import find
    from ropemodel.reports.build import requirements
    from ropemodel.sweeps.files import OutputError, OutputLock, cause

    html, pdf = _outputs(args)
    exe = find() if pdf is not None else None
    requirements()
    ctx = load(args.scene, assignments(args.set, "--set"), method=args.discrete)
    warn(ctx.scene.warnings)
    with ExitStack() as locks:
        for locked in (p for p in (html, pdf) if p is not None):
            locks.enter_context(OutputLock(locked))
        sheet = args.format == "json"
        text, page, lines, incomplete = _make(ctx, sheet, page=pdf is not None or not sheet)
        writers = ((html, lambda p: _write_text(p, text)), (pdf, lambda p: _write_pdf(p, page, exe)))
        written: list[Path] = []
        for path, write in writers:
            if path is None:
                continue
            kept = f"; {written[0]} was written" if written else "; nothing was written"
            try:
                write(path)
            except OSError as exc:
                raise OutputError(f"cannot write {path}: {cause(exc)}{kept}") from None
            except OutputError as exc:   # the browser could not print
                raise OutputError(f"cannot write {path}: {exc}{kept if written else ''}") from None
            written.append(path)
    for path in written:
        print(f"wrote {path}")
    for line in lines:
        print(line)
    for name, why in incomplete:
        warn([f"section {name!r} could not be computed (the page says why): {why.splitlines()[0]}"])
    return 1 if incomplete else 0
