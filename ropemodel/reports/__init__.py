"""Design reports: one self-contained HTML page (and its PDF) that a checker or an authority can file.

::

    from ropemodel.reports import build, load
    report = build(load("winch_sizing_fig9"))      # or load("my_scene.toml", {"alpha_u": "18 deg"})
    report.html                                     # the page; report.incomplete: sections not computed

or ``ropemodel report SCENE -o report.html --pdf report.pdf`` (:mod:`ropemodel.cli.report`).

The page refers to nothing outside itself: styles inline, no script, no font to fetch, pictures
as SVG ``data:`` URIs.  The PDF is the page printed by headless Chromium (:mod:`.browser`).
Needs the ``report`` extra (Jinja2, matplotlib).

Modules: :mod:`.context` (the scene and its analyses, each computed once when a section asks),
:mod:`.sheet` (the calculation sheet, ``--format json``), :mod:`.filing` (designation, normative numbers,
assumptions, missing data),
:mod:`.registry` (the sections), :mod:`.build` (the page), :mod:`.page` (Jinja2, escaping,
tables, formulas), :mod:`.figures` (matplotlib → SVG), :mod:`.browser` (Chromium),
:mod:`.sections` (one module per group of sections).

Sections
--------
A report is a list of *sections*.  Each is a function ``render(ctx) -> str`` returning an HTML
fragment, registered with a title and a predicate ``when(ctx) -> bool`` saying when it applies
(:func:`ropemodel.reports.registry.section`).  ``ctx`` is a :class:`~ropemodel.reports.context.Context`:
``ctx.scene`` (the scene as loaded), ``ctx.point`` (the scene at the values reported: its own, or a
sizing scene's recommended design), ``ctx.result`` (the forward solve there), ``ctx.design`` (the
sizing, when ``ctx.sizing``), ``ctx.simulation`` (the transient), ``ctx.at_design``.  A section that
raises a :class:`~ropemodel.errors.RopeModelError` shows the error in its place and is listed as
incomplete (``ropemodel report`` then exits 1).

The sections today, in page order (:data:`ropemodel.reports.sections.MODULES`): document (number,
revision, sign-off, history: the scene's ``[report]``), scene, inputs, rules, rope (its designation),
basis (normative numbers with source and status, assumptions, data still missing), equations (printed from
the model's expressions; the same as the calculation sheet, :mod:`.sheet`), results, checks (when the
model has margins), sizing (a winch with a catalogue rope), transient (``dynamics`` not ``"none"``), trip
(``dynamics = "trip"`` or a route of segments, with v_pj and t_ramp), sensitivity, references.

Adding a section, e.g. the energy cost of a trip on a route of segments: a module
``ropemodel/reports/sections/energy.py``::

    from ropemodel.reports import page
    from ropemodel.reports.registry import section
    from ropemodel.reports.sections.trip import reads

    PRICE = 0.15   # per kWh: an assumed tariff


    @section("energy", "Energy cost", when=lambda ctx: ctx.scene.effects.get("route") == "segments", reads=reads)
    def energy(ctx):
        kwh = {d: run.summary["E_trip"] / 3.6e6 for d, run in ctx.trips.items()}
        return page.table(["trip", "energy [kWh]", "cost at 0.15 per kWh"],
                          [[d, f"{e:.3f}", f"{PRICE * e:.2f}"] for d, e in kwh.items()])

and its name in :data:`ropemodel.reports.sections.MODULES` where it belongs (after ``"trip"``).  A section
whose numbers come from more than the equations' inputs says what else it reads (``reads=``, here the trips'
parameters): the basis of the calculation lists a default as an assumption only where a section reads it
(:attr:`Context.reads`).
That is the one place: the page, its table of contents, the error handling and the tests of every
built-in scene (``tests/test_report*.py``: no network reference, not blank in Chromium) pick it up.
"""

from ropemodel.reports.build import Report, build
from ropemodel.reports.context import Context, load
from ropemodel.reports.registry import SECTIONS, Section, section

__all__ = ["Context", "Report", "SECTIONS", "Section", "build", "load", "section"]
