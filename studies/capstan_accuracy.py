"""Capstan rotation: accuracy against a fine reference and cost against scipy's solve_ivp written as a user would.

Cases: random drives over the documented range (μ ∈ [0.05, 1], α0 ≤ 40 rad, 0 ≤ F_T ≤ 2F_p,
EA 10³–10⁷ N, R 0.01–1 m, L 0–10 m, F_p 1–10⁴ N), keeping those whose slack side stays wrapped.

* reference: DOP853 at rtol 1e-13 in F with the regime frozen between switches located by events
  (written here, numpy);
* ropemodel: ``ropemodel.capstan.batch.rotation_batch`` (published law ``li``) at its default
  rtol 1e-7 and, for the work-precision line, at other rtol; compiled to C where a compiler works,
  one batched call per tolerance; its error estimate ``delta_error`` is checked against the true error;
* the peer: ``solve_ivp`` on a plain numpy right side dδ/dF = 1/K(F, α0 ± δ/R) (eq. 26 in the
  tight + slack reading, switches evaluated inside the right side, no events: as a user would
  write it), LSODA, DOP853, Radau at several tolerances, on the first drives of the sample (all
  errors compared on those same drives).  The headline peer is the cheapest configuration at least
  as accurate as ropemodel's default; where none is, the cheapest of those within a factor 2 of the
  most accurate one's error, and the summary says so (it also gives the strictly most accurate and
  the cheapest configurations, with their ratios).  Stepping blindly over the jumps of K, and over
  regime-2 intervals of a few mN, none is as accurate on the full run's 100 drives (the best stall
  near 1.6e-7); on fewer drives, without such a jump, one can be (Radau at rtol 1e-12 on the fast
  run's 20, with scipy 1.17).
  Times are per point, measured in this run; only their ratios are reported.

    python studies/capstan_accuracy.py [--fast]
"""

from __future__ import annotations

import math
import timeit

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

from ropemodel.capstan.batch import rotation_batch  # noqa: E402
from ropemodel.core.evaluate import evaluate_columns  # noqa: E402
from ropemodel.numerics.capstan_rotation import ARGS, RTOL, attempts_function  # noqa: E402
from ropemodel.studykit import cli, output_dir, save_figure  # noqa: E402

NAME = "capstan_accuracy"
METHODS = ("LSODA", "DOP853", "Radau")
DEFAULT = f"ropemodel li, rtol {RTOL:g} (default)"


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
    """DOP853 at rtol 1e-13, regime frozen between event-located switches (restart just past each); NaN once
    the slack side unwraps (α2 = 0: outside the model)."""
    F_T, mu, EA, R, L, a0, F_p = d
    if F_T == 0:
        return 0.0

    def zs(F, x):
        a2 = a0 - x / R
        return (math.log1p(F / F_p) - mu * (a0 + x / R), F / F_p + math.expm1(-mu * max(a2, 0.0)), F / F_p - 1.0, a2)

    events = []
    for j in range(4):
        def ev(F, y, j=j):
            return zs(F, y[0])[j]
        ev.terminal = True
        events.append(ev)
    F, x = 0.0, 0.0
    flags = [v >= 0 for v in zs(0.0, 0.0)[:3]]
    for _ in range(8):
        def f(Fv, y):
            if Fv <= 0 and L == 0:
                return [0.0]
            return [1.0 / stiffness(Fv, F_p, mu, EA, R, L, a0 + y[0] / R, max(a0 - y[0] / R, 1e-300), flags)]
        sol = solve_ivp(f, (F, F_T), [x], method="DOP853", rtol=1e-13, atol=1e-16 * F_T * (L + R) / EA, events=events)
        if sol.status == -1:
            return np.nan
        F, x = sol.t[-1], sol.y[0, -1]
        if sol.status == 0:
            return x
        j = [k for k in range(4) if len(sol.t_events[k])][0]
        if j == 3:
            return np.nan
        F, x = sol.t_events[j][0] * (1 + 1e-15) + 1e-300, sol.y_events[j][0][0]
        if F >= F_T:
            return x
        flags = [v >= 0 for v in zs(F, x)[:3]]
    return np.nan


def seconds(fun, repeats=1):
    """The least wall time [s] of ``repeats`` calls of ``fun`` (this run; only ratios are reported)."""
    return min(timeit.repeat(fun, number=1, repeat=repeats))


def cases(n):
    """The first n random drives with a finite reference whose slack side stays wrapped, and the reference."""
    c = drives(2 * n + 100)
    args = list(c.values())
    keep, ref = [], []
    for i in range(len(args[0])):
        r = reference([a[i] for a in args])
        if np.isfinite(r) and c["alpha_0"][i] - r / c["R"][i] > 1e-3 * c["alpha_0"][i]:
            keep.append(i)
            ref.append(r)
            if len(keep) == n:
                break
    return {k: v[keep] for k, v in c.items()}, np.array(ref)


def rel(a, r):
    return np.where(r > 0, np.abs(a - r) / np.where(r > 0, r, 1.0), np.abs(a))


