"""Sizing sweeps: the least rope diameter d, pretension F_nwl and stroke at every point of a grid.

Each point is one continuous sizing optimisation of the :mod:`optimisation`
package's NLP (:class:`optimisation.problem.SizingProblem`: the scene's own
equations, built once; each point's values are the NLP's parameters).  Points
are taken in order (on a grid the last axis varies fastest), so each point's
predecessor is its neighbour.

``method="active-set"`` (the default, with ``warm=True``): neighbouring optima
share their active checks.  :class:`optimisation.fastmap.ActiveSetMap` solves
batches of points by Newton on a solved neighbour's active set and keeps a point
only where it is a KKT point of its own NLP (inactive checks hold, multipliers of
the right sign); IPOPT, warm-started, solves the points no known active set
explains, and points without a design are certified by the least-violation
problem.  The answers are IPOPT's (the same feasibility, the optimum to IPOPT's
tolerance; exact at a vertex), at a fraction of the cost
(``studies/sizing_map_speed.py``).

``method="ipopt"``: IPOPT at every point.  ``warm=True`` starts it from the
optimum of the previous point *with its multipliers* and IPOPT's warm-start
settings (``warm_start_init_point``, small barrier parameter and bound pushes):
an interior-point method given only a primal start moves back to the central
path and gains little; given the multipliers it needs fewer iterations
(``studies/sizing_map.py`` measures it).  ``warm=False`` (either method) starts
every point from the scene's design.  A point whose start fails is solved again
by the package's multi-start :func:`optimisation.design.solve_best`, so the
start changes cost, not the answer (IPOPT optima at tolerance 1e-10).  Points
with no feasible design are kept with ``feasible`` False and missing d, F_nwl,
stroke.
"""

from __future__ import annotations

import copy

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from optimisation.design import solve_best
from optimisation.fastmap import ActiveSetMap
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, declaration
from ropemodel.errors import InputError
from ropemodel.sweeps.points import grid, table
from ropemodel.envelope.cases import CASE_READS, joint_ends
from ropemodel.sweeps.worst import ROUTE_READS
from ropemodel.sweeps.validate import check_ranges, check_rules
from ropemodel.units import factor, label

#: points per chunk (a table of points is read in chunks; the active-set path keeps its state across them)
CHUNK = 4096
METHODS = ("active-set", "ipopt")


def sizing_sweep(scene, vary=None, *, points=None, warm: bool = True, method: str = "active-set",
                 progress: bool | None = None) -> pd.DataFrame:
    """Continuous sizing optimum at every point; columns: the varied inputs, ``d [mm]``, ``F_nwl [kN]``,
    ``stroke [mm]``, ``feasible``, ``iterations`` (IPOPT, all attempts; 0 where the point was solved on a
    neighbour's active set) and ``seconds`` (solver time; a batch solved together shares its time).

    ``method="active-set"`` (default, with ``warm``): :class:`optimisation.fastmap.ActiveSetMap`;
    ``"ipopt"``: IPOPT at every point.  ``warm=False``: IPOPT at every point from the scene's design.
    """
    if method not in METHODS:
        raise InputError(f"method {method!r}: valid methods: {', '.join(METHODS)}")
    problem = SizingProblem(scene, prune_places=False)   # the swept parameters may move the governing place
    scene = problem.scene                 # as sizing reads it (design checks on; a trip's ramps)
    q = scene.built.quantities
    pts = sizing_points(scene, problem, vary, points)
    # a factor a rule set gives from a varied length (n_rope from L_u) varies with it, and is shown
    names = list(pts.names) + sorted({p for n in pts.names for p in scene.ruled_by(n)} - set(pts.names))
    parts = []
    bar = tqdm(total=pts.n, unit="opt", desc="sizing", disable=(not progress) if progress is not None else None)
    follows = bool(scene.built.derived) and bool(set(names) & {*scene.built.edges, *ROUTE_READS, *CASE_READS})
    fast = ActiveSetMap(problem, names) if warm and method == "active-set" and not follows else None
    prev = None
    for start in range(0, pts.n, CHUNK):
        chunk = pts.chunk(start, min(pts.n, start + CHUNK))
        chunk.update(scene.rule_values({**scene.parameters, **chunk}, pts.names))
        if fast is not None:
            res = fast.run(np.column_stack([chunk[k] for k in names]), done=bar.update)
            x, feasible, iterations, seconds = res.x, res.feasible, res.iterations, res.seconds
        else:
            x, feasible, iterations, seconds, prev = _ipopt_points(problem, names, chunk, warm, prev, bar, follows)
        parts.append(sizing_frame(problem, q, chunk, x, feasible, iterations, seconds))
    bar.close()
    return pd.concat(parts, ignore_index=True)


