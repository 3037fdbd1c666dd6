"""Sizing-map speed: the active-set path against IPOPT and against scipy SLSQP, on the same map in one run.

The map: the Fig. 9 sizing scene (``winch_sizing_fig9``: 6x36-IWRC catalogue rope, rigid drum
D = 1.6 m, design checks) over load G_m × inclination alpha_u × route length L_u (full: 10 × 10 × 10 =
1000 points; ``--fast``: 4 × 4 × 4), points in grid order (last axis fastest).  Three ways to get the
least d, then F_nwl, then stroke at every point:

* **active set** — ``optimisation.sweep.sizing_sweep(scene, vary)`` (the default): neighbouring optima
  share their active checks, so batches of points are solved by Newton on a known active set and
  accepted by their multipliers; IPOPT only where no known active set explains a point; points without
  a design certified by the least-violation problem (:mod:`optimisation.fastmap`);
* **IPOPT** — ``sizing_sweep(scene, vary, method="ipopt")``: IPOPT (exact derivatives) at every point,
  warm-started from the previous optimum and its multipliers;
* **SLSQP** — the peer, written here as a user would: ``scipy.optimize.minimize(method="SLSQP")`` on the
  same compiled objective and constraint Functions of the sizing NLP (``casadi.Function`` called with
  numpy), the same scaled variables and bounds, gradients by scipy's finite differences (no ``jac``),
  each point started from the previous converged optimum, ``ftol=1e-12`` (the other two solve to 1e-10:
  a looser SLSQP would not give the same answers), at most 500 iterations.  A point counts as solved by
  SLSQP when it reports success and every margin is at least -1e-8.

Each contender computes the whole map from the scene (building its own problem) in each of ``rounds``
interleaved rounds after a warm-up; the best (least) wall time of each is taken: on a shared machine
other work only ever adds time.  The CPU time of the process is recorded too (it is less disturbed by
other processes; every contender runs on one thread).  Printed: the time ratios
SLSQP / active set and IPOPT / active set, how many points needed IPOPT on the active-set path, and the
agreement — feasibility point by point, and the largest difference of d, F_nwl and stroke (relative to
max(|value|, the variable's scale)) where both found a design.

    python studies/sizing_map_speed.py [--fast]
"""

from __future__ import annotations

import itertools
import time
import warnings
from importlib import resources

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from ropemodel.studykit import cli, output_dir, save_figure  # noqa: E402

NAME = "sizing_map_speed"
DESIGN = ("d [mm]", "F_nwl [kN]", "stroke [mm]")
TO_DISPLAY = (1e3, 1e-3, 1e3)   # SI -> mm, kN, mm


def axes(fast: bool) -> dict[str, np.ndarray]:
    """The map's axes (SI), first slowest."""
    n = 4 if fast else 10
    return {"G_m": np.linspace(200e3, 800e3, n), "alpha_u": np.radians(np.linspace(2.0, 30.0, n)),
            "L_u": np.linspace(600.0, 3000.0, n)}


