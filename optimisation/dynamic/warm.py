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
Newton — two or three Jacobians — and keeps the point only when it is a KKT point of the whole next problem:
every check holds (to :data:`~optimisation.ipopt.FEAS_TOL`) and the multipliers of the active set are
nonnegative (the objective's gradient is a nonnegative combination of the active checks' normals, no
feasible direction lowers it).  Anything else is left to IPOPT.
"""

from __future__ import annotations

import itertools
import time

import casadi as ca
import numpy as np

from optimisation.ipopt import FEAS_TOL, Solution, lexicographic_ok

#: a dynamic check's instant may move this far [s] between two problems and still be the same peak
NEAR = 0.1
NEWTON_STEPS = 8
#: a multiplier of an active check at least this negative (scaled) is not a KKT point
LAM_TOL = 1e-9


def _jacobian(problem) -> ca.Function:
    """(x, p) → (g, ∂g/∂x, ∇f, f) of ``problem``, built once per problem."""
    if "_warm_jac" not in problem.__dict__:
        problem.__dict__["_warm_jac"] = ca.Function(
            "warm_jac", [problem.xs, problem.p],
            [problem.g, ca.jacobian(problem.g, problem.xs), ca.gradient(problem.f, problem.xs), problem.f])
    return problem.__dict__["_warm_jac"]


def _instant(name: str) -> tuple[str, float | None]:
    """(``check[e] @ manoeuvre, place``, t [s]) of a dynamic constraint's name; (name, None) of a static one."""
    head, sep, tail = name.rpartition(", t = ")
    return (head, float(tail.removesuffix(" s"))) if sep else (name, None)


def _candidates(old_active: list[str], new, g0: np.ndarray) -> list[int]:
    """The next problem's constraints standing for the previous active ones (indices, no repeats)."""
    where: dict[str, list[tuple[float, int]]] = {}
    index: dict[str, int] = {}
    for k, name in enumerate(new.constraints):
        head, t = _instant(name)
        if t is None:
            index.setdefault(name, k)
        else:
            where.setdefault(head, []).append((t, k))
    out: list[int] = []
    for name in old_active:
        head, t = _instant(name)
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


def _newton(jac, x, p, rows, fixed, lbx):
    """Newton on g[rows] = 0 with x[fixed] = lbx[fixed]: the point, or None (singular, not converging)."""
    last = np.inf
    for _ in range(NEWTON_STEPS):
        g, J, _, _ = (np.asarray(a) for a in jac(x, p))
        r = np.concatenate([g.ravel()[rows], x[fixed] - lbx[fixed]])
        A = np.vstack([J[rows, :], np.eye(len(x))[fixed, :]])
        if np.linalg.cond(A) > 1e12:
            return None
        step = np.linalg.solve(A, -r)
        x = x + step
        size = float(np.max(np.abs(step)))
        if size < 1e-14 * max(1.0, float(np.max(np.abs(x)))) or size > 0.5 * last:
            return x
        last = size
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
    g0 = np.asarray(jac(x0, p)[0]).ravel()
    candidates = _candidates(list(sol.active), new, g0)
    m = len(x0) - len(fixed)
    for rows in itertools.combinations(candidates, m) if 0 < m <= len(candidates) else ():
        found = _kkt(jac, new, x0, p, list(rows), fixed, lbx, ubx)
        if found is not None:
            x, g, lam_g, lam_x, f = found
            out = Solution(x, f, g, lam_g, lam_x, True, "active set", 0, time.perf_counter() - t_start)
            out.active = [new.constraints[i] for i in rows]
            out.active_bounds = [(i, "lower") for i in fixed]
            out.polished = True
            out.lexicographic_ok = lexicographic_ok(new, out, p)
            return out
    return None


def _kkt(jac, new, x0, p, rows, fixed, lbx, ubx):
    """(x, g, lam_g, lam_x, f) when Newton on ``rows`` and ``fixed`` ends at a KKT point of ``new``, else None."""
    x = _newton(jac, x0.copy(), p, rows, fixed, lbx)
    if x is None or np.any(x < lbx - 1e-12) or np.any(x > ubx + 1e-12):
        return None
    g, J, grad, f = (np.asarray(a) for a in jac(x, p))
    g = g.ravel()
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
