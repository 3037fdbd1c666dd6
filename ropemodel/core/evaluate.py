"""The one evaluator over arrays: a compiled Function at many points, in chunks.

A :class:`Job` is everything a worker needs to evaluate a CasADi Function at a
chunk of points: the Function (it pickles, so a job can travel to a dask worker
or another process), which inputs vary and the values of those held constant.
It is compiled into an evaluator once per process (:func:`evaluator`).
:func:`evaluate_columns` is the entry point for whole arrays
(:meth:`ropemodel.problem.Problem.evaluate`, load curves, sweeps).

Two backends evaluate the same Function:

``"casadi"``
    ``Function.map`` over the chunk (``"thread"`` parallelisation with
    ``threads > 1``; serial with the constant inputs passed once otherwise).
    Works for every Function, including Newton blocks (``rootfinder``).
``"compiled"``
    CasADi's C code generation of the mapped Function, compiled once with the
    system C compiler (``$CC``, default ``cc``), cached in
    ``$ROPEMODEL_CACHE`` (default ``~/.cache/ropemodel``) and called through
    ``ctypes`` directly on numpy buffers: no conversion to ``DM`` and back,
    which dominates the cost of ``"casadi"`` on cheap models.  Blocks of points
    run on ``threads`` Python threads (``ctypes`` releases the GIL).

``"auto"`` picks ``"compiled"`` for explicit (SX) Functions of at least
:data:`COMPILE_MIN` points when a C compiler works, else ``"casadi"``.
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import shutil
import subprocess
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import casadi as ca
import numpy as np

from ropemodel.core.compile import MANY_INPUTS
from ropemodel.errors import InputError, SolveError

BACKENDS = ("auto", "casadi", "compiled")
BLOCK = 4096  # points per call of the compiled map: its work array stays in cache
COMPILE_MIN = 20000  # "auto" compiles to C only for at least this many points (gcc takes ~0.3 s)
#: constant inputs × points above which ``Function.map`` is not given the constants: CasADi's map repeats each
#: constant input at every point (a 3000-segment route's model evaluated at 3000 places of the load: 18·10^6
#: numbers), so the constants are folded into the Function first (:func:`folded`)
FOLD_MIN = 10**6
#: constant inputs above which they are folded in whatever the points: CasADi warns of a Function (and a map) of
#: more than 10 000 inputs on stderr, and hashing and mapping one costs more than folding its constants once (a
#: 10 000-segment route's model has 20 000)
FOLD_INPUTS = 1000


@dataclass
class Job:
    """A picklable description of how to evaluate one Function at chunks of points.

    function: one scalar input per name in ``varied`` then per constant, scalar outputs.
    varied: names of the inputs given as arrays (the first inputs of ``function``).
    constants: SI values of the inputs that do not vary (passed at each call; not part of ``key``).
    backend: ``"auto"``, ``"casadi"`` or ``"compiled"``; threads: threads per chunk;
    block: points per call of the compiled map (the last block is padded with copies of a point:
    keep it small for expensive Functions, such as error-controlled integrators).
    """

    function: ca.Function
    varied: list[str]
    constants: dict[str, float]
    backend: str = "auto"
    threads: int = 1
    block: int = BLOCK

    @cached_property
    def key(self) -> str:
        h = hashlib.sha256(_digest(self.function).encode())
        h.update(repr((self.varied, sorted(self.constants), self.backend, self.threads, self.block)).encode())
        return h.hexdigest()

    def __call__(self, inputs: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Every output at the points ``inputs`` (SI arrays of the varied inputs, one length)."""
        n = len(next(iter(inputs.values())))
        return evaluator(self)([np.asarray(inputs[k], dtype=float) for k in self.varied], n, _constants(self))


_EVALUATORS: dict[str, object] = {}
MAX_EVALUATORS = 64
_LOCK = threading.Lock()
#: id(Function) → (Function, digest of its serialisation): serialising costs ~1 ms a call for an
#: integrator; the Function is kept alive here, so its id cannot be reused while it is cached
_DIGESTS: dict[int, tuple] = {}
#: (id(Function), input order, outputs) → (Function, reordered Function), for evaluate_columns
_REORDERED: dict[tuple, tuple] = {}


