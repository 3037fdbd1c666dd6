"""Events inside one output step: a short slip episode located against scipy, for output steps up to 1 s.

The start-up of ropemodel/data/winch_start_slip.toml with an inextensible rope and a cosine
ramp: the drum's traction e^{μα} is set so that the stick margin dips below zero only for a
fraction ε of the peak ramp acceleration (a* = (1 − ε) a_max), a slip episode of 0.6 s
(ε = 1e-2) down to 21 ms (ε = 1e-5) around the peak.  The truth is Newton's law of the
inextensible loop solved by scipy's solve_ivp (DOP853, rtol 1e-13) with event functions
(onset by brentq on the stick margin, end where the rope's speed meets the drum's).  For
every output step sim_dt (0.01-1 s) and ε: whether the slip is found, the errors of its
start, end and length, and the wall time relative to sim_dt = 0.02 s (medians, same run).
The switching functions are checked with their rates on a detection grid of sim_dt/2
(:mod:`ropemodel.dynamics.hybrid`), so an episode between two outputs is still found.

    python studies/dynamics_events.py [--fast]
"""

from __future__ import annotations

import math
import time
import tomllib
from importlib import resources

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

import ropemodel as rm  # noqa: E402
from ropemodel.dynamics import simulate  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure

NAME = "dynamics_events"
DATA = resources.files("ropemodel.data")
G_N = 9.80665  # standard gravity [m/s²]
RTOL = 1e-12


def _scene(params=None, numerics=None):
    d = tomllib.loads(DATA.joinpath("winch_start_slip.toml").read_text())
    d["effects"].update({"rope_elasticity": "rigid", "ramp": "cosine"})
    d["parameters"].update({"t_end": "8 s", **(params or {})})
    d["numerics"].update(numerics or {})
    return rm.from_dict(d, bare="si")


def truth(eps):
    """(mu_d, slip start, slip end, slip length) of the inextensible loop, by scipy."""
    v = _scene().parameters
    m_C, m_S = (v["G_m"] + v["q_l"] * v["L_u"]) / G_N, v["q_l"] * v["L_u"] / G_N
    sa, ca_ = math.sin(v["alpha_u"]), math.cos(v["alpha_u"])
    half = v["F_nwl"] / 2
    G_C, G_S = (v["G_m"] + v["q_l"] * v["L_u"]) * sa, v["q_l"] * v["L_u"] * sa
    R_C = (v["mu_pm"] * v["G_m"] + v["mu_pl"] * v["q_l"] * v["L_u"]) * ca_
    R_S = v["mu_pl"] * v["q_l"] * v["L_u"] * ca_
    T, V = v["t_ramp"], v["v_pj"]
    a_max = math.pi / 2 * V / T
    a_s = a_max * (1 - eps)
    rho = (half + G_C + R_C + m_C * a_s) / (half + G_S - R_S - m_S * a_s)

    def th(s):
        return math.tanh(s / v["v_eps"])

    def vd(t):
        return V * 0.5 * (1 - math.cos(math.pi * min(t, T) / T))

    def ad(t):
        return a_max * math.sin(math.pi * t / T) if t < T else 0.0

    def margin(t):
        return rho * (half + G_S - R_S * th(vd(t)) - m_S * ad(t)) - (half + G_C + R_C * th(vd(t)) + m_C * ad(t))

    t0 = brentq(margin, 1.0, T / 2, xtol=1e-15)

    def rhs(t, y):
        a = (rho * (half + G_S - R_S * th(y[1])) - half - G_C - R_C * th(y[1])) / (m_C + rho * m_S)
        return [vd(t) - y[1], a]

    def caught_up(t, y):
        return vd(t) - y[1] if t > t0 + 1e-9 else 1.0

    caught_up.terminal, caught_up.direction = True, -1
    sol = solve_ivp(rhs, (t0, T), [0.0, vd(t0)], method="DOP853", rtol=1e-13, atol=1e-15, events=caught_up)
    return math.log(rho) / v["alpha_d"], t0, sol.t_events[0][0], sol.y_events[0][0][0]


def measure(eps_list, dts, repeats) -> pd.DataFrame:
    rows = []
    for eps in eps_list:
        mu_d, t0, t1, dist = truth(eps)
        for dt in dts:
            secs = []
            for _ in range(repeats):
                c0 = time.perf_counter()
                sim = simulate(_scene({"mu_d": mu_d}, {"sim_dt": dt, "sim_rtol": RTOL}))
                secs.append(time.perf_counter() - c0)
            ev = sim.summary["slip_events"]
            found = len(ev) == 1 and ev[0]["t_end"] is not None
            rows.append({"eps [-]": eps, "sim_dt [s]": dt, "slip_duration [s]": t1 - t0, "slip_length [m]": dist,
                         "inside_one_output_step": math.floor(t0 / dt) == math.floor(t1 / dt),
                         "found": found,
                         "err_t_start [s]": abs(ev[0]["t_start"] - t0) if ev else math.nan,
                         "err_t_end [s]": abs(ev[0]["t_end"] - t1) if found else math.nan,
                         "err_length [-]": abs(ev[0]["distance"] - dist) / dist if found else math.nan,
                         "seconds": float(np.median(secs))})
    df = pd.DataFrame(rows)
    for _, d in df.groupby("eps [-]"):
        base = d.loc[np.isclose(d["sim_dt [s]"], 0.02), "seconds"]
        df.loc[d.index, "time_ratio_to_dt_0.02 [-]"] = d["seconds"] / (float(base.iloc[0]) if len(base) else
                                                                       float(d["seconds"].median()))
    return df


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    if fast:
        df = measure([1e-3], [0.02, 0.7], repeats=1)
    else:
        df = measure([1e-2, 1e-3, 1e-4, 1e-5], [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 0.7, 1.0], repeats=3)
    df.to_csv(out / f"{NAME}.csv", index=False)

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.3))
    for c, (eps, d) in enumerate(df.groupby("eps [-]")):
        lab = f"eps = {eps:g} (slip {d['slip_duration [s]'].iloc[0] * 1e3:.0f} ms)"
        ax[0].loglog(d["sim_dt [s]"], np.maximum(d["err_t_start [s]"], 1e-16), "o-", color=f"C{c}", label=lab)
        ax[0].loglog(d["sim_dt [s]"], np.maximum(d["err_t_end [s]"], 1e-16), "s--", color=f"C{c}")
        inside = d[d["inside_one_output_step"]]
        ax[0].plot(inside["sim_dt [s]"], np.maximum(inside["err_t_end [s]"], 1e-16), "kx", ms=8)
        ax[1].semilogx(d["sim_dt [s]"], d["time_ratio_to_dt_0.02 [-]"], "o-", color=f"C{c}", label=lab)
    ax[0].set_xlabel("output step sim_dt [s]")
    ax[0].set_ylabel("|event time - scipy| [s]  (o start, s end)")
    ax[0].set_title(f"slip located (x: whole episode inside one output step), rtol {RTOL:g}")
    ax[0].legend(fontsize=7)
    ax[0].grid(True, which="both", alpha=0.3)
    ax[1].set_xlabel("output step sim_dt [s]")
    ax[1].set_ylabel("wall time / wall time at sim_dt = 0.02 s")
    ax[1].set_title("cost")
    ax[1].legend(fontsize=7)
    ax[1].grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: df.to_string(index=False))
