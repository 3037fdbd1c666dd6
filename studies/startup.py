"""What a command costs before it does any work: start-up as a ratio to ``python -c "import casadi"``.

Whole processes, measured in this run, interleaved (every round runs each command once, so a
loaded machine slows all of them alike), best of N rounds:

* ``python -c "import casadi"``: the peer, the least any CasADi tool can cost;
* ``ropemodel --help``: goal at most 2x the peer (nothing heavy is imported);
* ``ropemodel run`` on the built-in example: goal at most 4x the peer;
* ``python -c "import pint; pint.UnitRegistry()"``: what pint's unit registry would add on its own
  (the reason ropemodel reads units with its own small parser; see :mod:`ropemodel.units`).

``python studies/startup.py [--fast]`` writes ``startup.csv`` and ``startup.png``.
"""

from __future__ import annotations

import subprocess
import sys
import time

import pandas as pd

from ropemodel.studykit import cli, output_dir, save_figure

NAME = "startup"
PEER = "import casadi"
COMMANDS = {
    "python -c 'import casadi' (peer)": [sys.executable, "-c", PEER],
    "ropemodel --help": [sys.executable, "-m", "ropemodel", "--help"],
    "ropemodel run": [sys.executable, "-m", "ropemodel", "run"],
    "python -c 'import pint; UnitRegistry()'": [sys.executable, "-c", "import pint; pint.UnitRegistry()"],
}
GOALS = {"ropemodel --help": 2.0, "ropemodel run": 4.0}


def _time(argv) -> float:
    t = time.perf_counter()
    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    return time.perf_counter() - t


def measure(rounds: int) -> pd.DataFrame:
    """Best-of-``rounds`` wall time of each command and its ratio to the peer (interleaved rounds)."""
    available = dict(COMMANDS)
    try:
        import pint  # noqa: F401  (optional: measured only where installed)
    except ImportError:
        available.pop("python -c 'import pint; UnitRegistry()'")
    for argv in available.values():   # warm the file cache once
        _time(argv)
    best = {k: float("inf") for k in available}
    for _ in range(rounds):
        for name, argv in available.items():
            best[name] = min(best[name], _time(argv))
    peer = best["python -c 'import casadi' (peer)"]
    return pd.DataFrame([{"command": k, "ratio_to_peer": v / peer, "goal": GOALS.get(k)} for k, v in best.items()])


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = output_dir(__file__, out_dir)
    frame = measure(5)
    frame.to_csv(out / f"{NAME}.csv", index=False)
    fig, ax = plt.subplots(figsize=(7, 2.8))
    ax.barh(frame["command"], frame["ratio_to_peer"], color="#2471a3")
    for y, (r, g) in enumerate(zip(frame["ratio_to_peer"], frame["goal"])):
        ax.annotate(f"{r:.2f}x" + (f" (goal <= {g:g}x)" if g == g and g is not None else ""), (r, y),
                    xytext=(3, 0), textcoords="offset points", va="center", fontsize=8)
    ax.axvline(1.0, color="k", lw=0.8)
    ax.set_xlabel("start-up time / python -c 'import casadi' (best of 5, interleaved, same run)")
    ax.invert_yaxis()
    ax.set_xlim(0, max(frame["ratio_to_peer"]) * 1.6)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)
    return frame


if __name__ == "__main__":
    cli(main, __doc__, show=lambda f: f.to_string(index=False, float_format=lambda x: f"{x:.2f}"))
