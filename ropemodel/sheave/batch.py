"""Vectorised evaluation of the lining tension: closed form and ODE over many points."""

from __future__ import annotations

import numpy as np

from ropemodel.numerics.hajduk_integrators import RATIO_INPUTS, mapped_log_ratio_function
from ropemodel.papers import hajduk1992 as hj


def closed_log_ratio(mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0):
    """ln(S/S_0) from the exact solution (Hajduk 1992 eq. (19)) for numpy arrays (broadcast)."""
    return hj.log_tension_ratio(*np.broadcast_arrays(*(np.asarray(a, float) for a in
                                                       (mu, alpha, q_R, k_R, q_T, k_T))))


def ode_log_ratio(mu, alpha, q_R, k_R, q_T=0.0, k_T=1.0, beta=0.0, plugin="rk4", state="log",
                  rtol=1e-7, parallel=1):
    """ln(S/S_0) by integration for numpy arrays (broadcast), one CasADi ``map`` call.

    mu [-] (friction at zero pressure if beta > 0), alpha [rad], q_R, q_T = Q S_0 [-],
    k_R, k_T = λω [rad], beta = S_0/(p_c R a) [-] (Thirion friction; 0: constant μ).
    """
    cols = np.broadcast_arrays(*(np.asarray(a, float) for a in (mu, alpha, q_R, k_R, q_T, k_T, beta)))
    shape = cols[0].shape
    n = max(cols[0].size, 1)
    fm = mapped_log_ratio_function(plugin, state, float(rtol), n, int(parallel))
    out = fm(*[c.reshape(1, n) for c in cols])
    return np.asarray(out).reshape(shape)


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


__all__ = ["RATIO_INPUTS", "closed_log_ratio", "distribution", "ode_log_ratio"]
