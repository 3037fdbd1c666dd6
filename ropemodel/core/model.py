"""A model: the equations of a set of effect variants, with their quantities."""

from __future__ import annotations

import casadi as ca

from ropemodel.citations import cite
from ropemodel.effects import Equation, Symbols, all_quantities, effects_of, resolve_effects
from ropemodel.errors import InputError, suggest
from ropemodel.quantity import Quantity


class Model:
    """The equation system of ``model`` with the chosen effect variants.

    Attributes
    ----------
    effects: effect → variant, defaults filled in.
    submodels: one instance per effect.
    equations: every residual equation, in submodel order.
    outputs: names defined by the equations (unknowns of the forward problem).
    parameters: every other symbol the equations use (knowns of the forward problem).
    quantities: metadata of every output and parameter.
    symbols: name → CasADi SX symbol.
    """

    def __init__(self, model: str, effects: dict[str, str] | None = None, options: dict | None = None):
        self.name = model
        self.effects = resolve_effects(model, effects)
        specs = effects_of(model)
        self.submodels = [specs[e].variants[v](options) for e, v in self.effects.items()]
        self.symbols = Symbols()
        self.equations: list[Equation] = []
        defined: dict[str, str] = {}
        #: effect → variant of the submodels that built at least one equation
        self.built_effects: dict[str, str] = {}
        for sm in self.submodels:
            for eq in sm.equations(self.symbols):
                self.built_effects[sm.effect] = sm.variant
                for name in eq.names():
                    self.symbols[name]  # a call equation's names become symbols too
                if eq.defines in defined:
                    raise RuntimeError(f"{eq.defines} defined by both {defined[eq.defines]} and {sm.effect}")
                defined[eq.defines] = sm.effect
                self.equations.append(eq)
        self.outputs = [eq.defines for eq in self.equations]
        self.parameters = [n for n in self.symbols if n not in defined]
        known = all_quantities(model)
        missing = [n for n in self.symbols if n not in known]
        if missing:
            raise RuntimeError(f"no Quantity declared for {missing} in model {model}")
        self.quantities: dict[str, Quantity] = {n: known[n] for n in self.symbols}
        self.defined_by = defined

    @property
    def citations(self) -> list[str]:
        """Full references of every submodel in use."""
        return cite(k for sm in self.submodels for k in sm.citations)

    def structural(self, i: int):
        """An SX expression with the incidence of equation ``i`` (its residual, or a stand-in
        for a call equation: used for structure only, never evaluated)."""
        eq = self.equations[i]
        if eq.call is None:
            return eq.residual
        args = ca.vertcat(*[self.symbols[a] for a in eq.call[1]])
        return self.symbols[eq.defines] - ca.sum1(ca.sin(args))

    def equation_of(self, name: str) -> Equation:
        return self.equations[self.outputs.index(name)]

    def validate(self, values: dict[str, float]) -> None:
        """Range of every given value, then each submodel's cross-parameter checks."""
        for name, value in values.items():
            if name in self.quantities:
                self.quantities[name].check(value)
        for sm in self.submodels:
            sm.validate(values)

    def check_names(self, names, what: str = "parameter") -> None:
        """:class:`InputError` for a name that is not a quantity of this model."""
        for n in names:
            if n not in self.symbols:
                universe = all_quantities(self.name)
                if n in universe:
                    owners = [
                        f"{e} = {v!r}"
                        for e, spec in effects_of(self.name).items()
                        for v, cls in spec.variants.items()
                        if any(q.name == n for q in cls.quantities) and self.effects[e] != v
                    ]
                    hint = f"; it belongs to {' or '.join(owners)}" if owners else ""
                    raise InputError(f"{what} {n!r} is not used by this scene's effects{hint}")
                raise InputError(
                    f"unknown {what} {n!r} for model {self.name!r}{suggest(n, list(self.symbols))}"
                )