def _remember(cache: dict, key, value):
    with _LOCK:
        if len(cache) >= MAX_EVALUATORS:
            del cache[next(iter(cache))]
        cache[key] = value
    return value


def _digest(function: ca.Function) -> str:
    hit = _DIGESTS.get(id(function))
    if hit is not None and hit[0] is function:
        return hit[1]
    return _remember(_DIGESTS, id(function), (function, hashlib.sha256(function.serialize().encode()).hexdigest()))[1]


def evaluator(job: Job):
    """The evaluator of ``job``, compiled once per process."""
    key = job.key
    with _LOCK:
        ev = _EVALUATORS.get(key)
        if ev is None:
            if len(_EVALUATORS) >= MAX_EVALUATORS:  # oldest first out: dicts keep insertion order
                del _EVALUATORS[next(iter(_EVALUATORS))]
            ev = _EVALUATORS[key] = _make(job)
    return ev


def _constants(job: Job) -> list[float]:
    """Values of the constant inputs in the Function's input order (passed at every call: the
    evaluator is shared by every job with the same Function, whatever their values)."""
    return [job.constants[k] for k in job.function.name_in()[len(job.varied):]]


def _make(job: Job):
    backend = job.backend
    if backend not in BACKENDS:
        raise InputError(f"backend {backend!r}: valid backends: {', '.join(BACKENDS)}")
    fun = job.function
    n_var = len(job.varied)
    if backend == "auto":
        backend = "compiled" if fun.is_a("SXFunction") and compiler() else "casadi"
    if backend == "compiled":
        try:
            return _Compiled(fun, n_var, job.threads, job.block)
        except (OSError, RuntimeError, subprocess.CalledProcessError) as exc:
            if job.backend == "compiled":
                raise InputError(f"backend 'compiled' is not available: {exc}") from None
    return _Mapped(fun, n_var, job.threads)


def compiler() -> str | None:
    """Path of a working C compiler, or None."""
    return shutil.which(os.environ.get("CC", "cc"))


class _Mapped:
    """``Function.map``: serial with the constant inputs passed once (``reduce_in``), or
    ``"thread"`` with them repeated (CasADi's threaded map with ``reduce_in`` is ~30x slower
    than either, measured on the winch model)."""

    def __init__(self, fun, n_var, threads):
        self.fun, self.n_var, self.threads = fun, n_var, max(1, threads)
        self.maps = {}

    def __call__(self, inputs, n, const):
        fm = self.maps.get(n)
        if fm is None:
            if self.threads > 1:
                fm = self.fun.map(n, "thread", self.threads)
            else:
                fm = self.fun.map("eval_map", "serial", n, list(range(self.n_var, self.fun.n_in())), [], MANY_INPUTS)
            self.maps[n] = fm
        args = [ca.DM(v.reshape(1, n)) for v in inputs]
        if self.threads > 1:
            args += [ca.repmat(ca.DM(float(c)), 1, n) for c in const]
        else:
            args += [float(c) for c in const]
        res = fm.call(args)
        return {name: np.asarray(r).ravel() for name, r in zip(self.fun.name_out(), res)}


