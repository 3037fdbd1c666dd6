"""Peak rope force of a start-up and a braking against the ramp time and the rope's damping: a design chart.

The Fig. 9 haulage of Krauze et al. (2025) (ropemodel/data/winch_start.toml: load 50 m above
the return sheave, 1500 mm stroke, two turns on the drum) is started upward and braked while
lowering (ropemodel/data/winch_start_brake.toml) with linear drive ramps of 1-20 s and rope
damping (Kelvin-Voigt retardation time) 0-0.2 s.  For every case: the peak F_C, the dynamic
factor F_C_max / F_C_static, the least F_S, and whether the rope slipped on the drum, the
tensioner ran out of stroke or a rope span went slack.  The inextensible-rope value
(static + moving mass x ramp acceleration) is drawn for comparison.  The elastic peak stays
well above it even for long ramps because of the breakaway: the load stays (nearly) put while
the rope stretches by (resistance)/k, and when it breaks away the drum is already moving at
v_b, so the load oscillates on the rope with a force amplitude of about k·v_b/ω (18 kN for a
20 s ramp here: 191 + 7 + 18 = 216 kN against 214.5 kN simulated).  A cosine ramp does not
remove it (ramp = "cosine").  Rope damping of realistic size lowers the peak only a little.
Braking a lowered load ends at rest, where the smoothed resistance vanishes: the load creeps
(time constant ≈ (T_m + T_l)/(v_eps k), 12 s here) towards the frictionless holding force
0.5 F_nwl + G_lmC, 20 % above the moving F_C of the paper's downward column, so long braking
ramps level off near 1.16-1.2 rather than 1.  Also draws the history of the
four start-up example scenes.

    python studies/dynamic_factor.py [--fast]
"""

from __future__ import annotations

import time
import tomllib
from importlib import resources
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import ropemodel as rm  # noqa: E402
from ropemodel.dynamics import simulate  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure

NAME = "dynamic_factor"
FIGURES = Path(__file__).resolve().parent / "figures"
DATA = resources.files("ropemodel.data")
G_N = 9.80665  # standard gravity [m/s²]
CASES = {"start-up, upward": "winch_start.toml", "braking, downward": "winch_start_brake.toml"}


def _scene(name, params, numerics):
    d = tomllib.loads(DATA.joinpath(name).read_text())
    d["parameters"].update(params)
    d.setdefault("numerics", {}).update(numerics)
    return rm.from_dict(d, bare="si")


def chart(ramps, dampings, segments) -> pd.DataFrame:
    rows = []
    for case, name in CASES.items():
        for tau in dampings:
            for t_ramp in ramps:
                sc = _scene(name, {"t_ramp": float(t_ramp), "t_end": float(t_ramp) + 15.0, "rope_damping": float(tau)},
                            {"segments": segments})
                t0 = time.perf_counter()
                s = simulate(sc).summary
                rows.append({"case": case, "t_ramp [s]": t_ramp, "rope_damping [s]": tau,
                             "F_C_max [N]": s["F_C_max"], "F_C_static [N]": s["F_C_static"],
                             "dynamic_factor [-]": s["dynamic_factor"], "F_S_min [N]": s["F_S_min"],
                             "slip": s["slip"], "stroke_exhausted": s["stroke_exhausted"], "slack": s["slack"],
                             "rigid_factor [-]": _rigid_factor(sc), "seconds": time.perf_counter() - t0})
    return pd.DataFrame(rows)


def _rigid_factor(sc) -> float:
    """Inextensible rope: (F_C_static + (G_m + q_l L_u)/g · |a|) / F_C_static on the loaded side.

    Start-up upward: F_C grows by m_C a; braking downward: the deceleration also raises F_C.
    """
    v = sc.parameters
    d = sc.effects["travel"]
    F = rm.run(sc)[f"F_C_{d}"]
    return (F + (v["G_m"] + v["q_l"] * v["L_u"]) / G_N * v["v_pj"] / v["t_ramp"]) / F


def histories(t_end: float, segments: int) -> dict:
    out = {}
    for name in ("winch_start.toml", "winch_start_slip.toml", "winch_start_stroke.toml", "winch_start_motor.toml"):
        sim = simulate(_scene(name, {"t_end": t_end}, {"segments": segments}))
        out[sim.scene.name] = sim
    return out


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    ramps = [2.0, 6.0] if fast else [1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 14.0, 20.0]
    dampings = [0.05] if fast else [0.0, 0.02, 0.05, 0.1, 0.2]
    segments = 4 if fast else 8
    df = chart(ramps, dampings, segments)
    df.to_csv(out / f"{NAME}.csv", index=False)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharey=True)
    colors = plt.cm.viridis(np.linspace(0, 0.85, len(dampings)))
    for ax, case in zip(axes, CASES):
        d = df[df["case"] == case]
        for c, tau in zip(colors, dampings):
            dd = d[d["rope_damping [s]"] == tau]
            ax.plot(dd["t_ramp [s]"], dd["dynamic_factor [-]"], "-", color=c, label=f"tau = {tau:g} s")
            for flag, marker, ms in (("slip", "o", 8), ("stroke_exhausted", "s", 6), ("slack", "x", 7)):
                bad = dd[dd[flag]]
                ax.plot(bad["t_ramp [s]"], bad["dynamic_factor [-]"], marker, mfc="none", color="r", ms=ms)
        rig = d[d["rope_damping [s]"] == dampings[0]]
        ax.plot(rig["t_ramp [s]"], rig["rigid_factor [-]"], "k--", label="inextensible rope, in motion")
        ax.set_xscale("log")
        ax.set_xlabel("drive ramp time t_ramp [s]")
        ax.set_title(f"{case} (Fig. 9 haulage)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("dynamic factor F_C,max / F_C,static")
    axes[0].legend(fontsize=8, title="rope damping (Kelvin-Voigt)", title_fontsize=8)
    axes[1].text(0.02, 0.02, "red: o slip on the drum, [] tensioner out of stroke,\n"
                 "x a span went slack (simulation ends there: peak not reached)", transform=axes[1].transAxes,
                 fontsize=8, color="r")
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)

    sims = histories(12.0 if fast else 40.0, segments)
    fig, ax = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    for (title, sim), c in zip(sims.items(), ("C0", "C1", "C3", "C2")):
        h = sim.history
        t = h["t [s]"]
        ax[0].plot(t, h["F_C [N]"] / 1e3, color=c, label=title)
        ax[0].plot(t, h["F_S [N]"] / 1e3, color=c, ls=":")
        ax[1].plot(t, h["v_load [m/s]"], color=c)
        ax[1].plot(t, h["v_drum [m/s]"], color=c, ls=":", lw=0.8)
        ax[2].plot(t, h["take_up [m]"] * 1e3, color=c)
        pd.DataFrame(h).to_csv(out / f"history_{Path(sim.scene.source or 'scene').stem}.csv", index=False)
    ax[0].set_ylabel("F_C (solid), F_S (dotted) [kN]")
    ax[0].legend(fontsize=8)
    ax[1].set_ylabel("load (solid), drum (dotted) [m/s]")
    ax[2].set_ylabel("tensioner take-up [mm]")
    ax[2].set_xlabel("t [s]")
    for a in ax:
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "dynamic_start.png", dpi=110)
    if not fast:
        fig.savefig(FIGURES / "dynamic_start.png", dpi=110)
    plt.close(fig)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: df.drop(columns=["seconds"]).to_string(index=False))
