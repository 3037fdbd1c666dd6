"""What accuracy costs in time for the lined-sheave ODE: every method x tolerance, with scipy as the peer.

Cases (random, fixed seed) over the required range, split into
  easy: λω ∈ [0.1, 100] rad, q = Q S_0 ∈ [0, 1], α ∈ [0.1, 2π], μ ∈ [0.05, 0.6];
  hard: λω ∈ [1e-5, 1e-2] rad (stiff boundary layer), q ∈ [1, 1e3], α ∈ [π, 10π], μ ∈ [0.05, 0.6];
half isotropic, half anisotropic.  Error: max relative error of S at the end of the arc against
the exact solution (closed form, Newton in ln s).  Cost: wall time per point of a batched
evaluation (one CasADi ``map`` call over all points of a case set; for scipy one ``solve_ivp``
call per point, the same right side written in numpy), median of repeats, all measured in this
run.  ropemodel integrates ln S in the stretched angle (``ropemodel.numerics.hajduk_ode``); scipy gets the
same stretched right side (Radau, LSODA, DOP853), and, as a user would first write it, the
plain ODE in α with Radau ("Radau, plain α").

    python studies/lining_accuracy.py [--fast]
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from ropemodel.sheave import closed_log_ratio, ode_log_ratio  # noqa: E402
from ropemodel.numerics import hajduk_ode as lode  # noqa: E402
from ropemodel.papers import hajduk1992 as hj  # noqa: E402
from ropemodel.studykit import cli, output_dir  # noqa: E402

NAME = "lining_accuracy"
FIGURES = Path(__file__).resolve().parent / "figures"
DEFAULT = ("rk4", 1e-7)
CASADI = ("rk4", "rk", "cvodes", "idas", "collocation")
SCIPY = ("Radau", "LSODA", "DOP853")


def cases(n: int, hard: bool, seed: int) -> dict:
    rng = np.random.default_rng(seed)
    mu = rng.uniform(0.05, 0.6, n)
    if hard:
        k_R = 10 ** rng.uniform(-5, -2, n)
        q = 10 ** rng.uniform(0, 3, n)
        alpha = rng.uniform(np.pi, 10 * np.pi, n)
    else:
        k_R = 10 ** rng.uniform(-1, 2, n)
        q = rng.uniform(0, 1, n)
        alpha = rng.uniform(0.1, 2 * np.pi, n)
    aniso = np.arange(n) % 2 == 1
    share = np.where(aniso, rng.uniform(0.2, 0.8, n), 1.0)
    k_T = np.where(aniso, k_R * 10 ** rng.uniform(-1, 2, n), k_R)
    return {"mu": mu, "alpha": alpha, "q_R": q * share, "k_R": k_R, "q_T": q * (1 - share), "k_T": k_T}


def _timed(fun, repeats):
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fun()
        times.append(time.perf_counter() - t0)
    return out, float(np.median(times))


def _scipy_one(c, i, method, rtol, stretched):
    mu, a, qR, kR, qT, kT = (c[n][i] for n in ("mu", "alpha", "q_R", "k_R", "q_T", "k_T"))
    if stretched:
        kR_, kT_, k_e, _, tau_b = lode.stretch(qR, kR, qT, kT, 0.0, a)

        def f(sig, y):
            al = k_e * np.expm1(sig * tau_b)
            return [tau_b * (al + k_e) * hj.log_tension_slope(y[0], al, mu, qR, kR_, qT, kT_)]

        span = (0.0, 1.0)
    else:
        def f(al, y):
            return [hj.log_tension_slope(y[0], al, mu, qR, kR, qT, kT)]

        span = (0.0, a)
    sol = solve_ivp(f, span, [0.0], method=method, rtol=rtol, atol=rtol)
    return sol.y[0, -1] if sol.success else np.nan


def measure(n: int, rtols_casadi, rtols_scipy, repeats: int, scipy_n: int) -> pd.DataFrame:
    rows = []
    for label, hard in (("easy", False), ("hard", True)):
        c = cases(n, hard, seed=1 + hard)
        ref, t_closed = _timed(lambda: closed_log_ratio(**c), repeats)
        rows.append({"case": label, "method": "closed form (numpy)", "rtol": np.nan, "max rel. error": 0.0,
                     "time per point [s]": t_closed / n, "failures": 0})
        for plugin in CASADI:
            for rtol in rtols_casadi:
                ode_log_ratio(**c, plugin=plugin, rtol=rtol)  # build + warm up (compile not timed)
                y, t = _timed(lambda: ode_log_ratio(**c, plugin=plugin, rtol=rtol), repeats)
                err = np.abs(np.expm1(y - ref))
                rows.append({"case": label, "method": f"ropemodel {plugin}", "rtol": rtol,
                             "max rel. error": float(np.nanmax(err)), "time per point [s]": t / n,
                             "failures": int(np.sum(~np.isfinite(y)))})
        m = min(scipy_n, n)
        for method, stretched in [(s, True) for s in SCIPY] + [("Radau", False)]:
            name = f"scipy {method}" + ("" if stretched else ", plain α")
            for rtol in rtols_scipy:
                y, t = _timed(lambda: np.array([_scipy_one(c, i, method, rtol, stretched) for i in range(m)]),
                              max(1, repeats // 2))
                err = np.abs(np.expm1(y - ref[:m]))
                rows.append({"case": label, "method": name, "rtol": rtol,
                             "max rel. error": float(np.nanmax(err)) if np.isfinite(err).any() else np.nan,
                             "time per point [s]": t / m, "failures": int(np.sum(~np.isfinite(y)))})
    return pd.DataFrame(rows)


TARGET = 1e-6  # the accuracy the issue requires of the default ODE path


def cost_at_error(d: pd.DataFrame, target: float) -> tuple[float, float]:
    """(time per point, rtol) of a method's cheapest setting whose error on both case sets is <= target."""
    worst = d.groupby("rtol").agg({"max rel. error": "max", "time per point [s]": "sum", "failures": "sum"})
    ok = worst[(worst["max rel. error"] <= target) & (worst["failures"] == 0)]
    if not len(ok):
        return np.nan, np.nan
    best = ok["time per point [s]"].idxmin()
    return float(ok.loc[best, "time per point [s]"]), float(best)


