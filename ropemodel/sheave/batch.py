"""Vectorised evaluation of the lining tension: closed form and ODE over many points.

The ODE path evaluates :func:`ropemodel.numerics.hajduk_integrators.log_ratio_function` with
the array evaluator :func:`ropemodel.core.evaluate.evaluate_columns`: compiled to C (CasADi
code generation, system C compiler, cached) where a compiler works, else CasADi's virtual
machine.
"""

from __future__ import annotations

import numpy as np

from ropemodel.core.evaluate import compiler, evaluate_columns
from ropemodel.errors import SolveError
from ropemodel.numerics.hajduk_integrators import CODEGEN, DEFAULT, RATIO_INPUTS, log_ratio_function
from ropemodel.papers import hajduk1992 as hj

#: points per call of the compiled map (padding the last block costs little)
BLOCK = 64
#: below this many points "auto" stays on the virtual machine (no C compile for a handful of points)
COMPILE_MIN = 64


def closed_log_ratio(mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0):
    """ln(S/S_0) from the exact solution (Hajduk 1992 eq. (19)) for numpy arrays (broadcast)."""
    return hj.log_tension_ratio(*np.broadcast_arrays(*(np.asarray(a, float) for a in
                                                       (mu, alpha, q_R, k_R, q_T, k_T))))


def pick_backend(backend: str, n: int, codegen: bool = True) -> str:
    """``"auto"``: ``"compiled"`` when the Function can be generated as C (``codegen``), a C compiler
    is present and ``n`` >= :data:`COMPILE_MIN`, else ``"casadi"``; any other name unchanged."""
    if backend != "auto":
        return backend
    return "compiled" if codegen and n >= COMPILE_MIN and compiler() else "casadi"


def ode_log_ratio(mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0, beta=0.0, plugin=DEFAULT, state="log",
                  rtol=1e-7, parallel=1, backend="auto", with_error=False):
    """ln(S/S_0) by integration for numpy arrays (broadcast), error-controlled to ``rtol``.

    mu [-] (friction at zero pressure if beta > 0), alpha [rad], q_R, q_T = Q S_0 [-],
    k_R, k_T = λω [rad], beta = S_0/(p_c R a) [-] (Thirion friction; 0: constant μ).
    plugin, state, rtol: as ``[numerics]`` integrator, state, rtol of a sheave scene;
    backend: ``"auto"`` (C where a compiler works), ``"compiled"`` or ``"casadi"``;
    parallel: threads.  Returns y, or (y, err) with ``with_error`` (err: the estimate of the
    error of y, i.e. of the relative error of S).  :class:`SolveError` if a point cannot meet
    ``rtol``.
    """
    cols = np.broadcast_arrays(*(np.asarray(a, float) for a in (mu, alpha, q_R, k_R, q_T, k_T, beta)))
    shape = cols[0].shape
    n = max(cols[0].size, 1)
    f = log_ratio_function(plugin, state, float(rtol))
    columns = {name: np.resize(c.ravel(), n) for name, c in zip(RATIO_INPUTS, cols)}
    try:
        out = evaluate_columns(f, columns, {}, threads=int(parallel),
                               backend=pick_backend(backend, n, plugin in CODEGEN), block=BLOCK)
    except RuntimeError as exc:  # a SUNDIALS run that failed outright
        raise SolveError(f"the lining ODE ({plugin}) failed: {str(exc).splitlines()[-1]}") from None
    y, err = out["y"].reshape(shape), out["err"].reshape(shape)
    bad = ~np.isfinite(y)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        point = ", ".join(f"{k} = {columns[k][i]:.6g}" for k in RATIO_INPUTS)
        raise SolveError(f"the lining ODE ({plugin}) could not meet rtol = {rtol:g} at {int(bad.sum())} of {n} "
                         f"points (first: {point}); loosen [numerics] rtol or use method = 'closed'")
    return (y, err) if with_error else y


def distribution(scene, points: int | None = None):
    """Tension along the arc of a sheave scene as a DataFrame (columns carry units).

    ``scene``: a loaded ``model = "sheave"`` scene (:func:`ropemodel.load_scene`); it is
    solved first (so derived data such as Q_R of a ``voigt_physical`` lining are used).

    Columns: ``alpha [deg]``, ``S [kN]``, ``S/S_0 [-]`` and ``e^(mu alpha) [-]``
    (Euler–Eytelwein for comparison).  ``points`` equally spaced angles from 0 to
    the wrap angle (default: the scene's ``[numerics] points``).  Uses the scene's
    method (closed form, or the integrator chained over the segments).
    """
    from ropemodel.effects.sheave import distribution_frame
    from ropemodel.problem import run

    return distribution_frame(run(scene).values, scene, points)


__all__ = ["RATIO_INPUTS", "closed_log_ratio", "distribution", "ode_log_ratio", "pick_backend"]