def sizing_points(scene, problem, vary, points):
    """The checked points of a sizing sweep (a grid from ``vary`` or a table)."""
    inputs = {k: scene.built.quantities[k] for k in problem.params}
    if isinstance(vary, pd.DataFrame):
        points, vary = vary, None
    if (vary is None) == (points is None):
        raise InputError("give either vary={name: axis} (a grid) or a table of points")
    for k in (vary or {}) if vary is not None else points.columns:
        if k in problem.variables:
            raise InputError(f"cannot vary {k}: it is a design variable the sizing chooses")
    inputs.update({k: scene.built.quantities[k] for k in (vary if vary is not None else points.columns)
                   if k in scene.built.edge_set})       # a long route's segment, swept by name
    pts = grid(vary, inputs) if vary is not None else table(points, inputs, ignore=scene.built.outputs)
    check_ranges(pts, inputs)
    check_rules(scene.built, pts, dict(scene.parameters))
    return pts


def _ipopt_points(problem, names, chunk, warm, prev, bar, follows=False):
    """IPOPT at every point of ``chunk`` (warm: from the previous optimum and its multipliers); ``follows``: each
    point's NLP has a long route's numbers at its own values (:func:`at_values`)."""
    n = len(chunk[names[0]])
    x, feasible = np.full((n, len(problem.variables)), np.nan), np.zeros(n, bool)
    iterations, seconds = np.zeros(n, int), np.zeros(n)
    for i in range(n):
        values = {k: float(chunk[k][i]) for k in names}
        at = at_values(problem, values) if follows else problem
        p = problem.p_of({k: v for k, v in values.items() if k in problem.params})
        sol = solve_continuous(at, p, polish=False, start=prev if warm else None)
        iterations[i], seconds[i] = sol.iterations, sol.seconds
        if not sol.feasible:  # the package's multi-start (from the scene's design first)
            sol = solve_best(at, p)
            iterations[i] += sol.iterations
            seconds[i] += sol.seconds
        if sol.feasible:
            prev = sol.start
            x[i], feasible[i] = sol.xs, True
        bar.update(1)
    return x, feasible, iterations, seconds, prev


def at_values(problem, values: dict):
    """``problem`` (:class:`~optimisation.problem.SizingProblem`) with a long route's numbers in each case at SI
    ``values`` (a sweep's point: what the numbers are computed from, segments by name among them, which then move
    the places too); the model is not compiled again.  Its parameters are ``p_of`` the same values."""
    out = copy.copy(problem)
    edges = {k: v for k, v in values.items() if k in problem.scene.built.edge_set}
    out.scene = problem.scene.with_values(edges) if edges else problem.scene
    ends = joint_ends({**problem.scene.parameters, **values}) if problem.scene.route else None
    out._route_numbers = problem.problem.case_numbers(problem.candidates, ends, values)
    out._build_nlp()
    return out


def sizing_frame(problem, q, chunk, x, feasible, iterations, seconds) -> pd.DataFrame:
    """The sweep's columns for one chunk (scaled designs ``x``; NaN where there is none)."""
    cols = {label(k, q[k].display_unit): np.asarray(q[k].to_display(np.asarray(v, dtype=float)), dtype=float)
            for k, v in chunk.items()}
    si = np.where(feasible[:, None], x, np.nan) * problem.x_scale
    for i, (k, unit) in enumerate(_design_units(problem)):
        cols[label(k, unit)] = si[:, i] * factor(q[k].unit, unit)
    cols.update(feasible=feasible.astype(bool), iterations=iterations.astype(int), seconds=seconds.astype(float))
    return pd.DataFrame(cols)


def sizing_function(scene, warm: bool = True):
    """A vectorised function {name: SI array} → {"d", "F_nwl", "stroke": SI arrays} (for Sobol indices).

    Raises :class:`InputError` if a point has no feasible design (narrow the ranges).
    """

    q = scene.built.quantities
    units = [(k, u, factor(q[k].unit, u)) for k, u in declaration(scene).UNITS.items()]

    def func(columns):
        frame = sizing_sweep(scene, pd.DataFrame(columns), warm=warm, progress=False)
        if not frame["feasible"].all():
            bad = int((~frame["feasible"]).sum())
            raise InputError(f"{bad} sampled point(s) have no feasible design; narrow the ranges")
        return {k: frame[label(k, u)].to_numpy() / f for k, u, f in units}

    return func


def _design_units(problem) -> list[tuple[str, str]]:
    """(design variable, the unit a sweep shows it in), in the order of x."""
    return [(k, problem.sizing.UNITS[k]) for k in problem.variables]


def solve_times(frame: pd.DataFrame) -> dict:
    """Mean solver seconds and iterations per optimisation of a :func:`sizing_sweep` frame."""
    return {"seconds": float(np.mean(frame["seconds"])), "iterations": float(np.mean(frame["iterations"]))}
