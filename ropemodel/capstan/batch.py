"""The capstan's rotation δ(F_T) at many points: error-controlled, compiled to C where a compiler works.

:func:`rotation_batch` evaluates :func:`ropemodel.numerics.capstan_rotation.rotation_function`
with the project's array evaluator (:class:`ropemodel.core.evaluate.Job`: CasADi code generation,
system C compiler, cached; CasADi's virtual machine without a compiler).  The Job of each setting
is kept, so a call costs only its points (no re-hashing of the Function).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ropemodel.core.evaluate import Job, compiler
from ropemodel.errors import InputError, SolveError
from ropemodel.numerics.capstan_rotation import ARGS, RTOL, STEPS, rotation_function

#: points per call of the compiled map (the last block is padded with copies of a point, each a whole
#: integration: small blocks waste little)
BLOCK = 16
#: below this many points "auto" stays on the virtual machine
COMPILE_MIN = 64


def rotation_batch(F_T, mu, EA, R, L, alpha_0, F_p, variant="li", steps=STEPS, sharpness=30.0, rtol=RTOL,
                   backend="auto", threads=1, with_error=False):
    """δ [m] (cable displacement at the capstan rim; Δα = δ/R) for numpy arrays (broadcast).

    F_T [N] ≥ 0, mu [-], EA [N], R [m], L [m], alpha_0 [rad], F_p [N]; variant, steps, sharpness,
    rtol as the capstan scene's ``[effects] stiffness`` and ``[numerics]``; backend ``"auto"``
    (C when a compiler works and there are at least :data:`COMPILE_MIN` points), ``"compiled"``
    or ``"casadi"``.  Returns δ, or (δ, estimated relative error) with ``with_error``.
    :class:`InputError` if a load unwraps the slack side (α2 ≤ 0); :class:`SolveError` if a point
    cannot meet ``rtol``.
    """
    cols = np.broadcast_arrays(*(np.asarray(a, float) for a in (F_T, mu, EA, R, L, alpha_0, F_p)))
    shape = cols[0].shape
    n = max(cols[0].size, 1)
    if backend == "auto":
        backend = "compiled" if n >= COMPILE_MIN and compiler() else "casadi"
    columns = {name: np.ascontiguousarray(np.resize(c.ravel(), n)) for name, c in zip(ARGS, cols)}
    out = _job(variant, int(steps), float(sharpness), float(rtol), backend, int(threads))(columns)
    delta, err = out["delta"].reshape(shape), out["error"].reshape(shape)
    bad = ~np.isfinite(delta)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        point = ", ".join(f"{k} = {columns[k][i]:.6g}" for k in ARGS)
        raise SolveError(f"the capstan rotation could not meet rtol = {rtol:g} at {int(bad.sum())} of {n} points "
                         f"(first: {point}); is the slack side unwrapped there?")
    unwrapped = columns["alpha_0"] - delta.ravel() / columns["R"] <= 0
    if unwrapped.any():
        i = int(np.flatnonzero(unwrapped)[0])
        raise InputError(f"the load unwraps the slack side (alpha_2 <= 0) at {int(unwrapped.sum())} of {n} points "
                         f"(first: F_T = {columns['F_T'][i]:.6g} N): the model no longer applies there")
    return (delta, err) if with_error else delta


@lru_cache(maxsize=32)
def _job(variant, steps, sharpness, rtol, backend, threads) -> Job:
    return Job(rotation_function(variant, steps, sharpness, rtol), list(ARGS), {}, backend=backend, threads=threads,
               block=BLOCK)
