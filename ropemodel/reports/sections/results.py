"""Sections "results" (every output in the paper's units, up and down side by side, and the model's
extra tables) and "checks" (every design check with its margin, passed or failed)."""

from __future__ import annotations

import re

from ropemodel.errors import RopeModelError
from ropemodel.machines import default, machine_of
from ropemodel.reports import figures, page
from ropemodel.reports.registry import section
from ropemodel.reports.sections.inputs import derived_note

_DIR = re.compile(r"^(?P<base>.+)_(?P<dir>up|down)$")
#: the direction a pair's description names (the table's columns say it)
_TRAVEL = re.compile(r" \((?:upward|downward) travel\)$")
#: extra tables of a result that another section shows (the checks section shows the design checks)
SHOWN_ELSEWHERE = ("design checks",)
#: a margin this close to 0 [SI] is shown as 0 (an active check, met exactly up to rounding)
ZERO = 1e-9


def _machine(scene):
    """``scene``'s machine (the default machine's order and words for no scene, or a model that declares none)."""
    return (machine_of(scene) if scene is not None else None) or default()


def margins_of(names, scene=None) -> list[str]:
    """The margin outputs among ``names``: the checks of ``scene``'s machine (its report order), then any other
    ``*_margin*``."""
    names = list(names)
    known = _machine(scene).checks(names)
    return known + [n for n in names if "_margin" in n and n not in known]


def _source(model, name: str) -> str:
    src = model.equation_of(name).source if name in model.defined_by else ""
    note = derived_note(model, name)
    return f"{src}; {note}" if src and note else src or note


def _pairs(outputs) -> tuple[list[str], list[str]]:
    """(single outputs, bases of up/down pairs), in model order."""
    singles, bases = [], []
    for o in outputs:
        m = _DIR.match(o)
        if m is None:
            singles.append(o)
        elif m["base"] not in bases:
            bases.append(m["base"])
    return singles, bases


@section("results", "Results")
def results(ctx):
    result = ctx.result
    model, values, q = result.model, result.values, result.model.quantities
    outputs = [o for o in result.outputs if o not in set(margins_of(result.outputs, ctx.scene))]
    singles, bases = _pairs(outputs)
    html = page.fragment("<p>In the paper's units{{ at }}; equation numbers as in the papers.</p>",
                         at=", at the recommended design" if ctx.at_design else "")
    if bases:
        rows = []
        for b in bases:
            one = f"{b}_up" if f"{b}_up" in values else f"{b}_down"
            meaning = _TRAVEL.sub("", q[one].description)
            rows.append([b] + [page.show(q[f"{b}_{d}"], values[f"{b}_{d}"]) if f"{b}_{d}" in values else ""
                               for d in ("down", "up")] + [meaning, _source(model, one)])
        html += page.fragment("<h3>Both directions of travel</h3>")
        html += page.table(["quantity", "down", "up", "meaning", "equation"], rows,
                           kinds=["name", "num", "num", "", ""], cls="pairs")
    if singles:
        rows = [[n, page.show(q[n], values[n]), _meaning(q[n].description, result.where.get(n)), _source(model, n)]
                for n in singles]
        html += page.fragment("<h3>Single quantities</h3>")
        html += page.table(["quantity", "value", "meaning", "equation"], rows, kinds=["name", "num", "", ""],
                           cls="singles")
    html += worst_html(result)
    for title, frame in result.frames.items():
        if title not in SHOWN_ELSEWHERE:
            html += frame_html(title, frame)
    return html


def worst_html(result) -> str:
    """For a result at its worst case: where each result is worst (its extremes, their places and manoeuvres),
    and the results that vary with the case but have no worst."""
    env = getattr(result, "envelope", None)
    if env is None:
        return ""
    q = result.model.quantities
    rows = [[n, e.sense, page.show(q[n], e.value), e.text(env.params)] for n, ext in env.extremes.items()
            for e in ext]
    html = page.fragment("<h3>Where each result is worst</h3><p>Over {{ s }}, both directions of travel.</p>",
                         s=result.cases_text())
    html += page.table(["quantity", "worst", "value", "where"], rows, kinds=["name", "", "num", ""], cls="worst")
    if env.no_worst:
        html += page.fragment('<p class="note">Vary with the load\'s place or the manoeuvre and have no worst '
                              "(given at one point with <code>--set x_m=...</code>): {{ n }}.</p>",
                              n=", ".join(env.no_worst))
    return html


