"""A rule set read from its data file (``ropemodel/data/rules/<name>.toml``), every problem of it at once.

A rule is data: what it governs, where it applies (``where``: the kind of rope or drum, what is carried,
a mechanism group), its formula in the suspended length with the length's unit as the source writes
it, the ranges of length each piece of the formula holds for, its clause, the source, a status and the
evidence behind the status.  A formula is parsed by :class:`~ropemodel.formula.Formula` (arithmetic only,
never ``eval``); its value comes in SI, for floats, numpy arrays and CasADi expressions alike.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ropemodel import _math
from ropemodel.errors import InputError, Problems, suggest
from ropemodel.formula import Formula
from ropemodel.rules.vocabulary import CONTEXT, GOVERNS, LENGTH_UNITS, MACHINES, STATUSES
from ropemodel.units import UnitError, parse_unit

SET_KEYS = ("title", "authority", "source", "url", "machines", "notes", "choices", "rules")
RULE_KEYS = ("id", "governs", "where", "variables", "formula", "pieces", "unit", "clause", "status", "evidence",
             "scope")
#: lengths a rule may use (a model defines each for itself; see ropemodel.effects.rulebinding)
LENGTHS = ("suspended",)


@dataclass(frozen=True)
class Variable:
    """A rule's variable: a length the model defines (``length``), in the unit the source writes (``unit``)."""

    name: str
    length: str
    unit: str

    @property
    def factor(self) -> float:
        """SI per unit of the source (1 ft = 0.3048 m)."""
        return parse_unit(self.unit)[0]


@dataclass(frozen=True)
class Piece:
    """One piece of a rule's formula, valid for ``lower <= x < upper`` (x its variable, in the source's unit)."""

    formula: Formula
    lower: float = -math.inf
    upper: float = math.inf


@dataclass(frozen=True)
class Rule:
    """One rule of a set (see the module docstring); its value is in SI."""

    id: str
    governs: str
    clause: str
    status: str
    evidence: str
    pieces: tuple[Piece, ...]
    where: dict[str, tuple[str, ...]] = field(default_factory=dict)
    variables: tuple[Variable, ...] = ()
    unit: str = "1"
    scope: str = ""

    @property
    def factor(self) -> float:
        """SI per unit of the value as written (1 for a pure number, 1000 for kN)."""
        return parse_unit(self.unit)[0]

    def value(self, lengths: dict):
        """The value in SI for ``lengths`` (length name → SI value: float, numpy array or CasADi)."""
        xs = {v.name: lengths[v.length] / v.factor for v in self.variables}
        if len(self.pieces) == 1:
            return self._scaled(self.pieces[0].formula(**xs))
        x = next(iter(xs.values()))
        if isinstance(x, float):
            for p in self.pieces:
                if p.lower <= x < p.upper:
                    return self._scaled(p.formula(**xs))
            raise InputError(f"rule {self.id} ({self.clause}) has no value for {self.variables[0].name} = "
                             f"{x:.6g} {self.variables[0].unit}: it covers {self.domain_text()}")
        if isinstance(x, np.ndarray) and np.any(x < self.pieces[0].lower):
            raise InputError(f"rule {self.id} ({self.clause}) has no value for {self.variables[0].name} = "
                             f"{np.min(x):.6g} {self.variables[0].unit}: it covers {self.domain_text()}")
        out = self.pieces[-1].formula(**xs)
        for p in reversed(self.pieces[:-1]):           # every branch is a plain formula: safe to evaluate
            out = _math.if_else(x < p.upper, p.formula(**xs), out)
        return self._scaled(out)

    def _scaled(self, v):
        f = self.factor
        return v * f if f != 1.0 else v

    def domain_text(self) -> str:
        v = self.variables[0]
        lo, hi = self.pieces[0].lower, self.pieces[-1].upper
        parts = ([f"{v.name} >= {lo:g} {v.unit}"] if lo > -math.inf else []) + \
                ([f"{v.name} < {hi:g} {v.unit}"] if hi < math.inf else [])
        return " and ".join(parts) or "every length"

    def unicode(self) -> str:
        """The rule as a person reads it: ``7.0 − 0.0005·L for L < 4000 ft; 5.0 for L ≥ 4000 ft``."""
        if len(self.pieces) == 1:
            return self.pieces[0].formula.unicode() + self._unit_text()
        v = self.variables[0]
        parts = []
        for p in self.pieces:
            cond = []
            if p.lower > -math.inf:
                cond.append(f"{v.name} ≥ {p.lower:g} {v.unit}")
            if p.upper < math.inf:
                cond.append(f"{v.name} < {p.upper:g} {v.unit}")
            parts.append(f"{p.formula.unicode()} for {' and '.join(cond)}")
        return "; ".join(parts) + self._unit_text()

    def _unit_text(self) -> str:
        return "" if self.unit == "1" else f" {self.unit}"

    def python(self, names: dict[str, str]) -> str:
        """A Python expression of the value in SI, in the SI lengths ``names`` (length name → variable)."""
        subs = {v.name: f"{names[v.length]} / {v.factor!r}" if v.factor != 1.0 else names[v.length]
                for v in self.variables}
        out = self.pieces[-1].formula.python(subs)
        for p in reversed(self.pieces[:-1]):
            x = subs[self.variables[0].name]
            out = f"({p.formula.python(subs)}) if {x} < {p.upper!r} else ({out})"
        return f"({out}) * {self.factor!r}" if self.factor != 1.0 else out

    def matches(self, context: dict[str, str]) -> bool | None:
        """True or False; None when ``context`` lacks a key this rule's ``where`` names."""
        for key, allowed in self.where.items():
            if key not in context:
                return None
            if context[key] not in allowed:
                return False
        return True


