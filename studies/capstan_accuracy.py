"""Capstan rotation: accuracy against a fine reference and cost against scipy's solve_ivp written as a user would.

Cases: random drives over the documented range (μ ∈ [0.05, 1], α0 ≤ 40 rad, 0 ≤ F_T ≤ 2F_p,
EA 10³–10⁷ N, R 0.01–1 m, L 0–10 m, F_p 1–10⁴ N), keeping those whose slack side stays wrapped.

* reference: DOP853 at rtol 1e-13 in F with the regime frozen between switches located by events
  (written here, numpy);
* ropemodel: ``ropemodel.capstan.batch.rotation_batch`` at its defaults (published law ``li``,
  rtol 1e-7), compiled to C where a compiler works, one batched call;
* the peer: ``solve_ivp`` on a plain numpy right side dδ/dF = 1/K(F, α0 ± δ/R) (eq. 26 in the
  tight + slack reading, switches evaluated inside the right side, no events: as a user would
  write it), LSODA, DOP853, Radau at several tolerances; the headline is the cheapest configuration
  at least as accurate as ropemodel's default.  Only time ratios are reported.

    python studies/capstan_accuracy.py [--fast]
"""

from __future__ import annotations

import math
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from ropemodel.capstan.batch import rotation_batch  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure  # noqa: E402

NAME = "capstan_accuracy"
METHODS = ("LSODA", "DOP853", "Radau")


def drives(n, seed=5):
    rng = np.random.default_rng(seed)
    F_p = 10 ** rng.uniform(0, 4, n)
    return {"F_T": F_p * rng.uniform(0, 2, n), "mu": rng.uniform(0.05, 1.0, n), "EA": 10 ** rng.uniform(3, 7, n),
            "R": 10 ** rng.uniform(-2, 0, n), "L": np.where(rng.random(n) < 0.1, 0.0, 10 ** rng.uniform(-2, 1, n)),
            "alpha_0": rng.uniform(0.1, 40.0, n), "F_p": F_p}


def stiffness(F, F_p, mu, EA, R, L, a1, a2, flags=None):
    """K = K_ti + K_sl, eq. (26) read as tight + slack (regime from the state, or frozen ``flags``)."""
    z = (math.log1p(F / F_p) - mu * a1, F / F_p + math.expm1(-mu * a2), F / F_p - 1.0)
    tight, slack, unloaded = flags if flags is not None else [v >= 0 for v in z]
    kt = (mu * EA / (2 * R * -math.expm1(-mu * a1) + mu * L) if tight
          else mu * EA * (F_p + F) / (2 * R * F + mu * L * (F_p + F)))
    if unloaded:
        return kt
    if slack:
        return kt + mu * EA / (2 * R * -math.expm1(-mu * a2) + mu * L)
    return kt + mu * EA * (F_p - F) / (2 * R * F + mu * L * (F_p - F))


def peer(d, method, rtol):
    """What a user would write: dδ/dF = 1/K, the regime evaluated inside the right side."""
    F_T, mu, EA, R, L, a0, F_p = d
    if F_T == 0:
        return 0.0

    def f(F, y):
        if F <= 0 and L == 0:
            return [0.0]
        return [1.0 / stiffness(F, F_p, mu, EA, R, L, a0 + y[0] / R, a0 - y[0] / R)]

    sol = solve_ivp(f, (0.0, F_T), [0.0], method=method, rtol=rtol, atol=rtol * F_T * (L + R) / EA)
    return sol.y[0, -1] if sol.success else np.nan


