"""Performance of haulage sweeps: the CLI against numpy, cost against the number of points, peak memory.

1. **CLI vs numpy.**  ``ropemodel sweep`` of the Fig. 9 scene over a grid of
   inclination × load (every output, Parquet) against a plain numpy script that
   computes the same 31 outputs from the equations written out by hand
   (docs/physics.md §1) and writes the same columns to Parquet with the same row
   groups.  Both run as fresh processes (interpreter start and imports
   included); the best of ``repeat`` runs of each.  The two files are compared
   (largest relative difference), so the peer is also a correctness check.
   The ratio is also given in-process (no start-up on either side).
2. **Cost vs number of points**: in-process sweeps to Parquet of 10^3 … 3·10^6
   points against the numpy peer (wall time), and the model t = a + b·N^k of
   the sweep's CPU time (:func:`cost_model`; the sizes take turns, best of
   three): a, the fixed cost of a sweep (building the chunks' function,
   opening the file), and the exponent k of the part that grows with N over
   the sweeps of more than one chunk (k = 1: linear).  The slope of log t
   against log N would read the fixed cost as sub-linear growth wherever it is
   not negligible; wall time on a shared machine would measure the changing
   load of the other work.
3. **Peak memory** (full mode): the peak resident set (VmHWM) of a fresh
   process sweeping 10^6 and 10^7 points to Parquet (chunks of 65536 points),
   and of one that only imports and compiles: the chunking keeps it flat; the
   goal is < 2 GB at 10^7.

Only ratios to the peer measured in the same run are meaningful; absolute
times depend on the machine.  ``python studies/sweep_performance.py [--fast]``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from ropemodel.studykit import PEAK_RSS

ROOT = Path(__file__).resolve().parents[1]
NAME = "sweep_performance"
CLI = "import sys; from ropemodel.cli import main; sys.exit(main(sys.argv[1:]))"
ROW_GROUP = 65536  # the sweep's default chunk: one row group per chunk on both sides

# The Fig. 9 scene (ropemodel/data/krauze2025_fig9.toml), SI; the peer must not import ropemodel.
FIG9 = dict(L_u=1150.0, L_ul=500.0, mu_pm=0.05, mu_pl=0.05, F_nwl=20e3, v_pj=2.5, eta=1.0, q_l=80.0, q_lw=5.8e-6)

PEER = r'''
import sys, time, math
import numpy as np, pyarrow as pa, pyarrow.parquet as pq
def outputs(alpha, G_m, L_u, L_ul, mu_pm, mu_pl, F_nwl, v_pj, eta, q_l, q_lw):
    s, c = np.sin(alpha), np.cos(alpha)
    out = {}
    out["G_ml"] = G_m * s                                  # eq. (1)
    out["G_l1"] = q_l * (L_u - L_ul) * s                   # eq. (3)
    out["G_l2"] = q_l * L_ul * s                           # eq. (4)
    out["G_l"] = out["G_l1"] + out["G_l2"]                 # eq. (2)
    out["G_mo"] = G_m * c                                  # eq. (5)
    out["G_ls"] = q_l * L_u * s                            # eq. (6)
    out["T_m"] = mu_pm * G_m * c                           # eq. (7)
    out["T_l1"] = mu_pl * q_l * (L_u - L_ul) * c           # eq. (8), case 1
    out["T_l2"] = mu_pl * q_l * L_ul * c                   # eq. (9)
    out["T_l"] = out["T_l1"] + out["T_l2"]                 # eq. (10)
    out["T_ls"] = mu_pl * q_l * L_u * c                    # eq. (11)
    out["G_lmC"] = out["G_ml"] + out["G_l"]                # eq. (14)
    out["F_S_up"] = 0.5 * F_nwl + out["G_ls"] - out["T_ls"]                 # eq. (12)
    out["F_C_up"] = 0.5 * F_nwl + out["G_lmC"] + out["T_m"] + out["T_l"]    # eq. (13)
    out["F_S_down"] = 0.5 * F_nwl + out["G_ls"] + out["T_ls"]
    out["F_C_down"] = 0.5 * F_nwl + out["G_lmC"] - out["T_m"] - out["T_l"]
    out["mu_pl1"] = np.full_like(s, mu_pl)
    out["mu_pl2"] = np.full_like(s, mu_pl)
    out["dF_nwl"] = np.full_like(s, q_lw * F_nwl)          # eq. (22)
    out["EA"] = np.full_like(s, L_u / q_lw)                # the rope's stiffness, Hooke over the route
    for d in ("up", "down"):
        out[f"dF_C_{d}"] = q_lw * out[f"F_C_{d}"]           # eq. (19)
        out[f"dF_S_{d}"] = q_lw * out[f"F_S_{d}"]           # eq. (20)
        out[f"dF_CS_{d}"] = out[f"dF_C_{d}"] + out[f"dF_S_{d}"]   # eq. (21)
        out[f"dF_{d}"] = out[f"dF_CS_{d}"] + out["dF_nwl"]        # eq. (23)
    for d, sign in (("up", 1.0), ("down", -1.0)):   # signed: > 0 motoring, < 0 braking
        P = out[f"P_drum_{d}"] = sign * (out[f"F_C_{d}"] - out[f"F_S_{d}"]) * v_pj
        out[f"N_p_{d}"] = np.where(P > 0, P / eta, P * eta)
    return out
ORDER = ["G_ml","G_l1","G_l2","G_l","G_mo","G_ls","T_m","T_l1","T_l2","T_l","T_ls","G_lmC","F_S_up","F_C_up",
         "F_S_down","F_C_down","mu_pl1","mu_pl2","dF_nwl","EA","dF_C_up","dF_S_up","dF_CS_up","dF_up","dF_C_down",
         "dF_S_down","dF_CS_down","dF_down","P_drum_up","N_p_up","P_drum_down","N_p_down"]
UNIT = {k: ("kN", 1e-3) for k in ORDER}
UNIT.update({k: ("-", 1.0) for k in ("mu_pl1", "mu_pl2")})
UNIT.update({k: ("mm", 1e3) for k in ORDER if k.startswith("dF")})
UNIT["EA"] = ("MN", 1e-6)
UNIT.update({k: ("kW", 1e-3) for k in ("P_drum_up", "N_p_up", "P_drum_down", "N_p_down")})
def main(n_alpha, n_load, path, row_group, p):
    a = np.radians(np.linspace(5.0, 45.0, n_alpha))
    g = np.linspace(300e3, 500e3, n_load)
    A = np.repeat(a, n_load); G = np.tile(g, n_alpha)
    cols = {"alpha_u [deg]": np.degrees(A), "G_m [kN]": G * 1e-3}
    out = outputs(A, G, **p)
    for k in ORDER:
        u, f = UNIT[k]
        cols[f"{k} [{u}]"] = out[k] * f
    table = pa.table(cols)
    with pq.ParquetWriter(path, table.schema) as w:
        for s in range(0, table.num_rows, row_group):
            w.write_table(table.slice(s, row_group))
if __name__ == "__main__":
    import json
    main(int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), json.loads(sys.argv[5]))
'''


def _env():
    return {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}


def _timed(cmd) -> float:
    t = time.perf_counter()
    subprocess.run(cmd, check=True, env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return time.perf_counter() - t


def cli_vs_numpy(tmp: Path, n_alpha: int, n_load: int, repeat: int) -> dict:
    """Best-of-``repeat`` wall times of the CLI and of the numpy script, fresh processes, same file."""
    peer = tmp / "peer.py"
    peer.write_text(PEER)
    ours, theirs = tmp / "cli.parquet", tmp / "numpy.parquet"
    cli_cmd = [sys.executable, "-c", CLI, "sweep", "example", "--vary", f"alpha_u=5deg:45deg:{n_alpha}",
               "--vary", f"G_m=300kN:500kN:{n_load}", "-o", str(ours), "--no-progress", "--restart"]
    np_cmd = [sys.executable, str(peer), str(n_alpha), str(n_load), str(theirs), str(ROW_GROUP), json.dumps(FIG9)]
    t_cli, t_np = [], []
    for _ in range(repeat):
        t_cli.append(_timed(cli_cmd))
        t_np.append(_timed(np_cmd))
    import pyarrow.parquet as pq

    a, b = pq.read_table(ours), pq.read_table(theirs)
    if a.column_names != b.column_names:
        raise RuntimeError(f"the files differ in columns: {a.column_names} vs {b.column_names}")
    worst = 0.0
    for name in a.column_names:
        x, y = a[name].to_numpy(), b[name].to_numpy()
        worst = max(worst, float(np.max(np.abs(x - y) / np.maximum(np.abs(y), 1e-300 + np.abs(y).max() * 1e-12))))
    return {"points": n_alpha * n_load, "cli_s": min(t_cli), "numpy_s": min(t_np),
            "ratio": min(t_cli) / min(t_np), "max_rel_diff": worst, "bytes": ours.stat().st_size,
            "numpy_bytes": theirs.stat().st_size}


def _peer_module(tmp: Path):
    import importlib.util

    path = tmp / "peer_mod.py"
    path.write_text(PEER)
    spec = importlib.util.spec_from_file_location("sweep_peer", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def scaling(tmp: Path, sizes, repeat: int) -> list[dict]:
    """In-process time to Parquet against N, ropemodel vs the numpy peer (best of ``repeat``): wall time, and
    ropemodel's CPU time (every thread of this process), which a busy machine's other work does not inflate.
    The sizes take turns, so a change of the machine's load falls on every size alike."""
    import ropemodel as rm

    peer = _peer_module(tmp)
    scene = rm.load_scene()
    rm.sweep(scene, {"alpha_u": [0.1, 0.2], "G_m": [3e5]}, out=tmp / "warm.parquet", collect=False)  # compile once
    grids = [(max(1, n // max(1, round(math.sqrt(n)))), max(1, round(math.sqrt(n)))) for n in sizes]
    t_rm, cpu_rm, t_np = ({g: [] for g in grids} for _ in range(3))
    for _ in range(repeat):
        for n_alpha, n_load in grids:
            t, c = time.perf_counter(), time.process_time()
            rm.sweep(scene, {"alpha_u": f"5deg:45deg:{n_alpha}", "G_m": f"300kN:500kN:{n_load}"},
                     out=tmp / "s.parquet", collect=False, progress=False, restart=True)
            t_rm[n_alpha, n_load].append(time.perf_counter() - t)
            cpu_rm[n_alpha, n_load].append(time.process_time() - c)
            t = time.perf_counter()
            peer.main(n_alpha, n_load, str(tmp / "n.parquet"), ROW_GROUP, FIG9)
            t_np[n_alpha, n_load].append(time.perf_counter() - t)
    return [{"points": a * b, "ropemodel_s": min(t_rm[a, b]), "ropemodel_cpu_s": min(cpu_rm[a, b]),
             "numpy_s": min(t_np[a, b]), "ratio": min(t_rm[a, b]) / min(t_np[a, b])} for a, b in grids]


MEMORY = PEAK_RSS + r'''
import sys, time
import ropemodel as rm
n_alpha, n_load, path = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
t = time.perf_counter()
rm.sweep(rm.load_scene(), {"alpha_u": f"5deg:45deg:{n_alpha}", "G_m": f"300kN:500kN:{n_load}"}, out=path,
         collect=False, progress=False, restart=True)
print(peak_rss(), time.perf_counter() - t)
'''

BASELINE = PEAK_RSS + r'''
import ropemodel as rm, ropemodel.sweeps, pyarrow.parquet
rm.sweep(rm.load_scene(), {"alpha_u": [0.1, 0.2]}, progress=False)
print(peak_rss())
'''


def memory(tmp: Path, sizes) -> list[dict]:
    """Peak RSS (bytes) of a fresh process sweeping N points to Parquet; and of one that only imports."""
    base = subprocess.run([sys.executable, "-c", BASELINE], check=True, env=_env(), capture_output=True, text=True)
    rows = [{"points": 0, "peak_rss_bytes": int(base.stdout.split()[0]), "seconds": 0.0}]
    for n in sizes:
        n_load = 1000
        res = subprocess.run([sys.executable, "-c", MEMORY, str(n // n_load), str(n_load), str(tmp / "m.parquet")],
                             check=True, env=_env(), capture_output=True, text=True)
        rss, secs = res.stdout.split()
        rows.append({"points": n, "peak_rss_bytes": int(rss), "seconds": float(secs)})
    return rows


def cost_model(sizes, times) -> tuple[float, float, float]:
    """The fixed cost a [s], the cost b [s] and the exponent k of t = a + b·N^k from sweep times ``times`` [s]
    of ``sizes`` points; k = 1 is a cost linear in N.

    a is the smallest sweep's time (at 10^3 points its growing part is below 1 % of it); k and b are the
    least-squares line through log(t − a) against log(N − N_min) over the sweeps of more than one chunk of
    65536 points (at least two such sizes): a sweep of one partial chunk also pays the chunk's own costs.
    A linear cost gives k = 1 exactly, whatever a; the slope of log t itself would read the fixed cost as
    sub-linear growth.
    """
    n, t = np.asarray(sizes, float), np.asarray(times, float)
    first = int(np.argmin(n))
    big = n > ROW_GROUP
    if big.sum() < 2 or (t[big] <= t[first]).any():
        raise ValueError(f"t = a + b N^k needs two sweeps of more than {ROW_GROUP} points, each slower than the "
                         f"smallest: {dict(zip(n.tolist(), t.tolist()))}")
    k, log_b = np.polyfit(np.log(n[big] - n[first]), np.log(t[big] - t[first]), 1)
    return float(t[first]), float(np.exp(log_b)), float(k)


def _plot(scale, mem, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2 if mem else 1, figsize=(10 if mem else 5.5, 4), squeeze=False)
    ax = axes[0][0]
    n = [r["points"] for r in scale]
    ax.loglog(n, [r["ropemodel_s"] for r in scale], "o-", label="ropemodel.sweeps → Parquet")
    ax.loglog(n, [r["numpy_s"] for r in scale], "s--", label="numpy by hand → Parquet")
    ax.set_xlabel("points")
    ax.set_ylabel("seconds (this machine)")
    ax.set_title("haulage sweep: cost vs number of points")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    if mem:
        ax = axes[0][1]
        pts = [r["points"] for r in mem if r["points"]]
        ax.semilogx(pts, [r["peak_rss_bytes"] / 2 ** 20 for r in mem if r["points"]], "o-", label="sweep process")
        ax.axhline(mem[0]["peak_rss_bytes"] / 2 ** 20, color="gray", ls=":", label="imports + compile only")
        ax.axhline(2048, color="r", ls="--", label="2 GB goal")
        ax.set_xlabel("points")
        ax.set_ylabel("peak RSS [MiB]")
        ax.set_title("peak memory (chunks of 65536 points)")
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(out_dir=None, fast: bool = False, publish: bool = True) -> dict:
    """The study; ``publish=False`` keeps the full run's figure out of ``studies/figures/`` (for tests)."""
    out = Path(out_dir) if out_dir else ROOT / "studies" / "out" / NAME
    out.mkdir(parents=True, exist_ok=True)
    import pandas as pd

    with tempfile.TemporaryDirectory() as td:
        tmp = Path(td)
        if fast:
            mem = []
            head = cli_vs_numpy(tmp, 100, 100, repeat=1)
            scale = scaling(tmp, [2_000, 20_000], repeat=1)
        else:  # memory first: fresh processes, measured before this one grows
            mem = memory(tmp, [1_000_000, 10_000_000])
            head = cli_vs_numpy(tmp, 1000, 1000, repeat=3)
            scale = scaling(tmp, [1_000, 10_000, 100_000, 1_000_000, 3_000_000], repeat=3)
    sizes = [r["points"] for r in scale]
    fit = cost_model(sizes, [r["ropemodel_cpu_s"] for r in scale]) if sum(n > ROW_GROUP for n in sizes) > 1 else None
    pd.DataFrame([head]).to_csv(out / "cli_vs_numpy.csv", index=False)
    pd.DataFrame(scale).to_csv(out / "scaling.csv", index=False)
    if mem:
        pd.DataFrame(mem).to_csv(out / "memory.csv", index=False)
    _plot(scale, mem, out / f"{NAME}.png")
    if not fast and publish:
        figures = ROOT / "studies" / "figures"
        figures.mkdir(exist_ok=True)
        _plot(scale, mem, figures / f"{NAME}.png")
    print(f"{head['points']:.0f}-point haulage sweep, CLI to Parquet vs numpy script to the same Parquet "
          f"(fresh processes, best of runs): ratio {head['ratio']:.2f} "
          f"(max relative difference of the files {head['max_rel_diff']:.1e})")
    for r in scale:
        print(f"  in-process {r['points']:>9.0f} points: ropemodel / numpy = {r['ratio']:.2f}, "
              f"ropemodel {r['ropemodel_s'] / r['points'] * 1e9:.0f} ns/point")
    if fit:
        print(f"CPU time t = a + b N^k: k = {fit[2]:.3f} (1 = linear), fixed a = {fit[0] * 1e3:.0f} ms, "
              f"b N at 10^6 points = {fit[1] * 1e6 ** fit[2]:.2f} s (this machine)")
    else:
        print("CPU time t = a + b N^k: not fitted (--fast times two sizes)")
    for r in mem:
        label = "imports + compile only" if r["points"] == 0 else f"{r['points']:.0e} points"
        print(f"  peak RSS {label}: {r['peak_rss_bytes'] / 2 ** 20:.0f} MiB")
    a, b, k = fit or (None, None, None)
    return {"cli_vs_numpy": head, "scaling": scale, "exponent": k, "fixed_s": a, "b": b, "memory": mem}


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="small sizes, seconds (CI)")
    parser.add_argument("--out", default=None, help="output directory (default studies/out/sweep_performance)")
    a = parser.parse_args()
    main(a.out, a.fast)
