"""One chunk of a sweep: evaluate, check every point, build the table of results.

A :class:`ChunkJob` is everything a worker needs to turn a chunk of input points into
a table: the evaluation :class:`~ropemodel.core.evaluate.Job` (the Function restricted
to the swept outputs; it pickles, so a job can travel to a dask worker), the column
labels and unit factors, and the checks every solution must pass.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pyarrow as pa

from ropemodel.core.evaluate import Job
from ropemodel.errors import SolveError


@dataclass
class ChunkJob:
    """How to evaluate and check chunks of one sweep.

    job: the evaluation of the swept outputs (varied inputs first, then the constants).
    outputs: names of the outputs written.
    columns: (label, name, factor) of every column written: the varied inputs, then the outputs.
    checks: output name → (low, high, low_open, high_open, description) ranges a solution must meet.
    roundtrip: extra output → given output it must reproduce (the forward model at the solution).
    errors: ``"raise"`` (SolveError naming the first bad point) or ``"mark"``: NaN outputs at such a
        point, ``solved`` False and the reason in ``invalid``.
    physics: submodels whose :meth:`~ropemodel.effects.base.Submodel.invalid_mask` says where the
        model no longer holds (a slack rope); watch: per load case (its name, "" at a single point), the
        names they read → the output holding each (:mod:`ropemodel.sweeps.worst`).
    """

    job: Job
    outputs: list[str]
    columns: list[tuple[str, str, float]]
    checks: dict[str, tuple] = field(default_factory=dict)
    errors: str = "raise"
    roundtrip: dict[str, str] = field(default_factory=dict)
    physics: list = field(default_factory=list)
    watch: list[tuple[str, dict[str, str]]] = field(default_factory=list)
    #: inputs computed from the varied ones at each point (a long route's numbers, :class:`RouteStep`), or None
    derive: object = None


@dataclass
class RouteStep:
    """A long route's numbers at each point of a chunk (:meth:`ropemodel.core.model.Model.derive`): ``model`` the
    scene's, ``values`` the SI values the points leave alone (the scene's parameters and the sweep's base),
    ``names`` the numbers the swept Function takes."""

    model: object
    values: dict
    names: list[str]

    def __call__(self, inputs: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        n = len(next(iter(inputs.values())))
        merged = {**self.values, **inputs}
        varied = [k for k in inputs if k in self.model.edge_set]        # type: ignore[attr-defined]
        if varied:          # a segment that varies: the route's arrays point by point
            rows = [self.model.derive({**merged, **{k: float(inputs[k][i]) for k in inputs}})  # type: ignore[attr-defined]
                    for i in range(n)]
            return {k: np.array([r[k] for r in rows]) for k in self.names}
        got = self.model.derive(merged)                                   # type: ignore[attr-defined]
        return {k: np.broadcast_to(np.asarray(got[k], dtype=float), (n,)) for k in self.names}


def run_chunk(job: ChunkJob, start: int, inputs: dict[str, np.ndarray]) -> pa.Table:
    """Evaluate the points ``inputs`` (SI arrays of the varied inputs; first point has index ``start``)."""
    n = len(next(iter(inputs.values())))
    if job.derive is not None:
        inputs = {**inputs, **job.derive(inputs)}       # type: ignore[operator]
    outs = job.job(inputs)
    ok = np.ones(n, dtype=bool)
    for y in outs.values():
        ok &= np.isfinite(y)
    failures = {}
    if not ok.all():
        failures["no finite solution (an implicit block did not converge or a division by zero)"] = ~ok
    for extra, given in job.roundtrip.items():
        want = np.broadcast_to(inputs[given] if given in inputs else job.job.constants[given], (n,))
        with np.errstate(invalid="ignore"):
            bad = ok & ~(np.abs(outs[extra] - want) <= 1e-6 * np.maximum(1.0, np.abs(want)))
        if bad.any():
            failures[f"the solution does not reproduce the given {given} (no such solution, or the "
                     f"Newton iteration did not converge)"] = bad
            ok &= ~bad
    for name, (lo, hi, lo_open, hi_open, desc) in job.checks.items():
        y = outs[name]
        with np.errstate(invalid="ignore"):
            bad = ok & ((y < lo) | (y > hi) | (lo_open & (y == lo)) | (hi_open & (y == hi)))
        if bad.any():
            failures[f"{name} found outside its valid range ({desc})"] = bad
            ok &= ~bad
    if job.physics:
        failures.update(_outside_physics(job, inputs, outs, ok))
    if failures and job.errors == "raise":
        why, mask = next(iter(failures.items()))
        i = int(np.flatnonzero(mask)[0])
        at = ", ".join(f"{k} = {inputs[k][i]:.6g}" for k in job.job.varied if k not in getattr(job.derive, "names", ()))
        raise SolveError(f"point {start + i} ({at}, SI): {why}; {int((~ok).sum())} of the {n} points "
                         f"from {start} fail (errors='mark' keeps them with solved = False)")
    data = {}
    for label, name, f in job.columns:
        if name in inputs:
            data[label] = inputs[name] * f if f != 1.0 else np.ascontiguousarray(inputs[name], dtype=float)
        else:  # never a wrong number: an output of a point without a valid solution is NaN
            data[label] = np.where(ok, outs[name] * f, np.nan)
    if job.errors == "mark":
        reason = np.full(n, None, dtype=object)
        for why, mask in reversed(failures.items()):
            reason[mask] = why
        data["solved"] = ok
        data["invalid"] = pa.array(reason, type=pa.string())  # null where solved
    return pa.table(data)


def _outside_physics(job: ChunkJob, inputs: dict, outs: dict, ok: np.ndarray) -> dict:
    """Reason → mask of the solved points where the model no longer holds (``ok`` is updated)."""
    n = len(ok)
    found = {}
    for case, watch in job.watch:
        values = {}
        for name, key in watch.items():
            v = inputs.get(key, outs.get(key, job.job.constants.get(key)))
            values[name] = np.broadcast_to(np.asarray(v, dtype=float), (n,))
        for sm in job.physics:
            for why, mask in sm.invalid_mask(values).items():
                bad = ok & np.asarray(mask, dtype=bool)
                if bad.any():
                    found[f"outside the model{' with the load at ' + case if case else ''}: {why}"] = bad
                    ok &= ~bad
    return found
