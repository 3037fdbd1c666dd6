"""What the lining's creep takes from a Koepe hoist's braking window, against Euler–Eytelwein.

The issue-25 example hoist (H = 905 m, H_head = 56.7 m, conveyances 29.6 t, payload 22 t, 4 head ropes of
8.6 kg/m, 2 tail ropes of 15.5 kg/m, μ = 0.25 over α = 180°, D = 4.5 m) on a Voigt-lined wheel
(Hajduk 1992, eq. (19) on the wheel's arc: ``ropemodel.papers.koepe_lining``), for linings of measured
stiffness and assumed retardation times, against the rigid lining (Euler–Eytelwein):

* the four slip accelerations (``a_slip_hoist_accel`` … ``a_slip_lower_decel``), each the least over the
  wind (19 positions of the loaded conveyance, loaded and empty) against the rope speed v, 0 … 20 m/s;
* the admissible emergency-braking window of each direction, [max(d_min, d_free), min d_slip] over the
  wind (``koepe_slip.braking_window``), and the share of the rigid window the creep takes;
* where the window closes: the lining modulus E below which the crept lining's slip limit falls under the
  floor (at rest, where the lining has fully crept), by brentq on E.

Like for like: the rigid reference is Euler–Eytelwein without the ropes on the arc (``q_arc = 0``), the
limit Q → 0 of Hajduk's model, which leaves the arc's rope out too (docs/physics.md §7); the rigid limit
with the arc's rope (its inertia and centrifugal force) is drawn grey for scale.  Quasi-steady: the creep
is taken at the speed of the instant (k = λ v/R), as if the wheel had run at v long enough to fill the arc;
in a stop the rope on the arc has crept for less time than that, so the low-speed end is conservative.

Inputs and their sources:

* lining modulus E: 920 MPa, the flexural modulus of GM-3, a K25-class (Becorit-type) friction liner of
  Shore D 70–74 (maker's data sheet, https://top-factories.com/products/3372799.html, which compares it with
  K25); 600 MPa and 90 MPa, polyurethane of 70 and 42 Shore D (Vulkollan data quoted at
  https://www.pepsenpu.com/the-big-world-polyurethane-what-are-physical-properties-polyurethane-a-40.html:
  600 MPa at 70D; 2.25 MPa at 2.5 % elongation at 42D), the range of the softer PVC/PU liners; 5 MPa, a
  65 Shore A elastomer (same source): not a Koepe lining today (Hajduk names rubber), drawn to show where
  the window closes.  μ = 0.25 for polymer linings: TAS (Bezirksregierung Arnsberg, 7., "Werkstoffe für
  Treibscheibenfutter"); Stawowiak et al. 2019 measured μ >= 0.25 on Becorit K22 and K25SB.
* Poisson's ratio 0.45 (assumed: polymers 0.4–0.5), G = E/(2(1 + ν)); lining thickness under the rope
  h = 30 mm (assumed); contact width a = the rope's diameter, 46.4 mm for 8.6 kg/m of a 6x19 IWRC rope
  (EN 12385-4 via ropemodel's catalogue; the width is assumed).  Q_R = h/(E R² a), Q_T = μ/(G R a)
  (Hajduk 1992, eq. (3)): Q_T/Q_R = 2 μ (1 + ν) R/h ≈ 54, so the tangential compliance governs and h
  hardly matters.  As published, eq. (2)-(3) take the lining's shear strain itself as the rope's strain (no
  factor h/R, unlike the radial term); were the rope to follow only the lining surface's shift h γ, Q_T would
  be about R/h = 75 times smaller and so would the creep's effect.  The study uses the model as published.
* retardation time λ (assumed, λ_R = λ_T: no measured value for a hoist lining was found): 0.01, 0.1 and
  0.35 s, inside Hajduk's assumption that the lining recovers while the wheel turns through the free angle,
  λ <= (2π − α) R/v (0.35 s at 20 m/s); 3 s beyond it, dotted where λ v/R > 2π − α.
* d_min = 1.5 m/s², the least emergency deceleration of New Brunswick Reg. 96-105 s. 192(1) (drum hoists
  carrying persons; a scene's rule set supersedes it); d_free = s (T_L − T_E)/M with the suspended masses
  only (the wheel's and drive's inertia, not given, would lower it: leaving them out is conservative).

``python studies/koepe_lining.py [--fast]`` writes koepe_lining.csv (slip limits), koepe_lining_window.csv,
koepe_lining_summary.csv and koepe_lining.png.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import pandas as pd
from scipy.optimize import brentq

from ropemodel.papers import en12385
from ropemodel.papers import hajduk1992 as hj
from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_lining as kl
from ropemodel.papers import koepe_slip as ks
from ropemodel.studykit import cli, output_dir, save_figure

NAME = "koepe_lining"
#: the issue-25 example [SI]
H, H_HEAD, M_C, M_P = 905.0, 56.7, 29.6e3, 22e3
N_HEAD, Q_HEAD, N_TAIL, Q_TAIL = 4, 8.6, 2, 15.5
MU, ALPHA, R = 0.25, math.pi, 2.25
#: lining geometry (assumed, see the docstring) [-], [m]
NU, H_LINING = 0.45, 0.030
A_CONTACT = math.sqrt(Q_HEAD / en12385.construction("6x19-IWRC").W)
#: least emergency deceleration [m/s²] (New Brunswick Reg. 96-105 s. 192(1))
D_MIN = 1.5
#: linings: label → Young's modulus [Pa]
LININGS = {"K25-class, 920 MPa": 920e6, "PU 70 Shore D, 600 MPa": 600e6, "PU 42 Shore D, 90 MPa": 90e6,
           "rubber 65 Shore A, 5 MPa": 5e6}
#: retardation times [s] (assumed)
LAMBDAS = (0.01, 0.1, 0.35, 3.0)
#: the braking manoeuvre of each direction
BRAKING = {"hoisting": "hoist_decel", "lowering": "lower_decel"}


def compliances(E):
    """(Q_R, Q_T) [1/N] per rope of a lining of Young's modulus E [Pa] (Hajduk 1992, eq. (3))."""
    G = E / (2.0 * (1.0 + NU))
    return hj.radial_compliance(H_LINING, E, R, A_CONTACT), hj.tangential_compliance(MU, G, R, A_CONTACT)


