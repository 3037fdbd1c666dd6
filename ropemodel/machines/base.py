"""A machine's declaration (:class:`Machine`) and the registry the generic drivers read it from.

Each part of a declaration but its checks is optional: a machine without ``sizing`` cannot be sized
(``ropemodel size`` says so, naming the machines that can), one without ``transient`` has no transient, one
without ``trips`` makes no trips.  The drivers never ask which machine a scene is; they ask its declaration
(:func:`machine_of`, :func:`needing`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from ropemodel.errors import InputError


class Figure(NamedTuple):
    """What the report's transient section draws of a simulation's history: ``columns`` (the first is the
    abscissa; empty: every column, against ``t [s]``), one panel per unit of ``units`` (SI, as in the column
    names), and ``caption`` (plain text, before the number of output times)."""

    columns: tuple[str, ...] = ()
    units: tuple[str, ...] = ("N", "m/s", "m")
    caption: str = "Forces (kN), speeds (m/s) and lengths (m) against time"


@dataclass(frozen=True)
class Transient:
    """How :func:`ropemodel.dynamics.simulate` assembles and integrates a machine's transient.

    ``profile``: the variant class (of the ``dynamics`` effect) whose presence makes a transient;
    ``result``: the simulation it returns, built as ``result(scene, system)`` (with ``record`` and ``finish``;
    None: :class:`ropemodel.dynamics.Simulation`);
    ``numbers``: the static run's values as the transient's setup takes them;
    ``scale(setup)``: the switching functions' scales ``(v_scale [m/s], f_scale [N])`` of a bound setup;
    ``length(system)``: the length [m] whose ``sim_rtol / 10`` is the integrator's absolute tolerance.
    """

    profile: type
    result: type | None
    scale: Callable[[Any], tuple[float, float]]
    length: Callable[[Any], float]
    numbers: Callable[[dict], dict] = dict
    #: set the scales before the variants bind to the setup (they read them), not after (they set what
    #: the scales are taken from)
    before_bind: bool = False
    #: the report's note on a transient with an inextensible rope (a Jinja2 template of ``r``, the rope's
    #: variant, and ``trip``, where else the report shows the rope's stretch)
    rigid_note: str = ""
    #: ``dynamics`` variants (subclasses of ``profile``) another report section shows (the winch's whole trip)
    elsewhere: tuple[type, ...] = ()
    #: what the report's transient section says of it after ``dynamics = "..."`` (plain text)
    about: str = ""
    #: the history the report draws: its columns (empty: every column), one panel per unit, and the caption
    figure: Figure = Figure()


@dataclass(frozen=True)
class Machine:
    """What a machine declares (see the package's docstring).

    ``model``: the scene's ``model``; ``title``: the machine in words (``"rope haulage winch"``);
    ``checks(names)``: the margin outputs among ``names`` in the machine's report order;
    ``sizing``: its sizing declaration (what :mod:`optimisation` chooses, minimises and keeps), or None;
    ``manoeuvres``: what dynamic sizing takes it through (:mod:`optimisation.dynamic`), or None;
    ``transient``: how its transient is simulated (:class:`Transient`), or None;
    ``trips``: what its trips along a route take from it (:mod:`ropemodel.trips`), or None;
    ``sections``: the report sections its scenes may show (names of :mod:`ropemodel.reports` sections);
    ``check_text``: each check in words; ``words``: the checks of dynamic sizing in words, with the factors they
    apply (a :class:`ropemodel.views.checks.Vocabulary`, needed with ``manoeuvres``).
    """

    model: str
    title: str
    checks: Callable[[Iterable[str]], list[str]]
    sizing: Any = None
    manoeuvres: Any = None
    transient: Transient | None = None
    trips: Any = None
    sections: tuple[str, ...] = ()
    #: the submodel classes of a rope chosen from a catalogue (what the report derives from it, its designation)
    ropes: tuple[type, ...] = ()
    #: check (a margin's base name) → what it checks, in words (the report's table of checks)
    check_text: dict[str, str] = field(default_factory=dict)
    #: its checks in words where dynamic sizing shows them (:class:`ropemodel.views.checks.Vocabulary`), or None
    words: Any = None


#: model → its machine's declaration (every subpackage of :mod:`ropemodel.machines` registers its own)
MACHINES: dict[str, Machine] = {}
#: the model of a scene that names none (:mod:`ropemodel.scene_tables`'s default)
DEFAULT_MODEL = "winch"


def register(machine: Machine) -> Machine:
    """Declare ``machine`` for its model (once: a second declaration of a model is a programming error)."""
    if machine.model in MACHINES:
        raise RuntimeError(f"machine {machine.model!r} is declared twice")
    MACHINES[machine.model] = machine
    return machine


def machine_of(scene_or_model) -> Machine | None:
    """The declaration of a scene's machine (or of a model's name); None for a model that declares none
    (an analysis model such as a sheave or a capstan)."""
    model = scene_or_model if isinstance(scene_or_model, str) else scene_or_model.model
    return MACHINES.get(model)


def declared_machine(scene) -> Machine:
    """The declaration of ``scene``'s machine; :class:`InputError` for a model that declares none."""
    machine = machine_of(scene)
    if machine is None:
        raise InputError(f"model {scene.model!r} is not a machine: one of "
                         + ", ".join(repr(m.model) for m in machines()))
    return machine


