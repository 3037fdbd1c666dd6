"""Routes at survey scale: the cost of ``run``, ``trip`` and ``size`` against the number of points of a profile.

A 2 km incline (10 deg on average with a 700 m undulation of +-15 m, falling away from the drive) surveyed at
n points is written as a profile file (``[route_profile]``, ``distance [m],height [m]``) and each command
runs on it in a fresh process, timed (wall clock and CPU time, imports included) with its peak memory (VmHWM,
the peak resident set of that process alone: :data:`ropemodel.studykit.PEAK_RSS`).  The peer, measured in the
same run: a plain numpy evaluation of the steady rope forces at the drum with the load at every joint of the
route, both directions (docs/physics.md §4, the closed forms of the sums over segments, written out here), whose
worst ``F_C_up`` each ``run`` must equal to 1e-12.

Printed: time (wall, CPU) and memory per command and n, the time relative to the smallest n (growth) and to
the numpy peer.  ``--fast``: n = 10, 30, 100 (what the test runs); full: n = 10, 30, 100, 300, 1000, 3000,
10 000, every command.

The numbers measured before and after issue 22.4's second and third parts (1000 to 10 000 points) and what is
left are in studies/README.md, "Routes at survey scale".
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from ropemodel.studykit import PEAK_RSS, cli, output_dir, save_figure

G_M, Q_L, F_NWL, MU, G = 467e3, 80.0, 40e3, 0.05, 9.80665
PARAMETERS = """mu_pm = 0.05
mu_pl = 0.05
G_m = "467 kN"
v_pj = "2.5 m/s"
t_ramp = "5 s"
"""
RUN = """[effects]
route = "segments"
dynamics = "trip"
inertia = "rigid"
power = "drive"
[route_profile]
file = "profile.csv"
[parameters]
""" + PARAMETERS + """F_nwl = "40 kN"
q_l = "0.08 kN/m"
q_lw = "5.8 mm/kN"
eta = 0.85
"""
SIZE = """[effects]
route = "segments"
rope = "6x36-IWRC"
lining = "rigid"
dynamics = "trip"
[route_profile]
file = "profile.csv"
[parameters]
""" + PARAMETERS + """rope_grade = "1770 N/mm^2"
rope_E = "100 kN/mm^2"
mu_d = 0.2
alpha_d = "540 deg"
n_slip = 1.25
n_rope = 4.5
F_S_min = "5 kN"
"""
#: the largest profile ``size`` runs on, fast or full (every size since constraint generation: studies/README.md)
SIZE_UP_TO = 10_000
COMMANDS = {"run": (RUN, ["run", "--json"]), "trip": (RUN, ["trip", "--json"]),
            "size": (SIZE, ["size", "--json", "--no-limit"])}    # above 50 segments: above the route-sizing budget
#: in a fresh process: the command, then its wall time and peak memory on the last line of stdout
PROBE = PEAK_RSS + """import io, resource, sys, time
from contextlib import redirect_stdout
t0 = time.perf_counter()
from ropemodel.cli import main
buf = io.StringIO()
with redirect_stdout(buf):
    code = main(sys.argv[1:])
print(buf.getvalue())
use = resource.getrusage(resource.RUSAGE_SELF)
print(code, time.perf_counter() - t0, peak_rss(), use.ru_utime + use.ru_stime)
"""


def profile(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Horizontal distance from the drive and height [m] of the surveyed incline at n points."""
    x = np.linspace(0.0, 2000.0, n)
    return x, 500.0 - x * math.tan(math.radians(10.0)) - 15.0 * np.sin(2.0 * math.pi * x / 700.0)


