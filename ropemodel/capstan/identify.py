"""Identify μ and EA (optionally F_p, L) of a capstan drive from measured (F_T, Δα) points.

Least squares on the rotation, Δα_i = δ(F_T,i; θ)/R (:mod:`ropemodel.numerics.capstan_rotation`,
event-located and differentiable), solved with IPOPT through CasADi ``nlpsol`` in
the variables ln(θ_j/θ_j,0) (θ_0, the start, from the scene; bounds θ_0·10^{±6}).  Standard errors come from the
Gauss–Newton covariance s²(JᵀJ)⁻¹ at the optimum (IPOPT is given the same
Gauss–Newton Hessian, so the integrator is differentiated once, not twice), J = ∂Δα/∂θ, s² = RSS/(n − p)
(or σ² when the measurement noise σ is known).

Identifiability: the Jacobian scaled by the estimates, J·diag(θ̂), is decomposed;
a singular value below ``1e-8`` of the largest marks a direction the data cannot
determine, and the parameters that dominate it are flagged; a parameter whose
relative standard error exceeds 50 % is flagged as not determined either.  Both
are reported in :attr:`Identification.messages`, never silently.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import casadi as ca
import numpy as np
import pandas as pd

from ropemodel.numerics.capstan_rotation import ARGS, RTOL, STEPS, rotation, rotation_function, unwrap_load
from ropemodel.errors import InputError, Problems, SolveError
from ropemodel.scene import Scene, SceneLike, as_scene
from ropemodel.units import factor

FITTABLE = ("mu", "EA", "F_p", "L")
SINGULAR = 1e-8
#: IPOPT statuses taken as converged; "acceptable" happens where the optimum sits on a kink of the
#: published law (a data point at a regime switch of the estimate), where the gradient jumps.
CONVERGED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
REL_SE_LIMIT = 0.5
_UNITS = {"F_T": "N", "T": "N*m", "delta_alpha": "rad"}
_SHOWN = {"F_T": "N", "T": "N*m", "delta_alpha": "deg"}


def read_data(data, R: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Loads F_T [N] and rotations Δα [rad] from a DataFrame or a CSV (or Parquet) file.

    Columns: a load ``F_T`` (or a torque ``T``, converted with F_T = T/(2R), R [m]) and a
    rotation ``delta_alpha``, each with its unit in brackets (``"F_T [N]"``, ``"T [N*m]"``,
    ``"delta_alpha [deg]"``); other columns are ignored.  In a file the units are required (a
    header without one is refused with the fix); in a DataFrame built in Python a column without
    a unit holds SI values.  Every problem of the columns is listed at once; a value that is not a
    finite number, or a negative load, is refused naming its row.
    """
    from ropemodel.sweeps.points import read_points

    if isinstance(data, (str, Path)):
        data = read_points(data, what="identification data file")
    if not isinstance(data, pd.DataFrame):
        raise InputError("identification data must be a pandas DataFrame or a CSV file")
    cols = _data_columns(data)
    if "F_T" in cols:
        F = _data_column(data, *cols["F_T"], "F_T")
    else:
        if R is None:
            raise InputError("torque data need the wheel radius R to convert T to F_T = T/(2R)")
        F = _data_column(data, *cols["T"], "T") / (2.0 * R)
    negative = np.flatnonzero(F < 0)
    if negative.size:
        i = int(negative[0])
        raise InputError(f"identification data row {i + 1}: load F_T = {F[i]:.6g} N; loads F_T must be >= 0")
    return F, _data_column(data, *cols["delta_alpha"], "delta_alpha")


