"""The whole sizing answer for a scene: continuous optimum, catalogue design, margins, power,
sensitivities — or, when no design exists, which checks conflict and by how much."""

from __future__ import annotations

import re

from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np


from optimisation import discrete, generation
from optimisation.infeasibility import Diagnosis, diagnose
from optimisation.ipopt import Solution, solve_continuous
from optimisation.problem import SizingProblem, load_sizing
from optimisation.sensitivity import sensitivities
from ropemodel.errors import InputError
from ropemodel.machines.base import declared_machine, design_words
from ropemodel.machines.sizing import Declaration, declared
from ropemodel.papers import en12385 as ropes
from ropemodel.rules.apply import with_rule_terms
from ropemodel.rules.describe import summary as rules_summary
from ropemodel.scene import Scene, SceneLike
from ropemodel.views.design import DesignViews

#: default way to pick a catalogue diameter, chosen on the evidence of studies/discrete_design.py:
#: on 30 random scenes bonmin returned the same design as next-size-up every time it finished,
#: did not finish within 20 s on 3 of them (10 %), and took ~150x longer (median 3.6 s vs 25 ms).
DEFAULT_DISCRETE = "next-size-up"
#: wall-clock limit of a bonmin solve [s] (it can run far past its own time_limit option)
BONMIN_TIMEOUT = 60.0


@dataclass
class Design(DesignViews):
    """Result of :func:`size`.  Values SI; ``feasible`` False when no design exists.  In Jupyter it shows
    the design and every check as a table with units; ``to_frame()`` gives it as a DataFrame."""

    scene: Scene
    feasible: bool
    design: dict[str, float] | None = None          # recommended (catalogue) d, F_nwl, stroke
    continuous: dict[str, float] | None = None
    active: list[str] = field(default_factory=list)             # at the recommended design
    active_continuous: list[str] = field(default_factory=list)
    margins: dict[str, float] = field(default_factory=dict)     # each check's worst at the recommended design
    margins_continuous: dict[str, float] = field(default_factory=dict)
    #: check → where its worst margin is at the recommended design (segment, x_m, direction, manoeuvre; None:
    #: the same in every case)
    governing: dict[str, dict | str | None] = field(default_factory=dict)
    #: N_p_up, N_p_down at the recommended design: each at its worst over the load cases (larger magnitude)
    power: dict[str, float] = field(default_factory=dict)
    #: the drive's largest motoring and largest braking power over every case and direction, and where
    drive: dict[str, dict] = field(default_factory=dict)
    least_drum: float | None = None    # D_ratio_min * d [m] when the scene gives no drum diameter
    sensitivities: dict[str, dict[str, float]] = field(default_factory=dict)
    #: the parameters left out of :attr:`sensitivities`, and why ("" where none is)
    left_out: str = ""
    method: str = DEFAULT_DISCRETE
    diagnosis: Diagnosis | None = None
    units: dict[str, str] = field(default_factory=dict)
    message: str = ""
    lexicographic_ok: bool | None = None
    #: the rope's stiffness at the recommended design: EA [N], q_lw [m/N] (what the stroke rests on)
    rope: dict[str, float] = field(default_factory=dict)
    #: a declared sizing's objective: its value at the design (SI), per value of the integer enumerated, in words
    objective: dict[str, Any] = field(default_factory=dict)
    #: the transients a declared sizing simulated at the design: what each is, whether it holds, its margins
    verified: list[dict] = field(default_factory=list)
    #: the model solved at a declared sizing's design
    result: Any = None
    #: the load cases: every one the worst is taken over (``cases``), those that can govern, where each design is
    #: checked (``candidates``), and those the NLP made its checks in (``in_nlp``, :mod:`optimisation.generation`)
    load_cases: dict[str, int] = field(default_factory=dict)

    def to_dict(self) -> dict:
        """The JSON contract of ``ropemodel size --json`` (SI numbers)."""
        out = {"scene": self.scene.name, "feasible": self.feasible, "discrete_method": self.method}
        if self.design:
            out.update(self.design)
        if self.continuous:
            out["continuous"] = {**self.continuous, "active": self.active_continuous,
                                 "margins": self.margins_continuous}
        out["active"] = self.active
        out["margins"] = self.margins
        out["governing"] = self.governing
        out.update(self.power)
        if self.drive:
            out["drive_power"] = self.drive
        if self.least_drum is not None:
            out["D_min"] = self.least_drum
        out["sensitivities"] = self.sensitivities
        if self.left_out:
            out["sensitivities_left_out"] = self.left_out
        if self.diagnosis is not None and not self.diagnosis.feasible:
            infeasible = {"conflicting": self.diagnosis.conflicting,
                          "max_violation_scaled": self.diagnosis.max_violation,
                          "relax_alone": self.diagnosis.alone, "elastic": self.diagnosis.elastic,
                          "where": self.diagnosis.where.strip(), "needs": self.diagnosis.needs}
            if self.diagnosis.scan:
                infeasible["scan"] = self.diagnosis.scan
            out["infeasible"] = infeasible
        out["message"] = self.message
        if self.load_cases:
            out["load_cases"] = self.load_cases
        out.update(self.rope)
        if self.objective:
            out["objective"] = self.objective
        if self.verified:
            out["verified"] = self.verified
        out["elongation"] = self.scene.effects.get("elongation")
        rules = rules_summary(self.scene)
        if rules:
            out["rules"] = rules
        return out


