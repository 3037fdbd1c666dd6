"""``[numerics]`` options of the transient (model ``winch``)."""

from __future__ import annotations

from ropemodel.effects.base import choice, define_numerics, positive_number
from ropemodel.effects.transient.base import MODEL
from ropemodel.errors import InputError


def _int_check(low: int, high: int):
    def check(key, value):
        if isinstance(value, bool) or not isinstance(value, int) or not (low <= value <= high):
            raise InputError(f"numerics {key} = {value!r} must be an integer in [{low}, {high}]")
        return value

    return check


define_numerics(MODEL, "segments", 8, "Kelvin-Voigt elements per rope span (rope_elasticity = segments)",
                _int_check(1, 400))
# below ~1e-13 a double cannot hold the requested accuracy (SUNDIALS: "too much accuracy requested")
define_numerics(MODEL, "sim_rtol", 1e-8, "relative tolerance of the transient's integrator",
                positive_number(1e-13, 1e-2))
define_numerics(MODEL, "sim_dt", 0.02, "output step of the transient's history [s]", positive_number(0.0, 10.0))
define_numerics(MODEL, "sim_integrator", "cvodes", "CasADi integrator of the transient (BDF: cvodes, idas)",
                choice("cvodes", "idas"))
define_numerics(MODEL, "sizing", "static", "how `ropemodel size` and the report size the winch: static (the paper's "
                "forces) or dynamic (every check through start and stop in both directions; needs a transient)",
                choice("static", "dynamic"))