class Cases(NamedTuple):
    """The static cases over the wind, as arrays: loaded conveyance's depth [m], payload [kg], tensions [N],
    moving masses [kg] (M = T/g)."""

    y_L: np.ndarray
    payload: np.ndarray
    T_L: np.ndarray
    T_E: np.ndarray
    M_L: np.ndarray
    M_E: np.ndarray


def cases(n_positions: int) -> Cases:
    """Loaded and empty hoist at n_positions depths of the loaded conveyance, 0 … H."""
    y = np.tile(np.linspace(0.0, H, n_positions), 2)
    payload = np.repeat([M_P, 0.0], n_positions)
    T_L, T_E = kp.side_tensions(y, M_C, payload, H, H_HEAD, N_HEAD, Q_HEAD, N_TAIL, Q_TAIL)
    return Cases(y, payload, T_L, T_E, kp.side_mass(T_L), kp.side_mass(T_E))


def slip_limits(c: Cases, v, Q_R, Q_T, lam) -> dict[str, np.ndarray]:
    """Voigt lining: manoeuvre → a_slip [m/s²], shape (cases, speeds); v [m/s] a 1-d array."""
    out = {}
    for name, sides in ks.manoeuvre_sides(c.T_L, c.T_E, c.M_L, c.M_E).items():
        F_U, F_D, M_U, M_D = (np.asarray(a)[:, None] for a in sides)
        out[name] = np.asarray(kl.voigt_slip_acceleration(F_U, F_D, M_U, M_D, N_HEAD, MU, ALPHA, R,
                                                          np.asarray(v)[None, :], Q_R, lam, Q_T, lam))
    return out


def rigid_limits(c: Cases, v, arc: bool) -> dict[str, np.ndarray]:
    """Euler–Eytelwein: manoeuvre → a_slip [m/s²], shape (cases, speeds); with the arc's rope if ``arc``."""
    out, v, q = {}, np.asarray(v)[None, :], N_HEAD * Q_HEAD if arc else 0.0
    for name, sides in ks.manoeuvre_sides(c.T_L, c.T_E, c.M_L, c.M_E).items():
        F_U, F_D, M_U, M_D = (np.asarray(a)[:, None] for a in sides)
        out[name] = np.broadcast_to(ks.slip_acceleration(F_U, F_D, M_U, M_D, MU, ALPHA, q, R, v), (len(c.y_L), v.size))
    return out


