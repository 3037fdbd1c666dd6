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

import contextlib
import hashlib
import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import casadi as ca
import numpy as np
import pandas as pd
import pyarrow as pa

from ropemodel import __version__
from ropemodel.core.evaluate import COMPILE_MIN, Job, evaluator
from ropemodel.envelope import reads as case_reads
from ropemodel.envelope import with_ramps
from ropemodel.errors import InputError
from ropemodel.progress import bar, enabled, status
from ropemodel.problem import Problem
from ropemodel.scene import SceneLike, as_scene
from ropemodel.sweeps.chunk import ChunkJob
from ropemodel.sweeps.per_case import ROWS, case_job
from ropemodel.sweeps.schedule import results
from ropemodel.sweeps.files import OutputLock, check_disk, check_output, check_size
from ropemodel.sweeps.points import MAX_AXIS, Points, grid, table
from ropemodel.sweeps.store import ChunkStore, complete_rows, discard_parts, read_output
from ropemodel.sweeps.validate import check_ranges, check_rules, idle
from ropemodel.sweeps import worst as worst_case
from ropemodel.units import label
from ropemodel.views.records import SweepFileViews

CHUNK = 65536  # points per chunk: ~20 MB of results for 40 columns
ERRORS = ("raise", "mark")
MAX_THREADS = 1024  # threads per chunk evaluation (more is a typo, not a machine)
#: the columns ``errors="mark"`` adds: whether the point has a valid solution, and why not
MARK_COLUMNS = {"solved": pa.bool_(), "invalid": pa.string()}


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep: ``done`` of ``total`` points are kept on disk (``resumable``: in the
    output's parts, and a rerun of the same sweep resumes from them)."""

    def __init__(self, done: int, total: int, resumable: bool):
        super().__init__(done, total, resumable)
        self.done, self.total, self.resumable = done, total, resumable

    def __str__(self):
        text = f"{self.done} of {self.total} points done"
        return text + ("; rerun the same command to resume" if self.resumable else "")


@dataclass
class SweepFile(SweepFileViews, os.PathLike):
    """What ``sweep(..., collect=False)`` returns: the output file (path-like) and what it holds.

    status: ``"written"`` (computed now, or resumed) or ``"complete"`` (found finished: nothing computed).
    """

    path: Path
    rows: int
    columns: list[str]
    status: str

    def __fspath__(self) -> str:
        return str(self.path)

    def __str__(self) -> str:
        return str(self.path)


def sweep(scene: SceneLike, vary: Mapping | pd.DataFrame | None = None, outputs: Sequence[str] | None = None, *,
          points: pd.DataFrame | None = None, given: Mapping | Sequence[str] = (), find: Sequence[str] = (),
          out: str | os.PathLike | None = None, chunk_size: int = CHUNK, executor: Any = None,
          threads: int | None = None, backend: str = "auto", si: bool = False, errors: str = "raise",
          progress: bool | None = None, restart: bool = False, collect: bool = True) -> pd.DataFrame | SweepFile:
    """Evaluate ``scene`` at many points: a grid or a table of inputs, in chunks, resumable on disk.

    Parameters
    ----------
    scene: a :class:`~ropemodel.scene.Scene` (or a TOML scene file, or a built-in scene's name, loaded first);
        inputs not varied keep its values.
    vary: ``{name: axis}`` — a grid, the product of the axes (``"5deg:45deg:1000"``,
        ``(0, 0.7, 100)``, a list of values; numbers are SI) — or a DataFrame of points.
    outputs: names of the outputs to compute (default: every unknown of the problem).
    points: a DataFrame of points (alternative to ``vary``); columns are names (SI) or ``"name [unit]"``.
    given, find: an inverse problem, as in :class:`~ropemodel.problem.Problem`: ``given`` outputs
        (varied, or values in a dict ``{name: value}``; None: varied) replace the ``find`` parameters.
    out: ``.csv`` or ``.parquet`` path, checked and locked before any work (a second writer of it
        is refused); results are written chunk by chunk and an interrupted sweep rerun with the
        same arguments resumes where it stopped; a finished one is found complete and not
        recomputed (see :mod:`ropemodel.sweeps.store`).
    chunk_size: points per chunk, 1 to 1e8 (bounded memory: one chunk per worker in flight).
    executor: a ``concurrent.futures.Executor`` or a ``dask.distributed.Client``: chunks are
        submitted to it (the compiled Function travels pickled; each worker compiles it once).
    threads: threads per chunk evaluation, 1 to 1024 (default: the number of CPUs; 1 with an executor).
    backend: ``"auto"``, ``"casadi"`` (Function.map) or ``"compiled"`` (C code through ctypes).
    si: SI units in the columns instead of display units.
    errors: ``"raise"`` — a point without a valid solution raises SolveError naming it;
        ``"mark"`` — keep it (NaN outputs) with ``solved`` False and the reason in ``invalid``.
        A point where the model no longer holds (a rope that would have to push: slack) has
        no valid solution.
    progress: show a progress bar (default: when stderr is a terminal and not silenced; see
        :func:`ropemodel.progress.enabled`).
    restart: discard an unfinished sweep of ``out``, or recompute a finished one.
    collect: return the DataFrame (False: return a :class:`SweepFile`; memory stays bounded).

    Returns
    -------
    pandas.DataFrame or SweepFile
        One row per point: the varied inputs, then the outputs, each column named
        ``"name [unit]"`` in the quantity's display unit (``"alpha_u [deg]"``, ``"F_C_up [kN]"``,
        ``"dF_up [mm]"``; ``si=True``: ``"name [N]"``, ``"[m]"``, ``"[rad]"``). With
        ``errors="mark"`` two more columns: ``solved`` (bool) and ``invalid`` (why a point has no
        result; missing where it has one). ``collect=False``: the path of ``out``.

    Raises
    ------
    InputError: bad input, an output that cannot be written or is being written by another
        process, work that cannot fit (beyond the grid limits, results beyond memory or disk).
    OutputError: the output could not be written (disk full, I/O error); finished chunks are kept.
    SweepInterrupted: a KeyboardInterrupt; finished chunks are kept.

    Examples
    --------
    The pull on the winding rope over inclinations and loads (Krauze et al. 2025, eq. (12)):

    >>> import ropemodel as rm
    >>> df = rm.sweep(rm.load_scene(), vary={"alpha_u": "10deg:20deg:3", "G_m": ["300 kN", "467 kN"]},
    ...               outputs=["F_C_up", "dF_up"], progress=False)
    >>> df.round(2)
       alpha_u [deg]  G_m [kN]  F_C_up [kN]  dF_up [mm]
    0           10.0     300.0        97.37      805.14
    1           10.0     467.0       134.59     1021.03
    2           15.0     300.0       130.39     1042.59
    3           15.0     467.0       181.68     1340.06
    4           20.0     300.0       162.49     1273.87
    5           20.0     467.0       227.45     1650.66

    A route falling toward the drive leaves the unwinding rope slack: no result, and why:

    >>> rm.sweep(rm.load_scene(), vary={"alpha_u": ["-10 deg"]}, outputs=["F_C_up"], errors="mark",
    ...          progress=False).loc[0, "invalid"]
    'outside the model: F_S_up <= 0: the unwinding rope is slack (upward travel)'
    """
    scene = as_scene(scene)
    _check_options(errors, chunk_size, collect, out, threads)
    show = enabled(progress)
    out = check_output(out) if out is not None else None
    with OutputLock(out) if out is not None else contextlib.nullcontext():
        plan = _plan(scene, vary, outputs, points, given, find, chunk_size, si, errors, out, collect)
        if out is not None and not restart:
            found = _found(plan, out, collect)
            if found is not None:
                return found
        store = ChunkStore(out, plan.signature, plan.bounds, restart) if out is not None else None
        try:
            if store is not None:
                check_disk(plan.n - store.done_points, len(plan.labels()), store.path)
            job = _job(plan, backend, threads or (1 if executor is not None else (os.cpu_count() or 1)))
            if executor is None:  # compiled once per process: here, while a status line says so
                with status("sweep: compiling", show):
                    evaluator(getattr(job.job, "rows", job.job))
            tables = _run(job, plan, store, executor, show, collect)
            return _finish(plan, store, out, tables, collect)
        except SweepInterrupted:
            raise
        except KeyboardInterrupt:
            raise SweepInterrupted(store.done_points if store else 0, plan.n,
                                   store is not None and store.resumable) from None


def _check_options(errors, chunk_size, collect, out, threads) -> None:
    if errors not in ERRORS:
        raise InputError(f"errors={errors!r}: valid: {', '.join(ERRORS)}")
    _whole("chunk_size", chunk_size, MAX_AXIS)
    if threads is not None:
        _whole("threads", threads, MAX_THREADS)
    if not collect and out is None:
        raise InputError("collect=False needs an output file (out=...)")


def _whole(name: str, value, high: int) -> None:
    """:class:`InputError` unless ``value`` is a whole number in [1, high]."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 1 <= value <= high:
        shown = f"{str(value)[:20]}..." if len(str(value)) > 20 else repr(value)
        raise InputError(f"{name} = {shown}: must be a positive whole number, at most {high:g}")


@dataclass
class _Plan:
    """A sweep checked and ready to run: its problem, points, outputs, chunks and signature."""

    problem: Problem
    pts: Points
    base: dict
    outputs: list[str]
    si: bool
    errors: str
    bounds: list[tuple[int, int]]
    signature: dict
    worst: worst_case.Worst | None = None

    @property
    def n(self) -> int:
        return self.pts.n

    def labels(self) -> list[str]:
        q = self.problem.model.quantities
        cols = [label(k, q[k].unit if self.si else q[k].display_unit) for k in [*self.pts.names, *self.outputs]]
        cols += [label(c, worst_case.UNITS[k]) for c, k in (self.worst.where_columns(self.outputs) if self.worst
                                                            else [])]
        return cols + (list(MARK_COLUMNS) if self.errors == "mark" else [])


def _plan(scene, vary, outputs, points, given, find, chunk_size, si, errors, out, collect) -> _Plan:
    given_values = {k: v for k, v in given.items() if v is not None} if isinstance(given, dict) else {}
    scene = with_ramps(scene)
    problem = Problem(scene, list(given), find)
    model = problem.model
    inputs = {k: model.quantities[k] for k in problem.user_knowns}
    if isinstance(vary, pd.DataFrame):
        points, vary = vary, None
    if (vary is None) == (points is None):
        raise InputError("give either vary={name: axis} (a grid) or a table of points")
    inputs.update(worst_case.route_edges(problem, list(vary if vary is not None else points.columns)))
    pts = grid(vary, inputs) if vary is not None else table(points, inputs, ignore=model.outputs)
    if pts.n == 0:
        raise InputError("no points to sweep")
    worst, outputs = worst_case.plan(scene, problem, pts.names, find, outputs)
    outputs = _outputs(problem, outputs, pts.names)
    if not given and not find:
        idle(model, pts.names, outputs, case_reads(scene) if worst else set())
    check_size(pts.n, len(pts.names) + len(outputs) + 2 * (errors == "mark"), out=out, collect=collect)
    base = problem.inputs({**given_values, **{n: float(pts.values_of(n)[0]) for n in pts.names}})
    check_ranges(pts, inputs)
    check_rules(model, pts, base)
    size = max(1, min(chunk_size, ROWS // len(worst.cases))) if worst is not None and worst.follows else chunk_size
    bounds = [(k * size, min(pts.n, (k + 1) * size)) for k in range(-(-pts.n // size))]
    signature = _signature(scene, problem, pts, base, outputs, chunk_size, si, errors)
    return _Plan(problem, pts, base, outputs, si, errors, bounds, signature, worst)


def _found(plan: _Plan, out: Path, collect: bool):
    """The finished output of this very sweep, if ``out`` is one (nothing is computed then)."""
    rows = complete_rows(out, plan.signature)
    if rows is None:
        return None
    discard_parts(out, plan.signature)  # left if the output was finished just before they were removed
    if collect:
        types = {c: MARK_COLUMNS.get(c, pa.float64()) for c in plan.labels()}
        return read_output(out, types).to_pandas()
    return SweepFile(out, rows, plan.labels(), "complete")


def _run(job, plan: _Plan, store, executor, show: bool, collect: bool) -> dict:
    """Compute the chunks not yet on disk; {chunk: table} of those kept in memory."""
    todo = [k for k in range(len(plan.bounds)) if store is None or k not in store.done]
    done = 0 if store is None else store.done_points
    tables: dict[int, pa.Table] = {}
    shown = bar(plan.n, "sweep", unit="pt", flag=show, initial=done, unit_scale=True)
    chunks = results(job, plan.pts, plan.bounds, todo, executor)
    try:
        for k, t in chunks:
            if store is not None:
                store.write(k, t)
            if collect:
                tables[k] = t
            done += t.num_rows
            shown.update(t.num_rows)
    except KeyboardInterrupt:  # points kept on disk; without a file, those computed (and dropped)
        raise SweepInterrupted(done if store is None else store.done_points, plan.n,
                               store is not None and store.resumable) from None
    finally:
        chunks.close()
        shown.close()
    return tables


def _finish(plan: _Plan, store, out, tables, collect):
    if store is not None:
        if collect:
            for k in range(len(plan.bounds)):
                if k not in tables:
                    tables[k] = store.read(k)
        rows, columns = store.finish()
        if not collect:
            return SweepFile(out, rows, columns, "written")
    return pa.concat_tables([tables[k] for k in range(len(plan.bounds))]).to_pandas()


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


def _job(plan: _Plan, backend: str, threads: int) -> ChunkJob:
    """The problem's Function restricted to ``outputs``, inputs ordered varied first (at the worst over open cases
    of a long route whose numbers follow the points: :mod:`ropemodel.sweeps.per_case`), its columns and checks."""
    problem, outputs, si = plan.problem, plan.outputs, plan.si
    if backend == "auto" and plan.n < COMPILE_MIN:
        backend = "casadi"  # a C compile costs more than it saves on small sweeps
    physics = [sm for sm in problem.model.submodels if sm.invalid_needs_for(outputs)]
    if plan.worst is not None and plan.worst.follows:
        job, watch = case_job(problem, plan.worst, plan.pts.names, plan.base, outputs, physics, backend, threads)
        roundtrip, step = {}, None
    else:
        job, watch, roundtrip, step = _point_job(plan, physics, backend, threads)
    q = problem.model.quantities
    columns = []
    for name in list(plan.pts.names) + outputs:
        unit = q[name].unit if si else q[name].display_unit
        columns.append((label(name, unit), name, 1.0 if si else float(q[name].to_display(1.0))))
    if plan.worst is not None:
        columns += [(label(c, worst_case.UNITS[k]), c, 1.0) for c, k in plan.worst.where_columns(outputs)]
    checks = {n: (q[n].low, q[n].high, q[n].low_open, q[n].high_open,
                  f"{q[n].range_text()}, {q[n].description}") for n in problem.find if n in outputs}
    return ChunkJob(job, outputs, columns, checks, plan.errors, roundtrip, physics, watch, step)


def _point_job(plan: _Plan, physics, backend: str, threads: int):
    """(Job, watch, roundtrip, route step) of the Function of one point (each output at its worst over the cases
    inside it).  For an inverse problem the forward model is also evaluated at each solution, so that a
    Newton iteration that stopped without converging (no such parameter value) is caught
    per point: the given outputs must be reproduced (relative 1e-6, as ``Problem.solve``)."""
    problem, varied, base, outputs = plan.problem, plan.pts.names, plan.base, plan.outputs
    fun = problem.function
    computed = step.names if (step := worst_case.route_step(problem, plan.pts.names, plan.base, plan.worst)) else []
    order = [*varied, *computed] + [k for k in problem.knowns if k not in varied and k not in computed]
    syms = {k: ca.MX.sym(k) for k in [*problem.knowns, *varied]}     # a segment varied: the route step reads it
    args = {**{k: syms[k] for k in problem.knowns}, **problem.scene.rule_values(syms, varied)}   # + a rule's factor
    if plan.worst is None:
        res = fun.call(args)
        names, outs, per_case = list(outputs), [res[o] for o in outputs], [("", res)]
    else:
        names, outs, per_case = worst_case.columns(plan.worst, fun, args, base, outputs, problem.model.quantities)
    roundtrip = {}
    if problem.given:
        forward = Problem(problem.scene).function
        params = {k: args[k] if k in args else res[k] for k in problem.model.parameters}
        back = forward.call(params)
        for g in problem.given:
            roundtrip[f"roundtrip_{g}"] = g
            names.append(f"roundtrip_{g}")
            outs.append(back[g])
    watch = worst_case.watches(per_case, physics, problem, outputs, plan.worst is None, names, outs)
    sel = ca.Function("sweep_point", [syms[k] for k in order], outs, order, names)
    if fun.is_a("SXFunction"):
        sel = sel.expand()
    constants = {k: float(base[k]) for k in order[len(varied) + len(computed):]}
    return Job(sel, [*varied, *computed], constants, backend, threads), watch, roundtrip, step


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
        "version": __version__,
    }
    return json.loads(json.dumps(sig))