def _data_columns(data: pd.DataFrame) -> dict[str, tuple[str, str | None]]:
    """name → (column, unit or None) of the identification columns; every problem at once."""
    from ropemodel.sweeps.points import split_label

    cols: dict[str, tuple[str, str | None]] = {}
    found = Problems(" in the identification data")
    for c in data.columns:
        name, unit = split_label(str(c))
        if name not in _UNITS:
            continue
        if name in cols:
            found.add(f"{name} is given twice: columns {cols[name][0]!r} and {c!r}")
            continue
        if unit is None and data.attrs.get("source"):
            found.add(f"column {c!r} has no unit: label it with its unit, e.g. \"{name} [{_SHOWN[name]}]\"")
        cols[name] = (c, unit)
    if "delta_alpha" not in cols or not ({"F_T", "T"} & set(cols)):
        found.add(f"identification data need columns F_T (or T) and delta_alpha, e.g. 'F_T [N]' and "
                  f"'delta_alpha [deg]'; got {', '.join(map(str, data.columns))}")
    if {"F_T", "T"} <= set(cols):
        found.add("identification data give both a load F_T and a torque T: keep one")
    found.raise_if_any()
    if len(data) == 0:
        raise InputError("the identification data have a header but no rows")
    return cols


def _data_column(data: pd.DataFrame, col, unit: str | None, name: str) -> np.ndarray:
    from ropemodel.sweeps.points import finite_column

    try:
        f = factor(unit.strip(), _UNITS[name]) if unit is not None else 1.0
    except Exception:
        raise InputError(f"column {col!r}: cannot convert {unit!r} to {_UNITS[name]}") from None
    return finite_column(col, data[col], "identification data column") * f


@dataclass
class Identification:
    """Result of :func:`identify` (SI values)."""

    estimates: dict[str, float]
    standard_errors: dict[str, float]
    covariance: pd.DataFrame
    identifiable: dict[str, bool]
    messages: list[str]
    status: str
    iterations: int
    seconds: float
    rss: float
    n_points: int
    residuals: np.ndarray = field(repr=False)
    singular_values: np.ndarray = field(repr=False)

    @property
    def ok(self) -> bool:
        """IPOPT converged and every fitted parameter is determined by the data."""
        return self.status in CONVERGED and all(self.identifiable.values())

    def table(self) -> pd.DataFrame:
        """One row per parameter: estimate, standard error, relative SE, identifiable."""
        rows = []
        for k, v in self.estimates.items():
            se = self.standard_errors[k]
            rows.append({"parameter": k, "estimate": v, "standard_error": se,
                         "relative_se": se / abs(v) if v else math.inf, "identifiable": self.identifiable[k]})
        return pd.DataFrame(rows)

    def to_dict(self) -> dict:
        return {"estimates": self.estimates, "standard_errors": _finite(self.standard_errors),
                "identifiable": self.identifiable, "messages": self.messages, "status": self.status,
                "iterations": self.iterations, "rss": self.rss, "n_points": self.n_points}


def _finite(d):
    return {k: (v if math.isfinite(v) else None) for k, v in d.items()}


def reads(scene: Scene, fit: Sequence[str] = ("mu", "EA")) -> tuple[set[str], dict[str, str]]:
    """What an identification reads from ``scene`` (the rotation's parameters), and what it takes elsewhere:
    the loads are the data's, the fitted parameters' values only start the fit."""
    chosen = {k: "the loads are the data's" for k in ("F_T", "T")}
    chosen.update({k: "the fit starts from it; the estimate is the data's" for k in fit})
    return set(ARGS), chosen


