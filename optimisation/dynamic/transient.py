"""The transient dynamic sizing needs, built from any winch sizing scene.

A designer gives the route, the load, the drum and a rope construction, and the ramp time of the drive;
:func:`transient_scene` makes the rest of the transient itself:

* ``dynamics`` and ``travel``: every manoeuvre sets its own (start or stop, up or down,
  :mod:`.manoeuvres`); what the scene says about them (a trip, a start, nothing) is not read;
* ``inertia = "none"``: the transient has the inertia of every mass itself (static sizing's rigid-body
  forces of a trip's ramps would count it twice);
* the rope model, tensioner, ramp shape, drive and drum contact: the scene's where it chooses them, else
  the registry's defaults (a Kelvin–Voigt rope of ``[numerics] segments`` elements per span, a
  constant-force tensioner, a linear ramp, a drive that follows its ramp, a rigid drum contact); the drum's
  friction is the scene's own ``lining``;
* the parameters with a default (``m_t``, ``rope_damping``, ``v_eps``) take it, and the scene says so
  (``scene.defaults``, with the reason);
* what cannot be defaulted — ``t_ramp``, and what a chosen variant needs (``jerk_max`` of an S-curve,
  the motor of a torque-limited drive) — is asked for, every missing item at once, one line each;
* ``t_end``, how long each manoeuvre is followed: given, or :func:`horizon`.
"""

from __future__ import annotations

import dataclasses

from optimisation.design import solve_best
from optimisation.dynamic.manoeuvres import Manoeuvre, manoeuvre_scene
from optimisation.dynamic.positions import candidates
from optimisation.problem import SizingProblem, declaration, rope_problem
from optimisation.problem import reads as static_reads
from ropemodel.dynamics.assemble import chosen, transient_parts
from ropemodel.dynamics.smooth import slowest_period
from ropemodel.effects.transient.base import transient_effects
from ropemodel.errors import InputError
from ropemodel.machines.base import machine_of

#: the effects dynamic sizing sets itself
EFFECTS = {"dynamics": "start", "travel": "up", "inertia": "none"}
#: periods of the loop's slowest free oscillation followed after the ramp (the default t_end)
PERIODS = 2
#: the default t_end with an inextensible rope (no free oscillation): the ramp and half a ramp more
RIGID_AFTER = 0.5
X_M_NOTE = ("not given: each manoeuvre with the load at every candidate position (the ends and the middle of each "
            "segment), the worst of them governs")


def _design(scene) -> tuple[str, ...]:
    """The design variables of ``scene``'s machine (its sizing's: a sizing scene may leave them out)."""
    return tuple(declaration(scene).VARIABLES)


def _sized(scene) -> tuple[str, ...]:
    """What a sizing scene of ``scene``'s machine may leave out: its design and the dimensions its sizing
    frees."""
    return _design(scene) + tuple(declaration(scene).D_OPTIONAL)


def _optional(scene) -> tuple[str, ...]:
    """What the transient scene may leave out: :func:`_sized`'s and ``t_end`` (dynamic sizing sets it)."""
    return _sized(scene) + ("t_end",)


def missing(scene) -> list[str]:
    """What the transient dynamic sizing builds on ``scene`` needs and the scene does not give, one line each
    (e.g. ``t_ramp``), to be named together with the scene's other problems (none for a machine that is not
    sized: the scene's other problems say so)."""
    machine = machine_of(scene)
    if machine is None or machine.sizing is None:
        return []
    try:
        scene.with_effects(EFFECTS, optional=_optional(scene))
    except InputError as e:
        return [f"dynamic sizing: {p}" for p in e.problems]
    return []


