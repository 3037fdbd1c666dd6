"""Static sizing, static sizing with a dynamic factor, and dynamic sizing: what the static methods miss or waste.

For routes of the Fig. 9 haulage of Krauze et al. (2025) (its load, rope grade and drum; a 6x36-IWRC rope;
the route's length and inclination varied) and drive ramp times, four continuous designs (d, F_nwl,
stroke) are compared:

* ``static``: the paper's sizing on static forces (:mod:`optimisation`);
* ``static x 1.1``: the same with a flat dynamic factor 1.1 (German mining rules): rope safety and
  traction checked against 1.1·F_C (n_rope and n_slip times 1.1);
* ``static x k``: the same with the factor the transient actually shows at the static design, k = the
  largest F_C,max/F_C,static of its four manoeuvres with the load at each end and in the middle of the
  route (what ``ropemodel simulate`` reports as the dynamic factor);
* ``dynamic``: ``ropemodel size --dynamic`` (:mod:`optimisation.dynamic`): every check through start and
  stop in both directions, the load anywhere on the route; slip at its onset (``n_slip_dynamic`` = 1) and the
  scenes' 4 rope elements per span (the continuous optimum before the mesh control of
  :mod:`optimisation.dynamic.mesh`).

Every design is simulated through the four manoeuvres at every place of the load by the hybrid simulator
(``ok``: every check holds).
Columns ``d/F_nwl/stroke vs dynamic [%]``: positive wastes, negative misses.  ``seconds``: the solve time of
each method in this run; ``time ratio``: dynamic over static (same run, same machine).

    python studies/dynamic_sizing.py [--fast]
"""

from __future__ import annotations

import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import ropemodel as rm  # noqa: E402
from optimisation.design import solve_best  # noqa: E402
from optimisation.dynamic.problem import DynamicSizingProblem  # noqa: E402
from optimisation.dynamic.design import continuous_optimum  # noqa: E402
from optimisation.dynamic.start import factored_design, flat_factor  # noqa: E402
from optimisation.dynamic.verify import verify  # noqa: E402
from optimisation.problem import VARIABLES, SizingProblem, prepare  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure  # noqa: E402

NAME = "dynamic_sizing"
#: the Fig. 9 haulage with a transient (values with units, as in a scene file: the manoeuvres' scenes are
#: re-read from them); routes and ramps vary L_u, alpha_u and t_ramp
BASE = {
    "scene": {"name": "dynamic sizing study", "model": "winch"},
    "effects": {"rope": "6x36-IWRC", "checks": "design", "lining": "rigid", "power": "drive", "dynamics": "start",
                "travel": "up", "rope_elasticity": "segments", "tensioner": "constant_force"},
    "parameters": {"L_u": "1150 m", "L_ul": "500 m", "alpha_u": "16 deg", "mu_pm": 0.05, "mu_pl": 0.05,
                   "G_m": "467 kN", "v_pj": "2.5 m/s", "eta": 0.85, "rope_grade": "1770 N/mm^2",
                   "rope_E": "100 kN/mm^2",
                   "mu_d": 0.2, "alpha_d": "540 deg", "n_slip": 1.25, "n_rope": 4.5, "F_S_min": "5 kN", "D": "1.6 m",
                   "t_ramp": "4 s", "t_end": "12 s", "rope_damping": "0.05 s", "m_t": "1000 kg",
                   # slip judged at its onset through the manoeuvres (rho F_S(t) >= F_C(t)), as the flat factors
                   # are compared with: the dynamic slip factor's own reserve is not what this study measures
                   "n_slip_dynamic": 1.0},
    "numerics": {"segments": 4},
}
ROUTES = {"Fig. 9: 1150 m at 16 deg": {"L_u": "1150 m", "alpha_u": "16 deg"},
          "long, shallow: 2000 m at 8 deg": {"L_u": "2000 m", "alpha_u": "8 deg"},
          "short, steep: 600 m at 25 deg": {"L_u": "600 m", "alpha_u": "25 deg"}}
FLAT = 1.1
METHODS = ("static", f"static x {FLAT:g}", "static x k", "dynamic")


def scene(route: dict, t_ramp: float, segments: int):
    data = {k: dict(v) for k, v in BASE.items()}
    data["parameters"].update(route, t_ramp=f"{t_ramp:g} s", t_end=f"{max(12.0, t_ramp + 8.0):g} s")
    data["numerics"]["segments"] = segments
    return prepare(rm.from_dict(data, optional=VARIABLES, emit=False))


