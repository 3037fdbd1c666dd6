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
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

import casadi as ca
import numpy as np
import pandas as pd

from ropemodel.numerics.capstan_rotation import ARGS, rotation_function
from ropemodel.errors import InputError, SolveError
from ropemodel.units import factor

FITTABLE = ("mu", "EA", "F_p", "L")
SINGULAR = 1e-8
#: IPOPT statuses taken as converged; "acceptable" happens where the optimum sits on a kink of the
#: published law (a data point at a regime switch of the estimate), where the gradient jumps.
CONVERGED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
REL_SE_LIMIT = 0.5
_COL = re.compile(r"^\s*(?P<name>[A-Za-z_][A-Za-z_0-9]*)\s*(\[(?P<unit>[^\]]*)\])?\s*$")
_UNITS = {"F_T": "N", "T": "N*m", "delta_alpha": "rad"}


def read_data(data, R: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Loads F_T [N] and rotations Δα [rad] from a DataFrame or a CSV file.

    Columns: a load ``F_T`` (or a torque ``T``, converted with F_T = T/(2R), R [m]) and a
    rotation ``delta_alpha``, each optionally with a unit in brackets (``"F_T [N]"``,
    ``"delta_alpha [deg]"``); without a unit, SI.
    """
    if isinstance(data, (str, Path)):
        try:
            data = pd.read_csv(data)
        except (OSError, pd.errors.ParserError, UnicodeDecodeError) as exc:
            raise InputError(f"cannot read data file {data}: {exc}") from None
    if not isinstance(data, pd.DataFrame):
        raise InputError("identification data must be a pandas DataFrame or a CSV file")
    cols = {}
    for c in data.columns:
        m = _COL.match(str(c))
        if m and m["name"] in _UNITS:
            cols[m["name"]] = (c, (m["unit"] or _UNITS[m["name"]]).strip())
    if "delta_alpha" not in cols or not ({"F_T", "T"} & set(cols)):
        raise InputError(f"identification data need columns F_T (or T) and delta_alpha, e.g. 'F_T [N]' and "
                         f"'delta_alpha [deg]'; got {', '.join(map(str, data.columns))}")

    def column(name):
        col, unit = cols[name]
        try:
            f = factor(unit, _UNITS[name])
        except Exception:
            raise InputError(f"column {col!r}: cannot convert {unit!r} to {_UNITS[name]}") from None
        v = pd.to_numeric(data[col], errors="coerce").to_numpy(dtype=float) * f
        if not np.all(np.isfinite(v)):
            raise InputError(f"column {col!r} has missing or non-numeric values")
        return v

    if "F_T" in cols:
        F = column("F_T")
    else:
        if R is None:
            raise InputError("torque data need the wheel radius R to convert T to F_T = T/(2R)")
        F = column("T") / (2.0 * R)
    if np.any(F < 0):
        raise InputError("loads F_T must be >= 0")
    return F, column("delta_alpha")


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


def identify(scene, data, fit=("mu", "EA"), sigma: float | None = None, variant: str | None = None,
             ipopt_options: dict | None = None) -> Identification:
    """Least-squares fit of ``fit`` (from mu, EA, F_p, L) to measured (F_T, Δα) points.

    scene: capstan scene giving the other parameters and the starting values; data: DataFrame
    or CSV path (:func:`read_data`); sigma [rad]: known noise of Δα (else estimated from the
    residuals); variant: stiffness law (default: the scene's).  Returns :class:`Identification`.
    """
    if scene.model != "capstan":
        raise InputError(f"identification is for capstan scenes; this scene's model is {scene.model!r}")
    fit = tuple(fit)
    for name in fit:
        if name not in FITTABLE:
            raise InputError(f"cannot fit {name!r}; fittable parameters: {', '.join(FITTABLE)}")
    if len(set(fit)) != len(fit) or not fit:
        raise InputError("fit needs one or more distinct parameters")
    p0 = dict(scene.parameters)
    F, meas = read_data(data, p0.get("R"))
    n, k = F.size, len(fit)
    if n <= k:
        raise InputError(f"{n} data points cannot determine {k} parameters")
    variant = variant or scene.effects["stiffness"]
    fun = rotation_function(variant, scene.numerics.get("steps", 32), scene.numerics.get("sharpness", 30.0))
    theta0 = np.array([p0[name] for name in fit])
    if np.any(theta0 <= 0):
        raise InputError("starting values (the scene's) of fitted parameters must be > 0")
    x = ca.MX.sym("x", k)  # ln(θ/θ0): positive parameters over decades, well scaled
    theta = ca.exp(x) * ca.DM(theta0)
    env = {name: ca.MX(p0[name]) for name in ARGS[1:]}
    env.update({name: theta[j] for j, name in enumerate(fit)})
    delta = fun.map(n, "thread", 2)(ca.DM(F).T, *[env[a] for a in ARGS[1:]])
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
    opts = {"ipopt.print_level": 0, "print_time": False, "show_eval_warnings": False, "ipopt.sb": "yes", "ipopt.tol": 1e-8, "ipopt.acceptable_tol": 1e-4, "ipopt.acceptable_iter": 4,
            "ipopt.max_iter": 100, "hess_lag": hess}
    opts.update({f"ipopt.{a}": b for a, b in (ipopt_options or {}).items()})
    solver = ca.nlpsol("capstan_fit", "ipopt", nlp, opts)
    bound = np.full(k, math.log(1e6))
    t0 = time.perf_counter()
    sol = solver(x0=np.zeros(k), lbx=-bound, ubx=bound)
    seconds = time.perf_counter() - t0
    stats = solver.stats()
    x_hat = np.asarray(sol["x"]).ravel()
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
