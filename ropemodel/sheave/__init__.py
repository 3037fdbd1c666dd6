"""Analyses of the lined-sheave model (Hajduk 1992): tension along the arc, batch evaluation.

* :func:`distribution` — S along the arc of a sheave scene as a DataFrame;
* :func:`closed_log_ratio`, :func:`ode_log_ratio` — ln(S/S_0) over many points, by the
  exact implicit solution or by integration (:mod:`ropemodel.numerics.hajduk_integrators`).
"""

from ropemodel.sheave.batch import closed_log_ratio, distribution, ode_log_ratio

__all__ = ["closed_log_ratio", "distribution", "ode_log_ratio"]
