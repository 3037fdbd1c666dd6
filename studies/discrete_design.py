"""Catalogue diameters: "next size up, F_nwl and stroke re-optimised" vs one bonmin mixed-integer solve.

On random scenes (drum 1.0-2.5 m, so some catalogue sizes break the drum rule), both methods
start from the continuous IPOPT optimum.  Reported: how often they return the same design
(d exactly, F_nwl and stroke within 1e-8 relative to the value or, at zero, to its scale),
how often they agree that no catalogue size exists, how often bonmin does not finish within
a wall-clock limit (run in a forked process), and their median times (a bonmin time-out
counts at the limit).  The default of ``ropemodel size`` is chosen on this.
Also draws the design space of the example scene (ropemodel/data/winch_sizing_fig9.toml):
the least and greatest pretension against d from the scene's own equations (inverse solves),
the drum limit, the catalogue sizes, the continuous optimum and the catalogue design.

    python studies/discrete_design.py [--fast]
"""

from __future__ import annotations

from importlib import resources

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from optimisation import discrete  # noqa: E402
from optimisation.design import size, solve_best  # noqa: E402
from optimisation.problem import SizingProblem  # noqa: E402
from ropemodel.machines.winch.scenes import random_sizing_scene  # noqa: E402
from ropemodel.papers import en12385 as ropes  # noqa: E402
from ropemodel.problem import Problem  # noqa: E402
from ropemodel.scene import from_toml  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure

NAME = "discrete_design"


def compare(n: int, seed: int = 7, timeout: float = 30.0) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    rows = []
    k = 0
    while len(rows) < n:
        k += 1
        scene = random_sizing_scene(rng, name=f"s{k}")
        scene = scene.with_values({"D": float(rng.uniform(1.0, 2.5))})
        problem = SizingProblem(scene)
        sol = solve_best(problem)
        if not (sol.success and sol.g.min() >= -1e-8):
            continue                      # no continuous design: nothing to round
        d_star = problem.to_si(sol.xs)["d"]
        a = discrete.next_size_up(problem, d_star)
        b = discrete.bonmin_with_timeout(problem, timeout, x0=sol.xs)
        b_found, b_seconds, b_timeout = b.found, b.seconds, b.method.endswith("(timed out)")
        b_design = problem.to_si(b.solution.xs) if b.found else None
        row = {"scene": scene.name, "D": scene.parameters["D"], "d_continuous": d_star,
               "next_up_found": a.found, "bonmin_found": b_found, "bonmin_timed_out": b_timeout,
               "next_up_s": a.seconds, "bonmin_s": b_seconds, "next_up_sizes_tried": len(a.tried)}
        nan = {"d": np.nan, "F_nwl": np.nan, "stroke": np.nan}
        for tag, x in (("next_up", problem.to_si(a.solution.xs) if a.found else nan), ("bonmin", b_design or nan)):
            for v in ("d", "F_nwl", "stroke"):
                row[f"{v}_{tag}"] = x[v]
        if b_timeout:
            row["same_design"] = False
        elif a.found and b_found:
            scale = {"F_nwl": problem.F_ref, "stroke": 1.0}     # F_nwl may sit at its bound 0
            row["same_design"] = bool(row["d_next_up"] == row["d_bonmin"] and all(
                abs(row[f"{v}_bonmin"] - row[f"{v}_next_up"]) <= 1e-8 * max(abs(row[f"{v}_next_up"]), scale[v])
                for v in ("F_nwl", "stroke")))
        else:
            row["same_design"] = a.found == b_found
        rows.append(row)
    return pd.DataFrame(rows)


