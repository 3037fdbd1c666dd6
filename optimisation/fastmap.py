"""Sizing maps by active sets: neighbouring optima share their active checks.

On a map the optimum of one point and that of its neighbour are usually fixed by the same
checks (e.g. rope safety, slip and stroke going up: a vertex design).  :class:`ActiveSetMap`
takes the active set of a solved point and solves a whole batch of the following points
(grid order: last axis fastest) on it at once by Newton (:mod:`optimisation.activeset`);
a point is kept only where it is a KKT point of its own sizing NLP (inactive checks hold,
multipliers of the right sign).  A point that no known active set explains is solved by IPOPT,
warm-started from its nearest solved predecessor, and its active set joins the known ones.

Points with no design are handled the same way, through the *least violation* problem

    min  t + δ·f(x)   s.t.   g_i(x) + t >= 0 (every check),  x within its bounds,  t >= 0

(:class:`LeastViolation`; δ = :data:`DELTA` only pins the variables that no violated check fixes,
such as the stroke).  A point is declared without design when this problem has a KKT point
(solved by IPOPT, or by the batched Newton on a known active set) with t > :data:`CERTIFY`: every
design within reach violates some check by more than that.  The IPOPT sweep
(:func:`optimisation.sweep.sizing_sweep` with ``method="ipopt"``) declares the same points
infeasible after five failed solves; the tests check that both say the same, point by point.
Where the least violation is at most :data:`CERTIFY` the point goes through the full IPOPT path
(warm start, then :func:`optimisation.design.solve_best`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import cached_property

import casadi as ca
import numpy as np

from optimisation.activeset import BatchNLP, Mode, identify, regular_subset
from optimisation.design import solve_best
from optimisation.ipopt import IPOPT_OPTIONS, Start, solve_continuous
from optimisation.problem import SizingProblem

#: weight of the sizing objective in the least-violation problem (scaled objective of order 1..100)
DELTA = 1e-4
#: least maximum violation (scaled margins) above which a point has no design
CERTIFY = 1e-6
#: points solved together on one active set
BATCH = 256
#: known active sets kept (least recently used dropped first)
MAX_MODES = 12


class LeastViolation:
    """min t + δ·f  s.t.  g(x, p) + t >= 0, bounds of x, t >= 0 — in (x, t), scaled like the sizing NLP."""

    def __init__(self, problem: SizingProblem):
        t = ca.MX.sym("t")
        self.z = ca.vertcat(problem.xs, t)
        self.f = t + DELTA * problem.f
        self.g = problem.g + t
        self.p = problem.p
        lbx, ubx = problem.bounds()
        self.lbz, self.ubz = np.append(lbx, 0.0), np.append(ubx, np.inf)

    @cached_property
    def solver(self) -> ca.Function:
        """IPOPT on this problem (built when a point first needs it)."""
        return ca.nlpsol("least_violation", "ipopt", {"x": self.z, "p": self.p, "f": self.f, "g": self.g},
                         IPOPT_OPTIONS)

    def __call__(self, p, x0):
        """(success, z, g, lam_g, lam_x, iterations, seconds) from scaled ``x0``."""
        t0 = time.perf_counter()
        res = self.solver(x0=np.append(x0, 1.0), p=p, lbx=self.lbz, ubx=self.ubz, lbg=0.0, ubg=np.inf)
        seconds = time.perf_counter() - t0
        stats = self.solver.stats()
        out = (np.asarray(res[k]).ravel() for k in ("x", "g", "lam_g", "lam_x"))
        return (bool(stats["success"]), *out, int(stats.get("iter_count", 0)), seconds)


@dataclass
class MapPoints:
    """The map's answers at N points: scaled x (NaN without design), feasible, IPOPT iterations and solver
    seconds per point, and how each was solved: 0 active set, 1 IPOPT, 2 certified without design."""

    x: np.ndarray
    feasible: np.ndarray
    iterations: np.ndarray
    seconds: np.ndarray
    how: np.ndarray
    lam_g: np.ndarray
    lam_x: np.ndarray
    solved: np.ndarray

    @classmethod
    def empty(cls, N: int, n: int, ng: int) -> MapPoints:
        return cls(np.full((N, n), np.nan), np.zeros(N, bool), np.zeros(N, int), np.zeros(N), np.zeros(N, int),
                   np.zeros((N, ng)), np.zeros((N, n)), np.zeros(N, bool))


class ActiveSetMap:
    """The fast path of a sizing sweep; :meth:`run` solves consecutive chunks of points (its state — known
    active sets, the latest design as a warm start — carries from one chunk to the next).

    problem: the sizing NLP; varied: names of the parameters that differ between points.  IPOPT starts
    from the nearest solved predecessor's optimum and multipliers.
    """

    def __init__(self, problem: SizingProblem, varied, batch: int = BATCH):
        self.problem, self.batch = problem, batch
        self.varied = [problem.params.index(k) for k in varied]
        lbx, ubx = problem.bounds()
        self.design = BatchNLP(problem.xs, problem.p, problem.f, problem.g, lbx, ubx, self.varied, problem.p0)
        self.violation = LeastViolation(problem)
        self.modes: list[tuple[str, Mode]] = []
        self.start: Start | None = None
        self.last_infeasible = False
        self._pending = 0.0

    @cached_property
    def least(self) -> BatchNLP:
        """The batched Newton of the least-violation problem (built when a point first has no design)."""
        v = self.violation
        return BatchNLP(v.z, self.problem.p, v.f, v.g, v.lbz, v.ubz, self.varied, self.problem.p0)

    def run(self, PV, done=None) -> MapPoints:
        """Solve the points whose varied parameters are the rows of ``PV`` (SI, in ``varied`` order);
        ``done(n)`` is called after each batch of n points (a progress bar)."""
        PV = np.atleast_2d(np.asarray(PV, dtype=float))
        out = MapPoints.empty(PV.shape[0], 3, self.problem.g.numel())
        for s in range(0, PV.shape[0], self.batch):
            batch = np.arange(s, min(PV.shape[0], s + self.batch))
            todo = self._try(batch, PV, out, list(self.modes))
            while todo.size:
                k, todo = todo[0], todo[1:]
                mode = self._hard(int(k), PV, out)
                if mode is not None and todo.size:
                    todo = self._try(todo, PV, out, [mode])
            if done is not None:
                done(batch.size)
        last = np.flatnonzero(out.feasible)
        if last.size:
            j = last[-1]
            self.start = Start(out.x[j].copy(), out.lam_x[j].copy(), out.lam_g[j].copy())
        self.last_infeasible = bool(out.solved[-1] and not out.feasible[-1]) if out.solved.size else False
        return out

    # ------------------------------------------------------------ batches
    def _try(self, todo, PV, out, modes):
        """Newton on each known active set in turn (most recently useful first); returns the points left."""
        for kind, mode in modes:
            if not todo.size:
                break
            t0 = time.perf_counter()
            res = (self.design if kind == "design" else self.least).solve(mode, PV[todo])
            ok = res.ok if kind == "design" else res.ok & (res.x[:, -1] > CERTIFY)
            self._pending += time.perf_counter() - t0
            if not ok.any():
                continue
            idx = todo[ok]
            if kind == "design":
                out.x[idx], out.feasible[idx] = res.x[ok], True
                out.lam_g[idx], out.lam_x[idx] = res.lam_g[ok], res.lam_x[ok]
            out.solved[idx], out.how[idx] = True, 0 if kind == "design" else 2
            out.seconds[idx] += self._pending / idx.size
            self._pending = 0.0
            mode.x, mode.lam_g, mode.lam_x = res.x[ok][-1], res.lam_g[ok][-1], res.lam_x[ok][-1]
            self._use(kind, mode)
            todo = todo[~ok]
        return todo

    def _use(self, kind, mode):
        """Move ``mode`` to the front of the known active sets (keeping at most :data:`MAX_MODES`)."""
        self.modes = [(kind, mode)] + [(k, m) for k, m in self.modes if m is not mode]
        del self.modes[MAX_MODES:]

    # ------------------------------------------------------------ one point by IPOPT
    def _p(self, PV, k):
        p = self.problem.p0.copy()
        p[self.varied] = PV[k]
        return p

    def _start_for(self, k, out) -> Start | None:
        before = np.flatnonzero(out.feasible[:k])
        if before.size:
            j = before[-1]
            return Start(out.x[j].copy(), out.lam_x[j].copy(), out.lam_g[j].copy())
        return self.start

    def _hard(self, k, PV, out):
        """Point k by IPOPT (and the least-violation problem); returns its active set if it has a usable one."""
        p = self._p(PV, k)
        prev_infeasible = (not out.feasible[k - 1]) if k > 0 else self.last_infeasible
        start = self._start_for(k, out)
        x0 = start.x if start is not None else self.problem.x0()
        if prev_infeasible:
            decided, mode = self._certify(k, p, PV, out, x0)
            if decided:
                return mode
        sol = solve_continuous(self.problem, p, polish=False, start=start)
        self._count(k, out, sol.iterations, sol.seconds)
        if sol.feasible:
            return self._adopt(k, sol, PV, out)
        if not prev_infeasible:
            decided, mode = self._certify(k, p, PV, out, x0)
            if decided:
                return mode
        sol = solve_best(self.problem, p)
        self._count(k, out, sol.iterations, sol.seconds)
        if sol.feasible:
            return self._adopt(k, sol, PV, out)
        out.solved[k], out.how[k] = True, 1
        return None

    def _count(self, k, out, iterations, seconds):
        out.iterations[k] += iterations
        out.seconds[k] += seconds + self._pending
        self._pending = 0.0

    def _adopt(self, k, sol, PV, out):
        """A design found by IPOPT at point k: its active set, checked (and x polished) by Newton at k."""
        lbx, ubx = self.problem.bounds()
        cands = self._modes(self.design, sol.xs, sol.g, sol.lam_g, sol.lam_x, lbx, ubx, PV[[k]])
        mode = self._verified(self.design, cands, PV[[k]], "design")
        out.solved[k], out.feasible[k], out.how[k] = True, True, 1
        if mode is None:
            out.x[k], out.lam_g[k], out.lam_x[k] = sol.xs, sol.lam_g, sol.lam_x
            return None
        out.x[k], out.lam_g[k], out.lam_x[k] = mode.x, mode.lam_g, mode.lam_x
        return ("design", mode)

    def _certify(self, k, p, PV, out, x0):
        """The least-violation problem at point k by IPOPT: (True, its active set or None) when it shows that
        no design exists (t > :data:`CERTIFY`), else (False, None)."""
        ok, z, g, lam_g, lam_x, iters, secs = self.violation(p, x0)
        self._count(k, out, iters, secs)
        if not ok or z[-1] <= CERTIFY:
            return False, None
        out.solved[k], out.feasible[k], out.how[k] = True, False, 2
        v = self.violation
        cands = self._modes(self.least, z, g, lam_g, lam_x, v.lbz, v.ubz, PV[[k]])
        mode = self._verified(self.least, cands, PV[[k]], "violation")
        return True, (("violation", mode) if mode is not None else None)

    @staticmethod
    def _modes(nlp, x, g, lam_g, lam_x, lbx, ubx, pv):
        """Candidate :class:`Mode` s from a converged solve (x put exactly on its active bounds): the strict
        and the loose identification (:func:`optimisation.activeset.identify`), if they differ."""
        out = []
        for loose in (False, True):
            constraints, bounds = identify(g, lam_g, x, lam_x, lbx, ubx, loose=loose)
            z = x.copy()
            for i, side in bounds:
                z[i] = lbx[i] if side == "lower" else ubx[i]
            _, J, _ = nlp.first(z[None, :], pv)
            constraints, bounds = regular_subset(constraints, bounds, J[0], lam_g, nlp.n)
            if all((m.constraints, m.bounds) != (constraints, bounds) for m in out):
                out.append(Mode(constraints, bounds, z, lam_g.copy(), lam_x.copy()))
        return out

    def _verified(self, nlp, candidates, pv, kind):
        """The first candidate on which Newton at the point itself is accepted (with that result), or None."""
        for mode in candidates:
            res = nlp.solve(mode, pv)
            if res.ok[0] and (kind == "design" or res.x[0, -1] > CERTIFY):
                mode.x, mode.lam_g, mode.lam_x = res.x[0], res.lam_g[0], res.lam_x[0]
                self._use(kind, mode)
                return mode
        return None