#: the rope's stiffness a design states (the stroke rests on it)
ROPE_STIFFNESS = ("EA", "q_lw")


#: the drive power of each direction (signed: motoring > 0, braking < 0)
POWER = ("N_p_up", "N_p_down")


def at_design(problem: SizingProblem, xs):
    """At scaled ``xs``, over every load case (:meth:`SizingProblem.envelope`): each check's worst margin, where
    it is, the drive power of each direction at its worst, the drive's largest motoring and braking power with
    where, and every output's value (worst or the same everywhere)."""
    env = problem.envelope(xs)
    values = env.values()
    margins = {n: values[n] for n in problem.machine.checks(values)}
    governing = {n: env.worst(n).where(env.params) if n in env.extremes else None for n in margins}
    power = {n: values[n] for n in POWER if n in values}
    drive = {}
    for kind, sense, better in (("motoring", "largest", max), ("braking", "least", min)):
        ends: list[Any] = [e for n in POWER for e in env.extremes.get(n, ()) if e.sense == sense]
        ends += [_Flat(n, values[n]) for n in POWER if n in env.constant]
        if ends:
            top = better(ends, key=lambda e: e.value)
            if (top.value > 0) == (kind == "motoring") and top.value != 0:
                drive[kind] = {"value": top.value, "where": top.where(env.params)}
    return margins, governing, power, drive, values


class _Flat:
    """A power that is the same in every case (no place or manoeuvre to name but its direction)."""

    def __init__(self, name, value):
        self.name, self.value = name, value

    def where(self, params):
        return {"segment": None, "x_m": None, "direction": self.name.rsplit("_", 1)[1], "manoeuvre": None}


def rounded_up(problem: SizingProblem, xs) -> np.ndarray:
    """The design rounded up to the practical steps the machine declares, every check still held exactly at
    the rounded, printed values; else the design unrounded."""
    return problem.sizing.rounded_up(problem, xs)


def solve_best(problem: SizingProblem, p=None, x0=None) -> Solution:
    """IPOPT from ``x0`` (default: the scene's design or a computed start); if that fails, from a few
    other starts (mid-catalogue sizes)."""
    sol = solve_continuous(problem, p=p, x0=x0)
    if sol.feasible:
        return sol
    for d0 in (0.02, 0.04, 0.06):
        x0 = problem.x0()
        x0[0] = d0 / problem.x_scale[0]
        s = solve_continuous(problem, p=p, x0=x0)
        if s.feasible:
            return s
    return sol


def _solve(problem: SizingProblem, method: str):
    """The continuous optimum and the catalogue design of ``problem`` (the latter None where the former is not
    feasible)."""
    sol = solve_best(problem)
    if not sol.feasible:   # confirm independently: every catalogue size, F_nwl and stroke found with d fixed
        probe = discrete.next_size_up(problem, 0.0)
        if probe.solution is not None:
            sol = solve_best(problem, x0=probe.solution.xs)
    if not sol.feasible:
        return sol, None
    if method == "bonmin":
        return sol, discrete.bonmin_with_timeout(problem, BONMIN_TIMEOUT, x0=sol.xs)
    return sol, discrete.next_size_up(problem, problem.to_si(sol.xs)["d"])


