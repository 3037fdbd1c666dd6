"""Catalogue diameters: the continuous optimum rounded to a stocked size, two ways.

``next_size_up``  the smallest catalogue diameter >= d* (continuous optimum) at which F_nwl
                  and stroke, re-optimised by IPOPT with d fixed, satisfy every check; larger
                  sizes are tried in turn if one is infeasible (e.g. a slip check that tightens
                  with d), up to the catalogue's largest.
``bonmin``        one mixed-integer NLP (B-BB of bonmin through ``ca.nlpsol``): binaries b_k,
                  Σ b_k = 1, select d = Σ b_k d_k (normalised by Σ b_k), with F_nwl and
                  stroke continuous and the same objective and constraints.

Both give the lexicographic optimum over the catalogue when the feasible diameters form
an interval [d_lo, D/D_ratio_min]; the study ``studies/discrete_design.py`` compares them
on random scenes (agreement, time) and the default is chosen on that evidence.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import signal
import sys
import threading
import time
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from optimisation.ipopt import Solution, solve_continuous
from optimisation.problem import SizingProblem
from ropemodel.papers import en12385 as ropes


@contextlib.contextmanager
def _quiet():
    """Silence bonmin's node log, which it writes to the C-level stdout whatever its log options say."""
    sys.stdout.flush()
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(devnull)
        os.close(saved)


@contextlib.contextmanager
def _keep_sigint():
    """bonmin's CBC installs a C-level SIGINT handler of its own and leaves it in place, after which
    Ctrl-C no longer reaches Python: put Python's handler back afterwards (main thread only)."""
    handler = signal.getsignal(signal.SIGINT)
    try:
        yield
    finally:
        if handler is not None and threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, handler)


@dataclass
class DiscreteDesign:
    """A catalogue design: scaled x, the solution at that diameter, which method, how long."""

    solution: Solution | None
    method: str
    seconds: float
    tried: list[float]

    @property
    def found(self) -> bool:
        return self.solution is not None


def next_size_up(problem: SizingProblem, d_star: float, p=None, catalogue=None) -> DiscreteDesign:
    """Smallest catalogue size >= d* (minus 1e-9 m) with a feasible F_nwl, stroke (re-optimised)."""
    catalogue = ropes.diameters() if catalogue is None else sorted(catalogue)
    t0 = time.perf_counter()
    tried = []
    for dk in catalogue:
        if dk < d_star - 1e-9:
            continue
        tried.append(dk)
        x0 = problem.x0()
        x0[0] = dk / problem.x_scale[0]
        sol = solve_continuous(problem, p=p, x0=x0, fix_d=dk)
        if sol.feasible:
            return DiscreteDesign(sol, "next-size-up", time.perf_counter() - t0, tried)
    return DiscreteDesign(None, "next-size-up", time.perf_counter() - t0, tried)


