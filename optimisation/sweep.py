"""Sizing sweeps: the least rope diameter d, pretension F_nwl and stroke at every point of a grid.

Each point is one continuous sizing optimisation of the :mod:`optimisation`
package's NLP (:class:`optimisation.problem.SizingProblem`: the scene's own
equations, built once; each point's values are the NLP's parameters), solved
with IPOPT at the package's options.

``warm=True`` starts each optimisation from the optimum of the previous point
(its neighbour on the grid: the last axis varies fastest) *with its
multipliers* and IPOPT's warm-start settings (``warm_start_init_point``, small
barrier parameter and bound pushes): an interior-point method given only a
primal start moves back to the central path and gains little; given the
multipliers it typically needs a third of the iterations
(``studies/sizing_map.py`` measures it).  ``warm=False`` starts every point
from the scene's design.  Either way a point whose start fails is solved again
by the package's multi-start :func:`optimisation.design.solve_best`, so the
start changes cost, not the answer (both are IPOPT optima at tolerance 1e-10).
Points with no feasible design are kept with ``feasible`` False and missing d,
F_nwl, stroke.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from optimisation.design import solve_best
from optimisation.ipopt import solve_continuous
from optimisation.problem import VARIABLES, SizingProblem
from ropemodel.errors import InputError
from ropemodel.sweep.points import grid, table
from ropemodel.sweep.validate import check_ranges, check_rules
from ropemodel.units import label

DESIGN_UNITS = {"d": "mm", "F_nwl": "kN", "stroke": "mm"}


def sizing_sweep(scene, vary=None, *, points=None, warm: bool = True, progress: bool | None = None) -> pd.DataFrame:
    """Continuous sizing optimum at every point; columns: the varied inputs, ``d [mm]``, ``F_nwl [kN]``,
    ``stroke [mm]``, ``feasible``, ``iterations`` (IPOPT, all attempts) and ``seconds`` (solver time)."""
    problem = SizingProblem(scene)
    q = scene.built.quantities
    inputs = {k: q[k] for k in problem.params}
    if isinstance(vary, pd.DataFrame):
        points, vary = vary, None
    if (vary is None) == (points is None):
        raise InputError("give either vary={name: axis} (a grid) or a table of points")
    for k in (vary or {}):
        if k in VARIABLES:
            raise InputError(f"cannot vary {k}: it is a design variable the sizing chooses")
    pts = grid(vary, inputs) if vary is not None else table(points, inputs, ignore=scene.built.outputs)
    check_ranges(pts, inputs)
    check_rules(scene.built, pts, dict(scene.parameters))
    rows = []
    prev = None
    bar = tqdm(total=pts.n, unit="opt", desc="sizing", disable=(not progress) if progress is not None else None)
    for start in range(0, pts.n, 4096):
        chunk = pts.chunk(start, min(pts.n, start + 4096))
        for i in range(len(chunk[pts.names[0]])):
            values = {k: float(chunk[k][i]) for k in pts.names}
            p = problem.p_of(values)
            sol = solve_continuous(problem, p, polish=False, start=prev if warm else None)
            iters, secs = sol.iterations, sol.seconds
            if not sol.feasible:  # the package's multi-start (from the scene's design first)
                sol = solve_best(problem, p)
                iters, secs = iters + sol.iterations, secs + sol.seconds
            ok = sol.feasible
            if ok:
                prev = sol.start
            design = problem.to_si(sol.xs) if ok else dict.fromkeys(VARIABLES, math.nan)
            row = {label(k, q[k].display_unit): float(q[k].to_display(v)) for k, v in values.items()}
            for k in VARIABLES:
                row[label(k, DESIGN_UNITS[k])] = design[k] * (1e3 if DESIGN_UNITS[k] == "mm" else 1e-3)
            row.update(feasible=ok, iterations=iters, seconds=secs)
            rows.append(row)
            bar.update(1)
    bar.close()
    return pd.DataFrame(rows)


def sizing_function(scene, warm: bool = True):
    """A vectorised function {name: SI array} → {"d", "F_nwl", "stroke": SI arrays} (for Sobol indices).

    Raises :class:`InputError` if a point has no feasible design (narrow the ranges).
    """

    def func(columns):
        frame = sizing_sweep(scene, pd.DataFrame(columns), warm=warm, progress=False)
        if not frame["feasible"].all():
            bad = int((~frame["feasible"]).sum())
            raise InputError(f"{bad} sampled point(s) have no feasible design; narrow the ranges")
        return {"d": frame["d [mm]"].to_numpy() / 1e3, "F_nwl": frame["F_nwl [kN]"].to_numpy() * 1e3,
                "stroke": frame["stroke [mm]"].to_numpy() / 1e3}

    return func


def solve_times(frame: pd.DataFrame) -> dict:
    """Mean solver seconds and iterations per optimisation of a :func:`sizing_sweep` frame."""
    return {"seconds": float(np.mean(frame["seconds"])), "iterations": float(np.mean(frame["iterations"]))}