class _Compiled:
    """The mapped Function as C, compiled and called through ctypes on numpy buffers."""

    def __init__(self, fun, n_var, threads, block=BLOCK):
        self.n_var, self.threads, self.block = n_var, max(1, threads), int(block)
        self.names = fun.name_out()
        reduce_in = list(range(n_var, fun.n_in()))
        fm = fun.map("eval_block", "serial", self.block, reduce_in, [], MANY_INPUTS)
        cg = ca.CodeGenerator("eval_block.c", {"with_header": False})
        cg.add(fm)
        code = cg.dump()
        self.lib = ctypes.CDLL(str(_build(code)))
        self.entry = self.lib.eval_block
        self.entry.restype = ctypes.c_int
        self.sz = (fm.sz_arg(), fm.sz_res(), fm.sz_iw(), fm.sz_w())
        self.local = threading.local()
        self.pool = ThreadPoolExecutor(self.threads) if self.threads > 1 else None

    def _work(self):
        w = getattr(self.local, "w", None)
        if w is None:
            P = ctypes.POINTER(ctypes.c_double)
            w = self.local.w = ((P * self.sz[0])(), (P * self.sz[1])(),
                                (ctypes.c_longlong * max(1, self.sz[2]))(), np.zeros(max(1, self.sz[3])))
        return w

    def _block(self, ins, const, out, b):
        P = ctypes.POINTER(ctypes.c_double)
        arg, res, iw, w = self._work()
        s = b * self.block
        for i, x in enumerate(ins):
            arg[i] = x[s:s + self.block].ctypes.data_as(P)
        for i, c in enumerate(const):
            arg[self.n_var + i] = c.ctypes.data_as(P)
        for j in range(out.shape[0]):
            res[j] = out[j, s:s + self.block].ctypes.data_as(P)
        if self.entry(arg, res, iw, w.ctypes.data_as(P), 0):
            raise SolveError("the compiled function failed")

    def __call__(self, inputs, n, const):
        const = [np.array([c], dtype=float) for c in const]
        blocks = -(-n // self.block)
        m = blocks * self.block
        ins = []
        for v in inputs:
            x = np.empty(m)
            x[:n] = v
            x[n:] = v[-1] if n else 0.0  # padding: a copy of a valid point, dropped below
            ins.append(x)
        out = np.empty((len(self.names), m))
        if self.pool is not None and blocks > 1:
            list(self.pool.map(lambda b: self._block(ins, const, out, b), range(blocks)))
        else:
            for b in range(blocks):
                self._block(ins, const, out, b)
        return {name: out[j, :n] for j, name in enumerate(self.names)}


def _cache_dir() -> Path:
    root = os.environ.get("ROPEMODEL_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "ropemodel")
    path = Path(root) / "compiled"
    path.mkdir(parents=True, exist_ok=True)
    return path


def _build(code: str) -> Path:
    """Compile ``code`` into a shared library once; cached by the hash of the code."""
    cc = compiler()
    if cc is None:
        raise RuntimeError("no C compiler (set CC)")
    flags = ["-O2", "-shared", "-fPIC"]
    digest = hashlib.sha256((code + " ".join(flags)).encode()).hexdigest()[:24]
    lib = _cache_dir() / f"eval_{digest}.so"
    if lib.exists():
        return lib
    with tempfile.TemporaryDirectory(dir=_cache_dir()) as tmp:
        src = Path(tmp) / "eval_block.c"
        src.write_text(code)
        out = Path(tmp) / "lib.so"
        subprocess.run([cc, *flags, str(src), "-o", str(out), "-lm"], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        os.replace(out, lib)  # atomic: concurrent builders agree
    return lib


def reordered(function: ca.Function, order, outputs=None) -> ca.Function:
    """``function`` with its inputs in ``order`` (names) and only ``outputs`` (default all); SX stays SX (called on SX
    symbols: the same operations as an MX call expanded, without the MX graph of a route's 20 000 inputs)."""
    sym: Any = ca.SX.sym if function.is_a("SXFunction") else ca.MX.sym
    syms: dict[str, Any] = {k: sym(k) for k in function.name_in()}
    res = function.call(syms)
    outputs = list(function.name_out()) if outputs is None else list(outputs)
    return ca.Function(function.name(), [syms[k] for k in order], [res[o] for o in outputs], list(order), outputs,
                       MANY_INPUTS)


def folded(function: ca.Function, varied: list[str], constants: dict[str, float],
           outputs=None) -> tuple[ca.Function | None, dict[str, float]]:
    """The SX ``function`` with its inputs other than ``varied`` (names) fixed at ``constants`` (name → value):
    CasADi does the arithmetic on numbers once, here (the same operations in the same order, so the same results).
    Returns the Function of the ``varied`` inputs (in that order) to the ``outputs`` (default all) that still
    depend on them (None if none does), and the values of the others (a route's sums, its segments' coefficients:
    one number each, not one per point)."""
    syms = {k: ca.SX.sym(k) for k in varied}
    names = list(function.name_out()) if outputs is None else list(outputs)
    numbers = ca.vertsplit(ca.SX(ca.DM(list(map(float, constants.values()))))) if constants else []  # converted once
    got = function.call({**syms, **dict(zip(constants, numbers))})
    out = [got[k] for k in names]
    still = [e.is_constant() for e in out]
    values: Any = np.asarray(ca.evalf(ca.vertcat(*[e for e, c in zip(out, still) if c]))).ravel() if any(still) else []
    fixed = dict(zip((k for k, c in zip(names, still) if c), map(float, values)))
    moving = [(k, e) for k, e in zip(names, out) if k not in fixed]
    if not moving:
        return None, fixed
    return ca.Function(function.name(), [syms[k] for k in varied], [e for _, e in moving], list(varied),
                       [k for k, _ in moving], MANY_INPUTS), fixed


class _FoldedJob:
    """A :class:`Job` of a :func:`folded` Function (its constants inside it): evaluated by ``Function.map``,
    built here and not cached (a Function for one set of constants); the outputs that no longer vary are
    repeated, not evaluated at every point."""

    def __init__(self, function: ca.Function, varied: list[str], constants: dict[str, float], threads: int,
                 outputs=None):
        moving, self.fixed = folded(function, varied, constants, outputs)
        self.varied = varied
        self.mapped = None if moving is None else _Mapped(moving, len(varied), threads)

    def __call__(self, inputs: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        n = len(inputs[self.varied[0]])
        out = {} if self.mapped is None else self.mapped([inputs[k] for k in self.varied], n, [])
        out.update({k: np.full(n, v) for k, v in self.fixed.items()})
        return out


def evaluate_columns(function: ca.Function, columns: dict, constants: dict, threads: int = 1,
                     backend: str = "auto", chunk: int = 65536, block: int = BLOCK,
                     outputs=None) -> dict[str, np.ndarray]:
    """Every output of ``function`` (or only ``outputs``) at many points, in chunks: ``columns`` name → SI
    array (all one length) vary, ``constants`` name → SI float do not; together they name every input.

    The same engine as a sweep (compiled once per process, threads, bounded memory), without
    validation or files: a drop-in body for ``Problem.evaluate``.  ``block``: points per call of
    the compiled map (:class:`Job`).  Evaluated by CasADi with many constants at many points (above
    :data:`FOLD_MIN`, or more of them than :data:`FOLD_INPUTS`), the constants are folded in first (:func:`folded`):
    memory linear in the points.
    """
    columns = {k: np.ascontiguousarray(v, dtype=float).ravel() for k, v in columns.items()}
    n_points = len(next(iter(columns.values()))) if columns else 1
    if backend == "auto" and n_points < COMPILE_MIN:
        backend = "casadi"
    constants = {k: float(v) for k, v in constants.items()}
    if not columns:  # one point: vary any input over a single value
        k = next(iter(constants))
        columns = {k: np.array([constants.pop(k)])}
    n = len(next(iter(columns.values())))
    if any(len(v) != n for v in columns.values()):
        raise InputError(f"input arrays of different lengths: {sorted({len(v) for v in columns.values()})}")
    order = list(columns) + list(constants)
    given = set(order)
    missing = [k for k in function.name_in() if k not in given]
    if missing:
        raise InputError(f"no value for {', '.join(missing)}")
    job: Job | _FoldedJob
    if backend == "casadi" and function.is_a("SXFunction") and (len(constants) * n > FOLD_MIN
                                                                or len(constants) > FOLD_INPUTS):
        job = _FoldedJob(function, list(columns), constants, threads, outputs)    # by name: no reordering first
        names = list(function.name_out()) if outputs is None else list(outputs)
    else:
        key = (id(function), tuple(order), None if outputs is None else tuple(outputs))
        hit = _REORDERED.get(key)
        if hit is None or hit[0] is not function:
            hit = _remember(_REORDERED, key, (function, reordered(function, order, outputs)))
        job = Job(hit[1], list(columns), constants, backend=backend, threads=threads, block=block)
        names = list(hit[1].name_out())
    out = {o: np.empty(n) for o in names}
    for s in range(0, n, chunk):
        e = min(n, s + chunk)
        for o, v in job({k: c[s:e] for k, c in columns.items()}).items():
            out[o][s:e] = v
    return out