def edges(c: Cases, direction: str, d_slip) -> tuple:
    """The window [low, high] [m/s²] (``koepe_slip.braking_window``): low the rule's d_min or the deceleration
    without brake, the larger over the wind; high the slip limit d_slip (the least over the wind)."""
    s = 1.0 if direction == "hoisting" else -1.0
    d_free = float(np.max(ks.coasting_deceleration(c.T_L, c.T_E, c.M_L + c.M_E, s)))
    return ks.braking_window(d_slip, D_MIN, d_free=d_free)


def floor(c: Cases, direction: str) -> float:
    """Lower edge of the window [m/s²] (:func:`edges`)."""
    return float(edges(c, direction, math.inf)[0])


def ceiling_at_rest(c: Cases, E: float, direction: str) -> float:
    """Upper edge of the window [m/s²] at v = 0 (the lining fully crept, any λ) for a lining of modulus E [Pa]."""
    Q_R, Q_T = compliances(E)
    return float(np.min(slip_limits(c, np.array([0.0]), Q_R, Q_T, 1.0)[BRAKING[direction]]))


def closing_modulus(c: Cases, direction: str) -> float:
    """Lining modulus E [Pa] below which the window of ``direction`` is empty at rest (brentq on ln E)."""
    lo = floor(c, direction)
    return math.exp(brentq(lambda u: ceiling_at_rest(c, math.exp(u), direction) - lo, math.log(1e5),
                           math.log(1e11), xtol=1e-12, rtol=1e-14))


def measure(c: Cases, v: np.ndarray) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Long tables: the worst slip limits per lining, λ, speed and manoeuvre; the windows."""
    rigid, arc = rigid_limits(c, v, False), rigid_limits(c, v, True)
    rows, windows = [], []
    for label, E in {"rigid (Euler–Eytelwein)": math.inf, **LININGS}.items():
        Q_R, Q_T = compliances(E) if math.isfinite(E) else (0.0, 0.0)
        for lam in LAMBDAS if math.isfinite(E) else (0.0,):
            limits = slip_limits(c, v, Q_R, Q_T, lam)
            for name, a in limits.items():
                worst = np.argmin(a, axis=0)
                rows.append(pd.DataFrame({
                    "lining": label, "E [Pa]": E, "Q_R [1/N]": Q_R, "Q_T [1/N]": Q_T, "lambda [s]": lam,
                    "v [m/s]": v, "manoeuvre": name, "a_slip [m/s2]": a.min(axis=0),
                    "y_L at worst [m]": c.y_L[worst], "payload at worst [kg]": c.payload[worst],
                    "rigid [m/s2]": rigid[name].min(axis=0), "rigid with arc rope [m/s2]": arc[name].min(axis=0),
                    "within Hajduk's assumption": lam * v / R <= 2 * math.pi - ALPHA}))
            for direction, name in BRAKING.items():
                (low, high), high_rigid = edges(c, direction, limits[name].min(axis=0)), rigid[name].min(axis=0)
                windows.append(pd.DataFrame({
                    "lining": label, "E [Pa]": E, "lambda [s]": lam, "v [m/s]": v, "direction": direction,
                    "low [m/s2]": low, "high [m/s2]": high, "high rigid [m/s2]": high_rigid,
                    "share taken [-]": (high_rigid - high) / (high_rigid - low), "open": high >= low}))
    return pd.concat(rows, ignore_index=True), pd.concat(windows, ignore_index=True)


def opening_speed(c: Cases, E: float, lam: float, direction: str, v_max: float) -> float:
    """Speed [m/s] below which the window of ``direction`` is empty (brentq on v; the ceiling rises with v):
    0 when it is open at rest, inf when it is still empty at v_max."""
    Q_R, Q_T = compliances(E)
    lo, name = floor(c, direction), BRAKING[direction]

    def excess(v):
        return float(np.min(slip_limits(c, np.array([v]), Q_R, Q_T, lam)[name])) - lo

    if excess(0.0) >= 0.0:
        return 0.0
    if excess(v_max) < 0.0:
        return math.inf
    return brentq(excess, 0.0, v_max, xtol=1e-10, rtol=1e-13)


def summary(c: Cases, window: pd.DataFrame) -> pd.DataFrame:
    """Per lining and direction: the share of the rigid window taken at rest and at the top speed (each λ),
    the speed below which the window is empty (each λ), and the modulus at which it closes at rest."""
    rows = []
    for (label, direction), g in window[window["E [Pa]"] < math.inf].groupby(["lining", "direction"], sort=False):
        E, rest, v_max = g["E [Pa]"].iloc[0], g[g["v [m/s]"] == 0.0], g["v [m/s]"].max()
        row = {"lining": label, "direction": direction, "E [Pa]": E,
               "E closing the window at rest [Pa]": closing_modulus(c, direction),
               "low [m/s2]": g["low [m/s2]"].iloc[0], "high rigid [m/s2]": g["high rigid [m/s2]"].iloc[0],
               "high at rest [m/s2]": rest["high [m/s2]"].iloc[0],
               "share taken at rest [-]": rest["share taken [-]"].iloc[0]}
        for lam, gl in g.groupby("lambda [s]"):
            row[f"share taken at {v_max:g} m/s, lambda {lam:g} s [-]"] = \
                gl.loc[gl["v [m/s]"] == v_max, "share taken [-]"].iloc[0]
            row[f"empty below [m/s], lambda {lam:g} s"] = opening_speed(c, E, lam, direction, v_max)
        rows.append(row)
    return pd.DataFrame(rows)


#: line style of each retardation time; colour of each lining
STYLE = dict(zip(LAMBDAS, ("-", "--", "-.", ":")))
COLOUR = dict(zip(LININGS, ("#1f618d", "#17a589", "#d68910", "#c0392b")))


def _curves(ax, table: pd.DataFrame, value: str) -> None:
    """One line per lining and λ; the part outside Hajduk's assumption (λ v/R > 2π − α) drawn faint."""
    for (label, lam), g in table[table["E [Pa]"] < math.inf].groupby(["lining", "lambda [s]"], sort=False):
        inside = (lam * g["v [m/s]"] / R <= 2 * math.pi - ALPHA).to_numpy()
        ax.plot(g["v [m/s]"].where(inside), g[value], STYLE[lam], color=COLOUR[label], lw=1.2)
        ax.plot(g["v [m/s]"], g[value], STYLE[lam], color=COLOUR[label], lw=0.8, alpha=0.35)


