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
import time

import casadi as ca
import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from ropemodel.errors import InputError
from ropemodel.sweep.points import grid, table
from ropemodel.sweep.validate import check_ranges, check_rules
from ropemodel.units import label

DESIGN_UNITS = {"d": "mm", "F_nwl": "kN", "stroke": "mm"}
#: IPOPT settings for a start from a neighbour's optimum and multipliers
WARM = {"ipopt.warm_start_init_point": "yes", "ipopt.mu_init": 1e-6, "ipopt.warm_start_bound_push": 1e-9,
        "ipopt.warm_start_slack_bound_push": 1e-9, "ipopt.warm_start_mult_bound_push": 1e-9}


class _Solvers:
    """IPOPT on the package's NLP, cold (from the scene's design) and warm (from a neighbour)."""

    def __init__(self, problem):
        from optimisation.design import FEAS_TOL
        from optimisation.ipopt import IPOPT_OPTIONS

        self.problem, self.tol = problem, FEAS_TOL
        self.cold = ca.nlpsol("sizing_sweep_cold", "ipopt", problem.nlp(), IPOPT_OPTIONS)
        self.warm = ca.nlpsol("sizing_sweep_warm", "ipopt", problem.nlp(), {**IPOPT_OPTIONS, **WARM})
        self.lbx, self.ubx = problem.bounds()

    def solve(self, p, start=None):
        """(x, lam_x, lam_g, ok, iterations, seconds); ``start`` = a previous (x, lam_x, lam_g)."""
        if start is None:
            solver = self.cold
            x0 = self.problem.x0()
            args = {"x0": np.clip(x0, self.lbx, np.where(np.isfinite(self.ubx), self.ubx, x0))}
        else:
            solver = self.warm
            args = {"x0": start[0], "lam_x0": start[1], "lam_g0": start[2]}
        t = time.perf_counter()
        r = solver(p=p, lbx=self.lbx, ubx=self.ubx, lbg=0.0, ubg=np.inf, **args)
        secs = time.perf_counter() - t
        st = solver.stats()
        ok = bool(st["success"]) and bool(np.all(np.asarray(r["g"]) >= -self.tol))
        return (np.asarray(r["x"]).ravel(), np.asarray(r["lam_x"]).ravel(), np.asarray(r["lam_g"]).ravel(),
                ok, int(st.get("iter_count", 0)), secs)


def sizing_sweep(scene, vary=None, *, points=None, warm: bool = True, progress: bool | None = None) -> pd.DataFrame:
    """Continuous sizing optimum at every point; columns: the varied inputs, ``d [mm]``, ``F_nwl [kN]``,
    ``stroke [mm]``, ``feasible``, ``iterations`` (IPOPT, all attempts) and ``seconds`` (solver time)."""
    from optimisation.design import _margins_ok, solve_best
    from optimisation.problem import VARIABLES, SizingProblem

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
    pts = grid(vary, inputs) if vary is not None else table(points, inputs)
    check_ranges(pts, inputs)
    check_rules(scene.built, pts, dict(scene.parameters))
    solvers = _Solvers(problem)
    rows = []
    prev = None
    bar = tqdm(total=pts.n, unit="opt", desc="sizing", disable=(not progress) if progress is not None else None)
    for start in range(0, pts.n, 4096):
        chunk = pts.chunk(start, min(pts.n, start + 4096))
        for i in range(len(chunk[pts.names[0]])):
            values = {k: float(chunk[k][i]) for k in pts.names}
            p = problem.p_of(values)
            x, lx, lg, ok, iters, secs = solvers.solve(p, prev if warm else None)
            if not ok:  # the package's multi-start (from the scene's design first)
                sol = solve_best(problem, p)
                x, lx, lg, ok = sol.xs, sol.lam_x, sol.lam_g, _margins_ok(sol)
                iters, secs = iters + sol.iterations, secs + sol.seconds
            if ok:
                prev = (x, lx, lg)
            design = problem.to_si(x) if ok else dict.fromkeys(VARIABLES, math.nan)
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
