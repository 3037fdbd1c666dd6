"""How much the drum's contact compliance (capstan model of Li et al.) changes a start-up.

The start-up of ropemodel/data/winch_start.toml (Fig. 9 haulage, 8 elements per span) is
simulated with the rigid drum contact and with ``drum_contact = "capstan"`` (the tight span
in series with the slip zone's stiffness K_1 = μEA F_C/(R(F_C − F_S)), Li et al. eq. (12),
linearised at the static forces) for drum diameters D and drum friction μ_d.  Reported per
case: K_1, its ratio to the stiffness of the whole load-to-drum span EA/x_m, the change of
the peak rope force F_C_max and the largest deviation of the F_C history from the rigid
drum's (both relative to the rigid peak), and the wall time relative to the rigid drum
(medians, measured in the same run).  Contact compliance scales like D/μ_d, so the effect
grows with the drum and falls with friction.

    python studies/drum_contact.py [--fast]
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

NAME = "drum_contact"
DATA = resources.files("ropemodel.data")


def _scene(t_end, contact, D=None, mu_d=None):
    d = tomllib.loads(DATA.joinpath("winch_start.toml").read_text())
    d["parameters"]["t_end"] = t_end
    d["effects"]["drum_contact"] = contact
    if D is not None:
        d["parameters"]["D"] = D
    if mu_d is not None:
        d["parameters"]["mu_d"] = mu_d
    return rm.from_dict(d, bare="si")


def _run(scene, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        sim = simulate(scene)
        times.append(time.perf_counter() - t0)
    return sim, float(np.median(times))


def measure(t_end, diameters, frictions, repeats) -> tuple[pd.DataFrame, dict]:
    histories = {}
    rows = []
    for mu in frictions:
        rigid, t_rigid = _run(_scene(t_end, "rigid", mu_d=mu), repeats)
        rh = rigid.history
        peak = rigid.summary["F_C_max"]
        histories[("rigid", mu)] = rh
        v = rigid.scene.parameters
        k_span = v["L_u"] / v["q_lw"] / v["x_m"]
        for D in diameters:
            sim, secs = _run(_scene(t_end, "capstan", D=D, mu_d=mu), repeats)
            h = sim.history
            histories[(D, mu)] = h
            F = np.interp(rh["t [s]"], h["t [s]"], h["F_C [N]"])
            K = sim.summary["drum_contact"]["K_C"]
            rows.append({"D [m]": D, "mu_d [-]": mu, "K_1 [N/m]": K, "K_1 / k_span [-]": K / k_span,
                         "F_C_max [N]": sim.summary["F_C_max"], "F_C_max_rigid [N]": peak,
                         "dF_C_max [-]": (sim.summary["F_C_max"] - peak) / peak,
                         "max_dF_C_history [-]": float(np.max(np.abs(F - rh["F_C [N]"]))) / peak,
                         "slip": sim.summary["slip"], "seconds": secs,
                         "time_ratio_to_rigid [-]": secs / t_rigid})
    return pd.DataFrame(rows), histories


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    if fast:
        df, hist = measure(8.0, [2.5, 25.0], [0.25], repeats=1)
    else:
        df, hist = measure(30.0, [1.0, 2.5, 5.0, 10.0, 25.0], [0.15, 0.25, 0.4], repeats=3)
    df.to_csv(out / f"{NAME}.csv", index=False)

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.3))
    for c, (mu, d) in enumerate(df.groupby("mu_d [-]")):
        ax[0].loglog(d["D [m]"], np.abs(d["dF_C_max [-]"]), "o-", color=f"C{c}", label=f"peak F_C, mu_d = {mu:g}")
        ax[0].loglog(d["D [m]"], d["max_dF_C_history [-]"], "s--", color=f"C{c}",
                     label=f"F_C history (max), mu_d = {mu:g}")
    ax[0].set_xlabel("drum diameter D [m]")
    ax[0].set_ylabel("|capstan - rigid| / rigid peak F_C")
    ax[0].set_title("effect of the drum's contact compliance (Li et al. eq. 12)")
    ax[0].legend(fontsize=7)
    ax[0].grid(True, which="both", alpha=0.3)
    mu0 = sorted(df["mu_d [-]"].unique())[len(df["mu_d [-]"].unique()) // 2]
    rh = hist[("rigid", mu0)]
    ax[1].plot(rh["t [s]"], rh["F_C [N]"] / 1e3, "k-", lw=1.2, label="rigid contact")
    for D in (df["D [m]"].min(), df["D [m]"].max()):
        h = hist[(D, mu0)]
        ax[1].plot(h["t [s]"], h["F_C [N]"] / 1e3, lw=0.9, label=f"capstan, D = {D:g} m")
    ax[1].set_xlabel("t [s]")
    ax[1].set_ylabel("F_C [kN]")
    ax[1].set_title(f"start-up, Fig. 9 haulage, mu_d = {mu0:g}")
    ax[1].legend(fontsize=8)
    ax[1].grid(True, alpha=0.3)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: df.to_string(index=False))
