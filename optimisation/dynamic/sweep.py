"""Sweeps of the dynamic optimum: the least d, F_nwl and stroke through the four manoeuvres at every point of
a grid or table (``ropemodel sweep SCENE --sizing --dynamic``), as :func:`optimisation.sweep.sizing_sweep`
does for the static optimum — in chunks, on an executor (a ``dask.distributed.Client`` or a
``concurrent.futures`` pool) and resumable on disk, as the static sweeps of :mod:`ropemodel.sweeps`.

Each chunk of points (:data:`CHUNK` by default) is one job (:func:`run_dynamic_chunk`: the scene and the
points travel, pickled): it builds the dynamic NLP (:class:`~optimisation.dynamic.problem.DynamicSizingProblem`:
the points' values are its parameters), finds its first optimum as :func:`~optimisation.dynamic.design.size_dynamic`
finds it, and starts every further point from its predecessor's optimum (points are taken in order, so each
point's predecessor is its neighbour) on the predecessor's refined grid and cases, refined again and with more
cases where the point needs them.  Every point's design is simulated in every case by the hybrid simulator;
one the simulator does not confirm is an error (:class:`~ropemodel.errors.SolveError`), never a row.
Parameters that fix the transient's structure (the route's geometry, where the load is, t_end) cannot be
varied.

With ``out``, each finished chunk is committed to the output's parts directory and a rerun of the same sweep
(same scene, points, chunk size, version) computes only the chunks missing, then writes the output
(:class:`~ropemodel.sweeps.store.ChunkStore`); a finished output is found complete and not recomputed.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
import pyarrow as pa

from optimisation.design import solve_best
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.refine import solve_refined
from optimisation.dynamic.sensitivity import symbolic_params
from optimisation.dynamic.start import factored_start
from optimisation.dynamic.verify import verify
from optimisation.problem import SizingProblem
from optimisation.sweep import sizing_frame, sizing_points
from ropemodel import __version__
from ropemodel.errors import InputError, SolveError
from ropemodel.numerics.held import held_solver_output
from ropemodel.progress import bar, enabled
from ropemodel.sweeps.files import OutputLock, check_output
from ropemodel.sweeps.runner import SweepInterrupted
from ropemodel.sweeps.schedule import results
from ropemodel.sweeps.store import ChunkStore, complete_rows, discard_parts, read_output

#: points per chunk (one job on an executor; each chunk builds its NLP, some seconds, then warm-starts along it)
CHUNK = 8


@dataclass(frozen=True)
class DynamicChunk:
    """One dynamic sizing sweep's job: the transient scene (without its built model) and the varied names
    (pickles)."""

    scene: object
    names: tuple


def dynamic_sizing_sweep(scene, vary=None, *, points=None, progress: bool | None = None, out=None,
                         chunk_size: int = CHUNK, executor=None, restart: bool = False) -> pd.DataFrame:
    """Continuous dynamic optimum at every point; the columns of :func:`optimisation.sweep.sizing_sweep`
    (the varied inputs, ``d [mm]``, ``F_nwl [kN]``, ``stroke [mm]``, ``feasible``, ``iterations``,
    ``seconds``).  ``out``: a ``.csv`` or ``.parquet`` file written chunk by chunk, resumable (see the module);
    ``chunk_size``: points per job; ``executor``: a ``dask.distributed.Client`` or ``concurrent.futures``
    executor the chunks are submitted to; ``restart``: discard an unfinished sweep of ``out``."""
    problem = DynamicSizingProblem(scene)
    pts = sizing_points(problem.scene, problem, vary, points)
    allowed = set(symbolic_params(problem))
    fixed = [k for k in pts.names if k not in allowed]
    if fixed:
        raise InputError(f"cannot vary {', '.join(fixed)} in a dynamic sizing sweep: it fixes the transient's "
                         f"structure (its grid, where the load is); valid: {', '.join(sorted(allowed))}")
    if not 1 <= int(chunk_size) <= 10**6:
        raise InputError(f"chunk size {chunk_size}: points per chunk must be 1 to 1000000")
    bounds = [(s, min(s + int(chunk_size), pts.n)) for s in range(0, pts.n, int(chunk_size))]
    # a fresh copy of the scene, without its built model (CasADi expressions do not pickle): a worker builds it
    job = DynamicChunk(replace(problem.scene), tuple(pts.names))
    out = check_output(out) if out is not None else None
    with OutputLock(out) if out is not None else contextlib.nullcontext():
        signature = _signature(problem.scene, pts, chunk_size)
        if out is not None and not restart and complete_rows(out, signature) is not None:
            discard_parts(out, signature)
            return read_output(out, _types(out)).to_pandas()
        store = ChunkStore(out, signature, bounds, restart) if out is not None else None
        tables = _run(job, pts, bounds, store, executor, enabled(progress))
        if store is not None:
            tables.update({k: store.read(k) for k in range(len(bounds)) if k not in tables})
            store.finish()
    return pa.concat_tables([tables[k] for k in range(len(bounds))]).to_pandas()


def _types(out) -> dict:
    """Arrow types of the columns of the finished output ``out`` (a CSV does not keep them)."""
    if out.suffix.lower() != ".csv":
        return {}
    columns = pd.read_csv(out, nrows=0).columns
    return {c: pa.bool_() if c == "feasible" else pa.int64() if c == "iterations" else pa.float64() for c in columns}


def _signature(scene, pts, chunk_size) -> dict:
    sig = {"sweep": "sizing --dynamic", "model": scene.model, "effects": dict(sorted(scene.effects.items())),
           "numerics": repr(sorted(scene.numerics.items())),
           "parameters": hashlib.sha256(json.dumps(sorted(scene.parameters.items())).encode()).hexdigest(),
           "points": pts.fingerprint(), "n_points": pts.n, "chunk_size": int(chunk_size), "version": __version__}
    return json.loads(json.dumps(sig))


def _run(job, pts, bounds, store, executor, show: bool) -> dict:
    """The chunks not yet on disk: {chunk: table}, each committed to ``store`` as it arrives."""
    todo = [k for k in range(len(bounds)) if store is None or k not in store.done]
    done = 0 if store is None else store.done_points
    shown = bar(pts.n, "dynamic sizing", unit="opt", flag=show, initial=done)
    chunks = results(job, pts, bounds, todo, executor, run=run_dynamic_chunk)
    tables: dict[int, pa.Table] = {}
    try:
        for k, table in chunks:
            if store is not None:
                store.write(k, table)
            tables[k] = table
            shown.update(table.num_rows)
    except KeyboardInterrupt:
        raise SweepInterrupted(store.done_points if store is not None else 0, pts.n,
                               store is not None and store.resumable) from None
    finally:
        chunks.close()
        shown.close()
    return tables


def run_dynamic_chunk(job: DynamicChunk, start: int, chunk: dict) -> pa.Table:
    """The dynamic optimum at every point of ``chunk`` (name → values), each from its predecessor's: the rows
    of :func:`~optimisation.sweep.sizing_frame` as a table.  ``start``: the chunk's first point (unused: every
    chunk is independent)."""
    problem = DynamicSizingProblem(job.scene)
    q = problem.scene.built.quantities
    n = len(chunk[job.names[0]]) if job.names else 0
    x, feasible = np.full((n, 3), np.nan), np.zeros(n, bool)
    iterations, seconds = np.zeros(n, int), np.zeros(n)
    prev = None
    with held_solver_output():
        for i in range(n):
            values = {k: float(chunk[k][i]) for k in job.names}
            p = problem.p_of(values)
            begin, screen = prev, True
            if begin is None:
                begin = _first_start(problem, p)
                problem, screen = (problem.screened(begin, p), False) if begin is not None else (problem, True)
            if begin is not None:
                problem, sol = solve_refined(problem, begin, p=p, screen=screen)
                iterations[i], seconds[i] = sol.iterations, sol.seconds
                if sol.feasible:
                    _confirm(problem, sol.xs, values)
                    x[i], feasible[i], prev = sol.xs, True, sol.xs
    frame = sizing_frame(problem, q, {k: np.asarray(chunk[k]) for k in job.names}, x, feasible, iterations, seconds)
    return pa.Table.from_pandas(frame, preserve_index=False)


def _first_start(problem, p):
    """The start of the first point with a static design (None: no static design, so no dynamic one)."""
    sol = solve_best(SizingProblem(problem.scene), p)
    return factored_start(problem, sol.xs, p) if sol.feasible else None


def _confirm(problem, xs, values: dict) -> None:
    bad = [f"{v.manoeuvre}: " + "; ".join(v.failures) for v in verify(problem, xs, values) if not v.ok]
    if bad:
        point = ", ".join(f"{k} = {v:g}" for k, v in values.items())
        raise SolveError(f"the dynamic optimum at {point} fails in the hybrid simulator (" + " | ".join(bad) + ")")
