"""What alone would make a design exist: each remedy's value by Newton on the least-violation optimum's active set.

At the least-violation optimum (x*, t*) of :func:`~optimisation.dynamic.diagnose.diagnose_dynamic` the active
checks A (nonzero multipliers) and the active bounds B hold t* up: g_A(x*) = −t*.  Freeing one parameter q (scaled
τ = q / |q0|), the least (or largest) q with a design is where the least violation reaches 0, on the same active set
the square system

    g_A(x, τ) = 0,   x_B = its bounds          (as many equations as the free x and τ)

solved by Newton from (x*, τ0) — its first step is the envelope theorem's estimate τ0 − t*/(dt*/dτ).  Newton's
Jacobians are of the cases holding an active check alone (:meth:`DynamicSizingProblem.with_cases`): on the test scene
with a 2 s ramp two of the seven the NLP integrates.  The point is kept only when it answers the remedy problem of
:func:`~optimisation.dynamic.diagnose.free_by_ipopt` (min ±τ s.t. every check g(x, q) ≥ 0 of every case the NLP
integrates): every check holds there with q in the parameter's valid range, as that function verifies its own answer
(the scene's rules applied to q), and it is a KKT point — the objective's gradient a combination of the active checks'
normals with nonnegative multipliers and of the bounds' with the bounds' signs.  Otherwise (another active set,
singular, out of range) IPOPT solves the remedy problem (:func:`~optimisation.dynamic.diagnose.free_by_ipopt`).
Both judge the checks at the NLP's grid points; :func:`between_points` adds each check's exact minima between them
and solves again (judged at the grid points only, the test scene's named ramp t_ramp >= 2.184 s left checks of the
upward start short between them, measured by the hybrid simulator; now 2.187 s).
Measured on the test scene with a 2 s ramp: IPOPT took 83-498 CPU-s per parameter (22-105 iterations, each the seven
cases integrated with their sensitivities).
"""

from __future__ import annotations

import itertools

import casadi as ca
import numpy as np

from optimisation.dynamic.refine import MAX_ROUNDS, add_points, shortfalls
from optimisation.dynamic.screen import uncovered
from optimisation.dynamic.warm import LAM_TOL, instant, newton

#: a multiplier of the least-violation problem above this marks an active check or bound
ACTIVE = 1e-6
#: active sets tried at most (combinations of the active checks when more are active than fix the point)
MAX_SETS = 6
#: moves of the active checks' peaks followed at most (:func:`_solved`)
MOVES = 6


def between_points(problem, solve, at):
    """A remedy's (value [SI], scaled design) that holds between the grid points too, or None.

    ``solve(problem)`` → (value [SI], scaled design) or None: the remedy on ``problem``'s grid (every check holds
    at its points); ``at(problem, value)`` → the parameters the value's answer shows (rounded to the safe side).
    As the sizing's refinement (:func:`~optimisation.dynamic.refine.shortfalls`): each check's exact local minima
    at the remedy's design and shown value, the ones short of their back-off less half the integration's added to
    the grid, and the remedy solved again on that grid — Newton's active checks move onto the added points where
    they are lower (the peaks between points) — until every minimum keeps that margin; then the cases the NLP
    leaves out are screened there (:func:`~optimisation.dynamic.screen.uncovered`), one where a check comes within
    the back-off joins the problem, solved again (:data:`~optimisation.dynamic.refine.MAX_ROUNDS` rounds in all)."""
    for _ in range(MAX_ROUNDS):
        found = solve(problem)
        if found is None:
            return None
        value, xs = found
        p = at(problem, value)
        low = shortfalls(problem, xs, p)[1]
        more = [] if low else uncovered(problem, xs, p, problem.largest_backoff())
        if not low and not more:
            return found
        problem = problem.refined(add_points(problem, problem.grids, low, p)) if low else \
            problem.with_cases([*problem.selected, *more])
    return None


def active_of(problem, lam_g, lam_x, x, lbx, ubx) -> tuple[list[str], dict[int, float]]:
    """The least-violation optimum's active checks (names) and active bounds (design variable index → its bound,
    scaled) from its multipliers."""
    checks = [c for c, v in zip(problem.constraints, np.abs(lam_g)) if v > ACTIVE]
    bounds = {}
    for j, v in enumerate(np.abs(lam_x[:len(x)])):
        if v > ACTIVE:
            bounds[j] = lbx[j] if abs(x[j] - lbx[j]) <= abs(x[j] - ubx[j]) else ubx[j]
    return checks, bounds


def holding(problem, checks: list[str]):
    """``problem`` integrating only the cases of ``checks`` (names of its constraints; the static checks stay)."""
    tags = {instant(c)[0].split(" @ ", 1)[1] for c in checks if instant(c)[1] is not None}
    keep = [i for i in problem.selected if problem.tags[i] in tags]
    return problem.with_cases(keep) if keep and len(keep) < len(problem.selected) else problem