def machines() -> list[Machine]:
    """Every machine, the default first, then by model name (the order messages list them in)."""
    first = MACHINES[DEFAULT_MODEL]
    return [first, *(MACHINES[m] for m in sorted(MACHINES) if m != DEFAULT_MODEL)]


def design_words() -> str:
    """The design sizing chooses, machine by machine, in words (``"d, F_nwl, stroke for a rope haulage
    winch"``): what a message names where no scene is read yet."""
    return "; ".join(f"{', '.join(m.sizing.VARIABLES)} for a {m.title}" for m in machines() if m.sizing)


def default() -> Machine:
    """The machine of a scene that names no model."""
    return MACHINES[DEFAULT_MODEL]


def needing(part: str, scene, what: str):
    """The ``part`` of ``scene``'s machine declaration (e.g. ``"sizing"``), or :class:`InputError` naming the
    models that declare one: ``what`` is the question asked (``"sizing"``)."""
    machine = machine_of(scene)
    found = getattr(machine, part, None) if machine else None
    if found is None:
        able = [m.model for m in machines() if getattr(m, part) is not None]
        raise InputError(f"{what} needs model = " + " or ".join(f'"{m}"' for m in able)
                         + f", the scene has model = {scene.model!r}")
    return found


class DesignBox(NamedTuple):
    """The design box a scan behind a dynamic "no design" covers (:mod:`optimisation.dynamic.scan`), by the
    names of the sizing's design variables: ``catalogue`` takes every catalogue rope diameter within its sizing
    bounds; ``grid`` takes evenly spaced values from 0 to a top where the static checks fail for every catalogue
    diameter, found by doubling from ``top(problem, xs, p)`` (SI; ``xs`` the scaled design at the thickest
    rope, ``grid`` 0 and the ``held`` values); ``held`` (variable → SI value) are held at one value, each one
    that every check only gains from (so a point without a design there has none at any smaller value)."""

    catalogue: str
    grid: str
    held: dict
    top: Callable


class ManoeuvreCheck(NamedTuple):
    """A check through a manoeuvre: ``nlp(o, a)`` the constraint (≥ 0, in ``unit`` — N or m — before
    scaling), ``margin(o, a)`` the margin shown (its own ``shown`` unit); ``o`` the smooth mode's
    outputs at the samples, ``a`` the design's and scene's values the machine's ``values`` gives."""

    name: str
    text: str
    unit: str
    shown: str
    needs: str
    nlp: Callable
    margin: Callable


def model_order(names) -> list[str]:
    """The margin outputs among ``names`` (``*_margin``, ``*_margin_up|down``, ...) in the model's order."""
    return [n for n in names if "_margin" in n]