def _slip_panels(axes, limits: pd.DataFrame) -> None:
    for ax, name in zip(axes, ks.MANOEUVRES):
        t = limits[limits["manoeuvre"] == name]
        rigid = t[t["E [Pa]"] == math.inf]
        _curves(ax, t, "a_slip [m/s2]")
        ax.plot(rigid["v [m/s]"], rigid["a_slip [m/s2]"], "k--", lw=1.6, label="rigid, Euler–Eytelwein")
        ax.plot(rigid["v [m/s]"], rigid["rigid with arc rope [m/s2]"], color="0.6", lw=1.2,
                label="rigid, with the arc's rope")
        polymer = t[(t["E [Pa]"] >= 90e6) & (t["E [Pa]"] < math.inf)]
        top = max(rigid["a_slip [m/s2]"].max(), polymer["a_slip [m/s2]"].max())
        bottom = min(polymer["a_slip [m/s2]"].min(), rigid["rigid with arc rope [m/s2]"].min())
        ax.set_ylim(bottom - 0.02 * top, top + 0.01 * top)
        ax.text(0.02, 0.03, "rubber (5 MPa) lies below: see the window panels", transform=ax.transAxes, fontsize=7,
                color=COLOUR["rubber 65 Shore A, 5 MPa"])
        ax.set_title(f"a_slip_{name}" + (" (ropes arrive on the tight side)" if "accel" in name else ""),
                     fontsize=9)
        ax.set_xlabel("rope speed v [m/s]")
    axes[0].set_ylabel("slip limit, least over the wind [m/s²]")
    axes[0].legend(fontsize=7)


def _window_panel(ax, window: pd.DataFrame, direction: str) -> None:
    t = window[window["direction"] == direction]
    rigid = t[t["E [Pa]"] == math.inf]
    low = rigid["low [m/s2]"].iloc[0]
    ax.fill_between(rigid["v [m/s]"], low, rigid["high [m/s2]"], color="0.88", label="rigid window")
    ax.axhline(low, color="k", lw=1.0)
    ax.text(0.3, low, f" floor {low:.2f} m/s²", va="bottom", fontsize=7)
    _curves(ax, t, "high [m/s2]")
    closed = t[~t["open"]].iloc[::4 if len(t) > 200 else 1]
    ax.plot(closed["v [m/s]"], closed["high [m/s2]"], "x", color="k", ms=3.5, label="window empty")
    ax.set_title(f"{direction}: emergency-brake window (upper edge per lining)", fontsize=9)
    ax.set_xlabel("rope speed v [m/s]")
    ax.legend(fontsize=7, loc="lower right")


