"""Submodels, equations and the effect registry.

A *model* (``winch``, ``sheave``, ``capstan``) is assembled from *effects*; each
effect has named *variants*, and each variant is a :class:`Submodel` class
registered with :func:`register`.  An "off" variant is a submodel too (one that
builds no equations), so assembling a model never branches on whether an effect
is present: it looks the variant up in :data:`REGISTRY` and asks it for its
equations.

A submodel contributes

* ``quantities``: metadata (:class:`~ropemodel.quantity.Quantity`) of every
  symbol it introduces, inputs and outputs alike;
* ``equations(v)``: residuals ``r(v) = 0`` in CasADi SX, each naming the variable
  it *defines* (the output it computes in the forward problem).  The residual is
  acausal: the solver may use it for any of its variables;
* ``citations``: keys into :data:`ropemodel.citations.CITATIONS`;
* ``rules(values)``: cross-parameter checks (e.g. L_ul ≤ L_u) on SI values, one message per
  broken rule (or ``validate(values)`` raising :class:`~ropemodel.errors.InputError`);
* ``where(values)``: where each output taken at its worst (over positions, loads, manoeuvres) occurs.

Every quantity is declared once per model: a second, different declaration of the same name
raises at import (:func:`register`), so a default or a range cannot silently differ between
the effects that share a quantity.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar
from collections.abc import Callable

import casadi as ca

from ropemodel.errors import InputError, Problems, suggest
from ropemodel.quantity import Quantity


@dataclass(frozen=True)
class Equation:
    """One equation that defines ``defines`` in the forward problem.

    Either a residual ``residual == 0`` in CasADi SX (the usual, fully symbolic
    form), or — built with :meth:`from_call` — ``defines = fun(*args)`` for a
    CasADi Function that cannot be written in SX (an integrator, a rootfinder).

    Reports print the equation from these expressions (:mod:`ropemodel.core.formulas`), never from text:
    the residual solved for ``defines``.  Where that explicit form is an iteration (Newton unrolled in SX)
    rather than a formula, ``governing`` is the implicit equation it solves, written ``lhs - rhs`` in the
    same symbols (``ln s + q s (1 − e^(−α/k)) − μα``), and ``method`` says how it is solved; a call
    equation, or an error estimate, has no closed form: ``method`` names the method and ``tolerance`` its
    relative tolerance.
    """

    defines: str
    residual: ca.SX | None
    source: str
    call: tuple[ca.Function, tuple[str, ...]] | None = None
    #: the implicit equation (``lhs - rhs`` in SX) that an iterated explicit form solves, for reports
    governing: ca.SX | None = None
    #: how the value is computed where no closed form shows it (``"adaptive Dormand–Prince 5(4)"``)
    method: str = ""
    #: the relative tolerance that method meets, where it has one
    tolerance: float | None = None

    @classmethod
    def from_call(cls, defines: str, fun: ca.Function, args, source: str, method: str,
                  tolerance: float | None = None) -> Equation:
        """``defines = fun(*args)``: ``fun`` takes one scalar per name in ``args`` and returns one scalar.

        The compiled solver calls ``fun`` directly when it solves for ``defines``,
        and solves by Newton through ``fun``'s derivatives when an inverse
        question frees one of ``args``.  ``method`` (and ``tolerance``) say how ``fun`` computes it.
        """
        args = tuple(args)
        if fun.n_in() != len(args) or fun.n_out() != 1:
            raise RuntimeError(f"{fun.name()}: expected {len(args)} inputs and one output for {defines}")
        return cls(defines, None, source, (fun, args), method=method, tolerance=tolerance)

    def names(self) -> list[str]:
        """Every quantity the equation involves."""
        if self.call is not None:
            return [self.defines, *self.call[1]]
        if self.residual is None:
            return [self.defines]
        r = self.residual
        if r.is_scalar() and r.is_op(ca.OP_SUB) and r.dep(0).is_symbolic() and r.dep(1).is_symbolic():
            # y - x, as a route's 10 000 segments define their coefficients: what symvar gives, without its cost
            return list(dict.fromkeys((r.dep(0).name(), r.dep(1).name())))
        # symvar's names, in its order, as one list of strings (a route's sums name 20 000 symbols)
        return list(ca.Function("names", [], [r], {"allow_free": True}).get_free())


class Symbols(dict):
    """Name → scalar ``ca.SX`` symbol, created on first use."""

    def __missing__(self, name: str) -> ca.SX:
        sym = ca.SX.sym(name)
        self[name] = sym
        return sym


class Submodel:
    """Base class of every effect variant.  Subclasses set the class attributes and
    override :meth:`equations` (and :meth:`validate` where needed)."""

    model: ClassVar[str] = ""
    effect: ClassVar[str] = ""
    variant: ClassVar[str] = ""
    description: ClassVar[str] = ""
    citations: ClassVar[tuple[str, ...]] = ()
    quantities: ClassVar[tuple[Quantity, ...]] = ()
    #: the quantities :meth:`invalid_mask` reads (a sweep computes them even when not asked for)
    invalid_needs: ClassVar[tuple[str, ...]] = ()
    #: what this variant takes for granted, one sentence each (the report's "Assumptions")
    assumptions: ClassVar[tuple[str, ...]] = ()
    #: what a calculation with this variant still lacks before it is filed, one sentence each ("Data still missing")
    missing: ClassVar[tuple[str, ...]] = ()
    #: whether this variant's outputs depend on the load's place x_m only through the load's pull on its segment
    #: and the least tension of the winding rope (docs/physics.md §4, "Where the load governs"), so that the places
    #: :mod:`ropemodel.envelope.prune` keeps hold every worst case of them; False for a variant that reads x_m
    #: otherwise (the as-built elongation integrates the tension along the rope, the load's pull times x_m)
    place_through_pull: ClassVar[bool] = True

    def __init__(self, options: dict | None = None, effects: dict | None = None):
        #: the scene's ``[numerics]`` (and structural options such as the route's segments)
        self.options = dict(options or {})
        #: every effect of the model with its chosen variant (a submodel may adapt to the others)
        self.effects = dict(effects or {})

    def equations(self, v: Symbols) -> list[Equation]:
        """Residual equations of this submodel (none for an "off" variant)."""
        return []

    def derive(self, values) -> dict:
        """Parameters of this submodel's equations computed from the others for each load case (``derived``: a
        long route's numbers), at ``values`` (SI numbers or numpy arrays over points); {} for most."""
        return {}

    def validate(self, values: dict[str, float]) -> None:
        """Raise :class:`InputError` on inconsistent SI parameter values (or override :meth:`rules`)."""

    def rules(self, values: dict[str, float]) -> list[str]:
        """Every broken cross-parameter rule at the SI ``values`` (only names present are checked)."""
        try:
            self.validate(values)
        except InputError as exc:
            return list(exc.problems)
        return []

    def invalid(self, values: dict) -> list[str]:
        """Why a solved point lies outside the physics (e.g. a slack rope), one message each; [] if valid.

        ``values`` are the SI values of every known and solved quantity of the point.
        """
        return []

    def invalid_mask(self, values: dict) -> dict[str, object]:
        """Vectorised :meth:`invalid` for sweeps: reason → boolean array over the points of ``values``
        (only the names of :meth:`invalid_needs_for` are in ``values``)."""
        return {}

    def invalid_needs_for(self, outputs) -> tuple[str, ...]:
        """The quantities whose values decide whether ``outputs`` are valid (default: ``invalid_needs``)."""
        return self.invalid_needs

    def where(self, values: dict[str, float]) -> dict[str, str]:
        """Where each of this submodel's worst-case outputs occurs (output → text), for an output taken at its
        worst over positions, loads or manoeuvres; ``values`` as :meth:`invalid`.  ``{}`` for none."""
        return {}

    def frames(self, values: dict[str, float], scene, where: dict | None = None) -> dict:
        """Extra tables (title → pandas DataFrame with units in its columns) for a solved point; ``where``:
        output → the place that governs its value, when the values are each output's worst case
        (:mod:`ropemodel.envelope`)."""
        return {}

    def sibling(self, effect: str) -> Submodel:
        """The chosen variant of another ``effect`` of this model (built with the same options and effects),
        for what only it knows (e.g. the route's segments), found through the registry."""
        siblings = self.__dict__.setdefault("_siblings", {})    # built once: a route's knows 10 000 segments
        if effect not in siblings:
            spec = REGISTRY[self.model][effect]
            siblings[effect] = spec.variants[self.effects.get(effect, spec.default)](self.options, self.effects)
        return siblings[effect]


