"""What a filed calculation carries besides its numbers: the rope's designation, every normative number with
its source and status, the assumptions and the data still missing.

Each comes from where the number or the choice lives, never from a list kept here: the scene's rule set
(:mod:`ropemodel.rules.describe`), the rope catalogue (``ropemodel/data/ropes.toml``:
:mod:`ropemodel.papers.en12385`), each effect variant's ``assumptions`` and ``missing``
(:class:`ropemodel.effects.base.Submodel`), the defaults the calculation relied on (each with its reason), and
the scene's ``[report]`` table (:mod:`ropemodel.scene_report`).  The page (sections "document" and
"basis") and the calculation sheet (:mod:`ropemodel.reports.sheet`) show the same lists.

Statuses are the rule sets' (:data:`ropemodel.rules.vocabulary.STATUSES`): "confirmed", "to verify",
"engineering judgement", and "user-given" for a value the scene gives without a source.
"""

from __future__ import annotations

from collections.abc import Iterable

from ropemodel.core.formulas import shown
from ropemodel.core.infix import G_N
from ropemodel.papers import en12385 as ropes
from ropemodel.rules import describe
from ropemodel.reports.sections.inputs import catalogue_rope
from ropemodel.rules.vocabulary import GOVERNS, STATUSES
from ropemodel.scene_report import FINISHES, LAYS

USER = "user-given"
#: every status a normative number may have, with its meaning
STATUS_TEXT = {**STATUSES, USER: "a value the scene gives, with no source: the engineer's responsibility"}
GRAVITY = {"name": "g", "value": f"{G_N} m/s^2", "what": "standard acceleration of gravity",
           "source": "CGPM 1901 (3rd General Conference on Weights and Measures); ISO 80000-3", "status": "confirmed"}


# ------------------------------------------------------------------------------------------ the rope


def rope_designation(scene, values: dict) -> dict | None:
    """The rope's designation and its parts (None for a model without a catalogue rope).

    ``values``: SI values at the point reported (d, rope_grade, F_min).
    """
    rope = catalogue_rope(scene.built)
    if rope is None:
        return None
    rules = ropes.designation_rules()
    c = rope.construction
    filing = scene.filing
    given = dict(filing.rope) if filing is not None else {}
    construction = given.get("construction") or (c.rope_class if c else "")
    core = c.core if c else ""
    nan = float("nan")
    d_mm, grade, F_min = values.get("d", nan) * 1e3, values.get("rope_grade", nan) / 1e6, values.get("F_min", nan)
    out = {
        "designation": ropes.designation(d_mm, construction or "?", core or "?", grade, given.get("finish", "?"),
                                         given.get("lay", "?")),
        "standard": rules["standard"] if c else "none: the construction factors K, W, C are given by the scene",
        "class": c.rope_class if c else "", "core": f"{core} ({rules['cores'][core]})" if core else "",
        "construction": given.get("construction", ""), "nominal diameter": f"{d_mm:g} mm",
        "rope grade": f"{grade:g} N/mm^2", "minimum breaking force": f"{F_min / 1e3:.6g} kN",
        "wire finish": _coded(given.get("finish"), FINISHES), "lay": _coded(given.get("lay"), LAYS),
        "maker": given.get("maker", ""), "test certificate": given.get("certificate", ""),
        "system": f"{rules['system']}: {rules['order']}", "status": rules["status"], "evidence": rules["evidence"],
    }
    return out


def _coded(code: str | None, meanings: dict) -> str:
    return f"{code} ({meanings[code]})" if code else ""


def _rope_missing(scene, designation: dict | None) -> list[str]:
    if designation is None:
        return []
    rope = catalogue_rope(scene.built)
    given = dict(scene.filing.rope) if scene.filing is not None else {}
    out = [f"The rope's {what} ([report.rope] {key}) for its designation."
           for key, what in (("construction", "construction within its class (e.g. 6x36WS)"),
                             ("finish", "wire finish (U, A, B, ...)"),
                             ("lay", "type and direction of lay (sZ, zZ, ...)")) if key not in given]
    if rope.construction is None:
        out.append("A named construction of the catalogue (rope = \"6x36-IWRC\", ...): the factors K, W, C are the "
                   "scene's own, with no standard behind them.")
    return out


