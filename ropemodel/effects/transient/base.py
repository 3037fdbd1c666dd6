"""What a transient variant contributes, PyBaMM style: states, right-hand side, events, initial conditions.

A transient of a winch scene (start-up or braking, :mod:`ropemodel.dynamics`) is assembled from
the variants the scene picks for the effects of this package (``dynamics``, ``travel``, ``ramp``,
``rope_elasticity``, ``tensioner``, ``drive``, ``drum_contact``) plus the drum's ``lining``.  Each
variant is a :class:`TransientSubmodel` registered in the effect registry like every static one;
:func:`ropemodel.dynamics.simulate` asks the registry for the scene's variants and only *asks them*
(it names no variant).  A variant declares

* :meth:`~TransientSubmodel.states`: its named states (:class:`State`) — the layout of the state
  vector is the concatenation, in assembly order (:attr:`~TransientSubmodel.order`);
* :meth:`~TransientSubmodel.modes`: its discrete modes (e.g. the tensioner's carriage ``free`` or on an
  end stop); a mode of the whole system is one mode per variant (:class:`Mode`);
* :meth:`~TransientSubmodel.publish`: the named quantities it computes in a mode, for the others to
  read (:class:`Variables`, filled in assembly order: states first, then each variant);
* :meth:`~TransientSubmodel.set_rhs`: the right-hand side of its own states;
* :meth:`~TransientSubmodel.add_events_from`: its switching functions (:class:`Switch`), each ≥ 0 while
  the mode holds, with the event it fires, the mode that follows and the state jumps (resets);
* :meth:`~TransientSubmodel.initial_mode`, :meth:`~TransientSubmodel.steady` and
  :meth:`~TransientSubmodel.initial_values`: its initial conditions (the start is an equilibrium);
* ``quantities``: its parameters, like every submodel; ``energy``/``dissipation`` for the energy
  balance; ``summary``/``report`` for its part of the results.

Every expression may be a CasADi symbol: the values in :attr:`Setup.values` are floats for a
simulation and SX symbols for the symbolic smooth mode (:func:`ropemodel.dynamics.smooth_mode`);
structural choices (number of nodes, which switches exist) use :attr:`Setup.numbers`, always floats.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

import casadi as ca

from ropemodel.effects.base import REGISTRY, Submodel

MODEL = "winch"
#: standard gravity [m/s²]
G_N = 9.80665


@dataclass(frozen=True)
class State:
    """A named state: ``size`` scalars (a vector state, e.g. the node speeds, has size > 1)."""

    name: str
    size: int = 1
    doc: str = ""


class Layout:
    """Named index ranges of the state vector (no index arithmetic anywhere else).

    A *reference* to one scalar is a scalar state's name (``"z"``) or ``(name, i)`` (``("v", 0)``).
    """

    def __init__(self, states):
        self.states = tuple(states)
        self._at: dict[str, tuple[int, int]] = {}
        start = 0
        for s in self.states:
            if s.name in self._at:
                raise RuntimeError(f"state {s.name!r} declared twice")
            self._at[s.name] = (start, s.size)
            start += s.size
        self.nx = start

    def __contains__(self, name: str) -> bool:
        return name in self._at

    def size(self, name: str) -> int:
        return self._at[name][1]

    def slice(self, name: str) -> slice:
        start, size = self._at[name]
        return slice(start, start + size)

    def index(self, ref) -> int:
        """Index of one scalar: ``"z"`` or ``("v", 0)``."""
        name, i = (ref, 0) if isinstance(ref, str) else ref
        start, size = self._at[name]
        if not 0 <= i < size:
            raise IndexError(f"state {name} has {size} components, not {i + 1}")
        return start + i

    def split(self, x) -> dict:
        """Name → part of ``x`` (a scalar for a scalar state)."""
        return {s.name: x[self.index(s.name)] if s.size == 1 else x[self.slice(s.name)] for s in self.states}


@dataclass(frozen=True)
class Mode:
    """One discrete mode per variant: ``(effect, mode)`` pairs, hashable (the compile cache's key)."""

    items: tuple[tuple[str, str], ...]

    @classmethod
    def of(cls, modes: dict[str, str]) -> Mode:
        return cls(tuple(modes.items()))

    def __getitem__(self, effect: str) -> str:
        return dict(self.items)[effect]

    def replace(self, effect: str, mode: str) -> Mode:
        return Mode(tuple((e, mode if e == effect else m) for e, m in self.items))

    def __str__(self) -> str:
        return ", ".join(f"{e} {m}" for e, m in self.items)


@dataclass(frozen=True)
class Switch:
    """A switching function of a mode: ``g`` ≥ 0 while the mode holds (divided by ``scale`` for the
    event tests).  When it crosses zero the event ``name`` fires: the variant ``effect`` goes to mode
    ``target`` (``None``: a terminal event, the simulation ends there) and the states jump as ``reset``
    says, reference → SX expression in (x, t) evaluated just before the event."""

    name: str
    g: Any
    scale: float
    effect: str
    target: str | None
    reset: dict = field(default_factory=dict)

    @property
    def terminal(self) -> bool:
        return self.target is None


class Variables(dict):
    """The named quantities of one mode: the states, ``t``, then what each variant publishes."""

    def __missing__(self, key):
        raise KeyError(f"transient variable {key!r} is not published (published: {', '.join(self)})")

    def publish(self, **items) -> None:
        for k, value in items.items():
            if k in self:
                raise RuntimeError(f"transient variable {k!r} published twice")
            self[k] = value


@dataclass
class Setup:
    """What the variants of one transient are built from.

    values: SI values of the scene's parameters and of the static model's outputs (floats, or SX
        symbols for the symbolic smooth mode); numbers: the same at the scene's numbers (floats), for
        structural choices and checks; options: the scene's ``[numerics]``; parts: effect → the chosen
        transient variant; submodels: effect → every chosen submodel (static ones too: the lining).
    The variants fill in, in assembly order: ``direction``/``travel`` (the travel), ``phases`` and
    ``speed0`` (the profile: its phases and the drum's speed at t = 0), ``route`` and ``chain`` (the rope;
    the drum contact may replace the chain), and the orchestrator ``f_scale``/``v_scale`` (force and speed
    scales of the switching functions).
    """

    values: dict
    numbers: dict
    options: dict
    parts: dict
    submodels: dict
    direction: int = +1
    travel: str = "up"
    phases: list = field(default_factory=list)      # empty until the profile binds
    speed0: Any = 0.0
    route: Any = None
    chain: Any = None
    f_scale: float = 1.0
    v_scale: float = 1.0

    def part(self, effect: str) -> TransientSubmodel:
        return self.parts[effect]

    @property
    def symbolic(self) -> bool:
        """True when the values are CasADi symbols (no numeric integration)."""
        return any(isinstance(v, (ca.SX, ca.MX)) for v in self.values.values())


class TransientSubmodel(Submodel):
    """Base class of a transient variant: every hook has a neutral default (no state, one mode ``on``).

    ``order`` fixes the assembly order (publishing, states, events); ``column`` names the history
    column of its mode; ``smooth`` is its mode in the smooth regime (rope sticking on the drum,
    tensioner free, drive on its ramp) used by :func:`ropemodel.dynamics.smooth_mode`.
    ``gathered``: its quantities become scene parameters of every transient scene (declared by the
    profile, because a submodel is built without knowing the other effects' variants); a variant with
    required parameters of its own sets it False and declares them in :meth:`equations`.
    """

    order: ClassVar[int] = 50
    column: ClassVar[str | None] = None
    smooth: ClassVar[str] = "on"
    gathered: ClassVar[bool] = True
    #: added to the message of a rope slack at the start (why this variant may be the cause)
    slack_hint: ClassVar[str] = ""
    #: parameters that fix the structure (numbers of nodes, which span exists): never symbols
    structural: ClassVar[tuple[str, ...]] = ()
    #: quantities of the static model the variant reads (declared there, e.g. q_lw): scene parameters of a
    #: transient like its own ``quantities``, without claiming them (messages name their static owners)
    reads: ClassVar[tuple[str, ...]] = ()
    #: its parameters that only an elastic rope loop uses (a rigid loop does not move them: a tensioner's
    #: carriage mass); what a transient reads leaves them out with an inextensible rope
    elastic_only: ClassVar[tuple[str, ...]] = ()
    #: its parameters only dynamic sizing reads (a factor or a tolerance of its checks through a manoeuvre):
    #: the simulator never does, so a simulation's report does not list them among its assumptions
    sizing_only: ClassVar[tuple[str, ...]] = ()

    def equations(self, v):
        if not self.gathered:
            for name in (*(q.name for q in self.quantities), *self.reads):
                v[name]  # noqa: B018 - creating the symbol makes it a parameter of the scene
        return []

    def bind(self, setup: Setup) -> None:
        """Take the numbers (or symbols) of the scene; check what only this variant can check."""
        self.setup = setup

    @property
    def values(self) -> dict:
        return self.setup.values

    def states(self) -> tuple[State, ...]:
        return ()

    def modes(self) -> tuple[str, ...]:
        return ("on",)

    def initial_mode(self, ic) -> str:
        """The mode at t = 0; ``ic`` (:class:`ropemodel.dynamics.system.Initial`) solves equilibria and
        pins states."""
        return self.modes()[0]

    def initial_values(self, speed) -> dict:
        """Values of own states at the start other than 0 (reference → value); ``speed`` is the drive's."""
        return {}

    def steady(self, v: Variables, mode: str) -> list:
        """(reference, residual) pairs: own unknowns of the initial equilibrium and their equations."""
        return []

    def publish(self, v: Variables, mode: str) -> None:
        """Publish the quantities this variant computes in ``mode``."""

    def set_rhs(self, v: Variables, mode: str) -> dict:
        """State name → its time derivative (an SX, or a list of SX for a vector state)."""
        return {}

    def add_events_from(self, v: Variables, mode: str) -> list[Switch]:
        return []

    def project(self, v: Variables, mode: str) -> dict:
        """States to set (reference → SX) whenever the mode is made consistent (at the start, at a phase
        boundary, after an event): e.g. the rope on the drum takes the drum's speed while it sticks."""
        return {}

    def energy(self, v: Variables, mode: str):
        """Kinetic + potential energy held by this variant [J]."""
        return 0

    def dissipation(self, v: Variables, mode: str):
        """Power dissipated by this variant [W] (≥ 0)."""
        return 0

    def outputs(self, v: Variables, mode: str) -> dict:
        """History columns (label with unit → expression)."""
        return {}

    def moving_masses(self) -> dict:
        return {}

    def check_start(self, out: dict) -> None:
        """Raise :class:`~ropemodel.errors.InputError` if the start (history columns ``out`` at t = 0) is
        not a transient this variant can simulate."""

    def summary(self, run) -> dict:
        """Its part of the summary (SI); ``run`` has ``history``, ``events``, ``setup``."""
        return {}

    def report(self, summary: dict) -> list[str]:
        """Its lines of the readable report."""
        return []

    def ending(self, summary: dict) -> list[str]:
        """Lines that close the report (why the run ended early)."""
        return []


def transient_effects(model: str = MODEL) -> list[str]:
    """Names of the effects whose variants are transient submodels."""
    return [e for e, spec in REGISTRY[model].items()
            if any(issubclass(c, TransientSubmodel) for c in spec.variants.values())]


def gathered_parameters(model: str = MODEL) -> list[str]:
    """Names of the quantities every gathered transient variant declares or reads (parameters of every
    transient scene)."""
    out = []
    for effect in transient_effects(model):
        for cls in REGISTRY[model][effect].variants.values():
            if issubclass(cls, TransientSubmodel) and cls.gathered:
                out += [n for n in (*(q.name for q in cls.quantities), *cls.reads) if n not in out]
    return out


def event_table(events, names) -> list[dict]:
    """``[{"t": ..., "event": ...}]`` of the events called one of ``names``."""
    return [{"t": float(ev.t), "event": ev.name} for ev in events if ev.name in names]