def ours(c, ref, rtol, repeats, n_scipy):
    """A row for ropemodel at ``rtol``: true and estimated errors (also on the first ``n_scipy`` drives, the
    peers'), time per point, attempted steps."""
    d, est = rotation_batch(**c, rtol=rtol, with_error=True)  # also builds and compiles (cached): not timed
    t = seconds(lambda: rotation_batch(**c, rtol=rtol, with_error=True), repeats)
    err = rel(d, ref)
    attempts = evaluate_columns(attempts_function("li", rtol=rtol), {a: c[a] for a in ARGS}, {}, block=64)["attempts"]
    return {"method": DEFAULT if rtol == RTOL else f"ropemodel li, rtol {rtol:g}", "rtol": rtol,
            "max rel. error": float(err.max()), "max rel. error, scipy drives": float(err[:n_scipy].max()),
            "time per point [s]": t / len(ref), "failures": 0,
            "max estimate": float(est.max()), "max error / estimate": float(np.max(err / np.maximum(est, 1e-300))),
            "mean attempted steps": float(attempts.mean())}


def measure(n, n_scipy, rtols, our_rtols=(), repeats=3):
    c, ref = cases(n)
    rows = [ours(c, ref, r, repeats, n_scipy) for r in (RTOL, *our_rtols)]
    sub = [v[:n_scipy] for v in c.values()]
    for method in METHODS:
        for rtol in rtols:
            out = []
            t = seconds(lambda: out.append([peer([a[i] for a in sub], method, rtol) for i in range(n_scipy)]))
            ys = np.array(out[-1])
            err = rel(ys, ref[:n_scipy])
            rows.append({"method": f"scipy {method}", "rtol": rtol,
                         "max rel. error": float(np.nanmax(err)) if np.isfinite(err).any() else np.nan,
                         "time per point [s]": t / n_scipy, "failures": int(np.sum(~np.isfinite(ys)))})
    return pd.DataFrame(rows)


def summary(df):
    """The fair peer (module doc), its time ratio to ropemodel's default, and the error control's checks."""
    me = df[df["method"] == DEFAULT].iloc[0]
    scipy = df[df["method"].str.startswith("scipy") & (df["failures"] == 0)]
    ok = scipy[scipy["max rel. error"] <= me["max rel. error, scipy drives"]]     # on the same drives
    strict = scipy.loc[scipy["max rel. error"].idxmin()]
    if len(ok):
        best, basis = ok.loc[ok["time per point [s]"].idxmin()], "cheapest scipy configuration as accurate"
    else:
        close = scipy[scipy["max rel. error"] <= 2.0 * strict["max rel. error"]]
        best = close.loc[close["time per point [s]"].idxmin()]
        basis = "none as accurate: the cheapest within 2x of the most accurate scipy error"
    cheapest = scipy.loc[scipy["time per point [s]"].idxmin()]
    mine = df[df["method"].str.startswith("ropemodel")]

    def ratio(row):
        return row["time per point [s]"] / me["time per point [s]"]

    return pd.DataFrame([{
        "ropemodel max rel. error": me["max rel. error"],
        "ropemodel max rel. error, scipy drives": me["max rel. error, scipy drives"],
        "ropemodel max estimate": me["max estimate"],
        "ropemodel max error / estimate": mine["max error / estimate"].max(),
        "ropemodel max error / rtol": (mine["max rel. error"] / mine["rtol"]).max(),
        "ropemodel mean attempted steps": me["mean attempted steps"],
        "scipy configurations as accurate": len(ok), "peer basis": basis,
        "peer": f"{best['method']} rtol {best['rtol']:g}", "peer max rel. error": best["max rel. error"],
        "peer time / ropemodel time": ratio(best),
        "most accurate scipy": f"{strict['method']} rtol {strict['rtol']:g}",
        "most accurate scipy max rel. error": strict["max rel. error"],
        "most accurate scipy time / ropemodel time": ratio(strict),
        "cheapest scipy": f"{cheapest['method']} rtol {cheapest['rtol']:g}",
        "cheapest scipy max rel. error": cheapest["max rel. error"],
        "cheapest scipy time / ropemodel time": ratio(cheapest)}])


def plot(df, out, fast):
    fig, ax = plt.subplots(figsize=(7, 5))
    for m, g in df[df["method"].str.startswith("scipy")].groupby("method"):
        ax.plot(g["max rel. error"].clip(lower=1e-16), g["time per point [s]"], "s--", label=m)
    mine = df[df["method"].str.startswith("ropemodel")].sort_values("rtol")
    ax.plot(mine["max rel. error"], mine["time per point [s]"], "k.-",
            label="ropemodel li (compiled), rtol 1e-11..1e-5")
    o = df[df["method"] == DEFAULT].iloc[0]
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
    if fast:
        df = measure(200, 20, (1e-8, 1e-10, 1e-12), (1e-5,), repeats=3)
    else:
        df = measure(2000, 100, (1e-6, 1e-8, 1e-10, 1e-12, 1e-13), (1e-5, 1e-9, 1e-11), repeats=3)
    df.to_csv(out / f"{NAME}.csv", index=False)
    summary(df).to_csv(out / f"{NAME}_summary.csv", index=False)
    plot(df, out, fast)
    return df


if __name__ == "__main__":
    cli(main, __doc__, show=lambda d: d.to_string(index=False) + "\n\n" + summary(d).T.to_string())