@dataclass(frozen=True)
class RuleSet:
    """A rule set: its rules and where they come from (see :func:`read`)."""

    name: str
    title: str
    authority: str
    source: str
    url: str
    machines: tuple[str, ...]
    rules: tuple[Rule, ...]
    choices: dict[str, dict[str, str]] = field(default_factory=dict)
    notes: str = ""

    @property
    def status(self) -> str:
        """The weakest status among the rules (a set is only as confirmed as its least confirmed rule)."""
        order = list(STATUSES)
        return max((r.status for r in self.rules), key=order.index, default="engineering judgement")


def read(name: str, data: dict) -> RuleSet:
    """Check and build the rule set ``name`` from its TOML ``data``; :class:`InputError` lists every problem."""
    found = Problems(f" in rule set {name}")
    for key in data:
        if key not in SET_KEYS:
            found.add(f"unknown key {key!r}; valid: {', '.join(SET_KEYS)}{suggest(key, SET_KEYS)}")
    text = {k: _text(data, k, found, required=k != "notes") for k in ("title", "authority", "source", "url", "notes")}
    machines = data.get("machines", [])
    if not isinstance(machines, list) or not machines:
        found.add("machines: give the machines the set is written for, e.g. machines = [\"winch\"]")
        machines = []
    for m in machines:
        if m not in MACHINES:
            found.add(f"machines: unknown machine {m!r}; known: {', '.join(MACHINES)}{suggest(str(m), MACHINES)}")
    choices = _choices(data.get("choices", {}), found)
    rules = []
    raw = data.get("rules", [])
    if not isinstance(raw, list) or not raw:
        found.add("give the rules: one [[rules]] table each")
        raw = []
    for i, r in enumerate(raw, start=1):
        with found.collect():
            rules.append(_rule(r, choices, f"[[rules]] {r.get('id', i) if isinstance(r, dict) else i}"))
    ids = [r.id for r in rules]
    for dup in sorted({i for i in ids if ids.count(i) > 1}):
        found.add(f"rule id {dup!r} is used twice")
    found.raise_if_any()
    return RuleSet(name, text["title"], text["authority"], text["source"], text["url"], tuple(machines),
                   tuple(rules), choices, text["notes"])


def _text(data: dict, key: str, found: Problems, required: bool = True) -> str:
    value = data.get(key, "")
    if not isinstance(value, str) or (required and not value.strip()):
        found.add(f"{key}: give it as text")
        return ""
    return value.strip()


def _choices(raw, found: Problems) -> dict[str, dict[str, str]]:
    """``[choices.<key>]`` tables: value → what it means."""
    out: dict[str, dict[str, str]] = {}
    if not isinstance(raw, dict):
        found.add("choices: a table of [choices.<key>] tables")
        return out
    for key, values in raw.items():
        if key in CONTEXT:
            found.add(f"choices.{key}: {key} is given by the model, not chosen in a scene")
        if not isinstance(values, dict) or not values or not all(isinstance(v, str) for v in values.values()):
            found.add(f"choices.{key}: a table of value = \"what it means\" lines")
            continue
        out[key] = dict(values)
    return out


def _rule(r, choices: dict, where_text: str) -> Rule:
    found = Problems()
    if not isinstance(r, dict):
        raise InputError(f"{where_text}: a rule is a table")
    for key in r:
        if key not in RULE_KEYS:
            found.add(f"{where_text}: unknown key {key!r}; valid: {', '.join(RULE_KEYS)}{suggest(key, RULE_KEYS)}")
    for key in ("id", "governs", "clause", "status", "evidence"):
        if not isinstance(r.get(key), str) or not r[key].strip():
            found.add(f"{where_text}: give {key} as text")
    governs, status = r.get("governs"), r.get("status")
    if isinstance(governs, str) and governs not in GOVERNS:
        found.add(f"{where_text}: governs = {governs!r} is unknown; known: {', '.join(GOVERNS)}"
                  f"{suggest(governs, GOVERNS)}")
    if isinstance(status, str) and status not in STATUSES:
        found.add(f"{where_text}: status = {status!r}; valid: {', '.join(STATUSES)}")
    where = _where(r.get("where", {}), choices, where_text, found)
    variables = _variables(r.get("variables", {}), where_text, found)
    unit = r.get("unit", GOVERNS.get(str(governs), ("1",))[0])
    _check_unit(unit, str(governs), where_text, found)
    pieces = _pieces(r, variables, where_text, found)
    found.raise_if_any()
    return Rule(r["id"], str(governs), r["clause"].strip(), str(status), r["evidence"].strip(), tuple(pieces), where,
                variables, unit, str(r.get("scope", "")).strip())


