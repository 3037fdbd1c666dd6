"""Sizing map: the least rope diameter d and pretension F_nwl over route length × inclination × load.

Every point is one continuous sizing optimisation (:mod:`optimisation`, IPOPT)
of the scene ``ropemodel/data/winch_sizing_fig9.toml`` (Fig. 9 route, 6x36-IWRC
catalogue rope, rigid drum, design checks), run through
:func:`optimisation.sweep.sizing_sweep` with IPOPT at every point
(``method="ipopt"``; the default active-set path is timed against it and SLSQP in
``studies/sizing_map_speed.py``).  The grid is swept twice: warm
(each optimisation starts from its neighbour's optimum and multipliers, with
IPOPT's warm-start settings) and cold (from the scene's design); the answers
must agree, and on the points feasible in both the ratio of solver time per
optimisation (median), warm / cold, and the mean IPOPT iterations are printed,
with the whole sweep's wall-time ratio (infeasible points included).  Finally the Sobol indices of the
optimum (d, F_nwl) over uniform ranges of the three map axes.

``python studies/sizing_map.py [--fast]`` writes ``sizing_map.csv``,
``warm_cold.csv``, ``sobol_optimum.csv`` and ``sizing_map.png`` into
``studies/out/sizing_map/``.
"""

from __future__ import annotations

import time
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from ropemodel.studykit import cli, output_dir

ROOT = Path(__file__).resolve().parents[1]
NAME = "sizing_map"


def _plot(frame, loads, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, len(loads), figsize=(4.2 * len(loads), 7), squeeze=False)
    for j, g in enumerate(loads):
        sub = frame[np.isclose(frame["G_m [kN]"], g)]
        for i, (col, cmap) in enumerate((("d [mm]", "viridis"), ("F_nwl [kN]", "magma"))):
            pivot = sub.pivot(index="alpha_u [deg]", columns="L_u [m]", values=col)
            ax = axes[i][j]
            m = ax.pcolormesh(pivot.columns, pivot.index, pivot.to_numpy(), shading="nearest", cmap=cmap)
            cs = ax.contour(pivot.columns, pivot.index, pivot.to_numpy(), colors="w", linewidths=0.6)
            ax.clabel(cs, fontsize=7, fmt="%.0f")
            fig.colorbar(m, ax=ax, label=col)
            ax.set_title(f"least {col.split()[0]}, G_m = {g:.0f} kN", fontsize=10)
            ax.set_xlabel("route length L_u [m]")
            ax.set_ylabel("inclination alpha_u [deg]")
    fig.suptitle("Continuous sizing optimum (6x36-IWRC, rigid drum, design checks); blank: no feasible design",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    import ropemodel as rm
    from ropemodel.sensitivities import sobol_indices
    from optimisation.sweep import sizing_function, sizing_sweep

    out = output_dir(__file__, out_dir)
    scene = rm.load_scene(str(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml")))
    n = 3 if fast else 21
    loads = [467.0] if fast else [200.0, 467.0, 800.0]
    vary = {"G_m": [f"{g} kN" for g in loads], "alpha_u": f"2deg:30deg:{n}", "L_u": f"600m:3000m:{n}"}
    t = time.perf_counter()
    warm = sizing_sweep(scene, vary, warm=True, method="ipopt", progress=False)
    t_warm = time.perf_counter() - t
    t = time.perf_counter()
    cold = sizing_sweep(scene, vary, warm=False, progress=False)
    t_cold = time.perf_counter() - t
    both = warm["feasible"] & cold["feasible"]
    agree = float(np.nanmax(np.abs(warm.loc[both, "d [mm]"] - cold.loc[both, "d [mm]"]) / cold.loc[both, "d [mm]"]))
    same_feasible = bool((warm["feasible"] == cold["feasible"]).all())
    warm.to_csv(out / f"{NAME}.csv", index=False)
    rows = []
    for start, frame in (("warm (neighbour)", warm), ("cold (scene design)", cold)):
        f = frame[both]
        rows.append({"start": start, "optimisations": int(both.sum()),
                     "solver_s_per_opt_median": float(f["seconds"].median()),
                     "iterations_per_opt": float(f["iterations"].mean()),
                     "infeasible_points": int((~frame["feasible"]).sum()),
                     "iterations_per_infeasible_point": float(frame.loc[~frame["feasible"], "iterations"].mean())
                     if (~frame["feasible"]).any() else 0.0,
                     "wall_s_whole_sweep": t_warm if start.startswith("warm") else t_cold})
    timing = pd.DataFrame(rows)
    timing.to_csv(out / "warm_cold.csv", index=False)
    _plot(warm, loads, out / f"{NAME}.png")
    if not fast:
        (ROOT / "studies" / "figures").mkdir(exist_ok=True)
        _plot(warm, loads, ROOT / "studies" / "figures" / f"{NAME}.png")

    q = scene.built.quantities
    ranges = {"G_m": (300e3, 600e3), "alpha_u": (np.radians(5), np.radians(25)), "L_u": (600.0, 2500.0)}
    for k, (lo, hi) in ranges.items():
        q[k].check(lo), q[k].check(hi)
    sob = sobol_indices(sizing_function(scene), ranges, n=4 if fast else 256, seed=1)
    sob.to_csv(out / "sobol_optimum.csv", index=False)

    feas = warm["feasible"].mean()
    print(f"{len(warm)} sizing optimisations ({feas:.0%} feasible); warm and cold agree to {agree:.1e} in d, "
          f"same feasibility: {same_feasible}")
    print(f"feasible points: median solver time per optimisation, warm / cold = "
          f"{timing['solver_s_per_opt_median'][0] / timing['solver_s_per_opt_median'][1]:.2f}; "
          f"IPOPT iterations warm {timing['iterations_per_opt'][0]:.1f} vs cold {timing['iterations_per_opt'][1]:.1f}; "
          f"whole sweep wall time warm / cold = {t_warm / t_cold:.2f}")
    print("Sobol indices of the optimum over G_m 300-600 kN, alpha_u 5-25 deg, L_u 600-2500 m:")
    print(sob[sob["output"].isin(["d", "F_nwl"])][["output", "parameter", "S1", "S1_conf", "ST", "ST_conf"]]
          .to_string(index=False, float_format=lambda x: f"{x:.3f}"))
    return warm


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: f"{len(df)} points written")
