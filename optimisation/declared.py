"""Sizing a model that declares its sizing (:mod:`ropemodel.machines.sizing`): the winch's machinery, generic.

A declaration gives three continuous design variables (the first chosen from a catalogue), an integer it
enumerates (one continuous NLP per value: IPOPT with exact derivatives, :func:`optimisation.ipopt.solve_continuous`;
then the next catalogue size up with the others re-optimised, :func:`optimisation.discrete.next_size_up`), the
objective and every check as smooth CasADi expressions.  The lightest feasible design over the enumeration is
kept (the smaller integer on a tie), rounded to the declared steps where every check still holds, and verified
by the model itself: the scene solved at the design (``ropemodel run``'s equations, every margin >= 0).  No
design: which checks conflict and what in the scene would let a design exist
(:func:`optimisation.infeasibility.diagnose`, with the declaration's remedies), at the integer nearest to one.
"""

from __future__ import annotations

import itertools
import math
from typing import Any, cast

import casadi as ca
import numpy as np

from optimisation.design import Design
from optimisation.discrete import next_size_up
from optimisation.infeasibility import diagnose
from optimisation.ipopt import Solution, solve_continuous
from ropemodel.machines.sizing import Declaration
from ropemodel.problem import Problem
from ropemodel.scene import Scene

#: how the catalogue size is chosen
METHOD = "next-size-up"


class DeclaredProblem:
    """The NLP of a declared sizing, in the interface of :class:`optimisation.problem.SizingProblem` (what
    IPOPT, the catalogue step and the diagnosis read); the integer is an NLP parameter (:meth:`use`)."""

    def __init__(self, scene: Scene, declaration: Declaration):
        self.scene, self.decl = declaration.prepare(scene), declaration
        scene = self.scene
        self.variables = [x.name for x in declaration.variables]
        self.params = [k for k in scene.built.parameters if k not in self.variables] + list(declaration.allowances)
        self.p0 = np.array([scene.parameters.get(k, 0.0) for k in self.params], dtype=float)
        #: each allowance's value (raised while a transient does not hold)
        self.allowance = dict.fromkeys(declaration.allowances, 0.0)
        self.x_scale = np.array([x.scale for x in declaration.variables])
        self.count = int(round(scene.parameters.get(declaration.integer, declaration.counts(scene)[0])))
        self.xs = ca.MX.sym("x", len(self.variables))
        self.p = ca.MX.sym("p", len(self.params))
        v = {k: self.p[i] for i, k in enumerate(self.params)}
        v.update({k: self.xs[i] * self.x_scale[i] for i, k in enumerate(self.variables)})
        v = declaration.completed(scene, v)
        checks = declaration.checks(scene, v)
        self.constraints = [f"{c.check} @ {c.where}" for c in checks]
        self.units = {f"{c.check} @ {c.where}": c.unit for c in checks}
        scales = declaration.unit_scales(scene)
        self.g_scale = np.array([scales[c.unit] for c in checks])
        self._g_si = ca.vertcat(*[c.g for c in checks])
        self.g = self._g_si / ca.DM(self.g_scale)
        primary, secondary = declaration.objective(scene, v)
        self.mass = ca.Function("mass", [self.xs, self.p], [primary])
        self.m_ref = float(self.mass(self.x0(), self.p_at(self.count)))
        self.f_primary = primary / self.m_ref
        self.f = self.f_primary + secondary
        self.g_si = ca.Function("g_si", [self.xs, self.p], [self._g_si])

    # ------------------------------------------------------------------ the integer
    def p_at(self, count: int) -> np.ndarray:
        """The parameter vector with the integer at ``count``."""
        p = self.p0.copy()
        p[self.params.index(self.decl.integer)] = count
        for k, x in self.allowance.items():
            p[self.params.index(k)] = x
        return p

    def use(self, count: int) -> np.ndarray:
        """Solve for ``count`` from now on (starts follow it); its parameter vector."""
        self.count = count
        return self.p_at(count)

    # ------------------------------------------------------------------ SizingProblem's interface
    def nlp(self) -> dict:
        return {"x": self.xs, "p": self.p, "f": self.f, "g": self.g}

    def bounds(self, d_range=None) -> tuple[np.ndarray, np.ndarray]:
        """Scaled bounds of x (the first variable within ``d_range`` [SI] when given)."""
        b = self.decl.bounds(self.scene)
        if d_range is not None:
            b[0] = d_range
        return np.array([lo for lo, _ in b]) / self.x_scale, np.array([hi for _, hi in b]) / self.x_scale

    def x0(self) -> np.ndarray:
        """Scaled start for the current integer (the declaration's)."""
        start = self.decl.start(self.scene, self.count)
        return np.array([start[k] for k in self.variables]) / self.x_scale

    def to_si(self, xs) -> dict[str, float]:
        xs = np.asarray(xs, dtype=float).ravel()
        return {k: float(xs[i] * self.x_scale[i]) for i, k in enumerate(self.variables)}

    def margins(self, xs, p=None) -> dict[str, float]:
        """Every constraint's value (SI, its unit) at scaled ``xs``."""
        g = np.asarray(self.g_si(xs, self.p_at(self.count) if p is None else p)).ravel()
        return dict(zip(self.constraints, map(float, g)))

    @property
    def remedies(self):
        return self.decl.remedies