def scene():
    import ropemodel as rm

    return rm.load_scene(str(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml")))


def active_set(scn, ax, method="active-set"):
    from optimisation.sweep import sizing_sweep

    return sizing_sweep(scn, {k: list(v) for k, v in ax.items()}, method=method, progress=False)


def slsqp(scn, ax) -> pd.DataFrame:
    """The map by scipy SLSQP with finite-difference gradients, written as a user would."""
    import casadi as ca
    from scipy.optimize import minimize

    from optimisation.problem import SizingProblem

    problem = SizingProblem(scn)
    f = ca.Function("f", [problem.xs, problem.p], [problem.f])
    g = ca.Function("g", [problem.xs, problem.p], [problem.g])
    lbx, ubx = problem.bounds()
    bounds = [(lo, hi if np.isfinite(hi) else None) for lo, hi in zip(lbx, ubx)]
    x = problem.x0()
    rows = []
    for values in itertools.product(*ax.values()):
        p = problem.p0.copy()
        for name, v in zip(ax, values):
            p[problem.params.index(name)] = v
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = minimize(lambda z: float(f(z, p)), x, method="SLSQP", bounds=bounds,
                           constraints=[{"type": "ineq", "fun": lambda z: np.asarray(g(z, p)).ravel()}],
                           options={"ftol": 1e-12, "maxiter": 500})
        ok = bool(res.success) and float(np.min(np.asarray(g(res.x, p)))) >= -1e-8
        if ok:
            x = res.x
        si = res.x * problem.x_scale
        rows.append({**{k: v for k, v in zip(ax, values)}, "feasible": ok,
                     **{c: (si[i] * TO_DISPLAY[i] if ok else np.nan) for i, c in enumerate(DESIGN)}})
    return pd.DataFrame(rows)


def timed(fun, *args):
    """(result, wall seconds, CPU seconds of this process)."""
    t, c = time.perf_counter(), time.process_time()
    out = fun(*args)
    return out, time.perf_counter() - t, time.process_time() - c


def agreement(a: pd.DataFrame, b: pd.DataFrame, scale) -> dict:
    """Largest scaled difference of the design where both found one."""
    both = (a["feasible"] & b["feasible"]).to_numpy()
    out = {"both feasible": int(both.sum())}
    for c, s in zip(DESIGN, scale):
        va, vb = a[c].to_numpy()[both], b[c].to_numpy()[both]
        out[f"max diff {c.split()[0]}"] = float(np.max(np.abs(va - vb) / np.maximum(np.abs(vb), s))) if both.any() \
            else 0.0
    return out


def main(out_dir=None, fast: bool = False, rounds: int | None = None, publish: bool = True) -> pd.Series:
    """The study; ``rounds`` of timing (default 3); ``publish=False`` keeps the full run's figure out of
    ``studies/figures/`` (for tests)."""
    from optimisation.problem import SizingProblem

    out = output_dir(__file__, out_dir)
    scn, ax = scene(), axes(fast)
    rounds = rounds or 3
    small = {k: v[:2] for k, v in ax.items()}
    for fun in (active_set, slsqp):   # warm-up: libraries loaded, first-call costs paid
        fun(scn, small)
    active_set(scn, small, "ipopt")
    times = []
    for r in range(rounds):
        fastmap, *t_fast = timed(active_set, scn, ax)
        ipopt, *t_ipopt = timed(active_set, scn, ax, "ipopt")
        peer, *t_slsqp = timed(slsqp, scn, ax)
        for clock, i in (("wall", 0), ("cpu", 1)):
            times.append({"round": r, "clock": clock, "active set [s]": t_fast[i], "IPOPT warm [s]": t_ipopt[i],
                          "SLSQP FD [s]": t_slsqp[i]})
    times = pd.DataFrame(times)
    times.to_csv(out / "times.csv", index=False)
    best = times.groupby("clock").min()
    problem = SizingProblem(scn)
    scale = (problem.x_scale[0] * 1e3, problem.x_scale[1] / 1e3, problem.x_scale[2] * 1e3)
    fastmap.to_csv(out / f"{NAME}.csv", index=False)
    ipopt_agree, slsqp_agree = agreement(fastmap, ipopt, scale), agreement(fastmap, peer, scale)
    summary = pd.Series({
        "points": len(fastmap), "rounds": rounds, "feasible points": int(fastmap["feasible"].sum()),
        "points solved by IPOPT on the active-set path": int((fastmap["iterations"] > 0).sum()),
        "SLSQP / active set": best.loc["wall", "SLSQP FD [s]"] / best.loc["wall", "active set [s]"],
        "IPOPT / active set": best.loc["wall", "IPOPT warm [s]"] / best.loc["wall", "active set [s]"],
        "SLSQP / IPOPT": best.loc["wall", "SLSQP FD [s]"] / best.loc["wall", "IPOPT warm [s]"],
        "SLSQP / active set (CPU)": best.loc["cpu", "SLSQP FD [s]"] / best.loc["cpu", "active set [s]"],
        "IPOPT / active set (CPU)": best.loc["cpu", "IPOPT warm [s]"] / best.loc["cpu", "active set [s]"],
        "same feasibility as IPOPT": bool((fastmap["feasible"] == ipopt["feasible"]).all()),
        **{f"vs IPOPT: {k}": v for k, v in ipopt_agree.items()},
        "SLSQP failed where a design exists": int((fastmap["feasible"] & ~peer["feasible"]).sum()),
        "SLSQP solved where no design exists": int((~fastmap["feasible"] & peer["feasible"]).sum()),
        **{f"vs SLSQP: {k}": v for k, v in slsqp_agree.items()},
    })
    summary.to_csv(out / f"{NAME}_summary.csv", header=["value"])
    _plot(times, fastmap, peer, ipopt, scale, out, fast or not publish)
    print(f"{len(fastmap)}-point sizing map, best of {rounds} interleaved rounds (wall time): SLSQP (FD) / "
          f"active set = {summary['SLSQP / active set']:.1f}, IPOPT warm / active set = "
          f"{summary['IPOPT / active set']:.1f}, SLSQP / IPOPT = {summary['SLSQP / IPOPT']:.2f}; CPU time of the "
          f"process: {summary['SLSQP / active set (CPU)']:.1f} and {summary['IPOPT / active set (CPU)']:.1f}")
    print(f"active-set path: {summary['points solved by IPOPT on the active-set path']} of {len(fastmap)} points "
          f"needed IPOPT; same feasibility as IPOPT: {summary['same feasibility as IPOPT']}; largest difference "
          f"from IPOPT (d, F_nwl, stroke): " + ", ".join(f"{ipopt_agree[f'max diff {c.split()[0]}']:.1e}"
                                                         for c in DESIGN))
    print(f"SLSQP: failed at {summary['SLSQP failed where a design exists']} points with a design; largest "
          f"difference where it converged: " + ", ".join(f"{slsqp_agree[f'max diff {c.split()[0]}']:.1e}"
                                                          for c in DESIGN))
    return summary


def _plot(times, fastmap, peer, ipopt, scale, out, fast):
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    best = times[times["clock"] == "wall"][["active set [s]", "IPOPT warm [s]", "SLSQP FD [s]"]].min()
    rel = best / best["active set [s]"]
    labels = ["active set\n(batched Newton)", "IPOPT\n(warm-started)", "SLSQP\n(finite differences)"]
    ax[0].bar(labels, rel, color=["tab:green", "tab:blue", "tab:orange"])
    for i, v in enumerate(rel):
        ax[0].text(i, v, f"{v:.1f}x", ha="center", va="bottom")
    ax[0].set_yscale("log")
    ax[0].set_ylabel("wall time for the whole map / active-set time")
    ax[0].set_title(f"{len(fastmap)}-point sizing map, same run (best of {times['round'].nunique()})", fontsize=10)
    for other, label, m in ((ipopt, "IPOPT", "o"), (peer, "SLSQP", "x")):
        both = (fastmap["feasible"] & other["feasible"]).to_numpy()
        d = np.abs(fastmap["d [mm]"] - other["d [mm]"]).to_numpy() / np.maximum(other["d [mm]"].abs(), scale[0])
        ax[1].semilogy(np.flatnonzero(both), np.maximum(d[both], 1e-17), m, ms=3, label=f"{label} vs active set")
    ax[1].set_xlabel("point (grid order)")
    ax[1].set_ylabel("|Δd| / d")
    ax[1].legend(fontsize=8)
    ax[1].set_title("agreement of the least rope diameter", fontsize=10)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)


if __name__ == "__main__":
    cli(main, __doc__, show=lambda s: "\n".join(f"{k}: {v:.3g}" if isinstance(v, float) else f"{k}: {v}"
                                                 for k, v in s.items()))