def design_space(ax):
    text = resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml").read_text()
    scene = from_toml(text, source="winch_sizing_fig9.toml")
    result = size(scene, with_sensitivities=False)
    ds = np.linspace(0.025, 0.06, 200)
    curves = {}
    for margin, label in (("slip_margin_up", "least F_nwl: no slip (up)"),
                          ("slip_margin_down", "least F_nwl: no slip (down)"),
                          ("slack_margin_up", "least F_nwl: unwinding rope taut (up)"),
                          ("safety_margin_up", "most F_nwl: rope safety (up)"),
                          ("safety_margin_down", "most F_nwl: rope safety (down)")):
        pb = Problem(scene, given={margin: 0.0}, find=["F_nwl"])
        curves[label] = pb.evaluate({"d": ds})["F_nwl"]
    lo = np.maximum.reduce([v for k, v in curves.items() if k.startswith("least")])
    hi = np.minimum.reduce([v for k, v in curves.items() if k.startswith("most")])
    d_max = scene.parameters["D"] / scene.parameters["D_ratio_min"]
    ok = (hi >= lo) & (ds <= d_max)
    ax.fill_between(ds[ok] * 1e3, lo[ok] / 1e3, hi[ok] / 1e3, color="tab:green", alpha=0.15, label="feasible")
    for (label, v), ls in zip(curves.items(), ("-", "--", ":", "-", "--")):
        ax.plot(ds * 1e3, v / 1e3, ls, color="tab:blue" if label.startswith("least") else "tab:red", label=label)
    ax.axvline(d_max * 1e3, color="k", lw=1, label="drum limit d = D/30")
    for c in ropes.diameters():
        if ds[0] <= c <= ds[-1]:
            ax.axvline(c * 1e3, color="0.8", lw=0.5, zorder=0)
    c, dd = result.continuous, result.design
    ax.plot(c["d"] * 1e3, c["F_nwl"] / 1e3, "k*", ms=12, label=f"continuous optimum d = {c['d'] * 1e3:.2f} mm")
    ax.plot(dd["d"] * 1e3, dd["F_nwl"] / 1e3, "ko", mfc="none", ms=10,
            label=f"catalogue design d = {dd['d'] * 1e3:g} mm")
    ax.set_ylim(0, max(120, 1.3 * c["F_nwl"] / 1e3))
    ax.set_xlabel("rope diameter d [mm] (grey: catalogue sizes)")
    ax.set_ylabel("pretension F_nwl [kN]")
    ax.set_title(scene.name, fontsize=9)
    ax.legend(fontsize=7, loc="upper left")


def main(out_dir=None, fast: bool = False, timeout: float | None = None) -> pd.Series:
    """The study; ``timeout``: bonmin's wall-clock limit [s] (default 5 s in fast mode, 20 s in full mode;
    the tests give more, so that a loaded machine does not turn a slow bonmin into a time-out)."""
    out = output_dir(__file__, out_dir)
    df = compare(1 if fast else 30, timeout=timeout or (5.0 if fast else 20.0))
    df.to_csv(out / f"{NAME}.csv", index=False)
    both = df[df["next_up_found"] & df["bonmin_found"]]
    summary = pd.Series({
        "scenes": len(df),
        "same_answer_rate": df["same_design"].mean(),
        "both_found": len(both),
        "neither_found": int((~df["next_up_found"] & ~df["bonmin_found"]).sum()),
        "only_one_found": int((df["next_up_found"] != df["bonmin_found"]).sum()),
        "bonmin_timeouts": int(df["bonmin_timed_out"].sum()),
        "next_up_median_ms": 1e3 * df["next_up_s"].median(),
        "bonmin_median_ms": 1e3 * df["bonmin_s"].median(),
    })
    summary["time_ratio_bonmin_over_next_up"] = summary["bonmin_median_ms"] / summary["next_up_median_ms"]
    summary.to_csv(out / f"{NAME}_summary.csv", header=["value"])

    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    design_space(ax[0])
    ax[1].loglog(1e3 * df["next_up_s"], 1e3 * df["bonmin_s"], "o", ms=4)
    lim = [1e3 * min(df["next_up_s"].min(), df["bonmin_s"].min()) * 0.8,
           1e3 * max(df["next_up_s"].max(), df["bonmin_s"].max()) * 1.2]
    ax[1].plot(lim, lim, "k--", lw=0.8)
    ax[1].set_xlabel("next size up, re-optimised [ms]")
    ax[1].set_ylabel("bonmin B-BB [ms]")
    ax[1].set_title(f"{len(df)} random scenes: same answer in {100 * summary['same_answer_rate']:.0f}%, "
                    f"bonmin/next-up time {summary['time_ratio_bonmin_over_next_up']:.2g}", fontsize=9)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast, readme_name=f"sizing_{NAME}")
    return summary


if __name__ == "__main__":
    cli(main, __doc__)
