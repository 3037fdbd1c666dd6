"""``sweep``: evaluate a scene over a grid or a table of points, in chunks.

Columns and units
-----------------
The result is tidy: one row per point, one column per varied input, then one
per output, each labelled with its unit — ``alpha_u [deg]``, ``F_C_up [kN]``.
Values are in each quantity's *display unit* (the unit the source paper
uses, the same as ``Result.to_series()`` and ``ropemodel run``), so a sweep
reads like the paper's tables; ``si=True`` gives SI units instead
(``alpha_u [rad]``, ``F_C_up [N]``).  Dimensionless columns are ``[-]``.  Such
a frame (or a CSV/Parquet file of it) can be fed back as points: columns are
read through their unit labels.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections import deque

import casadi as ca
import pandas as pd
import pyarrow as pa
from tqdm.auto import tqdm

from ropemodel.errors import InputError
from ropemodel.problem import Problem
from ropemodel.core.evaluate import COMPILE_MIN, Job
from ropemodel.sweep.chunk import ChunkJob, run_chunk
from ropemodel.sweep.points import grid, table
from ropemodel.sweep.store import ChunkStore
from ropemodel.sweep.validate import check_ranges, check_rules
from ropemodel.units import label

CHUNK = 65536  # points per chunk: ~20 MB of results for 40 columns
ERRORS = ("raise", "mark")


def sweep(scene, vary=None, outputs=None, *, points=None, given=(), find=(), out=None,
          chunk_size: int = CHUNK, executor=None, threads: int | None = None, backend: str = "auto",
          si: bool = False, errors: str = "raise", progress: bool | None = None, restart: bool = False,
          collect: bool = True):
    """Evaluate ``scene`` at many points; a tidy DataFrame (see the module doc for columns and units).

    Parameters
    ----------
    scene: a :class:`~ropemodel.scene.Scene`; inputs not varied keep its values.
    vary: ``{name: axis}`` — a grid, the product of the axes (``"0deg:45deg:1000"``,
        ``(0, 0.7, 100)``, a list of values; numbers are SI) — or a DataFrame of points.
    outputs: names of the outputs to compute (default: every unknown of the problem).
    points: a DataFrame of points (alternative to ``vary``); columns are names (SI) or ``"name [unit]"``.
    given, find: an inverse problem, as in :class:`~ropemodel.problem.Problem`: ``given`` outputs
        (varied, or values in a dict ``{name: value}``; None: varied) replace the ``find`` parameters.
    out: ``.csv`` or ``.parquet`` path: results are written chunk by chunk and an interrupted
        sweep rerun with the same arguments resumes where it stopped (see :mod:`ropemodel.sweep.store`).
    chunk_size: points per chunk (bounded memory: one chunk per worker in flight).
    executor: a ``concurrent.futures.Executor`` or a ``dask.distributed.Client``: chunks are
        submitted to it (the compiled Function travels pickled; each worker compiles it once).
    threads: threads per chunk evaluation (default: the number of CPUs; 1 with an executor).
    backend: ``"auto"``, ``"casadi"`` (Function.map) or ``"compiled"`` (C code through ctypes).
    si: SI units in the columns instead of display units.
    errors: ``"raise"`` — a point without a valid solution raises SolveError naming it;
        ``"mark"`` — keep it (NaN outputs) with ``solved`` False.
    progress: show a progress bar (default: on a terminal, when there is more than one chunk).
    restart: discard an unfinished sweep of ``out`` instead of resuming it.
    collect: return the DataFrame (False: return the path of ``out``; memory stays bounded).
    """
    if errors not in ERRORS:
        raise InputError(f"errors={errors!r}: valid: {', '.join(ERRORS)}")
    if chunk_size < 1:
        raise InputError(f"chunk_size = {chunk_size}: must be at least 1")
    if not collect and out is None:
        raise InputError("collect=False needs an output file (out=...)")
    given_values = {k: v for k, v in given.items() if v is not None} if isinstance(given, dict) else {}
    problem = Problem(scene, list(given), find)
    model = problem.model
    inputs = {k: model.quantities[k] for k in problem.knowns}
    if isinstance(vary, pd.DataFrame):
        points, vary = vary, None
    if (vary is None) == (points is None):
        raise InputError("give either vary={name: axis} (a grid) or a table of points")
    pts = grid(vary, inputs) if vary is not None else table(points, inputs, ignore=model.outputs)
    if pts.n == 0:
        raise InputError("no points to sweep")
    outputs = _outputs(problem, outputs, pts.names)
    base = problem.inputs({**given_values, **{n: float(pts.values_of(n)[0]) for n in pts.names}})
    check_ranges(pts, inputs)
    check_rules(model, pts, base)
    if backend == "auto" and pts.n < COMPILE_MIN:
        backend = "casadi"  # a C compile costs more than it saves on small sweeps
    job = _job(problem, pts.names, base, outputs, si, errors, backend,
               threads or (1 if executor is not None else (os.cpu_count() or 1)))
    n_chunks = -(-pts.n // chunk_size)
    bounds = [(k * chunk_size, min(pts.n, (k + 1) * chunk_size)) for k in range(n_chunks)]
    store = None
    if out is not None:
        store = ChunkStore(out, _signature(scene, problem, pts, base, outputs, chunk_size, si, errors), restart)
    todo = [k for k in range(n_chunks) if store is None or k not in store.done]
    tables: dict[int, pa.Table] = {}
    bar = tqdm(total=pts.n, initial=sum(bounds[k][1] - bounds[k][0] for k in range(n_chunks) if k not in todo),
               unit="pt", unit_scale=True, desc="sweep",
               disable=(not progress) if progress is not None else (n_chunks < 2 or None))
    try:
        for k, t in _results(job, pts, bounds, todo, executor):
            if store is not None:
                store.write(k, t)
            if collect:
                tables[k] = t
            bar.update(t.num_rows)
    finally:
        bar.close()
    if store is not None:
        if collect:
            for k in range(n_chunks):
                if k not in tables:
                    tables[k] = store.read(k)
        store.finish(n_chunks)
    if not collect:
        return out
    return pa.concat_tables([tables[k] for k in range(n_chunks)]).to_pandas()


def _outputs(problem, outputs, varied):
    if outputs is None:
        return list(problem.unknowns)
    outputs = [outputs] if isinstance(outputs, str) else list(outputs)
    problem.model.check_names(outputs, "output")
    for o in outputs:
        if o not in problem.unknowns:
            raise InputError(f"output {o!r} is an input of this problem, not a result; results: "
                             f"{', '.join(problem.unknowns)}")
    if not outputs:
        raise InputError("no outputs to compute")
    return list(dict.fromkeys(outputs))


def _job(problem, varied, base, outputs, si, errors, backend, threads) -> ChunkJob:
    """The problem's Function restricted to ``outputs``, inputs ordered varied first.

    For an inverse problem the forward model is also evaluated at each solution, so that a
    Newton iteration that stopped without converging (no such parameter value) is caught
    per point: the given outputs must be reproduced (relative 1e-6, as ``Problem.solve``).
    """
    fun = problem.function
    order = list(varied) + [k for k in problem.knowns if k not in varied]
    syms = {k: ca.MX.sym(k) for k in problem.knowns}
    res = fun.call(syms)
    outs = [res[o] for o in outputs]
    names = list(outputs)
    roundtrip = {}
    if problem.given:
        forward = Problem(problem.scene).function
        params = {k: syms[k] if k in syms else res[k] for k in problem.model.parameters}
        back = forward.call(params)
        for g in problem.given:
            roundtrip[f"roundtrip_{g}"] = g
            names.append(f"roundtrip_{g}")
            outs.append(back[g])
    sel = ca.Function("sweep_point", [syms[k] for k in order], outs, order, names)
    if fun.is_a("SXFunction"):
        sel = sel.expand()
    q = problem.model.quantities
    columns = []
    for name in list(varied) + outputs:
        unit = q[name].unit if si else q[name].display_unit
        columns.append((label(name, unit), name, 1.0 if si else float(q[name].to_display(1.0))))
    checks = {n: (q[n].low, q[n].high, q[n].low_open, q[n].high_open,
                  f"{q[n].range_text()}, {q[n].description}") for n in problem.find if n in outputs}
    constants = {k: float(base[k]) for k in order[len(varied):]}
    return ChunkJob(Job(sel, list(varied), constants, backend, threads), outputs, columns, checks, errors, roundtrip)


def _signature(scene, problem, pts, base, outputs, chunk_size, si, errors) -> dict:
    sig = {
        "model": scene.model,
        "effects": dict(sorted(scene.effects.items())),
        "numerics": repr(sorted(scene.numerics.items())),
        "parameters": hashlib.sha256(json.dumps(sorted(scene.parameters.items())).encode()).hexdigest(),
        "given": {k: base.get(k) for k in problem.given if k not in pts.names},
        "find": list(problem.find),
        "points": pts.fingerprint(),
        "n_points": pts.n,
        "outputs": list(outputs),
        "chunk_size": chunk_size,
        "si": si,
        "errors": errors,
    }
    return json.loads(json.dumps(sig))


def _results(job, pts, bounds, todo, executor):
    """(chunk index, table) in chunk order; with an executor, a bounded window of chunks in flight."""
    if executor is None:
        for k in todo:
            start, stop = bounds[k]
            yield k, run_chunk(job, start, pts.chunk(start, stop))
        return
    window = max(2, 2 * _workers(executor))
    pending: deque = deque()
    it = iter(todo)
    for k in it:
        start, stop = bounds[k]
        pending.append((k, executor.submit(run_chunk, job, start, pts.chunk(start, stop))))
        if len(pending) >= window:
            break
    while pending:
        k, fut = pending.popleft()
        result = fut.result()
        nxt = next(it, None)
        if nxt is not None:
            start, stop = bounds[nxt]
            pending.append((nxt, executor.submit(run_chunk, job, start, pts.chunk(start, stop))))
        yield k, result


def _workers(executor) -> int:
    """Best guess of the executor's parallelism (only sizes the window of chunks in flight)."""
    n = getattr(executor, "_max_workers", None)
    if n:
        return int(n)
    info = getattr(executor, "nthreads", None)  # dask.distributed.Client
    if callable(info):
        try:
            return max(1, sum(info().values()))
        except Exception:  # a client that cannot answer: assume a small cluster
            return 4
    return 4
