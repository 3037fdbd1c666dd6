"""Sizing declarations: what ``ropemodel size`` chooses for a model, and what it must keep.

A machine whose design includes an integer enumerated (a Koepe hoist's number of head ropes) declares its sizing
as a :class:`Declaration` (a subclass, its instance the machine's ``sizing``: data and functions that build
CasADi expressions); the generic driver (:mod:`optimisation.declared`) turns a declaration into the same NLP
machinery the winch uses (IPOPT with exact derivatives, a catalogue step, the diagnosis of no design in the
user's terms).  A declaration imports nothing above the machines' layer: it knows its physics, not its solver.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from ropemodel.machines.base import machine_of


@dataclass(frozen=True)
class Variable:
    """A continuous design variable: its scene parameter, the scale IPOPT sees it in (SI per unit of x), its
    bounds (SI) and the steps its recommended value is rounded to (SI, coarsest first; none: not rounded)."""

    name: str
    scale: float
    low: float
    high: float
    steps: tuple[float, ...] = ()


@dataclass(frozen=True)
class Check:
    """One constraint g >= 0 of the NLP: the design check it belongs to (a margin output of the model), where
    it is made (words), its expression (CasADi) and the unit of g ("N", "m", "m/s^2" or "1")."""

    check: str
    where: str
    g: Any
    unit: str


@dataclass(frozen=True)
class Transient:
    """A transient a design must hold in: the allowance raised while it does not, the scene's effects and values
    (SI) that make it, and what it is in words."""

    allowance: str
    effects: dict
    values: dict
    words: str


class Declaration:
    """The sizing of one machine (a subclass per machine; its instance is the ``sizing`` of the machine's
    :class:`~ropemodel.machines.Machine`).

    The first of :attr:`variables` is chosen from a catalogue (:meth:`catalogue`, next size up); the
    integer :attr:`integer` is enumerated over :meth:`counts` (one continuous NLP each, the lightest feasible
    design kept).  ``v`` below maps every scene parameter and design variable to a value or a CasADi symbol.
    """

    model: ClassVar[str] = ""
    variables: ClassVar[tuple[Variable, ...]] = ()
    #: the integer design variable enumerated (a scene parameter), and what it counts
    integer: ClassVar[str] = ""
    #: check → (scene parameter that relaxes it, "min" or "max") for the diagnosis of no design
    remedies: ClassVar[dict[str, tuple[tuple[str, str], ...]]] = {}
    #: NLP parameters (0 by default) that tighten checks for what the rigid checks cannot see; each is raised
    #: (bisection) while a transient of :meth:`transients` naming it does not hold
    allowances: ClassVar[tuple[str, ...]] = ()
    #: what the objective is, in words (the output says it)
    objective_text: ClassVar[str] = ""
    #: what sizing chooses, in words (``ropemodel size``'s status line)
    CHOOSES: ClassVar[str] = "the design"
    #: dimensions a scene may leave out besides the design (none)
    D_OPTIONAL: ClassVar[tuple[str, ...]] = ()
    #: what a scene the report sizes is (a Jinja2 template of ``scene``)
    SCENE_TEXT: ClassVar[str] = "the {{ scene.model }}'s declared sizing"

    @property
    def VARIABLES(self) -> tuple[str, ...]:
        """The design variables' names: the integer enumerated, then the continuous ones."""
        return (self.integer, *(x.name for x in self.variables))

    def rope_problem(self, scene) -> str | None:
        """Why sizing cannot choose the scene's ropes, or None (a declaration chooses them from its catalogue)."""
        return None

    def reported(self, scene) -> bool:
        """Whether the report sizes ``scene``: a scene without a transient (sizing through one simulates every
        trial design: ``ropemodel size`` does it)."""
        return scene.effects.get("dynamics", "none") == "none"

    def prepare(self, scene):
        """The scene as sizing reads it (its checks switched on)."""
        raise NotImplementedError

    def counts(self, scene) -> tuple[int, ...]:
        """The values of :attr:`integer` enumerated."""
        raise NotImplementedError

    def catalogue(self, scene) -> list[float]:
        """The stocked sizes of the first variable (SI, ascending)."""
        raise NotImplementedError

    def bounds(self, scene) -> list[tuple[float, float]]:
        """(low, high) of each variable (SI): the declared bounds, narrowed by what the scene fixes."""
        return [(x.low, x.high) for x in self.variables]

    def unit_scales(self, scene) -> dict[str, float]:
        """What a constraint of each unit is divided by in the NLP (SI): a typical force, 1 otherwise."""
        return {"N": 1e4, "m": 1.0, "m/s^2": 1.0, "1": 1.0}

    def start(self, scene, count: int) -> dict[str, float]:
        """A starting design (SI) for ``count``."""
        raise NotImplementedError

    def completed(self, scene, v) -> dict:
        """``v`` with what follows from the design variables (e.g. a rope's mass and strength from its size)."""
        raise NotImplementedError

    def objective(self, scene, v):
        """(primary, secondary): the quantity minimised [SI] and a tie-breaker weighted far below it."""
        raise NotImplementedError

    def checks(self, scene, v) -> list[Check]:
        """Every constraint, smooth, one per state and side it is made in."""
        raise NotImplementedError

    def at_design(self, scene, design: dict[str, float]) -> dict[str, float]:
        """The scene's parameter values (SI) at a design: the variables and what follows from them."""
        raise NotImplementedError

    def transients(self, scene, values: dict, result) -> list[Transient]:
        """The transients a design (the scene's ``values`` at it, SI, and its solved ``result``) must hold in;
        none by default."""
        return []

    def holds(self, summary: dict) -> bool:
        """Whether a transient's summary shows the design holding."""
        raise NotImplementedError

    def reads(self, scene) -> tuple[set[str], dict[str, str]]:
        """What the sizing is computed from, and what it sets itself (name → how)."""
        raise NotImplementedError


def declared(model) -> Declaration | None:
    """The sizing of ``model`` (a scene or a model's name) when its machine declares it as a :class:`Declaration`
    (sized by :mod:`optimisation.declared`), else None (a sizing module such as the winch's, sized by
    :class:`optimisation.problem.SizingProblem`, or no sizing)."""
    sizing = getattr(machine_of(model), "sizing", None)
    return sizing if isinstance(sizing, Declaration) else None
