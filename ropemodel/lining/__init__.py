"""Integration of the Voigt-lining tension ODE (Hajduk 1992, eq. (5)-(6)) and batch evaluation.

* :mod:`ropemodel.lining.ode` — the right side in a stretched angle variable
  (resolves the boundary layer of width ~λω/(1+q) at α = 0 uniformly), with
  state ln s (the general ODE) or the exact invariant ln s + s C(α).
* :mod:`ropemodel.lining.integrators` — CasADi integrators (cvodes, idas,
  collocation, rk) wrapped as Functions of the physical parameters, with
  derivatives; the segment function behind the distribution S(α).
* :mod:`ropemodel.lining.batch` — vectorised evaluation of the closed form and
  of the ODE over many points, and :func:`distribution` (S along the arc as a
  DataFrame).
"""

from ropemodel.lining.batch import closed_log_ratio, distribution, ode_log_ratio
from ropemodel.lining.integrators import INTEGRATORS, log_ratio_function, segment_function

__all__ = ["INTEGRATORS", "closed_log_ratio", "distribution", "log_ratio_function", "ode_log_ratio",
           "segment_function"]
