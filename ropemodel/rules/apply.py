"""A rule set applied to a scene: which rule sets which parameter, and the values they give.

A scene picks a rule set in its ``[rules]`` table (read by :func:`read_rules`)::

    [rules]
    set = "us-30cfr-57"                 # a file of ropemodel/data/rules/
    carried = "persons"                 # a choice the set asks for, if any
    n_rope = { value = 6, reason = "the mine's own standard" }     # an override, with its reason

For each parameter the model binds (:mod:`ropemodel.effects.rulebinding`), the set's one matching rule
gives the value, at the scene's suspended length; an override replaces it and says why; a value set on
top of the file (``--set``) replaces it too and is marked user-given.  Every problem is collected with
the scene's others: an unknown set or key, a choice missing, a set written for another machine, a
parameter given both in ``[parameters]`` and by the rule set.

The values are parameters of the scene (origin ``"rules"`` or ``"rules override"``); :meth:`Applied.derive`
gives them again where a rule's input changes (``--set L_u``, a sweep over the route's length, a
derivative), as floats, numpy arrays or CasADi expressions.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ropemodel.effects.rulebinding import RULE_BINDINGS, Binding, ModelRules
from ropemodel.errors import InputError, Problems, suggest
from ropemodel.rules import registry
from ropemodel.rules.ruleset import Rule, RuleSet
from ropemodel.rules.vocabulary import GOVERNS, MACHINES

#: scene.origin of a value a rule gives, and of an override in [rules]
FROM_RULE = "rules"
FROM_OVERRIDE = "rules override"


@dataclass(frozen=True)
class Override:
    """A value of ``[rules]`` that replaces the set's rule (or stands where the set has none), with its reason."""

    parameter: str
    value: float
    reason: str
    text: str


@dataclass(frozen=True)
class Applied:
    """The rule set of a scene: the rule each bound parameter follows, the overrides and choices."""

    ruleset: RuleSet
    model: str
    choices: dict[str, str]
    governed: dict[str, tuple[Binding, Rule]]
    overrides: dict[str, Override] = field(default_factory=dict)

    @property
    def binds(self) -> ModelRules:
        return RULE_BINDINGS[self.model]

    def inputs_of(self, parameter: str, names: Iterable[str]) -> tuple[str, ...]:
        """The parameters (among ``names``) the rule of ``parameter`` reads."""
        _, rule = self.governed[parameter]
        names = list(names)
        return tuple(k for v in rule.variables for k in self.binds.lengths[v.length].inputs(names))

    def lengths(self, rule: Rule, values: Mapping) -> dict:
        """The lengths ``rule`` needs, from the parameter ``values`` (SI; floats, arrays or CasADi)."""
        return {v.length: self.binds.lengths[v.length].value(values) for v in rule.variables}

    def value(self, parameter: str, values: Mapping):
        """The value [SI] the rule of ``parameter`` gives at the parameter ``values``."""
        _, rule = self.governed[parameter]
        return rule.value(self.lengths(rule, values))

    def derive(self, values: Mapping, changed: Iterable[str], live: Iterable[str]) -> dict:
        """The values of the ``live`` parameters (those a rule sets: not overridden, not set by hand) whose
        inputs are among ``changed``, at ``values`` (floats, numpy arrays or CasADi expressions)."""
        changed = set(changed)
        out = {}
        for p in live:
            if p in self.governed and p not in changed and changed & set(self.inputs_of(p, values)):
                out[p] = self.value(p, values)
        return out

    def jacobian(self, values: Mapping, live: Iterable[str]) -> dict[str, dict[str, float]]:
        """∂value/∂input of each ``live`` parameter's rule at ``values`` (SI; one-sided at a piece's limit)."""
        out = {}
        for p in live:
            if p not in self.governed:
                continue
            inputs = self.inputs_of(p, values)
            if not inputs:
                continue
            syms = {k: ca.SX.sym(k) for k in inputs}
            x = ca.vertcat(*syms.values())
            f = ca.Function("rule_jacobian", [x], [ca.jacobian(self.value(p, {**values, **syms}), x)])
            d = np.asarray(f(ca.DM([values[k] for k in inputs]))).ravel()
            out[p] = {k: float(v) for k, v in zip(inputs, d)}
        return out


