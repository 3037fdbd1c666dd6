"""Li et al., Fig. 13-17: stiffness K and rotation Δα of the capstan drive against the load F_T, for
several preloads F_p, free lengths L and wheel radii R (μ = 0.25, EA = 50 kN, α0 = 64°).

The paper prints no numbers for these figures, only trends; this study draws the curves from the
model (eq. 26 as published, tight + slack reading; Δα from the self-consistent rotation integral)
and checks the trends the paper states: K falls with load to a floor that does not depend on F_p,
drops when F_T reaches F_p, rises with F_p, falls with L and R; Δα rises with load.  The continuous
variant is drawn dashed for F_p = 60 N, to show what the published slack-side jump amounts to.

    python studies/capstan_trends.py [--fast]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import ropemodel as rm  # noqa: E402
from ropemodel.capstan.curves import load_curve  # noqa: E402
from ropemodel.studykit import cli, output_dir

NAME = "capstan_trends"
FIGURES = Path(__file__).resolve().parent / "figures"
BASE = {"mu": 0.25, "EA": "50 kN", "R": "75 mm", "L": "360 mm", "alpha_0": "64 deg", "F_p": "60 N", "F_T": "0 N"}
FAMILIES = {  # parameter -> values (SI) and label
    "F_p": ([20.0, 60.0, 100.0], "F_p = {:g} N", 1.0),
    "L": ([0.2, 0.36, 0.6], "L = {:g} mm", 1e3),
    "R": ([0.05, 0.075, 0.1], "R = {:g} mm", 1e3),
}


def scene(variant="li", **values):
    return rm.from_dict({"scene": {"name": "Li et al. Fig. 13-17", "model": "capstan"},
                         "effects": {"stiffness": variant}, "parameters": {**BASE, **values}}, bare="si")


def curves(n: int) -> pd.DataFrame:
    frames = []
    for param, (vals, _, _) in FAMILIES.items():
        for v in vals:
            for variant in ("li", "continuous"):
                if variant == "continuous" and not (param == "F_p" and v == 60.0):
                    continue
                df = load_curve(scene(variant, **{param: v}), 100.0, n)
                df.insert(0, "variant", variant)
                df.insert(0, "value", v)
                df.insert(0, "family", param)
                frames.append(df)
    return pd.concat(frames, ignore_index=True)


def checks(data: pd.DataFrame) -> pd.DataFrame:
    """The paper's stated trends, each evaluated on the computed curves."""
    li = data[data["variant"] == "li"]
    rows = []

    def family(p):
        return {v: g.reset_index(drop=True) for v, g in li[li["family"] == p].groupby("value")}

    fp = family("F_p")
    floor = [g["K [N/m]"].iloc[-1] for g in fp.values()]  # at 100 N every preload is past F_T = F_p
    rows.append(("floor of K independent of F_p", max(floor) / min(floor) - 1 < 0.01, max(floor) / min(floor) - 1))
    for v, g in fp.items():
        i = int(np.searchsorted(g["F_T [N]"], v))
        if 0 < i < len(g):
            drop = g["K [N/m]"].iloc[i] / g["K [N/m]"].iloc[i - 1]
            rows.append((f"K drops where F_T reaches F_p = {v:g} N", drop < 0.75, drop))
    for p, sign in (("F_p", +1), ("L", -1), ("R", -1)):
        fam = family(p)
        vals = sorted(fam)
        k = np.array([fam[v]["K [N/m]"].to_numpy() for v in vals])
        # mean over the load range (the published jump breaks it pointwise near the slack switch)
        mean = k.mean(axis=1)
        ok = bool(np.all(sign * np.diff(mean) > 0))
        rows.append((f"mean K {'rises' if sign > 0 else 'falls'} with {p}", ok, float(mean[-1] / mean[0])))
    mono = all(np.all(np.diff(g["delta_alpha [rad]"].to_numpy()) > 0)
               for _, g in li.groupby(["family", "value"]))
    rows.append(("delta_alpha rises with load on every curve", mono, float(mono)))
    return pd.DataFrame(rows, columns=["trend", "holds", "measure"])


def plot(data: pd.DataFrame, path_list):
    fig, axes = plt.subplots(3, 2, figsize=(10, 11))
    for row, (param, (vals, fmt, scale)) in enumerate(FAMILIES.items()):
        for v in vals:
            for variant, style in (("li", "-"), ("continuous", "--")):
                g = data[(data["family"] == param) & (data["value"] == v) & (data["variant"] == variant)]
                if g.empty:
                    continue
                label = fmt.format(v * scale) + (" (continuous variant)" if variant == "continuous" else "")
                axes[row, 0].plot(g["F_T [N]"], g["K [N/m]"] / 1e3, style, label=label)
                axes[row, 1].plot(g["F_T [N]"], np.degrees(g["delta_alpha [rad]"]), style, label=label)
        axes[row, 0].set_ylabel("K [N/mm]")
        axes[row, 1].set_ylabel("Δα [deg]")
        axes[row, 0].legend(fontsize=8)
        axes[row, 1].legend(fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("F_T [N]")
    axes[0, 0].set_title("stiffness (Fig. 13, 16)")
    axes[0, 1].set_title("rotation of the capstan (Fig. 14, 15, 17)")
    fig.suptitle("Capstan drive, Li et al. eq. (26): μ = 0.25, EA = 50 kN, α0 = 64° (R = 75 mm, L = 360 mm, "
                 "F_p = 60 N unless varied)", fontsize=9)
    fig.tight_layout()
    for p in path_list:
        fig.savefig(p, dpi=100)
    plt.close(fig)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    data = curves(41 if fast else 401)
    data.to_csv(out / "curves.csv", index=False)
    table = checks(data)
    table.to_csv(out / "trends.csv", index=False)
    paths = [out / f"{NAME}.png"]
    if not fast:
        FIGURES.mkdir(exist_ok=True)
        paths.append(FIGURES / f"{NAME}.png")
    plot(data, paths)
    return table


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: df.to_string(index=False))