def _meaning(description: str, where: str | None) -> str:
    """A quantity's meaning, and where its worst case is when it is taken at its worst."""
    return f"{description}; worst case: {where}" if where else description


def frame_html(title: str, frame):
    """An extra table of the model, with a picture of its numeric columns against the first one."""
    html = page.fragment("<h3>{{ t }}</h3>", t=title)
    if len(frame) >= 10 and len(frame.columns) >= 2:
        uri = figures.panels(frame, frame.columns[0], list(figures.columns_by_unit(frame)))
        if uri:
            html += page.fragment('<figure><img src="{{ u }}" alt="{{ t }}"></figure>', u=uri, t=title)
    rows = [[f"{v:.6g}" if isinstance(v, float) else str(v) for v in r] for r in frame.itertuples(index=False)]
    return html + page.table(list(map(str, frame.columns)), rows, kinds=["num"] * len(frame.columns))


def check_rows(margins: dict, quantities: dict, scene=None, where: dict | None = None):
    """(rows, row classes, failed names) of a checks table: margin name, check, direction, margin, verdict,
    the rule the check applies (its factor's provenance in ``scene``) and, with ``where`` (margin → text),
    where the margin is least."""
    text = _machine(scene).check_text
    rows, classes, failed = [], [], []
    for n in margins_of(margins, scene):
        v = margins[n]
        base, way = (n.rsplit("_", 1) if _DIR.match(n) else (n, "-"))
        ok = v >= 0
        rows.append([n, text.get(base, quantities[n].description), way,
                     page.show(quantities[n], 0.0 if abs(v) < ZERO else v), "pass" if ok else "FAIL",
                     scene.check_basis(n) if scene is not None else "-"]
                    + ([where.get(n, "the same in every case")] if where else []))
        classes.append("pass" if ok else "fail")
        if not ok:
            failed.append(n)
    return rows, classes, failed


def checks_html(margins: dict, quantities: dict, scene=None, where: dict | None = None):
    """A verdict line and the table of every margin in ``margins`` (SI), each with its rule (see "Rules") and,
    with ``where`` (margin → text), where it is least (the load's place and the manoeuvre); nothing when there
    is none (no verdict over no checks)."""
    rows, classes, failed = check_rows(margins, quantities, scene, where)
    if not rows:
        return ""
    if failed:
        line = page.verdict(False, f"{len(failed)} of {len(rows)} checks FAIL: {', '.join(failed)}")
    else:
        line = page.verdict(True, f"All {len(rows)} checks pass.")
    head = ["margin", "check", "direction", "margin value", "result", "rule"] + (["where it is least"] if where else [])
    return line + page.table(head, rows, kinds=["name", "", "", "num", "", ""] + ([""] if where else []),
                             row_class=classes, cls="checks")


def _has_checks(ctx) -> bool:
    try:
        return bool(margins_of(ctx.result.outputs, ctx.scene))
    except RopeModelError:
        return bool(margins_of(ctx.scene.built.outputs, ctx.scene))


@section("checks", "Design checks", when=_has_checks)
def checks(ctx):
    result = ctx.result
    where = ("at the recommended design" if ctx.at_design else
             "at the scene's own values" + (" (its starting design; the sizing's design is checked under "
                                            "\"Sizing\")" if ctx.sizing else ""))
    html = page.fragment("<p>Every check {{ w }}: a margin ≥ 0 passes. Ratio margins are fractions "
                         "(0.1: 10 % to spare), the others in the quantity's unit.{{ e }}</p>", w=where,
                         e=_span(result))
    margins = {n: result.values[n] for n in margins_of(result.outputs, ctx.scene)}
    return html + checks_html(margins, result.model.quantities, result.scene, result.where)


def _span(result) -> str:
    """What the worst case spans, for a result at its worst (else nothing)."""
    text = getattr(result, "cases_text", None)
    return f" Each at its worst over {text()}, both directions." if text else ""