def with_rule_terms(scene, sensitivities: dict) -> dict:
    """∂x/∂p of a sizing with the rule set's terms added: a length the rules read (L_u) also moves the factors
    they give (∂x/∂L_u + ∂x/∂n_rope · dn_rope/dL_u).  ``sensitivities``: {p: {x: ∂x/∂p}} (SI)."""
    if scene.rules is None or not sensitivities:
        return sensitivities
    out = {p: dict(d) for p, d in sensitivities.items()}
    for r, d_r in scene.rules.jacobian(scene.parameters, scene.ruled()).items():
        for i, slope in d_r.items():
            if r in sensitivities and i in out:
                for x, v in sensitivities[r].items():
                    out[i][x] = out[i].get(x, 0.0) + v * slope
    return out


def read_rules(data: dict, model, params: dict, origin: dict, given: Iterable[str], found: Problems):
    """The scene's ``[rules]`` (None without one): the values it sets go into ``params`` and ``origin``.

    ``given``: the names of ``[parameters]`` (a value both given there and set by the rule set is an error).
    """
    raw = data.get("rules")
    if raw is None:
        return None
    if not isinstance(raw, dict):
        found.add("[rules] must be a table: set = \"<rule set>\", then choices and overrides")
        return None
    binds = RULE_BINDINGS.get(model.name)
    if binds is None:
        found.add(f"[rules]: model {model.name!r} meets no rule set (none of its parameters is bound to a rule)")
        return None
    bound = [b.parameter for b in binds.bindings if b.parameter in model.parameters and b.parameter not in params]
    ruleset = _ruleset(raw, found)
    if ruleset is not None and binds.machine not in ruleset.machines:
        found.add(_other_machine(ruleset, model.name, binds.machine))
        ruleset = None
    applied, pending = None, set(bound)
    if ruleset is not None:
        choices, overrides = _keys(raw, ruleset, binds, model, found)
        governed, pending = _select(ruleset, binds, choices, model, found)
        applied = Applied(ruleset, model.name, choices, governed, overrides)
        _fill(applied, model, params, origin, set(given), found)
        pending |= set(governed) | {p for p in bound if p in raw}
    for p in bound:      # a factor [rules] should have set but could not: its problem is said, not "missing"
        if p not in params and p in pending:
            origin[p] = f"{FROM_RULE} (refused)"
    return applied


def _ruleset(raw: dict, found: Problems) -> RuleSet | None:
    name = raw.get("set")
    if name is None:
        found.add(f"[rules] needs set = \"<rule set>\"; rule sets: {', '.join(registry.names())}")
        return None
    with found.collect():
        return registry.get(name)
    return None


def _other_machine(ruleset: RuleSet, model: str, machine: str) -> str:
    fits = [n for n, s in registry.rule_sets().items() if machine in s.machines]
    return (f"[rules] set = {ruleset.name!r} is written for {', '.join(ruleset.machines)} "
            f"({'; '.join(MACHINES[m] for m in ruleset.machines)}), not for this scene's model {model!r} "
            f"({MACHINES[machine]}): its rules do not apply to it; rule sets for {machine}: "
            f"{', '.join(fits) or 'none'}")


def _keys(raw: dict, ruleset: RuleSet, binds: ModelRules, model, found: Problems):
    """The choices and overrides of ``[rules]``, each checked."""
    choices: dict[str, str] = {}
    overrides: dict[str, Override] = {}
    bound = [b.parameter for b in binds.bindings if b.parameter in model.parameters]
    valid = ["set", *ruleset.choices, *bound]
    for key, value in raw.items():
        if key == "set":
            continue
        if key in ruleset.choices:
            if not isinstance(value, str) or value not in ruleset.choices[key]:
                found.add(f"[rules] {key} = {value!r}; valid: " + ", ".join(
                    f"{v!r} ({why})" for v, why in ruleset.choices[key].items()) + suggest(str(value),
                                                                                          ruleset.choices[key]))
            else:
                choices[key] = value
        elif key in bound:
            with found.collect():
                overrides[key] = _override(key, value, model.quantities[key])
        else:
            found.add(f"[rules]: unknown key {key!r}; valid: {', '.join(valid)} (set, the set's choices, and "
                      f"overrides of the parameters a rule may set){suggest(key, valid)}")
    return choices, overrides


