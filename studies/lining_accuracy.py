"""Lined sheave: accuracy and cost of the ODE path against scipy's solve_ivp written as a user would.

Cases: random points over the documented range (μ ∈ [0.05, 0.6], q = Q·S_0 ∈ [0, 10³] log-uniform,
λω ∈ [10⁻⁵, 10²] rad log-uniform, α ∈ [0, 10π], half anisotropic).  Error: max relative error of S
against the exact solution (Lambert W form, Newton in ln s).

* ropemodel: ``ropemodel.sheave.ode_log_ratio`` at its defaults (dopri5, rtol 1e-7), compiled to C
  (CasADi code generation, cached) where a compiler works; one batched call.
* the peer: ``scipy.integrate.solve_ivp`` on a plain numpy right side in ln S over α (the ODE as
  Hajduk eq. (5)-(6) gives it, no ropemodel code), one call per point, LSODA, DOP853 and Radau at
  several tolerances; the headline is the cheapest configuration at least as accurate as ropemodel's
  default.  Times are per point, measured in this run; only their ratio is reported.

    python studies/lining_accuracy.py [--fast]
"""

from __future__ import annotations

import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from ropemodel.sheave import closed_log_ratio, ode_log_ratio  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure  # noqa: E402

NAME = "lining_accuracy"
METHODS = ("LSODA", "DOP853", "Radau")


def cases(n: int, seed: int = 1) -> dict:
    rng = np.random.default_rng(seed)
    q = np.where(rng.random(n) < 0.1, 0.0, 10 ** rng.uniform(-6, 3, n))
    share = np.where(np.arange(n) % 2 == 1, rng.uniform(0, 1, n), 1.0)
    k_R = 10 ** rng.uniform(-5, 2, n)
    k_T = np.where(share < 1, 10 ** rng.uniform(-5, 2, n), k_R)
    return {"mu": rng.uniform(0.05, 0.6, n), "alpha": rng.uniform(0.0, 10 * np.pi, n), "q_R": q * share,
            "k_R": k_R, "q_T": q * (1 - share), "k_T": k_T}


def user_rhs(mu, qR, kR, qT, kT):
    """d(ln S)/dα as a user would type it from the paper (eq. 5-6), in numpy."""
    def f(a, y):
        s = np.exp(y[0])
        rate = qR * np.exp(-a / kR) / kR + qT * np.exp(-a / kT) / kT
        crept = qR * (1 - np.exp(-a / kR)) + qT * (1 - np.exp(-a / kT))
        return [(mu - s * rate) / (1 + s * crept)]
    return f


def scipy_point(c, i, method, rtol):
    mu, a, qR, kR, qT, kT = (c[k][i] for k in ("mu", "alpha", "q_R", "k_R", "q_T", "k_T"))
    if a == 0:
        return 0.0
    sol = solve_ivp(user_rhs(mu, qR, kR, qT, kT), (0.0, a), [0.0], method=method, rtol=rtol, atol=rtol)
    return sol.y[0, -1] if sol.success else np.nan


def _timed(fun, repeats=1):
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return out, best


def measure(n: int, n_scipy: int, rtols, repeats: int) -> pd.DataFrame:
    c = cases(n)
    ref = closed_log_ratio(**c)
    ode_log_ratio(**c)  # build and compile (cached), not timed
    y, t = _timed(lambda: ode_log_ratio(**c), repeats)
    rows = [{"method": "ropemodel dopri5 (default, rtol 1e-7)", "rtol": 1e-7,
             "max rel. error": float(np.max(np.abs(np.expm1(y - ref)))), "time per point [s]": t / n, "failures": 0}]
    _, t = _timed(lambda: closed_log_ratio(**c), repeats)
    rows.append({"method": "ropemodel closed form", "rtol": np.nan, "max rel. error": 0.0,
                 "time per point [s]": t / n, "failures": 0})
    sub = {k: v[:n_scipy] for k, v in c.items()}
    for method in METHODS:
        for rtol in rtols:
            ys, t = _timed(lambda: np.array([scipy_point(sub, i, method, rtol) for i in range(n_scipy)]))
            err = np.abs(np.expm1(ys - ref[:n_scipy]))
            rows.append({"method": f"scipy {method}", "rtol": rtol,
                         "max rel. error": float(np.nanmax(err)) if np.isfinite(err).any() else np.nan,
                         "time per point [s]": t / n_scipy, "failures": int(np.sum(~np.isfinite(ys)))})
    return pd.DataFrame(rows)


def summary(df: pd.DataFrame) -> pd.DataFrame:
    """The cheapest scipy configuration at least as accurate as ropemodel's default, and the time ratio."""
    ours = df.iloc[0]
    peers = df[df["method"].str.startswith("scipy") & (df["failures"] == 0)
               & (df["max rel. error"] <= ours["max rel. error"])]
    best = peers.loc[peers["time per point [s]"].idxmin()] if len(peers) else None
    ratio = best["time per point [s]"] / ours["time per point [s]"] if best is not None else np.nan
    return pd.DataFrame([{"ropemodel max rel. error": ours["max rel. error"],
                          "peer": f"{best['method']} rtol {best['rtol']:g}" if best is not None else "none",
                          "peer max rel. error": best["max rel. error"] if best is not None else np.nan,
                          "peer time / ropemodel time": ratio,
                          "closed form: ODE time / closed time": ours["time per point [s]"]
                          / df.iloc[1]["time per point [s]"]}])


def plot(df: pd.DataFrame, out, fast: bool) -> None:
    fig, ax = plt.subplots(figsize=(7, 5))
    for m, g in df[df["method"].str.startswith("scipy")].groupby("method"):
        ax.plot(g["max rel. error"].clip(lower=1e-16), g["time per point [s]"], "s--", label=m)
    o = df.iloc[0]
    ax.plot(o["max rel. error"], o["time per point [s]"], "k*", ms=14, label=o["method"])
    ax.axhline(df.iloc[1]["time per point [s]"], color="grey", ls=":", label="closed form")
    ax.set(xscale="log", yscale="log", xlabel="max relative error of S (vs exact solution)",
           ylabel="time per point [s] (this run; compare ratios only)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Lined sheave ODE: ropemodel (compiled) vs scipy solve_ivp, plain numpy right side", fontsize=9)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    if fast:
        df = measure(400, 12, (1e-8, 1e-10), repeats=2)
    else:
        df = measure(10000, 100, (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11), repeats=3)
    df.to_csv(out / f"{NAME}.csv", index=False)
    summary(df).to_csv(out / f"{NAME}_summary.csv", index=False)
    plot(df, out, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda d: d.to_string(index=False) + "\n\n" + summary(d).T.to_string())
