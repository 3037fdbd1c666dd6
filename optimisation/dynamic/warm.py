"""Re-solves of the dynamic NLP on its previous optimum's active set, by Newton, instead of IPOPT.

The dynamic NLP is solved several times in a row on problems that barely differ: the same cases on a grid
with the checks' exact minima added (:mod:`optimisation.dynamic.refine`), more cases, the transients rebuilt
at the optimum, d fixed at the next catalogue size.  Its optimum is usually a vertex: as many active checks
and bounds as variables (three), and the next problem's optimum is fixed by the same checks, each at its
peak's instant on the new grid.  IPOPT does not know that: from the previous optimum it re-entered the
central path and took 16-19 iterations (measured on the test scene of ``tests/_dynamic_scene.py``, each
iteration 0.5 CPU-s, the transients integrated with their sensitivities), primal start or warm start with
the multipliers alike (the previous optimum violates the added points by 4e-3: IPOPT's restoration).

:func:`on_active_set` solves the active checks of the next problem (the previous active set, each dynamic
check moved to its least grid point within :data:`NEAR` of its old instant; d's bound when d is fixed) by
Newton — chord steps: usually two Jacobians and a few evaluations of the checks alone — and keeps the point
only when it is a KKT point of the whole next problem: every check holds (to
:data:`~optimisation.ipopt.FEAS_TOL`) and the multipliers of the active set are nonnegative (the objective's
gradient is a nonnegative combination of the active checks' normals, no feasible direction lowers it).
Anything else is left to IPOPT.
"""

from __future__ import annotations

import itertools
import time

import casadi as ca
import numpy as np

from optimisation.ipopt import FEAS_TOL, Solution, jacobian_at, lexicographic_ok

#: a dynamic check's instant may move this far [s] between two problems and still be the same peak
NEAR = 0.1
NEWTON_STEPS = 8
#: a multiplier of an active check at least this negative (scaled) is not a KKT point
LAM_TOL = 1e-9
#: cases whose violated check :func:`on_active_set` tries in place of the same check's previous active row
MOVED = 2


def _jacobian(problem):
    """(x, p, rows) → (g, ∂g/∂x, ∇f, f) of ``problem`` (numpy; of ∂g/∂x the rows ``rows`` at least, the others may
    be NaN): g and its Jacobian those the IPOPT path evaluates and keeps (:func:`~optimisation.ipopt.jacobian_at`:
    the active set, the polish and the lexicographic test ask the same points again), the objective's gradient
    from its own Function, built once per problem."""
    if "_warm_objective" not in problem.__dict__:
        problem.__dict__["_warm_objective"] = ca.Function(
            "warm_objective", [problem.xs, problem.p], [ca.gradient(problem.f, problem.xs), problem.f])
    objective = problem.__dict__["_warm_objective"]

    def jac(x, p, rows):
        g, J = jacobian_at(problem, x, p, rows)
        grad, f = objective(x, p)
        return g, J, np.asarray(grad), np.asarray(f)

    return jac


def instant(name: str) -> tuple[str, float | None]:
    """(``check[e] @ manoeuvre, place``, t [s]) of a dynamic constraint's name; (name, None) of a static one."""
    head, sep, tail = name.rpartition(", t = ")
    return (head, float(tail.removesuffix(" s"))) if sep else (name, None)


def _candidates(old_active: list[str], new, g0: np.ndarray) -> list[int]:
    """The next problem's constraints standing for the previous active ones (indices, no repeats)."""
    where: dict[str, list[tuple[float, int]]] = {}
    index: dict[str, int] = {}
    for k, name in enumerate(new.constraints):
        head, t = instant(name)
        if t is None:
            index.setdefault(name, k)
        else:
            where.setdefault(head, []).append((t, k))
    out: list[int] = []
    for name in old_active:
        head, t = instant(name)
        i: int | None
        if t is None:
            i = index.get(name)
        else:
            near = [j for s, j in where.get(head, ()) if abs(s - t) <= NEAR]
            i = min(near, key=lambda j: g0[j]) if near else None
        if i is None:
            return []
        if i not in out:
            out.append(i)
    return out


def _residual(problem) -> ca.Function:
    """(x, p) → g of ``problem`` alone (its transients integrated without sensitivities), built once per problem."""
    if "_warm_g" not in problem.__dict__:
        problem.__dict__["_warm_g"] = ca.Function("warm_g", [problem.xs, problem.p], [problem.g])
    return problem.__dict__["_warm_g"]


