"""The continuous optimum with IPOPT through ``ca.nlpsol`` (exact first and second derivatives).

After IPOPT converges, the active set (margins at zero with a nonzero multiplier,
and active bounds) is identified; when it has as many members as variables and a
regular Jacobian — the usual vertex design — the point is polished by Newton on
the active constraints, so the design is exact to rounding (the weights of the
objective then play no part in it, see :mod:`optimisation.problem`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from optimisation.problem import VARIABLES, SizingProblem

IPOPT_OPTIONS: dict[str, Any] = {"ipopt.tol": 1e-10, "ipopt.acceptable_tol": 1e-8, "ipopt.print_level": 0,
                                 "print_time": False, "show_eval_warnings": False, "calc_lam_p": False,
                                 "ipopt.sb": "yes", "ipopt.max_iter": 500}
ACTIVE_G = 1e-7      # scaled margin below which a constraint counts as active
ACTIVE_LAM = 1e-9    # multiplier above which it counts as binding
#: scaled margin above which a design counts as meeting a check (IPOPT's own tolerance is 1e-10)
FEAS_TOL = 1e-8
#: IPOPT settings for a start from a neighbouring optimum and its multipliers (sizing maps): an
#: interior-point method given only a primal start moves back to the central path and gains little
WARM_OPTIONS: dict[str, Any] = {"ipopt.warm_start_init_point": "yes", "ipopt.mu_init": 1e-6,
                                "ipopt.warm_start_bound_push": 1e-9, "ipopt.warm_start_slack_bound_push": 1e-9,
                                "ipopt.warm_start_mult_bound_push": 1e-9}


@dataclass
class Solution:
    """An IPOPT solution in scaled variables, with its active set."""

    xs: np.ndarray
    f: float
    g: np.ndarray
    lam_g: np.ndarray
    lam_x: np.ndarray
    success: bool
    status: str
    iterations: int
    seconds: float
    active: list[str] = field(default_factory=list)
    active_bounds: list[tuple[int, str]] = field(default_factory=list)
    polished: bool = False
    lexicographic_ok: bool | None = None

    @property
    def feasible(self) -> bool:
        """IPOPT converged and every scaled margin is at least −:data:`FEAS_TOL`: a design."""
        return self.success and bool(np.all(self.g >= -FEAS_TOL))

    @property
    def start(self) -> Start:
        """This optimum and its multipliers, as the warm start of a neighbouring problem."""
        return Start(self.xs.copy(), self.lam_x.copy(), self.lam_g.copy())


@dataclass(frozen=True)
class Start:
    """A warm start: scaled x and the multipliers of the bounds and of the constraints."""

    x: np.ndarray
    lam_x: np.ndarray
    lam_g: np.ndarray


_SOLVERS: dict[tuple[int, bool, bool], tuple[SizingProblem, ca.Function]] = {}


def solver(problem: SizingProblem, warm: bool = False, at_scene: bool = False) -> ca.Function:
    """IPOPT on ``problem``'s NLP (built once per problem; ``warm``: with :data:`WARM_OPTIONS`; a problem's own
    ``ipopt_options``, if it has any, last; ``at_scene``: the NLP with the scene's parameters folded in, for
    ``p = p0`` only, where the problem has it)."""
    key = (id(problem), warm, at_scene)
    hit = _SOLVERS.get(key)
    if hit is None or hit[0] is not problem:
        options = {**IPOPT_OPTIONS, **(WARM_OPTIONS if warm else {}), **getattr(problem, "ipopt_options", {})}
        # asked of the class: hasattr on the instance would run the property and hide an AttributeError it raises
        folds = at_scene and hasattr(type(problem), "at_scene")
        nlp = problem.at_scene if folds else problem.nlp()
        hit = _SOLVERS[key] = (problem, ca.nlpsol("sizing_warm" if warm else "sizing", "ipopt", nlp, options))
    return hit[1]


def solve_continuous(problem: SizingProblem, p=None, x0=None, d_range=None, fix_d: float | None = None,
                     polish: bool = True, start: Start | None = None) -> Solution:
    """Least rope, then least pretension, then least stroke (see the objective in :mod:`optimisation.problem`).

    p: parameter vector (default: the scene's); x0: scaled start (default: the scene's design);
    d_range: (low, high) bounds of d [m]; fix_d: solve for F_nwl and stroke at this d [m];
    polish: identify the active set and refine a vertex by Newton (:func:`_polish`);
    start: a warm start (a neighbour's :attr:`Solution.start`), used instead of ``x0``.
    """
    p = problem.p0 if p is None else np.asarray(p, dtype=float)
    lbx, ubx = problem.bounds(d_range)
    if fix_d is not None:
        lbx[0] = ubx[0] = fix_d / problem.x_scale[0]
    at_scene = bool(np.array_equal(p, problem.p0))
    if start is not None:
        ipopt = solver(problem, warm=True, at_scene=at_scene)
        args = {"x0": start.x, "lam_x0": start.lam_x, "lam_g0": start.lam_g}
    else:
        ipopt = solver(problem, at_scene=at_scene)
        x0 = problem.x0() if x0 is None else np.asarray(x0, dtype=float)
        args = {"x0": np.clip(x0, lbx, np.where(np.isfinite(ubx), ubx, x0))}
    t0 = time.perf_counter()
    res = ipopt(p=p, lbx=lbx, ubx=ubx, lbg=0.0, ubg=np.inf, **args)
    seconds = time.perf_counter() - t0
    stats = ipopt.stats()
    sol = Solution(np.asarray(res["x"]).ravel(), float(res["f"]), np.asarray(res["g"]).ravel(),
                   np.asarray(res["lam_g"]).ravel(), np.asarray(res["lam_x"]).ravel(),
                   bool(stats["success"]), str(stats["return_status"]), int(stats.get("iter_count", -1)), seconds)
    if polish:
        _active_set(problem, sol, lbx, ubx, p)
        if sol.success:
            _polish(problem, sol, p, lbx, ubx)
            sol.lexicographic_ok = lexicographic_ok(problem, sol, p)
    return sol


def _active_set(problem, sol, lbx, ubx, p):
    """Active margins and bounds; x is put exactly on an active bound (IPOPT relaxes bounds by ~1e-8).  Where
    more are active than fix x, or with dependent normals (a check met at its worst in two load cases at once,
    e.g. the drum's force wherever the load is), an independent set is kept (the others are then inactive)."""
    sol.active_bounds = []
    for i in range(3):
        near = ACTIVE_G * max(1.0, abs(sol.xs[i]))
        if lbx[i] == ubx[i] or (abs(sol.xs[i] - lbx[i]) < near and sol.lam_x[i] < -ACTIVE_LAM):
            sol.active_bounds.append((i, "lower"))
            sol.xs[i] = lbx[i]
        elif np.isfinite(ubx[i]) and abs(sol.xs[i] - ubx[i]) < near and sol.lam_x[i] > ACTIVE_LAM:
            sol.active_bounds.append((i, "upper"))
            sol.xs[i] = ubx[i]
    active = [i for i, (g, lam) in enumerate(zip(sol.g, sol.lam_g)) if g < ACTIVE_G and abs(lam) > ACTIVE_LAM]
    if len(active) > 1:
        from optimisation.activeset import regular_subset

        J = jacobian_at(problem, sol.xs, p, active)[1]
        active = list(regular_subset(active, sol.active_bounds, J, sol.lam_g, len(sol.xs))[0])
    sol.active = [problem.constraints[i] for i in active]


#: evaluations of (g, ∂g/∂x) kept per problem (:func:`jacobian_at`)
KEPT = 4


def jacobian_at(problem, xs, p, rows=None) -> tuple[np.ndarray, np.ndarray]:
    """(g, ∂g/∂x) of ``problem`` at scaled ``xs`` and parameters ``p`` (numpy, read-only).  The last
    :data:`KEPT` evaluations are kept: the active set, the polish, the lexicographic test and the warm
    re-solves (:mod:`optimisation.dynamic.warm`) ask the same point in turn, and through the dynamic NLP's
    integrators each evaluation integrates every case with its sensitivities.

    ``rows``: the callers read these rows of ∂g/∂x only; a problem with ``jacobian_rows`` (the dynamic NLP)
    then differentiates only the blocks holding them (its static checks, each case's transient) and leaves the
    other rows NaN, so that a row nobody computed can never pass for a derivative."""
    key = (np.asarray(xs, float).tobytes(), np.asarray(p, float).tobytes())
    kept = problem.__dict__.setdefault("_jac_kept", {})
    hit = kept.get(key)
    if hit is None or np.isnan(hit[1] if rows is None else hit[1][list(rows)]).any():
        if rows is not None and hasattr(problem, "jacobian_rows"):
            g, J = problem.jacobian_rows(xs, p, rows)
            if hit is not None:
                J = np.where(np.isnan(J), hit[1], J)
        else:
            g, J = (np.asarray(a, float) for a in _jac_at(problem, p)[0](xs, p))
        g = g.ravel()
        g.flags.writeable = J.flags.writeable = False
        kept.pop(key, None)
        kept[key] = (g, J)
        while len(kept) > KEPT:
            kept.pop(next(iter(kept)))
    return kept[key]


def _jac_functions(problem):
    """(g, ∂g/∂x) and ∇f_primary of the problem's NLP as Functions of (x, p)."""
    if not hasattr(problem, "_jac_g"):
        problem._jac_g, problem._grad_f0 = _derivatives(problem, problem.g, problem.f_primary)
    return problem._jac_g, problem._grad_f0


def _derivatives(problem, g, f_primary) -> tuple[ca.Function, ca.Function]:
    """(x, p) → (g, ∂g/∂x) and (x, p) → ∇f_primary of the expressions ``g``, ``f_primary``."""
    jac = ca.Function("jac_g", [problem.xs, problem.p], [g, ca.jacobian(g, problem.xs)])
    return jac, ca.Function("grad_f0", [problem.xs, problem.p], [ca.gradient(f_primary, problem.xs)])


def _jac_at(problem, p):
    """:func:`_jac_functions` of the folded NLP at p = p0 (a route's derivatives then carry no segment), else of
    the parametric one."""
    if not (getattr(problem, "STATIC", False) and np.array_equal(np.asarray(p, dtype=float), problem.p0)):
        return _jac_functions(problem)
    if "_jac_folded" not in problem.__dict__:
        nlp = problem.at_scene
        primary = problem.__dict__.get("folded_primary", problem.f_primary)    # not folded: the NLP's own
        problem.__dict__["_jac_folded"] = _derivatives(problem, nlp["g"], primary)
    return problem.__dict__["_jac_folded"]


def _polish(problem, sol, p, lbx, ubx):
    """Newton on the active constraints when they fix x (vertex); keeps IPOPT's x otherwise.  Chord steps: the
    Jacobian at IPOPT's point throughout (it is within IPOPT's tolerance of the vertex, so the steps still
    shrink by orders of magnitude each), the constraints alone evaluated at the others (:func:`_g_at`) — through
    the dynamic NLP's integrators a Jacobian costs about nine evaluations of the constraints."""
    idx = [problem.constraints.index(c) for c in sol.active]
    fixed = [i for i, _ in sol.active_bounds]
    if len(idx) + len(fixed) != 3:
        return
    x, last = sol.xs.copy(), np.inf
    g, J = jacobian_at(problem, x, p, idx)
    A = np.vstack([J[idx, :], np.eye(3)[fixed, :]]) if fixed else J[idx, :]
    if np.linalg.cond(A) > 1e12:
        return
    for _ in range(20):
        r = np.concatenate([g.ravel()[idx], np.zeros(len(fixed))])
        step = np.linalg.solve(A, -r)
        x = x + step
        g = _g_at(problem, x, p)
        size = np.max(np.abs(step))
        # converged, or at the noise floor of g (a step no longer halves: e.g. g through an integrator)
        if size < 1e-15 * max(1.0, np.max(np.abs(x))) or size > 0.5 * last:
            break
        last = size
    if np.all(g > -1e-9) and np.all(x >= lbx - 1e-12) and np.all(x <= ubx + 1e-12):
        sol.xs, sol.g, sol.polished = x, g.copy(), True


def _g_at(problem, x, p) -> np.ndarray:
    """g of ``problem`` at scaled ``x``: alone where its Jacobian costs several evaluations (the dynamic NLP's
    integrators: ``STATIC`` False), else as :func:`jacobian_at` evaluates it (a static problem at p0: its folded
    NLP; a declared machine's problem)."""
    if getattr(problem, "STATIC", True):
        return jacobian_at(problem, x, p)[0]
    return np.asarray(problem.g_function(x, p), float).ravel()


def lexicographic_ok(problem, sol, p) -> bool:
    """True when the design is also a KKT point of the primary objective (rope mass) alone.

    The primary gradient must be a nonnegative combination of the active constraint
    normals (and active bound normals): then no feasible direction lowers the mass,
    so the weighted optimum respects the lexicographic order.
    """
    _, grad_f0 = _jac_at(problem, p)
    idx = [problem.constraints.index(c) for c in sol.active]
    J = jacobian_at(problem, sol.xs, p, idx)[1]
    gf = np.asarray(grad_f0(sol.xs, p)).ravel()
    normals = [J[i, :] for i in idx]
    for i, side in sol.active_bounds:
        e = np.zeros(3)
        e[i] = 1.0 if side == "lower" else -1.0
        normals.append(e)
    if not normals:
        return bool(np.linalg.norm(gf) < 1e-8)
    N = np.array(normals).T
    from scipy.optimize import nnls

    lam, resid = nnls(N, gf)
    return bool(resid <= 1e-6 * max(1.0, float(np.linalg.norm(gf))))


def design_of(problem: SizingProblem, sol: Solution) -> dict[str, float]:
    """The SI design (d, F_nwl, stroke) of a solution."""
    return problem.to_si(sol.xs)


__all__ = ["FEAS_TOL", "IPOPT_OPTIONS", "Solution", "Start", "VARIABLES", "WARM_OPTIONS", "design_of",
           "jacobian_at", "solve_continuous", "solver"]