def _solve(problem: DeclaredProblem, p) -> Solution:
    """IPOPT from the declaration's start, then from starts with the first variable halved and doubled."""
    sol = solve_continuous(cast(Any, problem), p=p)
    for factor in (0.5, 2.0):
        if sol.feasible:
            break
        x0 = problem.x0()
        x0[0] *= factor
        sol = solve_continuous(cast(Any, problem), p=p, x0=x0)
    return sol


def rounded(problem: DeclaredProblem, xs, p) -> np.ndarray:
    """``xs`` with each variable that declares steps rounded to them, coarsest first, down (lighter) or up, where
    every constraint still holds; else the variable as it is."""
    x = np.asarray(xs, dtype=float).copy()
    for i, var in enumerate(problem.decl.variables):
        for step, up in itertools.product(var.steps, (False, True)):
            trial = x.copy()
            si = trial[i] * problem.x_scale[i]
            trial[i] = (math.ceil(si / step - 1e-9) if up else math.floor(si / step + 1e-9)) * step / problem.x_scale[i]
            if min(problem.margins(trial, p).values()) >= 0.0:
                x = trial
                break
    return x


class Candidate:
    """The design of one value of the integer: its catalogue solution, rounded, and its objective [SI]."""

    def __init__(self, count: int, continuous: Solution, catalogue: Solution, xs, mass: float):
        self.count, self.continuous, self.catalogue, self.xs, self.mass = count, continuous, catalogue, xs, mass


def candidates(problem: DeclaredProblem) -> tuple[list[Candidate], dict[int, Solution]]:
    """The catalogue design of each value of the integer that has one, and every continuous solution."""
    found, tried = [], {}
    for n in problem.decl.counts(problem.scene):
        p = problem.use(n)
        sol = tried[n] = _solve(problem, p)
        if not sol.feasible:
            continue
        disc = next_size_up(cast(Any, problem), problem.to_si(sol.xs)[problem.variables[0]], p=p,
                            catalogue=problem.decl.catalogue(problem.scene))
        if disc.solution is None:
            continue
        xs = rounded(problem, disc.solution.xs, p)
        found.append(Candidate(n, sol, disc.solution, xs, float(problem.mass(xs, p))))
    return found, tried


def _active(problem: DeclaredProblem, sol: Solution, catalogue: bool) -> list[str]:
    """The active checks of a solution, and its active bounds (the catalogue's fixed size named as such)."""
    out = list(sol.active)
    for i, side in sol.active_bounds:
        lo, hi = problem.decl.bounds(problem.scene)[i]
        if i == 0 and catalogue:
            continue
        if lo != hi:
            out.append(f"{problem.variables[i]} {side} bound")
    return out + ([f"{problem.variables[0]} (catalogue size)"] if catalogue else [])


def static_design(problem: DeclaredProblem, design: Design) -> Design:
    """The lightest candidate at the problem's allowances, verified by the model itself; or why there is none."""
    declaration = problem.decl
    found, tried = candidates(problem)
    if not found:
        return _no_design(problem, design, tried)
    best = min(found, key=lambda c: (round(c.mass, 9), c.count))
    problem.use(best.count)
    integer = {declaration.integer: float(best.count)}
    design.design = {**integer, **declaration.at_design(problem.scene, {**integer, **problem.to_si(best.xs)})}
    design.continuous = {**integer, **problem.to_si(best.continuous.xs)}
    design.active_continuous = _active(problem, best.continuous, False)
    design.active = _active(problem, best.catalogue, True)
    values = {k: x for k, x in design.design.items() if k in problem.scene.built.parameters}
    design.result = result = Problem(problem.scene).solve(values)       # the model itself, at the design
    design.margins = {k: result[k] for k in result.outputs if "_margin" in k}
    design.governing = {k: result.where.get(k) for k in design.margins}
    design.objective = {"value": best.mass, "by_count": {c.count: c.mass for c in found}, "text":
                        declaration.objective_text, "integer": declaration.integer,
                        "enumerated": list(declaration.counts(problem.scene)), **problem.allowance}
    failed = [k for k, m in design.margins.items() if m < -1e-9]
    design.feasible = not failed
    design.message = "design found" if not failed else (
        f"the design fails {', '.join(failed)} in the model although the sizing's checks hold: report this")
    return design