def numpy_forces(x: np.ndarray, h: np.ndarray) -> dict[str, np.ndarray]:
    """F_C, F_S at the drum [N] with the load at the return-sheave end of each segment (columns) in steady motion,
    a start and a stop (rows, a = 0, +a_r, -a_r with a_r = v_pj/t_ramp), both directions (docs/physics.md §4):
    each side F_nwl/2 + q_l Σ L_i (sin α_i ± μ cos α_i), the load G_m (sin α_j ± μ cos α_j), and the rigid
    inertia ± m a of each side (winding: (G_m + q_l L_u)/g, unwinding: q_l L_u/g)."""
    dx, dh = np.diff(x), np.diff(h)
    L, a = np.hypot(dx, dh), np.arctan2(-dh, dx)
    rise, drag, L_u = Q_L * np.sum(L * np.sin(a)), MU * Q_L * np.sum(L * np.cos(a)), np.sum(L)
    acc = np.array([[0.0], [2.5 / 5.0], [-2.5 / 5.0]])
    out = {}
    for way, s in (("up", 1.0), ("down", -1.0)):
        load = G_M * (np.sin(a) + s * MU * np.cos(a))
        out[f"F_C_{way}"] = 0.5 * F_NWL + rise + s * drag + load + s * (G_M + Q_L * L_u) / G * acc
        out[f"F_S_{way}"] = 0.5 * F_NWL + rise - s * drag - s * Q_L * L_u / G * acc + 0.0 * load
    return out


def _probe(folder: Path, argv: list[str]) -> tuple[dict, float, float, float]:
    """The command's JSON, its wall time [s], peak memory [MB] and CPU time [s]."""
    done = subprocess.run([sys.executable, "-c", PROBE, *argv, str(folder / "scene.toml")], capture_output=True,
                          text=True, cwd=folder, check=False)
    *body, last = done.stdout.strip().splitlines()
    code, seconds, rss, cpu = last.split()
    if code != "0":
        raise RuntimeError(f"{argv[0]} failed on {folder}: {done.stderr.strip()[-400:]}")
    if "WARNING(" in done.stderr:     # CasADi's, e.g. "many inputs"
        raise RuntimeError(f"{argv[0]} on {folder} printed a solver warning: {done.stderr.strip()[-400:]}")
    return json.loads("\n".join(body)), float(seconds), float(rss) / 2**20, float(cpu)


def measure(n: int, folder: Path, size_up_to: int) -> list[dict]:
    """Every command on the profile of n points (``size`` up to ``size_up_to`` points), and the numpy peer, with
    the forces compared."""
    x, h = profile(n)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "profile.csv").write_text("distance [m],height [m]\n"
                                        + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, h)))
    t0 = time.perf_counter()
    repeat = 100
    for _ in range(repeat):
        forces = numpy_forces(x, h)
    peer = (time.perf_counter() - t0) / repeat
    rows = []
    for command, (scene, argv) in COMMANDS.items():
        if command == "size" and n > size_up_to:
            continue
        (folder / "scene.toml").write_text(scene)
        result, seconds, mb, cpu = _probe(folder, argv)
        row = {"points": n, "command": command, "seconds": seconds, "cpu_seconds": cpu, "peak_MB": mb,
               "numpy_seconds": peer}
        if command == "run":
            row["F_C_up"], row["F_C_up_numpy"] = result["F_C_up"], float(np.max(forces["F_C_up"]))
        rows.append(row)
    return rows


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    out = output_dir(__file__, out_dir)
    sizes = (10, 30, 100) if fast else (10, 30, 100, 300, 1000, 3000, 10000)
    table = pd.DataFrame([r for n in sizes for r in measure(n, out / f"n{n}", SIZE_UP_TO)])
    first = table.groupby("command")["seconds"].transform("first")
    table["growth"] = table["seconds"] / first
    table["vs_numpy"] = table["seconds"] / table["numpy_seconds"]
    table.to_csv(out / "route_scale.csv", index=False)
    _figure(table, out, fast)
    return table


def _figure(table: pd.DataFrame, out: Path, fast: bool) -> None:
    import matplotlib.pyplot as plt

    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(9.0, 3.6))
    for command, rows in table.groupby("command", sort=False):
        ax_t.loglog(rows["points"], rows["seconds"], "o-", label=command)
        ax_m.semilogx(rows["points"], rows["peak_MB"], "o-", label=command)
    peer = table.drop_duplicates("points")
    ax_t.loglog(peer["points"], peer["numpy_seconds"], "k:", label="numpy forces (peer)")
    ax_t.set(xlabel="points of the profile", ylabel="wall time [s]", title="time")
    ax_m.set(xlabel="points of the profile", ylabel="peak memory [MB]", title="memory")
    ax_t.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, __file__, out, "route_scale", fast)


if __name__ == "__main__":
    cli(main, __doc__, lambda t: t.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