def _where(raw, choices: dict, where_text: str, found: Problems) -> dict[str, tuple[str, ...]]:
    out: dict[str, tuple[str, ...]] = {}
    if not isinstance(raw, dict):
        found.add(f"{where_text}: where is a table, e.g. where = {{ rope = \"friction-drum\" }}")
        return out
    for key, value in raw.items():
        values = tuple(value) if isinstance(value, list) else (value,)
        valid = CONTEXT.get(key) or choices.get(key)
        if valid is None:
            found.add(f"{where_text}: where.{key}: unknown key; the model gives {', '.join(CONTEXT)}, the set's "
                      f"choices are {', '.join(choices) or 'none'}")
            continue
        for v in values:
            if v not in valid:
                found.add(f"{where_text}: where.{key} = {v!r}; valid: {', '.join(valid)}{suggest(str(v), valid)}")
        out[key] = values
    return out


def _variables(raw, where_text: str, found: Problems) -> tuple[Variable, ...]:
    if not isinstance(raw, dict):
        found.add(f"{where_text}: variables is a table, e.g. variables = {{ L = {{ length = \"suspended\", "
                  f"unit = \"ft\" }} }}")
        return ()
    out = []
    for name, spec in raw.items():
        if not isinstance(spec, dict) or spec.get("length") not in LENGTHS or spec.get("unit") not in LENGTH_UNITS:
            found.add(f"{where_text}: variables.{name} = {{ length = \"{'|'.join(LENGTHS)}\", unit = "
                      f"\"{'|'.join(LENGTH_UNITS)}\" }} (the unit the source writes the length in)")
            continue
        out.append(Variable(name, spec["length"], spec["unit"]))
    return tuple(out)


def _check_unit(unit, governs: str, where_text: str, found: Problems) -> None:
    si = GOVERNS.get(governs, ("1",))[0]
    try:
        if not isinstance(unit, str) or parse_unit(unit)[1] != parse_unit(si)[1]:
            found.add(f"{where_text}: unit {unit!r} is not a unit of {governs} (SI: {si})")
    except UnitError as exc:
        found.add(f"{where_text}: unit: {exc}")


def _pieces(r: dict, variables, where_text: str, found: Problems) -> list[Piece]:
    if ("formula" in r) == ("pieces" in r):
        found.add(f"{where_text}: give either formula = \"...\" or pieces = [{{ formula = \"...\", below = ... }}, "
                  f"...]")
        return []
    declared = r.get("variables", {})
    names = list(declared) if isinstance(declared, dict) else [v.name for v in variables]
    raw = [{"formula": r["formula"]}] if "formula" in r else r["pieces"]
    if not isinstance(raw, list) or not raw or not all(isinstance(p, dict) for p in raw):
        found.add(f"{where_text}: pieces is a list of {{ formula = \"...\", below = <length> }} tables")
        return []
    if len(raw) > 1 and len(names) != 1:
        found.add(f"{where_text}: a formula in pieces needs exactly one variable (the length the pieces split)")
        return []
    lower = raw[0].get("from", -math.inf)
    if not isinstance(lower, (int, float)) or isinstance(lower, bool):
        found.add(f"{where_text}: piece 1: from = <length> (in the variable's unit)")
        lower = -math.inf
    pieces: list[Piece] = []
    for i, p in enumerate(raw):
        extra = set(p) - {"formula", "below", "from"} - ({"from"} if i == 0 else set())
        if extra or ("from" in p and i > 0):
            found.add(f"{where_text}: piece {i + 1}: keys are formula, below (and from on the first piece)")
        upper = p.get("below", math.inf)
        last = i == len(raw) - 1
        if not isinstance(upper, (int, float)) or isinstance(upper, bool) or (upper == math.inf) != last \
                or upper <= lower:
            found.add(f"{where_text}: piece {i + 1}: every piece but the last ends with below = <length> (in the "
                      f"variable's unit), rising; the last piece has no below")
            upper = math.inf if last else lower + 1.0
        try:
            pieces.append(Piece(Formula.parse(p.get("formula"), names), lower, float(upper)))
        except InputError as exc:
            found.add(f"{where_text}: piece {i + 1}: {exc}" if len(raw) > 1 else f"{where_text}: {exc}")
        lower = float(upper)
    return pieces