# ------------------------------------------------------------------------------------------ numbers


def normative_numbers(scene) -> list[dict]:
    """Every normative number the calculation uses: name, value, what it is, source, status."""
    q = scene.built.quantities
    out = []
    for name, e in describe.factors(scene).items():
        out.append({"name": name, "value": q[name].show(e["value"]), "what": q[name].description,
                    "source": e["text"], "status": _status(e)})
    rope = catalogue_rope(scene.built)
    if rope is not None and rope.construction is not None:
        c = rope.construction
        status, _ = ropes.factors_status()
        for key, value, unit in (("K", c.K, ""), ("W", c.W, " kg/m^3"), ("C", c.C, "")):
            out.append({"name": f"rope_{key}", "value": f"{value:.6g}{unit}", "what": q[f"rope_{key}"].description,
                        "source": c.source, "status": status})
        grade = scene.parameters.get("rope_grade")
        if grade is not None:
            standard = any(abs(grade - g) < 0.5e6 for g in ropes.grades())
            out.append({"name": "rope_grade", "value": q["rope_grade"].show(grade), "what": "the rope grade R_r",
                        "source": "an EN 12385-4 grade (1570, 1770, 1960, 2160 N/mm^2)" if standard
                        else "not an EN 12385-4 grade: the scene's own", "status": status if standard else USER})
    if _uses_gravity(scene.built):
        out.append(dict(GRAVITY))
    return out


def _status(entry: dict) -> str:
    """The status of a factor: its rule's, or what a default or the user's own value is."""
    if entry["basis"] == "rule":
        return entry["status"]
    if entry["basis"] == "default":
        return "engineering judgement"
    return USER


def _uses_gravity(model) -> bool:
    """Whether an equation of ``model`` uses g (9.80665 in an expression the calculation sheet prints)."""
    texts = ((s.python or "") + (s.lhs or "") + (s.rhs or "") for s in (shown(model, eq) for eq in model.equations))
    return any(repr(G_N) in t for t in texts)


# ------------------------------------------------------------------------------------------ assumptions


def assumptions(scene, reads: Iterable[str]) -> list[str]:
    """What the calculation takes for granted: each chosen variant's assumptions, then each default relied on
    (one of the parameters in ``reads``, those the calculation is computed from)."""
    model, q, reads = scene.built, scene.built.quantities, set(reads)
    out = [a for sm in model.submodels for a in sm.assumptions]
    factors = describe.factors(scene)
    for name, why in scene.defaults.items():
        if name in reads and name not in factors:       # a default factor is listed with the normative numbers
            out.append(f"{name} = {q[name].show(scene.parameters[name])} (default): {why}")
    return out


def missing(scene, values: dict) -> list[str]:
    """What the calculation still lacks before it is filed, one sentence each."""
    out = [m for sm in scene.built.submodels for m in sm.missing]
    out += _rope_missing(scene, rope_designation(scene, values))
    factors = describe.factors(scene)
    if factors and scene.rules is None:
        out.append(f"A rule set ([rules] set = \"...\"): the factors {', '.join(factors)} have no source.")
    for r in describe.rule_rows(scene):
        if r["here"].startswith("not checked"):
            out.append(f"Rule {r['rule']} ({r['clause']}, {GOVERNS[r['governs']][1]}): not checked by ropemodel "
                       "for this machine: check it by hand.")
    for n in normative_numbers(scene):
        if n["status"] == "to verify":
            out.append(f"{n['name']} = {n['value']}: its source is 'to verify' ({n['source']}): read it before "
                       "filing.")
    return out