def identify(scene: SceneLike, data: pd.DataFrame | str | Path, fit: Sequence[str] = ("mu", "EA"),
             sigma: float | None = None, variant: str | None = None,
             ipopt_options: dict | None = None) -> Identification:
    """Identify a capstan drive's parameters from a measured load curve: least squares by IPOPT
    with exact derivatives, standard errors from the Jacobian (``ropemodel identify``).

    Parameters
    ----------
    scene : Scene or str or Path
        A capstan scene: the parameters not fitted, and the starting values of those fitted.
        A TOML scene file or a built-in scene's name is loaded first (:func:`ropemodel.load_scene`).
    data : pandas.DataFrame or str or Path
        Measured points: a load ``"F_T [N]"`` (or a torque ``"T [N*m]"``) and a rotation
        ``"delta_alpha [rad]"`` (any unit in brackets; in a file the units are required;
        :func:`read_data`).
    fit : sequence of str
        Parameters to fit, from ``mu`` [-], ``EA`` [N], ``F_p`` [N], ``L`` [m].
    sigma : float, optional
        Known standard deviation of the measured Δα [rad], > 0 (default: estimated from the
        residuals).
    variant : str, optional
        Stiffness law (default: the scene's ``stiffness``).
    ipopt_options : dict, optional
        Options passed to IPOPT.

    Returns
    -------
    Identification
        ``estimates`` and ``standard_errors`` (SI: mu [-], EA [N], F_p [N], L [m]),
        ``covariance``, ``identifiable`` (per parameter: determined by the data), ``ok``,
        ``status``, ``rss`` [rad²], ``n_points``; ``table()`` gives one row per parameter.

    Raises
    ------
    InputError
        Not a capstan scene, an unknown parameter to fit, bad data (every problem of its columns
        at once), a load that would unwrap the slack side.
    SolveError
        IPOPT found no fit.

    Examples
    --------
    Fit back μ and EA from a load curve computed with μ = 0.12 and EA = 40 kN (no noise), starting
    from the scene's μ = 0.25 and EA = 50 kN:

    >>> import ropemodel as rm
    >>> scene = rm.load_scene("capstan_li_experiment")
    >>> truth = scene.with_values({"mu": 0.12, "EA": "40 kN"})
    >>> curve = rm.load_curve(truth, "100 N", n=21)
    >>> fit = rm.identify(scene, curve[["F_T [N]", "delta_alpha [rad]"]])
    >>> round(fit.estimates["mu"], 6), round(fit.estimates["EA"])
    (0.12, 40000)
    >>> fit.ok
    True
    """
    scene = as_scene(scene)
    if scene.model != "capstan":
        raise InputError(f"identification is for capstan scenes; this scene's model is {scene.model!r}")
    fit = tuple(fit)
    for name in fit:
        if name not in FITTABLE:
            raise InputError(f"cannot fit {name!r}; fittable parameters: {', '.join(FITTABLE)}")
    if len(set(fit)) != len(fit) or not fit:
        raise InputError("fit needs one or more distinct parameters")
    if sigma is not None and (isinstance(sigma, bool) or not isinstance(sigma, (int, float))
                              or not math.isfinite(sigma) or sigma <= 0):
        raise InputError(f"sigma = {sigma!r}: the noise of delta_alpha must be a finite number > 0 [rad] "
                         f"(or None: estimated from the residuals)")
    p0 = dict(scene.parameters)
    F, meas = read_data(data, p0.get("R"))
    n, k = F.size, len(fit)
    if n <= k:
        raise InputError(f"{n} data points cannot determine {k} parameters")
    _check_information(F, fit)
    variant = variant or scene.effects["stiffness"]
    _check_unwrap(scene, F, meas, variant)
    fun = rotation_function(variant, scene.numerics.get("steps", STEPS), scene.numerics.get("sharpness", 30.0),
                            scene.numerics.get("rtol", RTOL))
    theta0 = np.array([p0[name] for name in fit])
    if np.any(theta0 <= 0):
        raise InputError("starting values (the scene's) of fitted parameters must be > 0")
    solver, pred, x = _least_squares(fun, F, meas, p0, fit, theta0, ipopt_options)
    bound = np.full(k, math.log(1e6))
    t0 = time.perf_counter()
    sol = solver(x0=np.zeros(k), lbx=-bound, ubx=bound)
    seconds = time.perf_counter() - t0
    stats = solver.stats()
    x_hat = np.asarray(sol["x"]).ravel()
    _check_inside(fit, x_hat, bound, theta0)
    est = np.exp(x_hat) * theta0
    jac = ca.Function("J", [x], [pred, ca.jacobian(pred, x)])
    pred_hat, J = (np.asarray(a) for a in jac(x_hat))
    pred_hat = pred_hat.ravel()
    J = J / est  # d pred / d theta (chain rule through θ = θ0·e^x)
    if not (np.all(np.isfinite(pred_hat)) and np.all(np.isfinite(J))):
        raise SolveError("the fitted model is not finite at the estimate")
    resid = meas - pred_hat
    rss = float(resid @ resid)
    s2 = sigma ** 2 if sigma is not None else rss / (n - k)
    return _summarise(fit, est, J, s2, resid, rss, n, stats, seconds)


