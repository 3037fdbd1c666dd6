"""Every check between the grid points: each check's exact local minima added to the time grid.

The NLP asks the checks at the points of each manoeuvre's time grid; between them a peak of the
rope force or a dip of the traction margin can be lower.  After each solve every check is read on
a dense grid (:data:`DT_DENSE`, the NLP's own integrator), every local minimum below
:data:`ADD_TOL` is located exactly (bounded Brent on the check integrated from the sample before,
to 1e-10 s), and the times whose margin is below half the back-off are added to the grid; the
problem is solved again from the previous optimum.  It stops when every exact local minimum of
every check keeps its back-off less half the integration's (:data:`~optimisation.dynamic.problem.BACKOFF`;
a check's back-off adds its mesh error estimate, :mod:`optimisation.dynamic.mesh`): the
optimum holds between the grid points, the other half of the back-off is left for the difference
between the NLP's integrator and the hybrid simulator's (:mod:`optimisation.dynamic.verify`).  Then
the cases the NLP leaves out (:mod:`optimisation.dynamic.screen`) are screened at the optimum: one where
a check comes within the back-off joins the NLP, which is solved again.
Each added point is a peak of a check at the current design; a peak moves little between two
solves, so the violation between points falls fast (``Refinement.rounds`` records it).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from optimisation.dynamic.problem import BACKOFF
from optimisation.dynamic.screen import check_scale, governing, uncovered
from optimisation.dynamic.start import DT_DENSE
from optimisation.dynamic.warm import on_active_set
from optimisation.ipopt import solve_continuous
from ropemodel.errors import SolveError

#: local minima below this (scaled) margin are located exactly
ADD_TOL = 1e-2
MAX_ROUNDS = 8
#: rebuilds of the transients at the optimum (each a choice made from the design's numbers, e.g. a branch of
#: Li's law, that the optimum changed; measured: one rebuild on the capstan-contact test scene)
MAX_REBUILDS = 4


@dataclass(frozen=True)
class Minimum:
    """An exact local minimum of a check through a manoeuvre: which path (index), check, component (the
    element for the tensions), phase, time [s], scaled margin (before the back-off)."""

    path: int
    check: str
    component: int
    phase: int
    t: float
    value: float


@dataclass
class Refinement:
    """What the refinement did: per round, the least exact margin between the grid points (scaled), how
    many points it added and the cases (manoeuvre and place) it added to the NLP."""

    rounds: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"rounds": [{"least_margin_scaled": v, "points_added": n, "cases_added": c}
                           for v, n, c in self.rounds]}


def _values(problem, xs, p):
    x_si = np.asarray(xs, float) * problem.x_scale
    return {k: float(v) for k, v in problem.values(x_si, p).items()}


def minima(problem, xs, p=None, tol: float = ADD_TOL) -> list[Minimum]:
    """Every local minimum below ``tol`` (scaled) of every check through every manoeuvre at design ``xs``,
    located exactly."""
    p = problem.p0 if p is None else np.asarray(p, float)
    a = _values(problem, xs, p)
    out = []
    for j, path in enumerate(problem.paths):
        pp = problem.pp0(path, xs, p)
        grid = path.uniform_grid(pp, DT_DENSE)
        times, o, X = path.samples(pp, grid)
        starts = np.cumsum([0] + [len(g) for g in grid])
        for check in path.checks:
            G = np.atleast_2d(np.asarray(check.nlp(o, a), float)) / check_scale(problem, check)
            for e, series in enumerate(G):
                for k in range(len(grid)):
                    lo, hi = starts[k], starts[k + 1]
                    out += _phase_minima(problem, path, j, check, e, k, times[lo:hi], series[lo:hi], X[:, lo:hi],
                                         pp, a, tol)
    return out


def _phase_minima(problem, path, j, check, e, k, t, g, X, pp, a, tol) -> list[Minimum]:
    found = []
    scale = check_scale(problem, check)
    for i in np.flatnonzero(g < tol):
        left = g[i - 1] if i > 0 else np.inf
        right = g[i + 1] if i + 1 < len(g) else np.inf
        if not (g[i] <= left and g[i] <= right):
            continue
        if i == 0 or i == len(g) - 1:           # a phase's end: the grid always has it
            found.append(Minimum(j, check.name, e, k, float(t[i]), float(g[i])))
            continue

        def value(out, check=check, e=e):
            return np.asarray(check.nlp(out, a), float).ravel()[e] / scale

        t_star = path.exact_minimum(k, X[:, i - 1], float(t[i - 1]), float(t[i + 1] - t[i - 1]), value, pp)
        found.append(Minimum(j, check.name, e, k, t_star, _value_at(path, k, X[:, i - 1], t[i - 1], t_star, pp, value)))
    return found


def _value_at(path, k, x_a, t_a, t, pp, value) -> float:
    x = x_a if t <= t_a else path.step(k)(x_a, t_a, t - t_a, pp)
    return float(value(path.sm.pieces[k].out.call({"x": x, "t": t, "p": pp})))


def shortfalls(problem, xs, p=None) -> tuple[list[Minimum], list[Minimum]]:
    """(every exact local minimum of every check within :data:`ADD_TOL` of the largest back-off at scaled design
    ``xs`` and parameters ``p``, those of them that do not keep their check's back-off less half the
    integration's): the points the refinement adds to the grid."""
    found = minima(problem, xs, p, ADD_TOL + problem.largest_backoff(0.0))
    return found, [m for m in found if m.value < problem.backoff(m.check, problem.selected[m.path]) - 0.5 * BACKOFF]


def add_points(problem, grids, points: list[Minimum], p=None):
    """``grids`` with the times of ``points`` added (as each phase's τ at the parameters ``p``)."""
    grids = [list(map(np.asarray, g)) for g in grids]
    for m in points:
        path = problem.paths[m.path]
        t0, t1 = path.phase_bounds(problem.pp0(path, p=p))[m.phase]
        g = grids[m.path]
        g[m.phase] = np.unique(np.concatenate([g[m.phase], [(m.t - t0) / (t1 - t0)]]))
    return grids


def _first_feasible(problem, starts, p, fix_d, warm=None):
    """IPOPT from each scaled start in turn until one ends feasible (the last attempt otherwise); first, with
    ``warm`` = (previous problem, its optimum), Newton on that optimum's active set
    (:func:`~optimisation.dynamic.warm.on_active_set`).  An IPOPT solve that stops at its acceptable level a hair
    outside a check (the noise floor of the checks through the integrators; its polish refused for the same
    reason) is finished by Newton on its own active set, kept at a KKT point of the problem, before the next start
    (measured on the three-segment route: IPOPT from the start stopped 1.2e-8 outside, and IPOPT from the next
    start took 19 iterations, 12.5 CPU-s, to the same active set)."""
    if warm is not None and (sol := on_active_set(*warm, problem, p, fix_d)) is not None:
        return sol
    for x0 in starts:
        sol = solve_continuous(problem, p=p, x0=x0, fix_d=fix_d)
        if sol.feasible:
            break
        if sol.success and (done := on_active_set(problem, sol, problem, p, fix_d)) is not None:
            return done
    return sol


def solve_refined(problem, x0, p=None, fix_d: float | None = None, record: Refinement | None = None, others=(),
                  screen: bool = True, warm=None):
    """IPOPT on ``problem`` from scaled ``x0``, then on grids refined by the checks' exact local minima
    until every minimum keeps half the back-off, and with the cases left out that come within the back-off
    added; then again on the transients built at the optimum if they differ there from the ones solved with
    (:meth:`~optimisation.dynamic.problem.DynamicSizingProblem.relinearised`).  Returns (problem on the final
    grid with its final cases, solution).

    ``screen``: first add the cases that govern a check at ``x0`` and ``p``
    (:func:`~optimisation.dynamic.screen.governing`) to those ``problem`` integrates (False: the caller has
    just screened there).  Without it a problem screened at another design can miss the case that governs
    the optimum; its first solve, lighter than the optimum, then ended a hair outside a check it does
    integrate and was returned as no design before the cases left out were screened (measured: the test
    scene re-solved from its optimum with G_m 0.1 % higher, the upward start with the load mid-route left
    out, d 46.09 mm against 46.20 mm, a margin of −1.005e-8).

    ``others``: further starts, tried in turn when a solve ends without a design (IPOPT can stop at an
    "acceptable" point that is not feasible: measured on a 2000 m route at 8 deg with a 5 s ramp, where the
    re-solve on the refined grid from the previous optimum stopped so, and the same NLP from the static
    design sized with the transient's factor solved to the same optimum in 17 iterations)."""
    if screen and (governs := set(governing(problem, x0, p)) - set(problem.selected)):
        problem = problem.with_cases([*problem.selected, *governs])
    for _ in range(MAX_REBUILDS):
        problem, sol = _refined(problem, x0, p, fix_d, record, others, warm)
        again = problem.relinearised(sol.xs, p) if sol.feasible else None
        if again is None:
            return problem, sol
        problem, x0, others, warm = again, sol.xs, (x0, *others), (problem, sol)
    raise SolveError(f"the manoeuvres' transients built at the optimum kept differing from the ones solved with "
                     f"after {MAX_REBUILDS} rebuilds; report it")


def _refined(problem, x0, p, fix_d, record, others, warm=None):
    """IPOPT from ``x0`` (then ``others``; first ``warm``'s active set) on grids refined until every exact local
    minimum keeps half the back-off: (problem on the final grid, solution)."""
    sol = _first_feasible(problem, [x0, *others], p, fix_d, warm)
    for _ in range(MAX_ROUNDS):
        if not sol.feasible:
            return problem, sol
        found, low = shortfalls(problem, sol.xs, p)
        more = [] if low else uncovered(problem, sol.xs, p, problem.largest_backoff())
        if record is not None:
            record.rounds.append((float(min((m.value for m in found), default=np.inf)), len(low),
                                  [problem.cases[i].tag for i in more]))
        if not low and not more:
            return problem, sol
        old = problem
        problem = problem.refined(add_points(problem, problem.grids, low, p)) if low else \
            problem.with_cases([*problem.selected, *more])
        sol = _first_feasible(problem, [sol.xs, x0, *others], p, fix_d, (old, sol))
    raise SolveError(f"the time grid and the cases of the dynamic checks did not converge in {MAX_ROUNDS} refinements")