@dataclass
class EffectSpec:
    """An effect of a model: its variants and which one a scene gets by default."""

    name: str
    default: str
    doc: str
    variants: dict[str, type[Submodel]]


#: model name → effect name → :class:`EffectSpec`
REGISTRY: dict[str, dict[str, EffectSpec]] = {}
#: model name → quantity name → (its one declaration, the first variant that declared it)
DECLARED: dict[str, dict[str, tuple[Quantity, str]]] = {}


def define_effect(model: str, effect: str, default: str, doc: str) -> None:
    """Declare an effect of ``model`` with its default variant and a one-line doc."""
    effects = REGISTRY.setdefault(model, {})
    if effect in effects:
        raise RuntimeError(f"effect {model}.{effect} defined twice")
    effects[effect] = EffectSpec(effect, default, doc, {})


def register(model: str, effect: str, variant: str) -> Callable[[type[Submodel]], type[Submodel]]:
    """Class decorator: register a submodel as ``variant`` of ``model``'s ``effect``."""

    def deco(cls: type[Submodel]) -> type[Submodel]:
        spec = REGISTRY[model][effect]
        if variant in spec.variants:
            raise RuntimeError(f"variant {model}.{effect}={variant} registered twice")
        declared = DECLARED.setdefault(model, {})
        for q in cls.quantities:
            first = declared.setdefault(q.name, (q, f"{effect} = {variant!r}"))
            if first[0] != q:
                raise RuntimeError(f"quantity {q.name!r} of model {model!r} is declared twice, differently, by "
                                   f"{first[1]} and {effect} = {variant!r}: declare it once and share it")
        cls.model, cls.effect, cls.variant = model, effect, variant
        spec.variants[variant] = cls
        return cls

    return deco


