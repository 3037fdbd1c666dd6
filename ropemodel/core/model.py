"""A model: the equations of a set of effect variants, with their quantities."""

from __future__ import annotations

from functools import cached_property

import casadi as ca

from ropemodel.citations import cite
from ropemodel.effects import Equation, Symbols, all_quantities, effects_of, misplaced, resolve_effects, route_arrays
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
    parameters: every other symbol the equations use (knowns of the forward problem), but the derived ones.
    arguments: the parameters and the derived (a long route's numbers): the compiled Functions' inputs.
    quantities: metadata of every output and parameter.
    symbols: name → CasADi SX symbol.
    """

    def __init__(self, model: str, effects: dict[str, str] | None = None, options: dict | None = None):
        self.name = model
        self.options = dict(options or {})
        self.effects = resolve_effects(model, effects)
        specs = effects_of(model)
        self.submodels = [specs[e].variants[v](options, self.effects) for e, v in self.effects.items()]
        self.symbols = Symbols()
        self.equations: list[Equation] = []
        defined: dict[str, str] = {}
        #: effect → variant of the submodels that built at least one equation
        self.built_effects: dict[str, str] = {}
        #: output → the names its equation involves (:meth:`Equation.names`, read once: a route's sums name
        #: every segment)
        self.names_of: dict[str, list[str]] = {}
        for sm in self.submodels:
            for eq in sm.equations(self.symbols):
                self.built_effects[sm.effect] = sm.variant
                names = eq.names()
                for name in names:
                    self.symbols[name]  # a call equation's names become symbols too
                if eq.defines in defined:
                    raise RuntimeError(f"{eq.defines} defined by both {defined[eq.defines]} and {sm.effect}")
                defined[eq.defines] = sm.effect
                self.names_of[eq.defines] = names
                self.equations.append(eq)
        self.outputs = [eq.defines for eq in self.equations]
        #: parameters of the equations computed from the others per load case (a long route's numbers): name ->
        #: the case inputs (``x_m``, ``a_h``) each follows
        self.derived: dict[str, tuple[str, ...]] = {k: f for sm in self.submodels
                                                    for k, f in getattr(sm, "derived", {}).items()}
        #: every input of the equations (the compiled Functions'): the parameters and the :attr:`derived`
        self.arguments = [n for n in self.symbols if n not in defined]
        self.parameters = [n for n in self.arguments if n not in self.derived]
        known = {**all_quantities(model), **{q.name: q for sm in self.submodels for q in sm.quantities}}
        #: every quantity this model could know: every variant's, and this instance's own (a route's segments)
        self.universe = known
        missing = [n for n in self.symbols if n not in known]
        if missing:
            raise RuntimeError(f"no Quantity declared for {missing} in model {model}")
        self.quantities: dict[str, Quantity] = {n: known[n] for n in self.symbols}
        self.defined_by = defined
        #: a long route's segments (``L_i``, ``alpha_i``, ``mu_wi``): the scene's parameters, read and set by name,
        #: that the equations take only through the route numbers :meth:`derive` computes from them
        self.edges: tuple[str, ...] = tuple(n for sm in self.submodels for n in getattr(sm, "edges", ()))
        self.edge_set = frozenset(self.edges)
        self.quantities.update({n: known[n] for n in self.edges})

    def derive(self, values) -> dict:
        """The :attr:`derived` parameters at ``values`` (SI numbers, or numpy arrays over points): {} without."""
        out: dict = {}
        for sm in self.submodels:
            if getattr(sm, "derived", None):
                out.update(sm.derive(values))
        return out

    def derive_through(self, values, edges) -> dict:
        """The :attr:`derived` parameters at one point (SI numbers ``values``) as CasADi expressions of the
        :attr:`edges` named in ``edges`` (name -> expression): what a derivative in a segment's value goes through."""
        out: dict = {}
        for sm in self.submodels:
            if getattr(sm, "derived", None):
                out.update(sm.derive_through(values, edges))  # type: ignore[attr-defined]
        return out

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
        return self.equations[self._index[name]]

    @cached_property
    def _index(self) -> dict[str, int]:
        return {o: i for i, o in enumerate(self.outputs)}

    def inputs_of(self, names=None) -> set[str]:
        """The parameters the outputs ``names`` (default: every output) are computed from, through the
        equations; a parameter among ``names`` is its own input.

        >>> m = Model("winch")
        >>> sorted(m.inputs_of(["G_ml"]))          # Krauze et al. (2025), eq. (1): G_ml = G_m sin α_u
        ['G_m', 'alpha_u']
        """
        todo = list(self.outputs if names is None else names)
        seen: set[str] = set()
        out: set[str] = set()
        while todo:
            name = todo.pop()
            if name in seen:
                continue
            seen.add(name)
            if name in self.defined_by:
                todo += self.names_of[name]
            elif name in self.derived:       # a route number: the segments, and what it takes per case
                out |= self.edge_set
                todo += [n for n in (*self.derived[name], "mu_pl", "L_ul") if n in self.symbols]
            elif name in self.symbols:
                out.add(name)
        return out

    @property
    def key(self) -> tuple:
        """What the equations depend on (model, effects, numerics): one compile serves every value."""
        return (self.name, tuple(sorted(self.effects.items())), repr(sorted(self.options.items())), bool(self.derived))

    def problems(self, values: dict[str, float]) -> list[str]:
        """Every value outside its valid range, then every broken cross-parameter rule (SI ``values``)."""
        out = []
        for name, value in values.items():
            if name in self.quantities:
                problem = self.quantities[name].range_problem(value)
                if problem:
                    out.append(problem)
        for sm in self.submodels:
            out += [p for p in sm.rules(values) if p not in out]
        return out

    def validate(self, values: dict[str, float]) -> None:
        """:class:`InputError` listing every out-of-range value and broken rule of ``values``."""
        found = self.problems(values)
        if found:
            raise InputError(problems=found)

    def owners(self, name: str) -> list[str]:
        """``effect = 'variant'`` of every other variant of this model that declares ``name``."""
        return [f"{e} = {v!r}" for e, spec in effects_of(self.name).items() for v, cls in spec.variants.items()
                if any(q.name == name for q in cls.quantities) and self.effects[e] != v]

    def name_problem(self, name: str, what: str = "parameter") -> str | None:
        """Why ``name`` is not a quantity of this model (a suggestion, or the variant that uses it), or None."""
        if name in self.symbols or name in self.edge_set:
            return None
        segments = self.options.get("route")
        past_the_end = route_arrays.beyond(name, len(segments)) if segments else None
        if past_the_end:       # a segment beyond the route: the valid names, not a lookalike
            return f"{what} {past_the_end}"
        if name in self.universe:
            owners = self.owners(name)
            hint = f"; it belongs to {' or '.join(owners)}" if owners else ""
            return f"{what} {name!r} is not used by this scene's effects{hint}"
        return misplaced(self.name, name, "") or (
            f"unknown {what} {name!r} for model {self.name!r}{suggest(name, list(self.universe))}")

    def check_names(self, names, what: str = "parameter") -> None:
        """:class:`InputError` naming every name that is not a quantity of this model."""
        found = [p for p in (self.name_problem(n, what) for n in names) if p]
        if found:
            raise InputError(problems=found)