def _modulus_panel(ax, c: Cases, moduli: np.ndarray, summ: pd.DataFrame) -> None:
    ax.axvspan(90e6, 920e6, color="0.9", label="polymer liners (90–920 MPa)")
    for direction, colour in (("hoisting", "#7d3c98"), ("lowering", "#2e4053")):
        ceiling = [ceiling_at_rest(c, E, direction) for E in moduli]
        ax.semilogx(moduli, ceiling, color=colour, label=f"{direction}: upper edge at rest")
        ax.axhline(floor(c, direction), color=colour, lw=0.8, ls=":")
        E_c = summ.loc[summ["direction"] == direction, "E closing the window at rest [Pa]"].iloc[0]
        ax.plot(E_c, floor(c, direction), "o", color=colour, mfc="none")
        ax.annotate(f"{direction} closes\nbelow {E_c / 1e6:.3g} MPa", (E_c, floor(c, direction)), fontsize=7,
                    xytext=(8, -26 if direction == "lowering" else 6), textcoords="offset points", color=colour)
    for label, E in LININGS.items():
        ax.axvline(E, color=COLOUR[label], lw=0.8)
    ax.set_xlabel("lining modulus E [Pa]  (Q_T = μ/(G R a), G = E/2.9)")
    ax.set_ylabel("[m/s²]")
    ax.set_ylim(-0.5, None)
    ax.set_title("the window at rest (lining fully crept) against the lining's stiffness", fontsize=9)
    ax.legend(fontsize=7)


def _share_panel(ax, window: pd.DataFrame) -> None:
    t = window[window["direction"] == "lowering"]
    _curves(ax, t.assign(share=t["share taken [-]"].clip(1e-4, 2.0)), "share")
    ax.set_yscale("log")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("rope speed v [m/s]")
    ax.set_ylabel("share of the rigid window taken [-]")
    ax.set_title("lowering: what the creep takes (1 = the window is gone)", fontsize=9)
    for label in LININGS:
        ax.plot([], [], color=COLOUR[label], label=label)
    for lam in LAMBDAS:
        ax.plot([], [], STYLE[lam], color="k", label=f"λ = {lam:g} s")
    ax.legend(fontsize=6.5, ncol=2)


def plot(c: Cases, limits: pd.DataFrame, window: pd.DataFrame, summ: pd.DataFrame, moduli, fast, out) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 4, figsize=(17, 8.6))
    _slip_panels(axes[0], limits)
    _window_panel(axes[1, 0], window, "hoisting")
    _window_panel(axes[1, 1], window, "lowering")
    _modulus_panel(axes[1, 2], c, moduli, summ)
    _share_panel(axes[1, 3], window)
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.suptitle("Koepe hoist of issue 25 on a Voigt-lined wheel (Hajduk 1992, eq. (19)) against Euler–Eytelwein: "
                 "slip limits and emergency-brake window over rope speed and lining stiffness.\n"
                 "Colour: lining; line style: retardation time λ (faint: beyond Hajduk's λ ≤ (2π − α)R/v); "
                 "every value the least over the wind, loaded and empty", fontsize=10)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    c = cases(3 if fast else 19)
    v = np.array([0.0, 2.0, 5.0, 10.0, 20.0]) if fast else np.linspace(0.0, 20.0, 81)
    limits, window = measure(c, v)
    summ = summary(c, window)
    limits.to_csv(out / f"{NAME}.csv", index=False)
    window.to_csv(out / f"{NAME}_window.csv", index=False)
    summ.to_csv(out / f"{NAME}_summary.csv", index=False)
    plot(c, limits, window, summ, np.logspace(6, 10, 9 if fast else 61), fast, out)
    return summ


def _show(summ: pd.DataFrame) -> str:
    cols = ["lining", "direction", "share taken at rest [-]", "E closing the window at rest [Pa]",
            "empty below [m/s], lambda 3 s"]
    return summ[cols].to_string(index=False, float_format=lambda x: f"{x:.4g}")


if __name__ == "__main__":
    cli(main, __doc__, show=_show)
