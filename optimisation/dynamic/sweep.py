"""Sweeps of the dynamic optimum: the least d, F_nwl and stroke through the four manoeuvres at every point of
a grid or table (``ropemodel sweep SCENE --sizing --dynamic``), as :func:`optimisation.sweep.sizing_sweep`
does for the static optimum.

The dynamic NLP is built once (:class:`~optimisation.dynamic.problem.DynamicSizingProblem`: the points'
values are its parameters) and its first optimum found as :func:`~optimisation.dynamic.design.size_dynamic`
finds it; every further point starts from its predecessor's optimum (points are taken in order, so each
point's predecessor is its neighbour) on the predecessor's refined grid and cases, refined again and with
more cases where the point needs them.  Every point's design is simulated in every case by the hybrid
simulator; one the simulator does not confirm is an error (:class:`~ropemodel.errors.SolveError`), never a
row.  Parameters that fix the transient's structure (the route's geometry, where the load is, t_end) cannot
be varied.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from optimisation.design import solve_best
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.refine import solve_refined
from optimisation.dynamic.sensitivity import symbolic_params
from optimisation.dynamic.start import factored_start
from optimisation.dynamic.verify import verify
from optimisation.problem import SizingProblem
from optimisation.sweep import sizing_frame, sizing_points
from ropemodel.errors import InputError, SolveError
from ropemodel.numerics.held import held_solver_output


def dynamic_sizing_sweep(scene, vary=None, *, points=None, progress: bool | None = None) -> pd.DataFrame:
    """Continuous dynamic optimum at every point; the columns of :func:`optimisation.sweep.sizing_sweep`
    (the varied inputs, ``d [mm]``, ``F_nwl [kN]``, ``stroke [mm]``, ``feasible``, ``iterations``,
    ``seconds``)."""
    problem = DynamicSizingProblem(scene)
    q = problem.scene.built.quantities
    pts = sizing_points(problem.scene, problem, vary, points)
    allowed = set(symbolic_params(problem))
    fixed = [k for k in pts.names if k not in allowed]
    if fixed:
        raise InputError(f"cannot vary {', '.join(fixed)} in a dynamic sizing sweep: it fixes the transient's "
                         f"structure (its grid, where the load is); valid: {', '.join(sorted(allowed))}")
    chunk = pts.chunk(0, pts.n)
    x, feasible = np.full((pts.n, 3), np.nan), np.zeros(pts.n, bool)
    iterations, seconds = np.zeros(pts.n, int), np.zeros(pts.n)
    prev = None
    bar = tqdm(total=pts.n, unit="opt", desc="dynamic sizing", disable=(not progress) if progress is not None else None)
    with held_solver_output():
        for i in range(pts.n):
            values = {k: float(chunk[k][i]) for k in pts.names}
            p = problem.p_of(values)
            start, screen = prev, True
            if start is None:
                start = _first_start(problem, p)
                problem, screen = (problem.screened(start, p), False) if start is not None else (problem, True)
            if start is not None:
                problem, sol = solve_refined(problem, start, p=p, screen=screen)
                iterations[i], seconds[i] = sol.iterations, sol.seconds
                if sol.feasible:
                    _confirm(problem, sol.xs, values)
                    x[i], feasible[i], prev = sol.xs, True, sol.xs
            bar.update(1)
    bar.close()
    return sizing_frame(problem, q, chunk, x, feasible, iterations, seconds)


def _first_start(problem, p):
    """The start of the first point with a static design (None: no static design, so no dynamic one)."""
    sol = solve_best(SizingProblem(problem.scene), p)
    return factored_start(problem, sol.xs, p) if sol.feasible else None


def _confirm(problem, xs, values: dict) -> None:
    bad = [f"{v.manoeuvre}: " + "; ".join(v.failures) for v in verify(problem, xs, values) if not v.ok]
    if bad:
        point = ", ".join(f"{k} = {v:g}" for k, v in values.items())
        raise SolveError(f"the dynamic optimum at {point} fails in the hybrid simulator (" + " | ".join(bad) + ")")