def _generated(scene: Scene, method: str):
    """(problem, continuous optimum, catalogue design) by constraint generation (:mod:`optimisation.generation`):
    solved on the cases that can be least, those a design found leaves below zero added until the continuous
    optimum and the catalogue design hold every check at every candidate; after :data:`generation.ROUNDS`
    rounds, the NLP of every candidate."""
    for first_range in (problem_range(scene), None):
        problem = SizingProblem(scene, generate=True, first_range=first_range)
        for _ in range(generation.ROUNDS):
            sol, disc = _solve(problem, method)
            designs = [sol.xs] if sol.feasible else []
            if disc is not None and disc.solution is not None:
                designs.append(rounded_up(problem, disc.solution.xs))
            if not all(problem.covers(xs) for xs in designs):
                break                           # a design outside the range its places were found for
            more = generation.uncovered(problem, designs)
            if not more:
                return problem, sol, disc
            problem = problem.with_cases(more)
    problem = SizingProblem(scene)
    return (problem, *_solve(problem, method))


def _diagnosed(problem: SizingProblem, **how) -> tuple[SizingProblem, Diagnosis]:
    """(problem, diagnosis) of a problem whose NLP holds some of the candidate cases (:func:`_generated`): the
    least-violation design is checked at every candidate, and a case more violated there than the NLP's least is
    added and the diagnosis made again, so the least maximum violation and the conflicting checks are those of
    every candidate (the exchange method of :mod:`optimisation.generation` applied to the least-violation NLP)."""
    for _ in range(generation.ROUNDS):
        diag = diagnose(problem, **how)
        if diag.feasible or diag.x_least is None or problem.cases == problem.candidates:
            return problem, diag
        more = generation.uncovered(problem, [diag.x_least])
        if not more:
            return problem, diag
        problem = problem.with_cases(more)
    return problem, diag


#: a route of more segments than this is sized without sensitivities in its segments' own values (L_i, alpha_i,
#: mu_wi): a surveyed profile's points, which the design does not vary; a derivative in each would pass through
#: every segment (20 000 of them at 10 000 points), and those values are folded in instead
ROUTE_SENSITIVITIES = 100      # a route held as route numbers per load case (above its VECTOR_ABOVE) too
SEGMENTS_LEFT_OUT = ("L_i, alpha_i and mu_wi of the route's {n} segments (more than {most}): size again with a "
                     "segment's value set (--set) to see its effect")
_SEGMENT = re.compile(r"(L_|alpha_|mu_w)\d+$")


def _sensitive(problem: SizingProblem) -> list[str] | None:
    """The parameters the sensitivities are taken in: every one (None), or on a route of more than
    :data:`ROUTE_SENSITIVITIES` segments all but the segments' own values."""
    if len(problem.scene.route) <= ROUTE_SENSITIVITIES and not problem.scene.built.derived:
        return None
    return [k for k in problem.params if not _SEGMENT.match(k)]


def problem_range(scene: Scene):
    """The range of the first design variable the places that can govern are first found for: the machine's
    catalogue (a winch: its rope diameters), or None (every value)."""
    catalogue = getattr(declared_machine(scene).sizing, "catalogue_range", None)
    return None if catalogue is None else catalogue()


def _size_declared(scene: Scene, method: str) -> Design:
    """The sizing of a model that declares it (:mod:`optimisation.declared`)."""
    from optimisation.declared import size_declared

    if method != DEFAULT_DISCRETE:
        raise InputError(f"the {scene.model}'s catalogue size is chosen next size up: --discrete {method} sizes "
                         f"only a machine sized in one NLP ({design_words()})")
    return size_declared(scene, cast(Declaration, declared(scene.model)))