def summary(df: pd.DataFrame) -> pd.DataFrame:
    """Default's error and cost; every method's cheapest setting reaching the required 1e-6 (time summed over
    one easy and one hard point), as a ratio to the default's cost."""
    d = df[(df["method"] == f"ropemodel {DEFAULT[0]}") & (df["rtol"] == DEFAULT[1])]
    err, cost = d["max rel. error"].max(), d["time per point [s]"].sum()
    rows = [{"method": f"default ({DEFAULT[0]}, rtol {DEFAULT[1]:g})", "rtol": DEFAULT[1], "max rel. error": err,
             "time per point (easy+hard) [s]": cost, "time / default's": 1.0}]
    for m in sorted(df["method"].unique()):
        if m.startswith("scipy") or m.startswith("ropemodel"):
            g = df[df["method"] == m]
            t, rtol = cost_at_error(g, TARGET)
            e = g[g["rtol"] == rtol]["max rel. error"].max() if np.isfinite(rtol) else np.nan
            rows.append({"method": f"{m}, cheapest with error <= {TARGET:g}", "rtol": rtol, "max rel. error": e,
                         "time per point (easy+hard) [s]": t, "time / default's": t / cost})
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, path: Path) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    styles = {m: (c, "o-" if m.startswith("ropemodel") else "s--")
              for m, c in zip(sorted(df["method"].unique()), plt.cm.tab10(np.linspace(0, 1, 10)))}
    for ax, (label, d) in zip(axes, df.groupby("case")):
        for m, g in d.groupby("method"):
            c, st = styles[m]
            g = g.sort_values("rtol")
            if m.startswith("closed"):
                ax.axhline(g["time per point [s]"].iloc[0], color=c, ls=":", label=m)
                continue
            ax.plot(g["max rel. error"].clip(lower=1e-16), g["time per point [s]"], st, color=c, ms=4, label=m)
        dd = d[(d["method"] == f"ropemodel {DEFAULT[0]}") & (d["rtol"] == DEFAULT[1])]
        ax.plot(dd["max rel. error"], dd["time per point [s]"], "k*", ms=14, label="default")
        ax.axvline(1e-6, color="grey", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("max relative error of S vs the closed form")
        ax.set_title(f"{label} cases")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("time per point [s] (batched, this machine)")
    axes[0].legend(fontsize=7, loc="lower left", ncol=2)
    fig.suptitle("Lined sheave: work-precision of the ODE path (ropemodel, CasADi) vs scipy solve_ivp", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    if fast:
        df = measure(16, (1e-5, 1e-7), (1e-5, 1e-7), repeats=1, scipy_n=4)
    else:
        df = measure(200, (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10), (1e-4, 1e-6, 1e-8, 1e-10),
                     repeats=3, scipy_n=20)
    df.to_csv(out / f"{NAME}.csv", index=False)
    s = summary(df)
    s.to_csv(out / f"{NAME}_summary.csv", index=False)
    plot(df, out / f"{NAME}.png")
    if not fast and out_dir is None:
        FIGURES.mkdir(exist_ok=True)
        plot(df, FIGURES / f"{NAME}.png")
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda d: summary(d).to_string(index=False))