def transient_scene(scene):
    """``scene`` (a winch sizing scene) with the transient dynamic sizing needs (see the module); a scene
    already made by it is returned as it is.  :class:`~ropemodel.errors.InputError` names every
    parameter the transient needs and cannot default, one line each."""
    if _made(scene):
        return scene
    problems = [why for why in [rope_problem(scene)] if why is not None]      # all at once with the transient's
    problems += missing(scene)
    if problems:
        raise InputError(problems=problems) from None
    sc = scene.with_effects(EFFECTS, optional=_optional(scene))
    read = reads(sc)[0] | {"x_m"}      # a default nothing reads is no default used (an inextensible rope's damping)
    defaults = {k: why for k, why in sc.defaults.items() if k not in _design(scene) and k in read}
    if "x_m" in defaults:
        defaults["x_m"] = X_M_NOTE
    if "t_end" in sc.parameters:
        return dataclasses.replace(sc, defaults=defaults)
    t_ramp = sc.parameters["t_ramp"]
    period = horizon(sc.with_values({"t_end": 2 * t_ramp}, origin="sizing"))
    if period is None:
        t_end = (1 + RIGID_AFTER) * t_ramp
        why = f"t_ramp + {RIGID_AFTER:g} t_ramp = {t_end:.4g} s: an inextensible rope does not oscillate"
    else:
        t_end = t_ramp + PERIODS * period
        why = (f"t_ramp + {PERIODS} T_1 = {t_end:.4g} s, T_1 = {period:.4g} s the longest period of the rope loop's "
               f"free oscillation (any load position, the static optimum's rope): the peaks after the ramp are in "
               f"its first period, and it decays")
    sc = sc.with_values({"t_end": t_end}, origin="sizing")
    return dataclasses.replace(sc, defaults={**defaults, "t_end": why})


def _made(scene) -> bool:
    """Whether ``scene`` is already in the form :func:`transient_scene` returns."""
    return (all(scene.effects.get(k) == v for k, v in EFFECTS.items()) and "t_end" in scene.parameters
            and not set(scene.defaults) & set(_design(scene)) and scene.defaults.get("x_m", X_M_NOTE) == X_M_NOTE)


def transient_effects_of(scene) -> dict:
    """The transient's effects (``dynamics`` and ``travel`` excepted: each manoeuvre's own) → (variant, whether
    the scene chose it)."""
    chosen = scene.raw.get("effects", {})
    return {e: (scene.effects[e], e in chosen) for e in transient_effects(scene.model)
            if e not in ("dynamics", "travel") and e in scene.effects}


def reads(scene) -> tuple[set[str], dict[str, str]]:
    """What dynamic sizing of the transient ``scene`` (:func:`transient_scene`) is computed from: what static
    sizing reads, and the parameters of the transient's chosen variants (the ramp, the rope model, the
    tensioner, ...; with an inextensible rope not what only an elastic loop uses); and what it sets itself
    (name → how): the design variables and, unless the scene pins it, where the load is."""
    names, sets = static_reads(scene)
    parts = transient_parts(scene, chosen(scene))
    elastic = all(getattr(part, "elastic", True) for part in parts)
    for part in parts:
        names |= {q.name for q in part.quantities} | set(part.reads)
        if not elastic:     # an inextensible rope: the carriage does not move, its mass is not read
            names -= set(part.elastic_only)
    if scene.origin.get("x_m") == "default":
        sets["x_m"] = "dynamic sizing makes every manoeuvre with the load at every candidate position itself"
    else:
        sets.pop("x_m", None)
    return names, sets


def horizon(scene) -> float | None:
    """T_1 [s]: the longest period of the free oscillation of ``scene``'s rope loop in steady motion over
    the candidate positions of the load (None: nothing oscillates, an inextensible rope), at the static
    optimum (a start computed from the scene where there is none).

    Each place's period is :func:`ropemodel.dynamics.smooth.slowest_period` of its upward stop, which starts
    from the steady motion.  The thinnest rope sizing can return (the static optimum's; dynamic sizing only
    thickens it) is the softest, so its period is the longest."""
    static = SizingProblem(scene)
    sol = solve_best(static)
    design = static.to_si(sol.xs if sol.feasible else static.x0())
    periods = [period for at in candidates(scene)
               for period in [slowest_period(manoeuvre_scene(scene, Manoeuvre("stop", "up", at), design,
                                                              _sized(scene)))] if period is not None]
    return max(periods) if periods else None
