"""How a model meets rule sets: the lengths its rules are written in, and which parameter each rule sets.

A rule says what it governs in the world (``rope_safety`` of a ``friction-drum`` rope; see
:mod:`ropemodel.rules.vocabulary`); a model binds those words to its own parameters here, once, with
:func:`bind_rules`.  The checks read their parameters as before: whether a value came from a rule, an
override or the user is the scene's business (:mod:`ropemodel.rules.apply`), never the checks'.

A rule "in the suspended length" needs each model to say what that length is for it: a
:class:`Length` is a function of the model's parameters (floats, numpy arrays and CasADi symbols
alike), the parameters it reads, and what it means, with the status of that definition.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Length:
    """A length a rule may use (``suspended``), as this model defines it.

    value: ``value(parameters) -> length [m]``; inputs: ``inputs(names) -> the parameters it reads`` among
    the names a scene has; text: what it is; status: of the definition (``"engineering judgement"`` where
    no text defines it for this machine).
    """

    name: str
    value: Callable[[Mapping], object]
    inputs: Callable[[Iterable[str]], tuple[str, ...]]
    text: str
    status: str


@dataclass(frozen=True)
class Binding:
    """Rules governing ``governs`` (for the kind of rope or drum in ``context``) set ``parameter``, which
    the checks ``checks`` (margin names without direction) read."""

    governs: str
    parameter: str
    checks: tuple[str, ...]
    context: dict[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class ModelRules:
    """A model's side of the rule sets: the machine it is, its lengths and its bindings."""

    machine: str
    lengths: dict[str, Length]
    bindings: tuple[Binding, ...]

    def binding_of(self, parameter: str) -> Binding | None:
        return next((b for b in self.bindings if b.parameter == parameter), None)

    def binding_of_check(self, check: str) -> Binding | None:
        return next((b for b in self.bindings if check in b.checks), None)


#: model name → its :class:`ModelRules`
RULE_BINDINGS: dict[str, ModelRules] = {}


def bind_rules(model: str, machine: str, lengths: tuple[Length, ...], bindings: tuple[Binding, ...]) -> None:
    """Declare how ``model`` meets rule sets (once per model)."""
    if model in RULE_BINDINGS:
        raise RuntimeError(f"rules of model {model!r} bound twice")
    params = [b.parameter for b in bindings]
    if len(set(params)) != len(params):
        raise RuntimeError(f"model {model!r}: a parameter bound to two rules")
    RULE_BINDINGS[model] = ModelRules(machine, {ln.name: ln for ln in lengths}, tuple(bindings))