def case(sc) -> list[dict]:
    """The four designs of one scene, each simulated through the four manoeuvres."""
    static = SizingProblem(sc)
    t0 = time.perf_counter()
    s0 = solve_best(static)
    t_static = time.perf_counter() - t0
    problem = DynamicSizingProblem(sc)
    k = flat_factor(problem, s0.xs)
    designs, seconds = {"static": s0.xs}, {"static": t_static}
    for name, factor in ((METHODS[1], FLAT), (METHODS[2], k)):
        t0 = time.perf_counter()
        sol = factored_design(static, factor, factor, x0=s0.xs)
        designs[name], seconds[name] = (sol.xs if sol.feasible else None), t_static + time.perf_counter() - t0
    t0 = time.perf_counter()
    s0 = solve_best(static)
    problem, sol, diagnosis = continuous_optimum(problem, s0.xs)
    designs["dynamic"], seconds["dynamic"] = (sol.xs if diagnosis is None else None), time.perf_counter() - t0
    dyn = problem.to_si(designs["dynamic"]) if designs["dynamic"] is not None else None
    rows = []
    for name in METHODS:
        xs = designs[name]
        row = {"method": name, "k": k if name == "static x k" else (FLAT if name == METHODS[1] else 1.0),
               "seconds": seconds[name], "time ratio": seconds["dynamic"] / t_static, "design": xs is not None}
        if xs is not None:
            si = problem.to_si(xs)
            verdicts = verify(problem, xs)
            row.update({"d [mm]": si["d"] * 1e3, "F_nwl [kN]": si["F_nwl"] * 1e-3, "stroke [m]": si["stroke"],
                        "ok": all(v.ok for v in verdicts),
                        "failures": " | ".join(f"{v.manoeuvre} at {v.where}: {v.failures[0]}"
                                               for v in verdicts if not v.ok)})
            if dyn is not None:
                row.update({f"{v} vs dynamic [%]": 100 * (si[v] / dyn[v] - 1) for v in VARIABLES})
        rows.append(row)
    return rows


def study(routes: dict, ramps, segments: int) -> pd.DataFrame:
    rows = []
    for route, values in routes.items():
        for t_ramp in ramps:
            for row in case(scene(values, t_ramp, segments)):
                rows.append({"route": route, "t_ramp [s]": t_ramp, **row})
    return pd.DataFrame(rows)


def figure(df: pd.DataFrame):
    cases = list(dict.fromkeys(zip(df["route"], df["t_ramp [s]"])))
    fig, axes = plt.subplots(3, 1, figsize=(max(7.0, 1.3 * len(cases) + 3), 8), sharex=True)
    width = 0.8 / (len(METHODS) - 1)
    colors = dict(zip(METHODS, ("C3", "C1", "C2", "C0")))
    for ax, v in zip(axes, VARIABLES):
        for j, method in enumerate(METHODS[:-1]):
            d = df[df["method"] == method].set_index(["route", "t_ramp [s]"]).loc[cases]
            x = np.arange(len(cases)) + (j - 1) * width
            bars = ax.bar(x, d[f"{v} vs dynamic [%]"], width, color=colors[method], label=method)
            for xi, has in zip(x, d["design"].astype(bool)):
                if not has:
                    ax.text(xi, 0, "no design", rotation=90, ha="center", va="bottom", fontsize=6,
                            color=colors[method])
            for bar, ok in zip(bars, d["ok"]):
                if not ok:
                    bar.set_hatch("///")
                    bar.set_edgecolor("k")
        ax.axhline(0, color=colors["dynamic"], lw=1.5, label="dynamic (every check in all four manoeuvres)")
        none = df[(df["method"] == "dynamic") & ~df["design"].astype(bool)].set_index(["route", "t_ramp [s]"]).index
        for i, c in enumerate(cases):
            if c in none:
                ax.text(i, 0, "dynamic sizing:\nno design", ha="center", va="center", fontsize=7)
        ax.set_ylabel(f"{v} vs dynamic [%]")
        ax.grid(axis="y", alpha=0.3)
    axes[0].legend(fontsize=7, ncol=2, title="hatched: fails in a simulated manoeuvre", title_fontsize=7)
    axes[-1].set_xticks(np.arange(len(cases)))
    axes[-1].set_xticklabels([f"{r.split(':')[0]}\nt_ramp {t:g} s" for r, t in cases], fontsize=7)
    axes[0].set_title("Continuous designs against the dynamic optimum (below 0: misses, above: wastes)")
    fig.tight_layout()
    return fig


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    routes = dict(list(ROUTES.items())[:1]) if fast else ROUTES
    ramps = [4.0] if fast else [3.0, 5.0, 8.0]
    df = study(routes, ramps, segments=4)
    df.to_csv(out / f"{NAME}.csv", index=False)
    save_figure(figure(df), __file__, out, NAME, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: df.drop(columns=["failures"]).to_string(index=False))