def size(scene: SceneLike, method: str = DEFAULT_DISCRETE, with_sensitivities: bool = True) -> Design:
    """Size the winch of ``scene``: the lightest catalogue rope, then the least pretension, then the least stroke
    (Krauze et al. 2025: every design check of eq. (12)-(23) as a constraint; ``ropemodel size``).

    Parameters
    ----------
    scene : Scene or str or Path
        A winch scene with a catalogue rope (``rope = "catalogue"`` or a construction such as
        ``"6x36-IWRC"``), or its TOML file or built-in name (read by
        :func:`optimisation.problem.load_sizing`).  It needs no starting design (d, F_nwl, stroke)
        and no power effect: the design checks are switched on here, and the drive power is
        reported when ``v_pj`` is given.  Without a drum diameter ``D`` (rigid drum), the least
        drum, D_ratio_min·d, is a result.
    method : {"next-size-up", "bonmin"}
        How the catalogue diameter is chosen.
    with_sensitivities : bool
        Also compute ∂x*/∂p of the continuous optimum (from its KKT system).

    Returns
    -------
    Design
        ``feasible``; ``design``: the catalogue design, SI (``d`` [m], ``F_nwl`` [N],
        ``stroke`` [m]); ``continuous``: the continuous optimum, SI; ``active``: the checks that
        limit it; ``margins`` of every check at the catalogue design [-]; ``to_dict()``: what
        ``ropemodel size --json`` prints.  When no design exists: ``message`` and ``diagnosis``
        (the conflicting checks and how much they conflict).

    Raises
    ------
    InputError
        The scene cannot be sized (not a winch, a rope without a catalogue, bad values).

    Examples
    --------
    The Fig. 9 haulage: the 38 mm rope of the catalogue, limited by slip and by the stroke
    on the way up:

    >>> from optimisation import size
    >>> design = size("winch_sizing_fig9", with_sensitivities=False)
    >>> design.design["d"], design.design["F_nwl"], design.design["stroke"]    # m, N, m
    (0.038, 43600.0, 4.763)
    >>> design.active
    ['slip_margin_up', 'stroke_margin_up', 'd (catalogue size)']
    """
    scene = load_sizing(scene, emit=False)
    if declared(scene.model) is not None:           # a model that declares its sizing (not the winch)
        return _size_declared(scene, method)
    problem, sol, disc = _generated(scene, method)
    design = Design(problem.scene, False, method=method, units=dict(problem.units),
                    load_cases={"cases": len(problem.all_cases), "candidates": len(problem.candidates),
                                "in_nlp": len(problem.cases)})
    if not sol.feasible:
        problem, design.diagnosis = _diagnosed(problem)
        if design.diagnosis.feasible:   # IPOPT failed on a feasible problem: say so, do not guess
            design.message = f"IPOPT failed ({sol.status}) although a feasible design exists"
        else:
            design.message = design.diagnosis.text(problem.units)
        return design
    design.continuous = problem.to_si(sol.xs)
    design.active_continuous = list(sol.active) + [f"{problem.variables[i]} {side} bound"
                                                    for i, side in sol.active_bounds]
    design.margins_continuous = at_design(problem, sol.xs)[0]
    design.lexicographic_ok = sol.lexicographic_ok
    if with_sensitivities:
        design.sensitivities = with_rule_terms(problem.scene, sensitivities(problem, sol, params=_sensitive(problem)))
        design.left_out = "" if _sensitive(problem) is None else SEGMENTS_LEFT_OUT.format(
            n=len(problem.scene.route), most=ROUTE_SENSITIVITIES)
    d_star = design.continuous["d"]
    if disc.solution is None:
        cat = ropes.diameters()
        above = [dk for dk in cat if dk >= d_star - 1e-9]
        if not above:
            design.message = (f"no catalogue diameter: the continuous optimum d = {d_star * 1e3:.4g} mm is above "
                              f"the largest catalogue size {cat[-1] * 1e3:g} mm")
        else:
            problem, diag = _diagnosed(problem, fix_d=above[0], x0=sol.xs)
            design.diagnosis = diag
            design.message = "no catalogue diameter meets every check; " + diag.text(problem.units)
        if disc.method.endswith("(timed out)"):
            design.message = (f"bonmin did not finish within {BONMIN_TIMEOUT:g} s; use --discrete next-size-up. "
                              + design.message)
        return design
    dsol = disc.solution
    design.feasible = True
    xs = rounded_up(problem, dsol.xs)
    design.design = problem.to_si(xs)
    design.active = list(dsol.active) + [f"{problem.variables[i]} {side} bound" for i, side in dsol.active_bounds
                                         if i != 0] + ["d (catalogue size)"]
    design.margins, design.governing, design.power, design.drive, values = at_design(problem, xs)
    if problem.least_drum:
        design.least_drum = values["D"]
    design.rope = {k: values[k] for k in ROPE_STIFFNESS if k in values}
    design.message = "design found"
    if sol.lexicographic_ok is False:
        design.message += problem.sizing.NOT_LEXICOGRAPHIC
    return design