def _override(name: str, value, q) -> Override:
    example = f"{name} = {{ value = {'6' if q.dimensionless else chr(34) + '5 ' + q.display_unit + chr(34)}, " \
              f"reason = \"...\" }}"
    if not isinstance(value, dict) or set(value) != {"value", "reason"}:
        raise InputError(f"[rules] {name}: an override gives its value and its reason, e.g. {example}")
    reason = value["reason"]
    if not isinstance(reason, str) or not reason.strip():
        raise InputError(f"[rules] {name}: the override needs a reason (why not the rule set's value), e.g. "
                         f"{example}")
    si = q.check(q.to_si(value["value"], "refuse"), f"[rules] {name}")
    return Override(name, si, reason.strip(), str(value["value"]))


def _select(ruleset: RuleSet, binds: ModelRules, choices: dict, model, found: Problems) -> tuple[dict, set]:
    """(parameter → (binding, the one rule of the set that governs it here), the parameters waiting for a
    choice the scene did not make)."""
    out, pending = {}, set()
    for b in binds.bindings:
        if b.parameter not in model.parameters:
            continue
        context = {**b.context, **choices}
        rules = [r for r in ruleset.rules if r.governs == b.governs]
        missing = sorted({k for r in rules if r.matches(context) is None for k in r.where if k not in context})
        for key in missing:
            found.add(f"[rules] set = {ruleset.name!r} needs {key} to choose its rule for {b.parameter} "
                      f"({GOVERNS[b.governs][1]}): " + ", ".join(
                          f"{key} = {v!r} ({why})" for v, why in ruleset.choices[key].items()))
        matched = [r for r in rules if r.matches(context)]
        if missing:
            pending.add(b.parameter)
        if missing or not matched:
            continue
        if len(matched) > 1:
            raise RuntimeError(f"rule set {ruleset.name}: rules {', '.join(r.id for r in matched)} all govern "
                               f"{b.governs} here ({context}): the data file must tell them apart")
        for v in matched[0].variables:
            if v.length not in binds.lengths:
                found.add(f"[rules] rule {matched[0].id} needs the {v.length} length, which model {model.name!r} "
                          f"does not define")
        out[b.parameter] = (b, matched[0])
    return out, pending


def _fill(applied: Applied, model, params: dict, origin: dict, given: set, found: Problems) -> None:
    """Put the values the rule set gives (or its overrides) into ``params``; conflicts are problems."""
    q = model.quantities
    for p, ov in applied.overrides.items():
        if p in given:
            found.add(f"{p} is given twice: in [parameters] and as an override in [rules]; keep one")
            continue
        params[p], origin[p] = ov.value, FROM_OVERRIDE
    for p, (_, rule) in applied.governed.items():
        if p in applied.overrides or origin.get(p) not in (None, "default"):
            if p in given and p not in applied.overrides:
                found.add(f"{p} is set by rule set {applied.ruleset.name!r} ({rule.clause}: {rule.unicode()}); "
                          f"remove it from [parameters], or override it in [rules] with its reason: "
                          f"{p} = {{ value = ..., reason = \"...\" }}")
            continue
        inputs = applied.inputs_of(p, params)
        if rule.variables and (not inputs or any(k not in params or q[k].range_problem(params[k], k)
                                                 for k in inputs)):
            continue        # the missing or invalid length is named with the scene's other problems
        try:
            value = applied.value(p, params)
        except InputError as exc:
            found.add(f"[rules] {p}: {exc}")
            continue
        problem = q[p].range_problem(value, f"{p} from rule {rule.id} ({rule.clause})")
        if problem:
            found.add(problem)
            continue
        params[p], origin[p] = value, FROM_RULE


def refresh(applied: Applied, params: dict, origin: dict, changed: Iterable[str]) -> dict:
    """Values of the rule-set parameters whose inputs ``changed`` (floats), for :meth:`Scene.with_values`."""
    live = [p for p, o in origin.items() if o == FROM_RULE]
    return {p: float(v) for p, v in applied.derive(params, changed, live).items()}
