"""Load curves of a capstan scene: K(F_T), Δα(F_T) and the rest from 0 to a maximum load."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ropemodel.numerics.capstan_rotation import RTOL, STEPS, check_wrap
from ropemodel.errors import InputError, SolveError
from ropemodel.problem import Problem
from ropemodel.scene import Scene, SceneLike, as_scene
from ropemodel.sweeps.files import check_size
from ropemodel.sweeps.points import MAX_AXIS
from ropemodel.units import label, to_si

#: columns of a load curve, in this order (the load first)
CURVE_OUTPUTS = ("T", "K", "K_ti", "K_sl", "delta", "delta_alpha", "alpha_1", "alpha_2", "theta_s1", "theta_s2",
                 "regime", "delta_error")


def reads(scene: Scene) -> tuple[set[str], dict[str, str]]:
    """What a load curve of ``scene`` is computed from, and what it sets itself (the load: F_T, or T = 2 R F_T)."""
    axis = "the curve's loads run from --from (F_min) to --to (F_max)"
    return scene.built.inputs_of(), {"F_T": axis, "T": axis}


def load_curve(scene: SceneLike, F_max: float | str, n: int = 201, F_min: float | str = 0.0,
               display: bool = False) -> pd.DataFrame:
    """Load curve of a capstan cable drive: its outputs at ``n`` loads F_T from ``F_min`` to ``F_max``
    (Li et al., piecewise stiffness; ``ropemodel curve``).

    Parameters
    ----------
    scene : Scene or str or Path
        A capstan scene (either ``load`` variant: a pull F_T or a torque T).
        A TOML scene file or a built-in scene's name is loaded first (:func:`ropemodel.load_scene`).
    F_max, F_min : float or str
        Highest and lowest load F_T [N] (SI numbers, or strings with units such as ``"100 N"``),
        0 ≤ F_min < F_max.
    n : int
        Number of loads, 2 to 1e8, evenly spaced.
    display : bool
        Columns in the quantities' display units (``"K [N/mm]"``, ``"delta_alpha [deg]"``)
        instead of SI.

    Returns
    -------
    pandas.DataFrame
        One row per load; columns labelled with units: ``"F_T [N]"``, ``"T [N*m]"``, ``"K [N/m]"``
        (equivalent stiffness), ``"K_ti [N/m]"``, ``"K_sl [N/m]"`` (tight and slack sides),
        ``"delta [m]"``, ``"delta_alpha [rad]"``, ``"alpha_1 [rad]"``, ``"alpha_2 [rad]"``,
        ``"theta_s1 [rad]"``, ``"theta_s2 [rad]"``, ``"regime [-]"`` (1 to 4), ``"delta_error [-]"``
        (the rotation's estimated relative error).

    Raises
    ------
    InputError
        Not a capstan scene, a bad load range or ``n``, a load that would unwrap the slack side
        (α2 ≤ 0).
    SolveError
        A load without a finite solution.

    Examples
    --------
    The drive of Li et al.'s experiment: at no load the wrap sticks and each free side is a spring
    EA/L = 50 kN / 0.36 m = 138.89 N/mm; at 100 N the slack side has let go (regime 4):

    >>> import ropemodel as rm
    >>> c = rm.load_curve(rm.load_scene("capstan_li_experiment"), "100 N", n=3, display=True)
    >>> c[["F_T [N]", "K [N/mm]", "K_sl [N/mm]", "regime [-]"]].round(2)
       F_T [N]  K [N/mm]  K_sl [N/mm]  regime [-]
    0      0.0    277.78       138.89         1.0
    1     50.0    197.55        98.85         3.0
    2    100.0     98.57         0.00         4.0
    """
    scene = as_scene(scene)
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
    for end in (0, -1):   # ranges and rules at both ends: the unwrap check at F_max, L = 0 at F_T = 0
        scene.built.validate({**p, **{k: v[end] for k, v in columns.items()}})
    out = problem.evaluate(columns)
    values = {**columns, "F_T": F, **{k: np.asarray(v) for k, v in out.items()}}
    bad = [k for k, v in values.items() if not np.all(np.isfinite(v))]
    if bad:
        raise SolveError(f"non-finite {', '.join(bad)} on the load curve")
    last = int(np.argmin(values["alpha_2"]))
    if values["alpha_2"][last] <= 0:
        check_wrap(F[last], values["delta"][last], p["mu"], p["EA"], p["R"], p["L"], p["alpha_0"], p["F_p"],
                   scene.effects["stiffness"], scene.numerics.get("steps", STEPS),
                   scene.numerics.get("sharpness", 30.0), scene.numerics.get("rtol", RTOL))
    q = scene.built.quantities
    data = {}
    for name in ("F_T",) + CURVE_OUTPUTS:
        unit = q[name].display_unit if display else q[name].unit
        data[label(name, unit)] = q[name].to_display(values[name]) if display else values[name]
    return pd.DataFrame(data)
