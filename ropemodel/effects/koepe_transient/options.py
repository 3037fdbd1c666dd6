"""``[numerics]`` options of the Koepe transient (model ``koepe``); the same names and checks as the winch's."""

from __future__ import annotations

from ropemodel.effects.base import choice, define_numerics, positive_number, whole_number
from ropemodel.effects.koepe import MODEL

define_numerics(MODEL, "segments", 8, "Kelvin-Voigt elements per head-rope span (dynamics = braking or start)",
                whole_number(1, 200))
# below ~1e-13 a double cannot hold the requested accuracy (SUNDIALS: "too much accuracy requested")
define_numerics(MODEL, "sim_rtol", 1e-8, "relative tolerance of the transient's integrator",
                positive_number(1e-13, 1e-2))
define_numerics(MODEL, "sim_dt", 0.01, "output step of the transient's history [s]", positive_number(0.0, 10.0))
define_numerics(MODEL, "sim_integrator", "cvodes", "CasADi integrator of the transient (BDF: cvodes, idas)",
                choice("cvodes", "idas"))
