"""What accuracy costs in time: rope segments x integrator tolerance against a fine reference.

The start-up of ropemodel/data/winch_start.toml (Fig. 9 haulage, 20 s) is simulated with
1-32 Kelvin-Voigt elements per rope span and relative tolerances 1e-4 ... 1e-10 of CasADi's
cvodes (BDF), and with idas at the default segments.  The reference is 64 elements per span
at rtol 1e-10.  Errors: the peak rope force F_C_max, and the largest deviation of the F_C
history (both relative to the static F_C); time: median wall time of one simulation
(compile included, as a user meets it) and its ratio to the default (8 segments, rtol 1e-8),
all measured in the same run.

    python studies/dynamics_accuracy.py [--fast]
"""

from __future__ import annotations

import time
import tomllib
from importlib import resources

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import ropemodel as rm  # noqa: E402
from ropemodel.dynamics import simulate  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure

NAME = "dynamics_accuracy"
FIGURE = "dynamic_accuracy"
DATA = resources.files("ropemodel.data")


def _scene(t_end, segments, rtol, integrator="cvodes"):
    d = tomllib.loads(DATA.joinpath("winch_start.toml").read_text())
    d["parameters"]["t_end"] = t_end
    d["numerics"].update({"segments": segments, "sim_rtol": rtol, "sim_integrator": integrator, "sim_dt": 0.02})
    return rm.from_dict(d, bare="si")


def _run(t_end, segments, rtol, integrator="cvodes", repeats=3):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        sim = simulate(_scene(t_end, segments, rtol, integrator))
        times.append(time.perf_counter() - t0)
    return sim, float(np.median(times))


def measure(t_end, segments, rtols, ref_segments, ref_rtol, repeats) -> pd.DataFrame:
    ref, ref_s = _run(t_end, ref_segments, ref_rtol, repeats=1)
    rh = ref.history
    scale = ref.summary["F_C_static"]
    rows = []
    cases = [(n, r, "cvodes") for n in segments for r in rtols] + [(segments[len(segments) // 2], r, "idas")
                                                                    for r in rtols]
    for n, rtol, integ in cases:
        sim, secs = _run(t_end, n, rtol, integ, repeats)
        h = sim.history
        F = np.interp(rh["t [s]"], h["t [s]"], h["F_C [N]"])
        rows.append({"segments": n, "rtol": rtol, "integrator": integ,
                     "err_F_C_max [-]": abs(sim.summary["F_C_max"] - ref.summary["F_C_max"]) / scale,
                     "err_F_C_history [-]": float(np.max(np.abs(F - rh["F_C [N]"]))) / scale,
                     "energy_residual [-]": sim.summary["energy_residual"],
                     "seconds": secs, "nodes": sim.summary["n_nodes"]})
    df = pd.DataFrame(rows)
    default = df[(df["segments"] == 8) & (df["rtol"] == 1e-8) & (df["integrator"] == "cvodes")]
    base = float(default["seconds"].iloc[0]) if len(default) else float(df["seconds"].median())
    df["time_ratio_to_default [-]"] = df["seconds"] / base
    df.attrs["reference_seconds"] = ref_s
    return df


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    if fast:
        df = measure(6.0, [2, 4], [1e-4, 1e-8], ref_segments=8, ref_rtol=1e-9, repeats=1)
    else:
        df = measure(20.0, [1, 2, 4, 8, 16, 32], [1e-4, 1e-6, 1e-8, 1e-10], ref_segments=64, ref_rtol=1e-10,
                     repeats=3)
    df.to_csv(out / f"{NAME}.csv", index=False)

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.3))
    cv = df[df["integrator"] == "cvodes"]
    for n, d in cv.groupby("segments"):
        ax[0].loglog(d["seconds"], np.maximum(d["err_F_C_history [-]"], 1e-16), "o-", ms=4, label=f"{n} segments")
    idas = df[df["integrator"] == "idas"]
    ax[0].loglog(idas["seconds"], np.maximum(idas["err_F_C_history [-]"], 1e-16), "kx--", label="idas")
    ax[0].set_xlabel("wall time per simulation [s]")
    ax[0].set_ylabel("max |F_C(t) - reference| / F_C,static")
    ax[0].set_title("work-precision (rtol 1e-4 ... 1e-10 along each line)")
    ax[0].legend(fontsize=7)
    ax[0].grid(True, which="both", alpha=0.3)
    tight = cv[cv["rtol"] == cv["rtol"].min()]
    ax[1].loglog(tight["segments"], tight["err_F_C_max [-]"], "o-", label="peak F_C")
    ax[1].loglog(tight["segments"], tight["err_F_C_history [-]"], "s-", label="F_C history (max)")
    n = tight["segments"].to_numpy(float)
    ax[1].loglog(n, tight["err_F_C_max [-]"].iloc[0] * n[0] / n, "k:", label="first order")
    ax[1].set_xlabel("Kelvin-Voigt elements per rope span")
    ax[1].set_ylabel("error / F_C,static")
    ax[1].set_title(f"discretisation error at rtol {cv['rtol'].min():g}")
    ax[1].legend(fontsize=8)
    ax[1].grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_figure(fig, __file__, out, FIGURE, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: df.to_string(index=False))