def _rows_residual(problem, rows):
    """(x, p) → g of ``problem``, at least its rows ``rows``: only the blocks holding them where the problem evaluates
    g by blocks (:meth:`~optimisation.dynamic.problem.DynamicSizingProblem.g_rows`: a Newton step on the active
    checks integrates only the cases holding them, measured on the three-segment route two of six), else all."""
    if hasattr(problem, "g_rows"):
        return lambda x, p: problem.g_rows(x, p, rows)
    return _residual(problem)


def newton(jac, residual, x, p, rows, fixed, lbx, start=None):
    """Newton on g[rows] = 0 with x[fixed] = lbx[fixed]: the point, or None (singular, not converging).  ``jac``:
    (x, p, rows) → (g, ∂g/∂x, ...), ``residual``: (x, p) → g (of both, the rows ``rows`` are read).

    Chord steps: the Jacobian of the first point is kept while each step at least halves the last, and taken
    again where one does not; g alone is evaluated between (through the integrators a tenth of the cost of g
    with its Jacobian, which needs the sensitivities).  It stops where a step with a fresh Jacobian does not
    halve either (the noise floor of g through an integrator) or is below rounding.  ``start``: (g, J) at ``x``
    to begin with instead — J the previous problem's at its optimum, a chord like any other (:func:`_carried`)."""
    g, J = (np.asarray(a) for a in (start or jac(x, p, rows)[:2]))
    fresh, last = start is None, np.inf
    A = None
    for _ in range(NEWTON_STEPS):
        if fresh or A is None:
            A = np.vstack([J[rows, :], np.eye(len(x))[fixed, :]])
            if np.linalg.cond(A) > 1e12:
                return None
        step = np.linalg.solve(A, -np.concatenate([g.ravel()[rows], x[fixed] - lbx[fixed]]))
        size = float(np.max(np.abs(step)))
        if size > 0.5 * last and not fresh:     # the chord slows: take this point's Jacobian and step again
            g, J = (np.asarray(a) for a in jac(x, p, rows)[:2])
            fresh = True
            continue
        x = x + step
        if size < 1e-14 * max(1.0, float(np.max(np.abs(x)))) or size > 0.5 * last:
            return x
        last, fresh = size, False
        g = np.asarray(residual(x, p))
    return x


def on_active_set(old, sol, new, p=None, fix_d: float | None = None) -> Solution | None:
    """The optimum of problem ``new`` on the active set of ``sol`` (the optimum of problem ``old``), or None
    when that active set does not give a KKT point of ``new`` (IPOPT then solves it)."""
    t_start = time.perf_counter()
    p = new.p0 if p is None else np.asarray(p, float)
    lbx, ubx = new.bounds()
    if fix_d is not None:
        lbx[0] = ubx[0] = fix_d / new.x_scale[0]
    fixed = sorted({i for i, _ in sol.active_bounds} | ({0} if fix_d is not None else set()))
    if any(lbx[i] != ubx[i] and side == "upper" for i, side in sol.active_bounds):
        return None
    jac = _jacobian(new)
    x0 = np.clip(np.asarray(sol.xs, float), lbx, ubx)
    g0 = np.asarray(_residual(new)(x0, p)).ravel()
    candidates = _candidates(list(sol.active), new, g0)
    start = _carried(old, sol, new, p, candidates, g0)
    m = len(x0) - len(fixed)
    for rows, carried in _orders(new, candidates, m, g0, start):
        found = _kkt(jac, new, x0, p, list(rows), fixed, lbx, ubx, carried)
        if found is not None:
            x, g, lam_g, lam_x, f = found
            out = Solution(x, f, g, lam_g, lam_x, True, "active set", 0, time.perf_counter() - t_start)
            out.active = [new.constraints[i] for i in rows]
            out.active_bounds = [(i, "lower") for i in fixed]
            out.polished = True
            out.lexicographic_ok = lexicographic_ok(new, out, p)
            return out
    return None


def check_of(name: str) -> str:
    """The check a constraint's name is of (``slip_margin_back`` of ``slip_margin_back @ downward start, ...``)."""
    return name.partition(" @ ")[0]


