"""Load curves of a capstan scene: K(F_T), Δα(F_T) and the rest from 0 to a maximum load."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ropemodel.numerics.capstan_rotation import RTOL, STEPS, check_wrap
from ropemodel.errors import InputError, SolveError
from ropemodel.problem import Problem
from ropemodel.sweep.files import check_size
from ropemodel.sweep.points import MAX_AXIS
from ropemodel.units import label, to_si

#: columns of a load curve, in this order (the load first)
CURVE_OUTPUTS = ("T", "K", "K_ti", "K_sl", "delta", "delta_alpha", "alpha_1", "alpha_2", "theta_s1", "theta_s2",
                 "regime", "delta_error")


def load_curve(scene, F_max, n: int = 201, F_min=0.0, display: bool = False) -> pd.DataFrame:
    """The scene's outputs at ``n`` loads F_T evenly spaced from ``F_min`` to ``F_max``.

    scene: a capstan :class:`~ropemodel.scene.Scene` (either load variant); F_max, F_min:
    loads F_T [N] (numbers in SI or strings with units, e.g. ``"100 N"``); n ≥ 2.
    Returns a DataFrame whose column labels carry units: ``"F_T [N]"``, ``"K [N/m]"``,
    ``"delta_alpha [rad]"``, ... in SI, or in the quantities' display units
    (``"K [N/mm]"``, ``"delta_alpha [deg]"``) with ``display=True``.
    Raises :class:`InputError` if a load would unwrap the slack side (α2 ≤ 0).
    """
    if scene.model != "capstan":
        raise InputError(f"load curves are for capstan scenes; this scene's model is {scene.model!r}")
    F_max = to_si("F_max", F_max, "N", bare="si")   # numbers SI (Python); text carries its unit
    F_min = to_si("F_min", F_min, "N", bare="si")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 2 <= n <= MAX_AXIS:
        shown = f"{str(n)[:20]}..." if len(str(n)) > 20 else repr(n)
        raise InputError(f"n = {shown}: a load curve needs a whole number of points 2 <= n <= {MAX_AXIS:.0e}")
    check_size(int(n), len(CURVE_OUTPUTS) + 2, what="a load curve is kept in memory")
    if not 0.0 <= F_min < F_max:
        raise InputError(f"load range [{F_min:g}, {F_max:g}] N: need 0 <= F_min < F_max")
    F = np.linspace(F_min, F_max, int(n))
    p = scene.parameters
    torque = scene.effects.get("load") == "torque"
    problem = Problem(scene)
    columns = {"T": 2.0 * p["R"] * F} if torque else {"F_T": F}
    scene.built.validate({**p, **{k: v[-1] for k, v in columns.items()}})  # ranges and the unwrap check at F_max
    out = problem.evaluate(columns)
    values = {**columns, "F_T": F, **{k: np.asarray(v) for k, v in out.items()}}
    bad = [k for k, v in values.items() if not np.all(np.isfinite(v))]
    if bad:
        raise SolveError(f"non-finite {', '.join(bad)} on the load curve")
    last = int(np.argmin(values["alpha_2"]))
    if values["alpha_2"][last] <= 0:
        check_wrap(F[last], values["delta"][last], p["mu"], p["EA"], p["R"], p["L"], p["alpha_0"], p["F_p"],
                   scene.effects["stiffness"], scene.numerics.get("steps", STEPS), scene.numerics.get("sharpness", 30.0),
                   scene.numerics.get("rtol", RTOL))
    q = scene.built.quantities
    data = {}
    for name in ("F_T",) + CURVE_OUTPUTS:
        unit = q[name].display_unit if display else q[name].unit
        data[label(name, unit)] = q[name].to_display(values[name]) if display else values[name]
    return pd.DataFrame(data)
