"""Benchmark: IPOPT (exact CasADi derivatives) vs scipy SLSQP (finite-difference gradients) on the
same sizing NLP — same scaled variables, objective, constraints, bounds and starting point.

Random feasible scenes (feasibility decided by the least-maximum-violation NLP of
optimisation.infeasibility, not by either contender).  Reports per method: success rate
(converged, every margin >= -1e-6, and — for SLSQP — the same optimum as IPOPT within 1e-4
relative in d, F_nwl and stroke), median wall time, the ratio of medians, and the agreement of the optima.

    python studies/sizing_benchmark.py [--fast]
"""

from __future__ import annotations

import time
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.optimize import minimize  # noqa: E402

from optimisation.infeasibility import diagnose  # noqa: E402
from optimisation.ipopt import solver  # noqa: E402
from optimisation.problem import SizingProblem  # noqa: E402
from ropemodel.machines.winch.scenes import random_sizing_scene  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure  # noqa: E402

NAME = "sizing_benchmark"


def _ipopt(problem, x0):
    lbx, ubx = problem.bounds()
    ipopt = solver(problem)
    t0 = time.perf_counter()
    res = ipopt(x0=x0, p=problem.p0, lbx=lbx, ubx=ubx, lbg=0.0, ubg=np.inf)
    dt = time.perf_counter() - t0
    x = np.asarray(res["x"]).ravel()
    g = np.asarray(res["g"]).ravel()
    return x, g, bool(ipopt.stats()["success"]), dt


def _slsqp(problem, x0):
    import casadi as ca

    f = ca.Function("f", [problem.xs, problem.p], [problem.f])
    g = ca.Function("g", [problem.xs, problem.p], [problem.g])
    p = problem.p0
    lbx, ubx = problem.bounds()
    bounds = [(lo, hi if np.isfinite(hi) else None) for lo, hi in zip(lbx, ubx)]
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = minimize(lambda x: float(f(x, p)), x0, method="SLSQP", bounds=bounds,
                       constraints=[{"type": "ineq", "fun": lambda x: np.asarray(g(x, p)).ravel()}],
                       options={"ftol": 1e-12, "maxiter": 500})
    dt = time.perf_counter() - t0
    return res.x, np.asarray(g(res.x, p)).ravel(), bool(res.success), dt


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    n = 6 if fast else 120
    rng = np.random.default_rng(20261121)
    rows, tried = [], 0
    while len(rows) < n:
        tried += 1
        scene = random_sizing_scene(rng, name=f"s{tried}")
        problem = SizingProblem(scene)
        if not diagnose(problem).feasible:
            continue
        x0 = problem.x0()
        xi, gi, oki, ti = _ipopt(problem, x0)
        xs, gs, oks, ts = _slsqp(problem, x0)
        di, ds = problem.to_si(xi), problem.to_si(xs)
        row = {"scene": scene.name, "ipopt_ok": oki and gi.min() >= -1e-6, "ipopt_s": ti,
               "slsqp_converged": oks, "slsqp_feasible": gs.min() >= -1e-6, "slsqp_s": ts}
        for i, k in enumerate(("d", "F_nwl", "stroke")):
            row[f"{k}_ipopt"], row[f"{k}_slsqp"] = di[k], ds[k]
            # relative to the value, or to the variable's scale where the value is ~0 (F_nwl at its bound)
            row[f"rel_diff_{k}"] = abs(ds[k] - di[k]) / max(abs(di[k]), problem.x_scale[i])
        row["slsqp_ok"] = oks and row["slsqp_feasible"] and max(row[f"rel_diff_{k}"] for k in
                                                                 ("d", "F_nwl", "stroke")) <= 1e-4
        rows.append(row)
    df = pd.DataFrame(rows)
    df.to_csv(out / f"{NAME}.csv", index=False)
    summary = {
        "scenes": len(df), "generated": tried,
        "ipopt_success_rate": df["ipopt_ok"].mean(), "slsqp_success_rate": df["slsqp_ok"].mean(),
        "ipopt_median_ms": 1e3 * df["ipopt_s"].median(), "slsqp_median_ms": 1e3 * df["slsqp_s"].median(),
    }
    summary["time_ratio_slsqp_over_ipopt"] = summary["slsqp_median_ms"] / summary["ipopt_median_ms"]
    both = df[df["ipopt_ok"] & df["slsqp_converged"]]
    for k in ("d", "F_nwl", "stroke"):
        summary[f"median_rel_diff_{k}"] = float(both[f"rel_diff_{k}"].median()) if len(both) else float("nan")
        summary[f"max_rel_diff_{k}"] = float(both[f"rel_diff_{k}"].max()) if len(both) else float("nan")
    pd.Series(summary).to_csv(out / f"{NAME}_summary.csv", header=["value"])

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    bins = np.logspace(np.log10(min(df["ipopt_s"].min(), df["slsqp_s"].min()) * 1e3 * 0.8),
                       np.log10(max(df["ipopt_s"].max(), df["slsqp_s"].max()) * 1e3 * 1.2), 30)
    ax[0].hist(1e3 * df["ipopt_s"], bins=bins, alpha=0.7, label=f"IPOPT, exact derivatives "
               f"({100 * summary['ipopt_success_rate']:.0f}% ok)")
    ax[0].hist(1e3 * df["slsqp_s"], bins=bins, alpha=0.7, label=f"SLSQP, FD gradients "
               f"({100 * summary['slsqp_success_rate']:.0f}% ok)")
    ax[0].set_xscale("log")
    ax[0].set_xlabel("wall time per solve [ms]")
    ax[0].set_ylabel("scenes")
    ax[0].legend(fontsize=8)
    ax[0].set_title(f"{len(df)} random feasible scenes: median ratio {summary['time_ratio_slsqp_over_ipopt']:.2g}")
    for k, m in (("d", "o"), ("F_nwl", "s"), ("stroke", "^")):
        ax[1].semilogy(np.arange(len(df)), np.maximum(df[f"rel_diff_{k}"], 1e-17), m, ms=3, label=k)
    ax[1].axhline(1e-4, color="k", lw=0.8, ls="--")
    ax[1].set_xlabel("scene")
    ax[1].set_ylabel("|SLSQP - IPOPT| / IPOPT")
    ax[1].legend(fontsize=8)
    ax[1].set_title("agreement of the optima")
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)
    return pd.Series(summary)


if __name__ == "__main__":
    cli(main, __doc__)