def _orders(new, candidates: list[int], m: int, g0: np.ndarray, start):
    """The active sets :func:`on_active_set` tries on ``new``, each with the first chord :func:`newton` starts from:
    every ``m`` of ``candidates`` (the previous active set's rows, with ``start``); then, where they are exactly
    ``m``, each of them replaced by the same check's worst row in a case where it is violated at the previous optimum
    (``g0`` below −:data:`~optimisation.ipopt.FEAS_TOL`; at most :data:`MOVED` such cases, worst first, no carried
    chord): the check's worst case moved, as when the screening adds a case the previous optimum violates
    (measured on the three-segment route: the rope safety of the upward start moved from the load at 600 m to 950 m,
    the same check's IPOPT re-solve took 13 iterations, 11 CPU-s, against 2.5 CPU-s for both Newton attempts)."""
    yield from ((rows, start) for rows in itertools.combinations(candidates, m) if 0 < m <= len(candidates))
    if not 0 < m == len(candidates):
        return
    heads = {instant(new.constraints[i])[0] for i in candidates}
    worst: dict[str, int] = {}
    for k in map(int, np.flatnonzero(g0 < -FEAS_TOL)):
        head = instant(new.constraints[k])[0]
        if head not in heads and (head not in worst or g0[k] < g0[worst[head]]):
            worst[head] = k
    for k in sorted(worst.values(), key=lambda k: g0[k])[:MOVED]:
        for i in (i for i in candidates if check_of(new.constraints[i]) == check_of(new.constraints[k])):
            yield [k if j == i else j for j in candidates], None


def _carried(old, sol, new, p, candidates: list[int], g0: np.ndarray):
    """(g0, J) for :func:`newton`'s first chord on ``new``: J the previous problem's Jacobian at its optimum
    ``sol`` (kept from its own KKT test, :func:`~optimisation.ipopt.jacobian_at`), each candidate row the row of
    the previous active check it stands for (:func:`_candidates`: the same check, its instant moved within
    :data:`NEAR`) — rather than a Jacobian of ``new`` at a point that is not yet its solution: a Jacobian costs
    about nine evaluations of the checks through the integrators.  The point Newton ends at is fixed by the
    checks' values alone; the KKT test there takes the exact Jacobian of ``new``.  None when the previous
    active set does not map row for row."""
    if len(candidates) != len(sol.active):
        return None
    J_old = jacobian_at(old, sol.xs, p, [old.constraints.index(name) for name in sol.active])[1]
    J = np.zeros((len(g0), J_old.shape[1]))
    for i, name in zip(candidates, sol.active):
        J[i] = J_old[old.constraints.index(name)]
    return g0, J


def _kkt(jac, new, x0, p, rows, fixed, lbx, ubx, start=None):
    """(x, g, lam_g, lam_x, f) when Newton on ``rows`` and ``fixed`` ends at a KKT point of ``new``, else None."""
    x = newton(jac, _rows_residual(new, rows), x0.copy(), p, rows, fixed, lbx, start)
    if x is None or np.any(x < lbx - 1e-12) or np.any(x > ubx + 1e-12):
        return None
    g, J, grad, f = (np.asarray(a) for a in jac(x, p, rows))
    g = g.ravel().copy()        # the kept evaluation is read-only; the solution's own g is not
    if np.any(g < -FEAS_TOL):
        return None
    # ∇f = Σ λ_i ∇g_i + Σ ν_j e_j: λ_i >= 0 for the checks; ν of a bound: its multiplier (sign as IPOPT's lam_x)
    A = np.vstack([J[rows, :], np.eye(len(x))[fixed, :]]).T
    lam = np.linalg.solve(A, grad.ravel())
    free_bound = [k for k, i in enumerate(fixed) if lbx[i] == ubx[i]]
    checks, bounds = lam[:len(rows)], lam[len(rows):]
    if np.any(checks < -LAM_TOL) or any(bounds[k] < -LAM_TOL for k in range(len(fixed)) if k not in free_bound):
        return None
    lam_g = np.zeros(len(g))
    lam_g[rows] = -checks        # IPOPT's sign for g >= 0 at its lower bound
    lam_x = np.zeros(len(x))
    lam_x[fixed] = -bounds
    return x, g, lam_g, lam_x, float(np.asarray(f).ravel()[0])