def models() -> list[str]:
    """Names of the registered models."""
    return sorted(REGISTRY)


def effects_of(model: str) -> dict[str, EffectSpec]:
    """The effects of ``model``; :class:`InputError` for an unknown model."""
    if model not in REGISTRY:
        raise InputError(f"unknown model {model!r}; valid models: {', '.join(models())}{suggest(model, REGISTRY)}")
    return REGISTRY[model]


def resolve_effects(model: str, chosen: dict[str, str] | None, problems=None) -> dict[str, str]:
    """Fill in default variants and check every effect and variant name.

    With ``problems`` (a :class:`~ropemodel.errors.Problems`) every mistake is recorded there and the
    default variant is used in its place; without, the first mistake raises :class:`InputError`.
    """

    found = Problems() if problems is None else problems
    specs = effects_of(model)
    chosen = dict(chosen or {})
    out = {}
    for name in chosen:
        if name not in specs:
            found.add(misplaced(model, name, "[effects]") or
                      f"unknown effect {name!r} for model {model!r}; valid effects: "
                      f"{', '.join(sorted(specs))}{suggest(name, specs)}")
    for name, spec in specs.items():
        variant = chosen.get(name, spec.default)
        if not isinstance(variant, str) or variant not in spec.variants:
            found.add(f"effect {name} = {variant!r} is not a variant; valid variants: "
                      f"{', '.join(sorted(spec.variants))}{suggest(str(variant), spec.variants)}")
            variant = spec.default
        out[name] = variant
    if problems is None:
        found.raise_if_any()
    return out


def misplaced(model: str, name: str, table: str) -> str | None:
    """``"alpha_u is a parameter: move it to [parameters]"`` when ``name`` belongs in another table."""
    where = {"[parameters]": name in all_quantities(model) if model in REGISTRY else False,
             "[effects]": name in REGISTRY.get(model, {}),
             "[numerics]": name in NUMERICS.get(model, {})}
    kind = {"[parameters]": "a parameter", "[effects]": "an effect", "[numerics]": "a numerics option"}
    for right, hit in where.items():
        if hit and right != table:
            return f"{name} is {kind[right]} of model {model!r}: move it to {right}"
    return None


def all_quantities(model: str) -> dict[str, Quantity]:
    """Every quantity any variant of ``model`` knows (for name checks and suggestions)."""
    out: dict[str, Quantity] = {}
    for spec in effects_of(model).values():
        for cls in spec.variants.values():
            for q in cls.quantities:
                out.setdefault(q.name, q)
    return out


@dataclass
class NumericsOption:
    """A ``[numerics]`` option of a model: default, doc, and ``check(key, value) -> value``."""

    default: object
    doc: str
    check: Callable[[str, object], object]


#: model name → option name → :class:`NumericsOption`
NUMERICS: dict[str, dict[str, NumericsOption]] = {}


def define_numerics(model: str, key: str, default, doc: str, check: Callable[[str, object], object]) -> None:
    """Declare a ``[numerics]`` option of ``model``."""
    NUMERICS.setdefault(model, {})[key] = NumericsOption(default, doc, check)


def numerics_of(model: str) -> dict[str, NumericsOption]:
    """The ``[numerics]`` options of ``model`` (possibly none)."""
    effects_of(model)
    return NUMERICS.get(model, {})


def choice(*allowed):
    """A ``check`` for :func:`define_numerics` that accepts one of ``allowed``."""

    def check(key, value):
        if value not in allowed:
            raise InputError(f"numerics {key} = {value!r} is not one of {', '.join(map(repr, allowed))}"
                             f"{suggest(str(value), [str(a) for a in allowed])}")
        return value

    return check


def whole_number(low: int, high: int):
    """A ``check`` for :func:`define_numerics` accepting a whole number in [low, high] (not 2.5, not true)."""

    def check(key, value):
        if isinstance(value, bool) or not isinstance(value, int) or not (low <= value <= high):
            raise InputError(f"numerics {key} = {value!r} must be a whole number in [{low}, {high}]")
        return value

    return check


def positive_number(low: float = 0.0, high: float = float("inf")):
    """A ``check`` for :func:`define_numerics` accepting a number in (low, high]."""

    def check(key, value):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (low < value <= high):
            raise InputError(f"numerics {key} = {value!r} must be a number in ({low:g}, {high:g}]")
        return float(value)

    return check