def bonmin(problem: SizingProblem, p=None, catalogue=None, x0=None) -> DiscreteDesign:
    """Mixed-integer solve with bonmin over every catalogue size.

    One binary b_k per catalogue size, Σ b_k = 1, and d = Σ b_k d_k / Σ b_k: the
    normalisation keeps d a convex combination of catalogue sizes in every relaxed
    node, also at IPOPT iterates where Σ b_k ≠ 1 yet (d → 0 would make the drum
    margin D/(30 d) infinite).  At integer points it is exactly the chosen size.
    (An ordered incremental formulation was tried first: its relaxation has many
    tied fractional vertices and bonmin branched through thousands of nodes.)
    """
    catalogue = np.array(ropes.diameters() if catalogue is None else sorted(catalogue))
    p = problem.p0 if p is None else np.asarray(p, dtype=float)
    nk = len(catalogue)
    b = ca.MX.sym("b", nk)
    y = ca.MX.sym("y", 2)           # scaled F_nwl, stroke
    eps = 1e-12     # keeps d defined where a node's start point has every free b_k = 0
    d_s = (ca.dot(b, ca.DM(catalogue / problem.x_scale[0])) + eps * catalogue[0] / problem.x_scale[0]) \
        / (ca.sum1(b) + eps)
    xs = ca.vertcat(d_s, y)
    sub = ca.Function("sub", [problem.xs, problem.p], [problem.f, problem.g])
    f, g = sub(xs, problem.p)
    z = ca.vertcat(b, y)
    nlp = {"x": z, "p": problem.p, "f": f, "g": ca.vertcat(g, ca.sum1(b))}
    opts: dict[str, Any] = {
        "discrete": [True] * nk + [False, False], "print_time": False, "show_eval_warnings": False,
        "calc_lam_p": False, "bonmin.print_level": 0, "bonmin.bb_log_level": 0, "bonmin.nlp_log_level": 0,
        "bonmin.algorithm": "B-BB", "bonmin.integer_tolerance": 1e-9, "bonmin.time_limit": 120.0,
        "bonmin.node_limit": 2000, "bonmin.num_resolve_at_infeasibles": 0, "bonmin.num_resolve_at_node": 0,
        "bonmin.num_resolve_at_root": 0, "bonmin.num_retry_unsolved_random_point": 0}
    solver = ca.nlpsol("sizing_minlp", "bonmin", nlp, opts)
    ng = problem.g.numel()
    x_start = problem.x0() if x0 is None else np.asarray(x0)
    k0 = min(int(np.searchsorted(catalogue, x_start[0] * problem.x_scale[0] - 1e-12)), nk - 1)
    z0 = np.concatenate([np.eye(nk)[k0], np.maximum(x_start[1:], 0.0)])
    lbz = np.concatenate([np.zeros(nk), [0.0, 0.0]])
    ubz = np.concatenate([np.ones(nk), [np.inf, np.inf]])
    lbg = np.concatenate([np.zeros(ng), [1.0]])
    ubg = np.concatenate([np.full(ng, np.inf), [1.0]])
    t0 = time.perf_counter()
    try:
        with _quiet(), _keep_sigint():
            res = solver(x0=z0, p=p, lbx=lbz, ubx=ubz, lbg=lbg, ubg=ubg)
        ok = bool(solver.stats()["success"])
    except RuntimeError:     # bonmin raises on some infeasible trees instead of returning a status
        res, ok = None, False
    seconds = time.perf_counter() - t0
    if not ok or res is None:
        return DiscreteDesign(None, "bonmin", seconds, [])
    zopt = np.asarray(res["x"]).ravel()
    dk = float(catalogue[int(np.argmax(zopt[:nk]))])
    # the same lexicographic answer at that size, with multipliers and active set (for the report)
    x0 = np.concatenate([[dk / problem.x_scale[0]], zopt[nk:]])
    sol = solve_continuous(problem, p=p, x0=x0, fix_d=dk)
    if not sol.feasible:
        return DiscreteDesign(None, "bonmin", seconds, [dk])
    return DiscreteDesign(sol, "bonmin", seconds, [dk])


def bonmin_with_timeout(problem: SizingProblem, timeout: float, p=None, x0=None) -> DiscreteDesign:
    """:func:`bonmin` in a forked process with a wall-clock limit [s].

    On some scenes bonmin branches (or stalls inside a node NLP) far beyond its own
    ``time_limit`` option (studies/discrete_design.py: 3 of 30 random scenes over 20 s).
    On time-out the result is "not found" with ``timed_out`` in the method name.
    POSIX only (fork); elsewhere it runs in-process without a limit.
    """
    if "fork" not in mp.get_all_start_methods():
        return bonmin(problem, p=p, x0=x0)
    ctx = mp.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)

    def work():
        r = bonmin(problem, p=p, x0=x0)
        child.send((r.tried[0] if r.found else None, r.seconds))

    proc = ctx.Process(target=work)
    t0 = time.perf_counter()
    # Ctrl-C is the parent's to answer: the child starts with SIGINT blocked (bonmin's CBC would
    # otherwise catch it, stop its search early and report what it had), and ends with the parent
    blocked = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        proc.start()
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, blocked)
    try:
        proc.join(timeout)
    finally:
        timed_out = proc.is_alive()
        if timed_out:   # or interrupted: never leave the child running
            proc.terminate()
            proc.join()
    if timed_out:
        return DiscreteDesign(None, "bonmin (timed out)", time.perf_counter() - t0, [])
    if not parent.poll():
        return DiscreteDesign(None, "bonmin", time.perf_counter() - t0, [])
    dk, seconds = parent.recv()
    if dk is None:
        return DiscreteDesign(None, "bonmin", seconds, [])
    start = problem.x0() if x0 is None else np.array(x0, dtype=float)
    start[0] = dk / problem.x_scale[0]
    sol = solve_continuous(problem, p=p, x0=start, fix_d=dk)
    return DiscreteDesign(sol if sol.feasible else None, "bonmin", seconds, [dk])
