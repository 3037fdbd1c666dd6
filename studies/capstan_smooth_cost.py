"""What the smooth capstan law costs and buys: sharpness s against its error from the published law
(eq. 26 as published, ``li``) and against IPOPT iterations and time when identifying μ and EA.

For each sharpness s: the largest error of the rotation Δα(F_T) over 0-100 N relative to Δα(100 N),
the largest relative error of K (which cannot vanish: the published K jumps, a smooth K cannot follow
a jump), and the mean relative K error; then one identification of μ, EA from the same synthetic
data (the ``li`` law's rotation at μ = 0.25, EA = 50 kN plus Gaussian noise) by IPOPT with the smooth
law, against the same fit with the ``li`` law in the same run: iterations, IPOPT status, time as a
ratio to the ``li`` fit, and the estimates' bias from the truth in units of their standard errors.

    python studies/capstan_smooth_cost.py [--fast]
"""

from __future__ import annotations

import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import ropemodel as rm  # noqa: E402
from ropemodel.capstan.curves import load_curve  # noqa: E402
from ropemodel.capstan.identify import identify  # noqa: E402
from ropemodel.numerics.capstan_rotation import rotation  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure

NAME = "capstan_smooth_cost"
BASE = {"mu": 0.25, "EA": "50 kN", "R": "75 mm", "L": "360 mm", "alpha_0": "64 deg", "F_p": "60 N", "F_T": "0 N"}
TRUE = {"mu": 0.25, "EA": 5e4}
NOISE = 1e-5  # [rad]


def scene(variant, sharpness=30.0, **values):
    return rm.from_dict({"scene": {"model": "capstan"}, "effects": {"stiffness": variant},
                         "parameters": {**BASE, **values}, "numerics": {"sharpness": float(sharpness)}}, bare="si")


def data(n_points: int, seed: int = 0) -> pd.DataFrame:
    sc = scene("li")
    p = sc.parameters
    F = np.linspace(0.0, 100.0, n_points)
    exact = rotation(F, TRUE["mu"], TRUE["EA"], p["R"], p["L"], p["alpha_0"], p["F_p"]) / p["R"]
    rng = np.random.default_rng(seed)
    return pd.DataFrame({"F_T [N]": F, "delta_alpha [rad]": exact + rng.normal(0.0, NOISE, F.size)})


def fit(variant, sharpness, measured):
    start = scene(variant, sharpness, mu=0.4, EA=3e4)
    t0 = time.perf_counter()
    res = identify(start, measured)
    wall = time.perf_counter() - t0
    row = {"iterations": res.iterations, "status": res.status, "ipopt_seconds": res.seconds, "wall_seconds": wall}
    for k, v in TRUE.items():
        row[f"{k}_hat"] = res.estimates[k]
        row[f"{k}_bias_in_se"] = (res.estimates[k] - v) / res.standard_errors[k]
    return row


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    sharp = [30.0] if fast else [5.0, 10.0, 20.0, 50.0, 100.0, 200.0]
    n_curve, n_data = (21, 11) if fast else (2001, 41)
    ref = load_curve(scene("li"), 100.0, n_curve)
    measured = data(n_data)
    base = fit("li", 30.0, measured)
    rows = [{"sharpness": np.inf, "variant": "li", "max_dalpha_error": 0.0, "max_K_error": 0.0,
             "mean_K_error": 0.0, **base, "time_ratio_to_li": 1.0}]
    curves = {}
    for s in sharp:
        cur = load_curve(scene("smooth", s), 100.0, n_curve)
        curves[s] = cur
        da = np.abs(cur["delta_alpha [rad]"] - ref["delta_alpha [rad]"]).max() / ref["delta_alpha [rad]"].iloc[-1]
        ek = np.abs(cur["K [N/m]"] / ref["K [N/m]"] - 1)
        r = fit("smooth", s, measured)
        rows.append({"sharpness": s, "variant": "smooth", "max_dalpha_error": da, "max_K_error": ek.max(),
                     "mean_K_error": ek.mean(), **r, "time_ratio_to_li": r["wall_seconds"] / base["wall_seconds"]})
    table = pd.DataFrame(rows)
    table.to_csv(out / "smooth_cost.csv", index=False)

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    ax = axes[0]
    ax.plot(ref["F_T [N]"], ref["K [N/m]"] / 1e3, "k-", lw=2, label="li (published)")
    for s, cur in curves.items():
        ax.plot(cur["F_T [N]"], cur["K [N/m]"] / 1e3, "--", label=f"smooth, s = {s:g}")
    ax.set_xlabel("F_T [N]")
    ax.set_ylabel("K [N/mm]")
    ax.legend(fontsize=7)
    ax.set_title("K: published vs smooth (F_p = 60 N)")
    sm = table[table["variant"] == "smooth"]
    ax = axes[1]
    ax.loglog(sm["sharpness"], sm["max_dalpha_error"], "o-", label="max |ΔΔα| / Δα(100 N)")
    ax.loglog(sm["sharpness"], sm["mean_K_error"], "s-", label="mean |ΔK|/K")
    ax.loglog(sm["sharpness"], sm["max_K_error"], "^-", label="max |ΔK|/K (the jumps)")
    ax.set_xlabel("sharpness s")
    ax.set_ylabel("error relative to the published law")
    ax.legend(fontsize=7)
    ax.set_title("accuracy")
    ax = axes[2]
    ax.semilogx(sm["sharpness"], sm["iterations"], "o-", label="IPOPT iterations (smooth)")
    ax.axhline(base["iterations"], color="k", ls=":", label=f"li: {base['iterations']} iterations ({base['status']})")
    ax.set_xlabel("sharpness s")
    ax.set_ylabel("iterations")
    ax2 = ax.twinx()
    ax2.semilogx(sm["sharpness"], sm["time_ratio_to_li"], "s--", color="C3", label="time / li fit time")
    ax2.set_ylabel("time ratio to the li fit", color="C3")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7)
    ax.set_title("identification of μ, EA by IPOPT")
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast, dpi=100)
    return table


if __name__ == "__main__":
    cli(main, __doc__)