def _least_squares(fun, F: np.ndarray, meas: np.ndarray, p0: dict, fit, theta0: np.ndarray, ipopt_options):
    """(IPOPT solver, predicted rotations, decision variable x = ln(θ/θ0)) of the fit."""
    k = len(fit)
    x = ca.MX.sym("x", k)  # ln(θ/θ0): positive parameters over decades, well scaled
    theta = ca.exp(x) * ca.DM(theta0)
    env = {name: ca.MX(p0[name]) for name in ARGS[1:]}
    env.update({name: theta[j] for j, name in enumerate(fit)})
    delta = fun.map(F.size, "thread", 2)(ca.DM(F).T, *[env[a] for a in ARGS[1:]])[0]
    pred = (delta / env["R"]).T
    y_scale = max(float(np.sqrt(np.mean(meas ** 2))), 1e-300)
    r = (pred - ca.DM(meas)) / y_scale
    nlp = {"x": x, "f": 0.5 * ca.sumsqr(r)}
    # Gauss–Newton Hessian of the Lagrangian, lam_f·JᵀJ (upper triangle): no second derivatives
    # of the integrator are needed, and it is the information matrix the covariance uses.
    Jr = ca.jacobian(r, x)
    lam_f, lam_g, p_nlp = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", 0), ca.MX.sym("p", 0)
    hess = ca.Function("nlp_hess_l", [x, p_nlp, lam_f, lam_g], [ca.triu(lam_f * (Jr.T @ Jr))],
                       ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])
    opts: dict[str, Any] = {"ipopt.print_level": 0, "print_time": False, "show_eval_warnings": False,
                            "calc_lam_p": False, "ipopt.sb": "yes", "ipopt.tol": 1e-8, "ipopt.acceptable_tol": 1e-4,
                            "ipopt.acceptable_iter": 4, "ipopt.max_iter": 100, "hess_lag": hess}
    opts.update({f"ipopt.{a}": b for a, b in (ipopt_options or {}).items()})
    return ca.nlpsol("capstan_fit", "ipopt", nlp, opts), pred, x


def _check_information(F: np.ndarray, fit) -> None:
    """:class:`InputError` if the loads cannot determine ``fit``: each distinct load F_T > 0 gives one
    equation (a repeated row only repeats it, and at F_T = 0 the rotation is 0 whatever the parameters)."""
    loads = np.unique(F[F > 0])
    if loads.size >= len(fit):
        return
    zeros, repeats = int(np.count_nonzero(F == 0)), int(np.count_nonzero(F > 0)) - loads.size
    raise InputError(f"the identification data hold {loads.size} distinct load{'s' if loads.size != 1 else ''} "
                     f"F_T > 0 in {F.size} rows ({repeats} repeat a load, {zeros} at F_T = 0, where the rotation "
                     f"is 0 whatever the parameters): fitting {', '.join(fit)} needs at least {len(fit)} distinct "
                     f"loads > 0; measure at more loads, or fit fewer (--fit)")