def _functions(problem, i: int, scale: float):
    """(z → g, z → (g, ∂g/∂z)) of ``problem`` at the scene's parameters but the i-th, τ·scale; z = (x, τ)."""
    z = ca.MX.sym("z", len(problem.variables) + 1)
    p0 = problem.p0
    pv = ca.vertcat(ca.DM(p0[:i]), z[-1] * scale, ca.DM(p0[i + 1:]))
    g = problem.g_function(z[:-1], pv)
    return ca.Function("g_freed", [z], [g]), ca.Function("jac_freed", [z], [g, ca.jacobian(g, z)])


def newton_remedy(problem, name: str, sense: str, least, checks, bounds, box, verified):
    """The least (``sense`` "min") or largest ("max") value [SI] of parameter ``name`` with a design, by Newton on
    the least-violation optimum's active set (``least``: its design, scaled; ``checks``, ``bounds``:
    :func:`active_of`; ``box``: (lbx, ubx, lo, hi), the design's and τ's bounds); ``verified``: value, x → whether
    every check of ``problem`` holds there (the caller's verification).  Returns (the value [SI], the scaled design
    there), or None when it does not give the answer."""
    i = problem.params.index(name)
    scale = abs(problem.p0[i]) or 1.0
    sub = holding(problem, checks)
    residual, jacobian = _functions(sub, i, scale)
    rows_all = [sub.constraints.index(c) for c in checks if c in sub.constraints]
    if len(rows_all) < len(checks):
        return None
    lbx, ubx, lo, hi = box
    held = {j: lbx[j] for j in range(len(least)) if lbx[j] == ubx[j]}      # the box's held variables
    fixed = sorted({**bounds, **held})
    pinned = np.zeros(len(least) + 1)
    pinned[fixed] = [{**bounds, **held}[j] for j in fixed]
    z0 = np.concatenate([least, [problem.p0[i] / scale]])
    m = len(z0) - len(fixed)

    def jac(z, _p, _rows=None):
        g, J = jacobian(z)
        return np.asarray(g).ravel(), np.asarray(J)

    heads: dict[str, list[int]] = {}
    for k, c in enumerate(sub.constraints):
        heads.setdefault(instant(c)[0], []).append(k)
    for rows in itertools.islice(itertools.combinations(rows_all, m), MAX_SETS):
        z = _solved(jac, residual, z0, list(rows), fixed, pinned, heads, sub.constraints)
        if z is None or np.any(z[:-1] < lbx - 1e-12) or np.any(z[:-1] > ubx + 1e-12) or not lo <= z[-1] <= hi:
            continue
        if _kkt(jac(z, None)[1], list(rows), fixed, bounds, lbx, ubx, sense) and verified(z[-1] * scale, z[:-1]):
            return float(z[-1] * scale), z[:-1]
    return None


def _solved(jac, residual, z, rows, fixed, pinned, heads, names):
    """Newton on ``rows`` (changed in place), each active check's peak followed: where another grid point of the
    same check in the same case is lower at Newton's point (the peak moved with the parameter: the ramp time
    stretches the manoeuvre), it takes the row's place and Newton goes on from there (:data:`MOVES` times)."""
    for _ in range(MOVES):
        z = newton(jac, lambda z, _p: np.asarray(residual(z)).ravel(), z.copy(), None, rows, fixed, pinned)
        if z is None:
            return None
        g = np.asarray(residual(z)).ravel()
        moved = [min(heads[instant(names[r])[0]], key=lambda k: g[k]) for r in rows]
        if all(g[k] >= g[r] - 1e-12 for k, r in zip(moved, rows)):
            return z
        rows[:] = moved
    return None


def _kkt(J, rows, fixed, bounds, lbx, ubx, sense) -> bool:
    """Whether ∇(±τ) = Σ μ_i ∇g_i + Σ ν_j e_j with μ ≥ 0 for the checks ``rows`` and ν of a bound with its sign
    (≥ 0 at a lower bound, ≤ 0 at an upper; any for a variable held, its bounds equal)."""
    n = J.shape[1]
    A = np.vstack([J[rows, :], np.eye(n)[fixed, :]]).T
    grad = np.zeros(n)
    grad[-1] = 1.0 if sense == "min" else -1.0
    try:
        lam = np.linalg.solve(A, grad)
    except np.linalg.LinAlgError:
        return False
    checks, nu = lam[:len(rows)], lam[len(rows):]
    signs = [0.0 if lbx[j] == ubx[j] else 1.0 if bounds[j] == lbx[j] else -1.0 for j in fixed]
    return bool(np.all(checks >= -LAM_TOL) and all(s * v >= -LAM_TOL for s, v in zip(signs, nu)))
