"""The calculation sheet: every equation the report shows, with a Python expression that recomputes it.

``ropemodel report SCENE --format json -o calc.json`` writes :func:`sheet`.  Each equation is one entry
(:func:`entries`), printed from the expression the model computes (:mod:`ropemodel.core.formulas`)::

    {"name": "G_ml", "formula": "G_ml = G_m sin α_u", "python": "G_m * math.sin(alpha_u)",
     "inputs": {"G_m": 467000.0, "alpha_u": 0.279...}, "value": 128722.9..., "unit": "N",
     "source": "eq. (1)", "cites": ["krauze2025"], "kind": "closed", ...}

A checker recomputes it with ``eval(e["python"], {"math": math}, e["inputs"])`` (SI throughout).  An
equation without a closed form says so: ``"kind": "implicit"`` (an iteration; ``"equation": {"lhs",
"rhs"}`` are its governing equation's sides, equal at the value, evaluated with the inputs and the value
under its own name) or ``"numerical"`` (an integrator or an error estimate: ``"python": null``; ``"method"``
and ``"tolerance"`` say how it was computed).  A name that is a Python keyword is written with ``_``
appended (``lambda_``), in ``inputs`` and in the expressions alike; a value without limit (a stroke not
given) is the string ``"inf"``, which ``float`` reads.
"""

from __future__ import annotations

import math

from ropemodel.citations import CITATIONS
from ropemodel.core.formulas import shown
from ropemodel.core.infix import identifier

#: the sheet's format, raised when an entry changes meaning
FORMAT = 1
EVALUATE = ('closed: eval(e["python"], {"math": math}, e["inputs"]) == e["value"]; implicit: e["equation"]["lhs"] '
            'and ["rhs"] evaluated with e["inputs"] and {name: e["value"]} agree; SI units; "inf" is float("inf")')


def number(x):
    """An SI value for JSON: a float, or ``"inf"``/``"-inf"`` (JSON has no infinity); None if not computed."""
    if x is None:
        return None
    x = float(x)
    if math.isnan(x):
        return None
    return x if math.isfinite(x) else ("inf" if x > 0 else "-inf")


def groups(model):
    """(submodel, its equations) in the model's order, for each submodel that builds an equation."""
    for sm in model.submodels:
        eqs = [eq for eq in model.equations if model.defined_by[eq.defines] == sm.effect]
        if eqs:
            yield sm, eqs


def entries(model, values: dict) -> list[dict]:
    """Every equation of ``model`` at the SI ``values`` (parameters and outputs) as sheet entries."""
    out = []
    for sm, eqs in groups(model):
        for eq in eqs:
            out.append(entry(model, eq, values, f'{sm.effect} = "{sm.variant}"', list(sm.citations)))
    return out


def references(model) -> dict[str, str]:
    """Citation key → full reference, of every submodel of ``model`` (what the entries' ``cites`` name)."""
    return {k: CITATIONS[k] for sm in model.submodels for k in sm.citations}


def entry(model, eq, values: dict, effect: str, cites: list[str]) -> dict:
    """One equation as the sheet writes it (see the module docstring)."""
    s = shown(model, eq)
    q = model.quantities[eq.defines]
    e = {"name": eq.defines, "kind": s.kind, "formula": s.formula, "python": s.python,
         "inputs": {identifier(n): number(values.get(n)) for n in s.inputs},
         "value": number(values.get(eq.defines)), "unit": q.unit, "source": eq.source, "effect": effect,
         "cites": cites}
    if s.kind == "implicit":
        e["equation"] = {"lhs": s.lhs, "rhs": s.rhs}
    if s.method:
        e["method"] = s.method
    if s.kind != "closed" or s.tolerance is not None:
        e["tolerance"] = s.tolerance
    return e


def document(ctx) -> dict:
    """The document's filing data: number, revision, title, sign-off and history (``[report]``)."""
    from ropemodel.reports.sections.document import filing, title

    f = filing(ctx)
    return {"document": f.document, "project": f.project, "title": title(ctx), "revision": f.revision,
            "signoff": [{"role": s.role, "name": s.name, "date": s.date and s.date.isoformat()} for s in f.signatures],
            "history": [{"revision": r.revision, "date": r.date.isoformat(), "description": r.description, "by": r.by}
                        for r in f.history]}


def basis(ctx, values: dict) -> dict:
    """The rope's designation, the normative numbers, the assumptions and the data still missing."""
    from ropemodel.reports import filing

    return {"rope": filing.rope_designation(ctx.scene, values), "normative": filing.normative_numbers(ctx.scene),
            "statuses": filing.STATUS_TEXT, "assumptions": filing.assumptions(ctx.scene, ctx.reads),
            "missing": filing.missing(ctx.scene, values)}


def sheet(ctx) -> dict:
    """The calculation sheet of a report's context (:class:`~ropemodel.reports.context.Context`), as JSON data."""
    from ropemodel.reports.sections.scene import stamp, version

    result, scene = ctx.result, ctx.scene
    # a result at its worst case: the equations at one case, where each holds with its own inputs
    point, at = result.point() if hasattr(result, "point") else (result, None)
    return {
        "sheet": "ropemodel calculation sheet", "format": FORMAT, "ropemodel": version(), "created": stamp(ctx),
        "scene": {"name": scene.name, "model": scene.model, "file": scene.source, "sha256": scene.digest},
        "at": "the recommended design" if ctx.at_design else "the scene's values",
        "units": "SI", "evaluate": EVALUATE,
        "document": document(ctx), "basis": basis(ctx, result.values),
        "equations": entries(point.model, point.values), "equations_at": at,
        "references": references(result.model),
    }