def _check_unwrap(scene, F: np.ndarray, meas: np.ndarray, variant: str) -> None:
    """:class:`InputError` naming the first data row beyond the unwrap limit (the slack side unwrapped,
    α2 ≤ 0, where the model does not apply): a load beyond the limit at the scene's parameters (the
    fit's start), or a measured rotation of at least the initial wrap α0."""
    p, o = scene.parameters, scene.numerics
    args = (p["mu"], p["EA"], p["R"], p["L"], p["alpha_0"], p["F_p"])
    settings = (variant, o.get("steps", STEPS), o.get("sharpness", 30.0), o.get("rtol", RTOL))
    largest = rotation(float(F.max()), *args, *settings) if F.size else 0.0
    if math.isfinite(largest) and largest / p["R"] < p["alpha_0"] and not np.any(meas >= p["alpha_0"]):
        return   # the rotation grows with the load: the largest load does not unwrap, so none does
    limit = unwrap_load(*args, *settings)
    beyond = np.flatnonzero((F >= limit) | (meas >= p["alpha_0"]))
    if beyond.size:
        i = int(beyond[0])
        raise InputError(
            f"identification data row {i + 1}: F_T = {F[i]:.6g} N, delta_alpha = {math.degrees(meas[i]):.6g} deg is "
            f"beyond the unwrap limit (the slack side unwraps, alpha_2 <= 0, and the model no longer applies; "
            f"{beyond.size} of {F.size} rows): the largest valid load at the scene's values is F_T < {limit:.6g} N, "
            f"and a rotation must stay below alpha_0 = {math.degrees(p['alpha_0']):.6g} deg")


def _check_inside(fit, x_hat: np.ndarray, bound: np.ndarray, theta0: np.ndarray) -> None:
    """:class:`SolveError` if an estimate ran to the edge of the search range θ0·10^{±6}: the data do
    not determine it, and the value there is the range's, not the data's."""
    edge = np.flatnonzero(np.abs(x_hat) >= bound * (1.0 - 1e-6))
    if edge.size:
        j = int(edge[0])
        raise SolveError(f"the fit of {fit[j]} ran to the edge of its search range "
                         f"({math.exp(x_hat[j]) * theta0[j]:.3g}, "
                         f"10^{'+' if x_hat[j] > 0 else '-'}6 times the scene's value): the data do not determine it; "
                         f"check their units and signs, or start from other values")


def _summarise(fit, est, J, s2, resid, rss, n, stats, seconds) -> Identification:
    Js = J * est  # sensitivity to relative changes
    sv = np.linalg.svd(Js, compute_uv=False) if Js.size else np.zeros(0)
    _, _, Vt = np.linalg.svd(Js)
    messages, identifiable = [], {name: True for name in fit}
    smax = sv[0] if sv.size and sv[0] > 0 else 0.0
    for i, s in enumerate(sv):
        if smax == 0.0 or s < SINGULAR * smax:
            v = np.abs(Vt[i])
            names = [fit[j] for j in range(len(fit)) if v[j] > 0.3]
            for name in names:
                identifiable[name] = False
            messages.append(f"the data cannot determine {' and '.join(names)} "
                            f"(singular information matrix: scaled singular value {s:.3g} of {smax:.3g})")
    info = J.T @ J
    try:
        cov = s2 * np.linalg.inv(info) if all(identifiable.values()) else s2 * np.linalg.pinv(info)
    except np.linalg.LinAlgError:
        cov = np.full((len(fit), len(fit)), np.inf)
    se = {name: float(math.sqrt(cov[j, j])) if cov[j, j] >= 0 else math.inf for j, name in enumerate(fit)}
    for name in fit:
        if not identifiable[name]:
            se[name] = math.inf
        elif se[name] > REL_SE_LIMIT * abs(est[fit.index(name)]):
            identifiable[name] = False
            messages.append(f"{name} is not determined by the data: standard error {se[name]:.3g} is "
                            f"{se[name] / abs(est[fit.index(name)]):.0%} of the estimate")
    status = stats.get("return_status", "unknown")
    if status not in CONVERGED:
        messages.append(f"IPOPT did not converge: {status}")
    return Identification(
        estimates={name: float(est[j]) for j, name in enumerate(fit)}, standard_errors=se,
        covariance=pd.DataFrame(cov, index=list(fit), columns=list(fit)), identifiable=identifiable,
        messages=messages, status=status, iterations=int(stats.get("iter_count", -1)), seconds=seconds,
        rss=rss, n_points=n, residuals=resid, singular_values=sv)