def reference(d):
    """DOP853 at rtol 1e-13, regime frozen between event-located switches (restart just past each)."""
    F_T, mu, EA, R, L, a0, F_p = d
    if F_T == 0:
        return 0.0

    def zs(F, x):
        return (math.log1p(F / F_p) - mu * (a0 + x / R), F / F_p + math.expm1(-mu * (a0 - x / R)), F / F_p - 1.0)

    events = []
    for j in range(3):
        def ev(F, y, j=j):
            return zs(F, y[0])[j]
        ev.terminal = True
        events.append(ev)
    F, x = 0.0, 0.0
    flags = [v >= 0 for v in zs(0.0, 0.0)]
    for _ in range(6):
        def f(Fv, y):
            if Fv <= 0 and L == 0:
                return [0.0]
            return [1.0 / stiffness(Fv, F_p, mu, EA, R, L, a0 + y[0] / R, a0 - y[0] / R, flags)]
        sol = solve_ivp(f, (F, F_T), [x], method="DOP853", rtol=1e-13, atol=1e-16 * F_T * (L + R) / EA, events=events)
        if sol.status == -1:
            return np.nan
        F, x = sol.t[-1], sol.y[0, -1]
        if sol.status == 0:
            return x
        j = [k for k in range(3) if len(sol.t_events[k])][0]
        F, x = sol.t_events[j][0] * (1 + 1e-15) + 1e-300, sol.y_events[j][0][0]
        if F >= F_T:
            return x
        flags = [v >= 0 for v in zs(F, x)]
    return np.nan


def measure(n, n_scipy, rtols):
    c = drives(4 * n)
    args = list(c.values())
    ref = np.array([reference([a[i] for a in args]) for i in range(4 * n)])
    keep = np.flatnonzero(np.isfinite(ref) & (c["alpha_0"] - ref / c["R"] > 1e-3 * c["alpha_0"]))[:n]
    c = {k: v[keep] for k, v in c.items()}
    ref = ref[keep]
    rotation_batch(**c)  # build and compile (cached), not timed
    t0 = time.perf_counter()
    d = rotation_batch(**c)
    t = (time.perf_counter() - t0) / len(ref)

    def rel(a, r):
        return np.where(r > 0, np.abs(a - r) / np.where(r > 0, r, 1.0), np.abs(a))

    rows = [{"method": "ropemodel (li, rtol 1e-7)", "rtol": 1e-7, "max rel. error": float(rel(d, ref).max()),
             "time per point [s]": t, "failures": 0}]
    sub = [v[:n_scipy] for v in c.values()]
    for method in METHODS:
        for rtol in rtols:
            t0 = time.perf_counter()
            ys = np.array([peer([a[i] for a in sub], method, rtol) for i in range(n_scipy)])
            t = (time.perf_counter() - t0) / n_scipy
            err = rel(ys, ref[:n_scipy])
            rows.append({"method": f"scipy {method}", "rtol": rtol,
                         "max rel. error": float(np.nanmax(err)) if np.isfinite(err).any() else np.nan,
                         "time per point [s]": t, "failures": int(np.sum(~np.isfinite(ys)))})
    return pd.DataFrame(rows)


def summary(df):
    ours = df.iloc[0]
    ok = df[df["method"].str.startswith("scipy") & (df["failures"] == 0)
            & (df["max rel. error"] <= ours["max rel. error"])]
    best = ok.loc[ok["time per point [s]"].idxmin()] if len(ok) else None
    return pd.DataFrame([{"ropemodel max rel. error": ours["max rel. error"],
                          "peer": f"{best['method']} rtol {best['rtol']:g}" if best is not None else "none as accurate",
                          "peer time / ropemodel time": (best["time per point [s]"] / ours["time per point [s]"]
                                                         if best is not None else np.nan)}])


def plot(df, out, fast):
    fig, ax = plt.subplots(figsize=(7, 5))
    for m, g in df[df["method"].str.startswith("scipy")].groupby("method"):
        ax.plot(g["max rel. error"].clip(lower=1e-16), g["time per point [s]"], "s--", label=m)
    o = df.iloc[0]
    ax.plot(o["max rel. error"], o["time per point [s]"], "k*", ms=14, label=o["method"])
    ax.set(xscale="log", yscale="log", xlabel="max relative error of the rotation (vs event-located DOP853)",
           ylabel="time per point [s] (this run; compare ratios only)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Capstan rotation: ropemodel (compiled) vs scipy solve_ivp, plain numpy right side", fontsize=9)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    df = measure(200, 20, (1e-8, 1e-10)) if fast else measure(2000, 100, (1e-6, 1e-8, 1e-10, 1e-12))
    df.to_csv(out / f"{NAME}.csv", index=False)
    summary(df).to_csv(out / f"{NAME}_summary.csv", index=False)
    plot(df, out, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda d: d.to_string(index=False) + "\n\n" + summary(d).T.to_string())
