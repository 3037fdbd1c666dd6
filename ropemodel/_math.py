"""Elementary functions that work on floats, numpy arrays and CasADi symbols alike.

The equation functions in :mod:`ropemodel.papers` call these, so one function per
published equation serves scalar checks, vectorised numpy evaluation and the
symbolic CasADi model.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

_CASADI = (ca.SX, ca.MX, ca.DM)


def _is_casadi(*args) -> bool:
    return any(isinstance(a, _CASADI) for a in args)


def _unary(np_fun, ca_fun):
    def f(x):
        if _is_casadi(x):
            return ca_fun(x)
        if isinstance(x, (int, float)):   # a Python number stays a Python float
            return float(np_fun(x))
        return np_fun(x)

    f.__name__ = np_fun.__name__
    f.__doc__ = f"{np_fun.__name__} of a float, numpy array or CasADi expression."
    return f


sin = _unary(np.sin, ca.sin)
cos = _unary(np.cos, ca.cos)
exp = _unary(np.exp, ca.exp)
log = _unary(np.log, ca.log)
log1p = _unary(np.log1p, ca.log1p)
expm1 = _unary(np.expm1, ca.expm1)
sqrt = _unary(np.sqrt, ca.sqrt)
fabs = _unary(np.abs, ca.fabs)


def _scalar(out, *args):
    """A Python float when every argument is a Python (or numpy) scalar, as the unary functions give."""
    return float(out) if all(np.ndim(a) == 0 for a in args) else out


def if_else(cond, a, b):
    """``a`` where ``cond`` else ``b``.  Both branches are evaluated: keep each safe."""
    if _is_casadi(cond, a, b):
        return ca.if_else(cond, a, b)
    return _scalar(np.where(cond, a, b), cond, a, b)


def fmax(a, b):
    """Element-wise maximum."""
    return ca.fmax(a, b) if _is_casadi(a, b) else _scalar(np.maximum(a, b), a, b)


def fmin(a, b):
    """Element-wise minimum."""
    return ca.fmin(a, b) if _is_casadi(a, b) else _scalar(np.minimum(a, b), a, b)