def held(problem: DeclaredProblem, design: Design) -> dict[str, list[dict]]:
    """Each transient of the design (:meth:`~ropemodel.machines.sizing.Declaration.transients`) simulated: per
    allowance, what each gave (its words, whether it holds, its summary's numbers)."""
    from ropemodel.dynamics import simulate

    out: dict[str, list[dict]] = {}
    for t in problem.decl.transients(problem.scene, design.design or {}, design.result):
        scene = problem.scene.with_effects(t.effects, optional=tuple(t.values)).with_values(t.values)
        summary = simulate(scene, progress=False).summary
        out.setdefault(t.allowance, []).append(
            {"transient": t.words, "holds": problem.decl.holds(summary),
             **{k: x for k, x in summary.items() if isinstance(x, (int, float)) and "margin" in k}})
    return out


#: the allowance's bisection: its largest value, and the width at which it stops
ALLOWANCE_MAX, ALLOWANCE_TOL = 0.9, 0.01


def size_declared(scene: Scene, declaration: Declaration) -> Design:
    """Size ``scene`` by its model's declaration (module docstring): a :class:`~optimisation.design.Design`.

    With transients to hold in, every design is simulated; while one does not hold, the allowances of those that
    failed are raised together (doubling from 0.05, then bisection to :data:`ALLOWANCE_TOL`, no design above
    counting as too much) and the design sized again: the lightest design that holds in every transient, or the
    reason there is none."""
    problem = DeclaredProblem(scene, declaration)
    low, high, ceiling, kept, raised = 0.0, None, None, None, set()
    while True:
        design = static_design(problem, Design(problem.scene, False, method=METHOD, units=dict(problem.units)))
        k = max(problem.allowance.values(), default=0.0)
        if design.feasible:
            runs = held(problem, design)
            design.verified = [r for rs in runs.values() for r in rs]
            failing = {a for a, rs in runs.items() if not all(r["holds"] for r in rs)}
            raised |= failing
            if not failing:
                kept, high = design, k
            else:
                low = k
        elif k == 0.0:
            return design                    # no design even for the rigid checks
        else:
            ceiling = k
        upper = high if high is not None else ceiling
        if not raised or (upper is not None and upper - low <= ALLOWANCE_TOL) or (upper is None and
                                                                                  low >= ALLOWANCE_MAX):
            break
        k = (low + upper) / 2 if upper is not None else min(max(2 * low, 0.05), ALLOWANCE_MAX)
        problem.allowance.update(dict.fromkeys(raised, k))
    if kept is not None:
        return kept
    failed = "; ".join(r["transient"] for r in (design.verified or []) if not r["holds"])
    design.feasible = False
    design.message = (f"no design holds in the transients ({failed or 'as before'}): the rigid checks with an "
                      f"allowance of {k:.3g} of the slip limits for the elastic ropes: {design.message}")
    return design


def _no_design(problem: DeclaredProblem, design: Design, tried: dict[int, Solution]) -> Design:
    """The diagnosis at the value of the integer whose continuous problem came nearest to a design."""
    feasible = [n for n, s in tried.items() if s.feasible]     # a continuous design, no catalogue size
    nearest = feasible[0] if feasible else min(tried, key=lambda n: -float(np.min(tried[n].g)))
    p = problem.use(nearest)
    fix = None
    if feasible:
        d_star = problem.to_si(tried[nearest].xs)[problem.variables[0]]
        fix = next((d for d in problem.decl.catalogue(problem.scene) if d >= d_star - 1e-9), None)
    design.diagnosis = diag = diagnose(cast(Any, problem), p=p, fix_d=fix, x0=tried[nearest].xs)
    counts = problem.decl.counts(problem.scene)
    where = f"{problem.decl.integer} = {counts[0]} to {counts[-1]} (diagnosed at {problem.decl.integer} = {nearest})"
    if diag.feasible:
        design.message = f"IPOPT failed at every {where} although a feasible design exists"
    else:
        diag.where = f" with {where}"
        design.message = diag.text(problem.units)
    return design
