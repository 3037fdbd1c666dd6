"""A sweep at the worst over open load cases whose long route's numbers follow the points.

A route of more than 100 segments is held as route numbers per load case (:mod:`ropemodel.papers.route_numbers`),
computed from the segments, μ_pl, L_ul and the case's place and acceleration (which follow the segments' lengths
and the ramps: v_pj, t_ramp, a_e).  Where a sweep at the worst over open cases varies one of those, each point and
case has its own numbers: the scene's Function is evaluated at every (point, case) (the numbers computed in numpy,
one route step per point where a segment varies, else one for the chunk grouped by distinct a_h and μ_pl), and
each output is reduced to its worst over the cases per point as :func:`ropemodel.envelope.worst.symbolic_worst`
does inside the other path's Function (:mod:`ropemodel.sweeps.worst`): the least or largest, of two senses the one
of larger magnitude, the first case of a tie, a NaN first case kept.  A chunk holds at most :data:`ROWS` (point,
case) pairs.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from ropemodel.core.evaluate import Job
from ropemodel.envelope.cases import distinct, joint_ends

#: (point, case) pairs per chunk: a chunk's points are at most this over the cases
ROWS = 65536


@dataclass
class CaseJob:
    """Evaluates a chunk of points at every case and reduces each output to its worst (the interface of a
    :class:`~ropemodel.core.evaluate.Job`: ``varied``, ``constants``, called on the points' SI arrays).

    rows: the scene's Function at one (point, case): the varied inputs, the case inputs, the route numbers.
    model: the scene's model (its route step); values: the SI values the points leave alone; cases, depends:
    the sweep's (:class:`ropemodel.sweeps.worst.Worst`); senses: output -> its worst's senses; watch: a physics
    check's column -> (output, case index)."""

    rows: Job
    model: object
    values: dict
    cases: list
    depends: dict
    senses: dict
    watch: dict
    varied: list
    numbers: list

    @property
    def constants(self) -> dict:
        return self.rows.constants

    def __call__(self, inputs: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        n, m = len(next(iter(inputs.values()))), len(self.cases)
        values = {**self.values, **inputs}
        ends = joint_ends(values) if any(c.joint is not None for c in self.cases) else None
        at = [c.values(values, ends) for c in self.cases]
        case = {k: np.stack([np.broadcast_to(np.asarray(a[k], dtype=float), (n,)) for a in at], axis=1)
                for k in at[0]}
        rows = {k: np.repeat(np.broadcast_to(np.asarray(v, dtype=float), (n,)), m) for k, v in inputs.items()}
        rows.update({k: v.ravel() for k, v in case.items()})
        rows.update(self._numbers(values, inputs, case, n, m))
        got = {k: v.reshape(n, m) for k, v in self.rows({k: rows[k] for k in self.rows.varied}).items()}
        out = {}
        for o, senses in self.senses.items():
            deps = self.depends.get(o, ())
            idx = distinct(self.cases, deps)
            if not deps:
                out[o] = got[o][:, idx[0]]
                continue
            out[o], k = worst(got[o][:, idx], senses)
            for inp in deps:
                out[f"{o}@{inp}"] = case[inp][:, idx][np.arange(n), k]
        out.update({name: got[o][:, k] for name, (o, k) in self.watch.items()})
        return out

    def _numbers(self, values: dict, inputs: dict, case: dict, n: int, m: int) -> dict:
        """The route numbers the rows Function takes at every (point, case), point-major."""
        if any(k in self.model.edge_set for k in inputs):     # type: ignore[attr-defined]  # a segment varies
            per = [self.model.derive({**values, **{k: float(v[i]) for k, v in inputs.items()},  # type: ignore[attr-defined]
                                      **{k: v[i] for k, v in case.items()}}) for i in range(n)]
            return {k: np.concatenate([np.broadcast_to(np.asarray(p[k], dtype=float), (m,)) for p in per])
                    for k in self.numbers}
        flat = {**values, **{k: np.repeat(np.broadcast_to(np.asarray(v, dtype=float), (n,)), m)
                             for k, v in inputs.items()}, **{k: v.ravel() for k, v in case.items()}}
        got = self.model.derive(flat)                           # type: ignore[attr-defined]
        return {k: np.broadcast_to(np.asarray(got[k], dtype=float), (n * m,)) for k in self.numbers}


def worst(y: np.ndarray, senses) -> tuple[np.ndarray, np.ndarray]:
    """(worst, index) per row of ``y`` (points x cases), as :func:`ropemodel.envelope.worst.symbolic_worst`."""
    best = {}
    rows = np.arange(len(y))
    for sense in senses:
        fill, arg = (np.inf, np.argmin) if sense == "least" else (-np.inf, np.argmax)
        k = np.where(np.isnan(y[:, 0]), 0, arg(np.where(np.isnan(y), fill, y), axis=1))
        best[sense] = (y[rows, k], k)
    if len(best) == 1:
        return next(iter(best.values()))
    (lo, i_lo), (hi, i_hi) = best["least"], best["largest"]
    pick = np.abs(hi) >= np.abs(lo)
    return np.where(pick, hi, lo), np.where(pick, i_hi, i_lo)


class _At:
    """A case's outputs as (output, case index) markers, for :func:`ropemodel.sweeps.worst.watches`."""

    def __init__(self, k: int):
        self.k = k

    def __getitem__(self, name: str) -> tuple[str, int]:
        return name, self.k


def case_job(problem, worst_, varied, base: dict, outputs, physics, backend: str, threads: int):
    """(:class:`CaseJob`, names of its extra columns, the physics checks' watch) of a sweep at the worst over
    ``worst_``'s cases whose route numbers follow the points ``varied``."""
    from ropemodel.sweeps.worst import watches

    model, scene, fun = problem.model, problem.scene, problem.function
    keys = [k for k in worst_.cases[0].values(scene.parameters, worst_.ends) if k not in varied]
    numbers = [k for k in problem.knowns if k in model.derived]
    row_in = [*varied, *keys, *numbers]
    syms = {k: ca.MX.sym(k) for k in dict.fromkeys([*problem.knowns, *varied])}
    res = fun.call({**{k: syms[k] for k in problem.knowns}, **scene.rule_values(syms, varied)})
    names: list = []
    marks: list = []
    watch = watches([(c.name(), _At(k)) for k, c in enumerate(worst_.cases)], physics, problem, outputs, False,
                    names, marks)
    needed = list(dict.fromkeys([*outputs, *(o for o, _ in marks)]))
    order = row_in + [k for k in problem.knowns if k not in row_in]
    sel = ca.Function("sweep_case", [syms[k] for k in order], [res[o] for o in needed], order, needed)
    if fun.is_a("SXFunction"):
        sel = sel.expand()
    constants = {k: float(base[k]) for k in order[len(row_in):]}
    values = {**scene.parameters, **{k: v for k, v in base.items() if k not in model.derived}}
    senses = {o: model.quantities[o].worst for o in outputs}
    job = CaseJob(Job(sel, row_in, constants, backend, threads), model, values, worst_.cases, worst_.depends,
                  senses, dict(zip(names, marks)), list(varied), numbers)
    return job, watch
