"""What a scene's factors rest on, in words and in JSON: the rule (set, clause, status), the override and
its reason, or "user-given"; and what each rule of the set does for this machine.
"""

from __future__ import annotations

import math

from ropemodel.effects.rulebinding import RULE_BINDINGS
from ropemodel.rules.apply import FROM_OVERRIDE, FROM_RULE
from ropemodel.rules.vocabulary import GOVERNS

#: scene.origin of a value the user gave → how the outputs say it
USER = {"scene": "user-given (scene file)", "--set": "user-given (--set)", "api": "user-given (Python)",
        "sizing": "chosen by the sizing"}


def kind(scene, parameter: str) -> str:
    """``"rule"``, ``"override"``, ``"default"`` or ``"user-given"``: where ``parameter``'s value comes from."""
    o = scene.origin.get(parameter)
    return {FROM_RULE: "rule", FROM_OVERRIDE: "override", "default": "default"}.get(o or "", "user-given")


def basis(scene, parameter: str, short: bool = False) -> str:
    """Where the value of ``parameter`` comes from, one line (``short``: for a column of a table)."""
    applied = scene.rules
    ruled = applied.governed.get(parameter) if applied is not None else None
    k = kind(scene, parameter)
    if k == "rule" and ruled is not None:
        rule = ruled[1]
        head = f"{applied.ruleset.name} {rule.clause} ({rule.status})"
        return head if short else f"{head}: {rule.unicode()}"
    if k == "override":
        ov = applied.overrides[parameter]
        what = f"{applied.ruleset.name} {ruled[1].clause}" if ruled else f"rule set {applied.ruleset.name}"
        return f"override of {what}: {ov.reason}"
    if k == "default":
        q = scene.built.quantities[parameter]
        return f"default: {q.default_note or q.equation or q.show(scene.parameters[parameter])}"
    text = USER.get(scene.origin.get(parameter, ""), "user-given")
    if ruled is not None:
        text += f", in place of {applied.ruleset.name} {ruled[1].clause}"
    return text


def check_basis(scene, check: str, short: bool = True) -> str:
    """The rule a check applies (``check``: a margin name, with or without direction and position)."""
    base = check.split(" @ ")[0]
    base = base.rsplit("_", 1)[0] if base.endswith(("_up", "_down")) else base
    binds = RULE_BINDINGS.get(scene.model)
    b = binds.binding_of_check(base) if binds else None
    if b is None or b.parameter not in scene.parameters:
        return "-"
    return f"{b.parameter}: {basis(scene, b.parameter, short)}"


def factors(scene) -> dict:
    """Bound parameter → {value (SI), basis, text, checks, and the rule's clause, formula and inputs}."""
    binds = RULE_BINDINGS.get(scene.model)
    if binds is None:
        return {}
    applied = scene.rules
    out = {}
    for b in binds.bindings:
        if b.parameter not in scene.parameters:
            continue
        entry = {"value": scene.parameters[b.parameter], "basis": kind(scene, b.parameter),
                 "text": basis(scene, b.parameter), "checks": list(b.checks)}
        ruled = applied.governed.get(b.parameter) if applied is not None else None
        if ruled is not None and entry["basis"] == "rule":
            entry.update(_rule_entry(applied, ruled[1], scene.parameters))
        elif entry["basis"] == "override":
            entry["reason"] = applied.overrides[b.parameter].reason
        out[b.parameter] = entry
    return out


def _rule_entry(applied, rule, values) -> dict:
    lengths = applied.lengths(rule, values)
    names = {v.length: v.name for v in rule.variables}
    return {"set": applied.ruleset.name, "rule": rule.id, "clause": rule.clause, "status": rule.status,
            "formula": rule.unicode(), "python": rule.python(names),
            "inputs": {names[k]: float(v) for k, v in lengths.items()}}


def summary(scene) -> dict:
    """The JSON ``"rules"`` object of ``run``, ``size`` and the report ({} for a model without rules)."""
    found = factors(scene)
    if not found:
        return {}
    applied = scene.rules
    out: dict = {"set": None if applied is None else applied.ruleset.name}
    if applied is not None:
        rs = applied.ruleset
        out.update(title=rs.title, authority=rs.authority, source=rs.source, url=rs.url, status=rs.status,
                   choices=dict(applied.choices), lengths=lengths(scene), rules=rule_rows(scene))
    out["factors"] = found
    return out


def lengths(scene) -> dict:
    """The lengths the scene's rules are evaluated at: name → {value [m], definition, status}."""
    applied = scene.rules
    if applied is None:
        return {}
    used = {v.length for _, r in applied.governed.values() for v in r.variables}
    out = {}
    for name in sorted(used):
        ln = applied.binds.lengths[name]
        inputs = ln.inputs(scene.parameters)
        value = float(ln.value(scene.parameters)) if inputs and all(k in scene.parameters for k in inputs) \
            else math.nan
        out[name] = {"value": value if math.isfinite(value) else None, "unit": "m", "definition": ln.text,
                     "status": ln.status, "from": list(inputs)}
    return out


def rule_rows(scene) -> list[dict]:
    """Every rule of the scene's set: what it governs, its clause, formula, status and what it does here."""
    applied = scene.rules
    if applied is None:
        return []
    binds = applied.binds
    chosen = {r.id: p for p, (_, r) in applied.governed.items()}
    bound = {b.governs for b in binds.bindings}
    rows = []
    for r in applied.ruleset.rules:
        if r.id in chosen:
            p = chosen[r.id]
            here = (f"sets {p}" if kind(scene, p) == "rule" else f"would set {p}: {basis(scene, p)}")
        elif r.governs not in bound:
            here = f"not checked by ropemodel for this machine ({GOVERNS[r.governs][1]}): check it by hand"
        else:
            here = "does not apply here (" + ", ".join(f"{k} = {'/'.join(v)}" for k, v in r.where.items()) + ")"
        rows.append({"rule": r.id, "governs": r.governs, "clause": r.clause, "formula": r.unicode(),
                     "status": r.status, "evidence": r.evidence, "scope": r.scope, "here": here})
    return rows
