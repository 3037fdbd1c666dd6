"""Hajduk (1992) Fig. 5: tension ratio S/S_0 along the arc of a Voigt-lined sheave, with Euler–Eytelwein.

The paper's parameter ranges: μ = 0.2 and 0.3, λω = (0.01 … 2)π, Q = 1e-5 and 1e-2 1/N,
here with S_0 = 10 kN (q = Q S_0 = 0.1 and 100, the reference table of docs/physics.md §3).  Curves by
the closed form (sheave scenes, method "closed"); the default ODE path (method "ode") is
drawn as markers for every curve and its largest deviation is written to the CSV.  The
reference-table points are checked and marked.

    python studies/hajduk_fig5.py [--fast]
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import ropemodel as rm  # noqa: E402
from ropemodel.sheave import distribution  # noqa: E402
from ropemodel.studykit import cli, output_dir  # noqa: E402

NAME = "hajduk_fig5"
FIGURES = Path(__file__).resolve().parent / "figures"
S_0 = 1e4
MUS = (0.2, 0.3)
QS = (1e-5, 1e-2)
K_OVER_PI = (0.01, 0.1, 0.5, 2.0)
# docs/physics.md §3: (mu, q, k/pi) -> s(pi/2), s(pi), s(2pi)
TABLE = {(0.2, 0.1, 0.01): (1.212743, 1.597677, 2.685966), (0.2, 0.1, 2.0): (1.329433, 1.749747, 2.921169),
         (0.2, 100.0, 0.01): (0.036301, 0.038781, 0.043839), (0.3, 0.1, 0.5): (1.460686, 2.133928, 4.312762),
         (0.3, 100.0, 2.0): (0.117940, 0.086236, 0.071543)}


def scene(mu, Q, k, method):
    return rm.from_dict({"scene": {"model": "sheave", "name": "Hajduk Fig. 5"}, "effects": {"lining": "voigt"},
                         "parameters": {"S_0": S_0, "mu": mu, "alpha": 2 * math.pi, "Q": Q, "lambda": 1.0,
                                        "omega": k},
                         "numerics": {"method": method}}, bare="si")


def measure(points: int, k_over_pi) -> pd.DataFrame:
    rows = []
    for mu in MUS:
        for Q in QS:
            for kp in k_over_pi:
                k = kp * math.pi
                closed = distribution(scene(mu, Q, k, "closed"), points=points)
                ode = distribution(scene(mu, Q, k, "ode"), points=points)
                for (_, c), (_, o) in zip(closed.iterrows(), ode.iterrows()):
                    rows.append({"mu [-]": mu, "Q [1/N]": Q, "q [-]": Q * S_0, "lambda*omega/pi [-]": kp,
                                 "alpha [deg]": c["alpha [deg]"], "S/S_0 closed [-]": c["S/S_0 [-]"],
                                 "S/S_0 ode [-]": o["S/S_0 [-]"], "e^(mu alpha) [-]": c["e^(mu alpha) [-]"]})
    df = pd.DataFrame(rows)
    df["ode rel. error [-]"] = (df["S/S_0 ode [-]"] / df["S/S_0 closed [-]"] - 1).abs()
    return df


def table_check() -> pd.DataFrame:
    rows = []
    for (mu, q, kp), ref in TABLE.items():
        sc = scene(mu, q / S_0, kp * math.pi, "closed")
        for a, r in zip((math.pi / 2, math.pi, 2 * math.pi), ref):
            got = rm.run(sc.with_values({"alpha": a}))["S_ratio"]
            rows.append({"mu [-]": mu, "q [-]": q, "lambda*omega/pi [-]": kp, "alpha [deg]": math.degrees(a),
                         "reference [-]": r, "closed form [-]": got, "6 digits agree": round(got, 6) == r})
    return pd.DataFrame(rows)


def plot(df: pd.DataFrame, check: pd.DataFrame, path: Path) -> None:
    fig, axes = plt.subplots(2, 2, figsize=(10, 8), sharex=True)
    colors = plt.cm.viridis(np.linspace(0, 0.85, df["lambda*omega/pi [-]"].nunique()))
    for i, mu in enumerate(MUS):
        for j, Q in enumerate(QS):
            ax = axes[j, i]
            d = df[(df["mu [-]"] == mu) & (df["Q [1/N]"] == Q)]
            for c, (kp, g) in zip(colors, d.groupby("lambda*omega/pi [-]")):
                ax.plot(g["alpha [deg]"], g["S/S_0 closed [-]"], color=c, label=f"λω = {kp:g}π")
                ax.plot(g["alpha [deg]"][::4], g["S/S_0 ode [-]"][::4], "o", color=c, ms=3, mfc="none")
            g = d[d["lambda*omega/pi [-]"] == d["lambda*omega/pi [-]"].iloc[0]]
            ax.plot(g["alpha [deg]"], g["e^(mu alpha) [-]"], "k--", label=r"Euler–Eytelwein $e^{\mu\alpha}$")
            t = check[(check["mu [-]"] == mu) & (check["q [-]"] == Q * S_0)]
            ax.plot(t["alpha [deg]"], t["reference [-]"], "rx", ms=8, label="reference table")
            ax.set_yscale("log")
            ax.set_title(f"μ = {mu}, Q = {Q:g} 1/N (q = {Q * S_0:g})")
            ax.grid(True, which="both", alpha=0.3)
            if j == 1:
                ax.set_xlabel("angle of contact α [deg]")
            if i == 0:
                ax.set_ylabel("S/S_0 [-]")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Tension along the arc of a Voigt-lined sheave (Hajduk 1992, Fig. 5); "
                 "lines: closed form, circles: ODE (default path)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    df = measure(13 if fast else 73, (0.01, 2.0) if fast else K_OVER_PI)
    check = table_check()
    df.to_csv(out / f"{NAME}.csv", index=False)
    check.to_csv(out / f"{NAME}_table.csv", index=False)
    plot(df, check, out / f"{NAME}.png")
    if not fast and out_dir is None:
        FIGURES.mkdir(exist_ok=True)
        plot(df, check, FIGURES / f"{NAME}.png")
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda d: f"{NAME}: {len(d)} points; largest ODE deviation from the closed form "
                                   f"{d['ode rel. error [-]'].max():.2e}")
