"""Plumbing shared by the scripts in ``studies/``: output folders, figures, the command line.

A study is ``studies/<name>.py`` with ``main(out_dir=None, fast=False)`` that
writes CSV and PNG into ``out_dir`` (default ``studies/out/<name>/``) and returns
its table; the pictures the README shows are also written to
``studies/figures/`` in full mode.  Kept in the package (not beside the scripts)
so that a study imports it the same way whether it runs as a script, from
``studies/run_all.py`` or from a test.
"""

from __future__ import annotations

import argparse
from pathlib import Path

#: Python source of ``peak_rss()``, for the code of a fresh process that measures its own peak memory: VmHWM
#: (Linux), which exec resets.  Not ru_maxrss: a child inherits its parent's peak through fork and exec, so a
#: process started from a test worker reports the worker's peak (1.9 GB in CI's slow tier for a sizing that stays
#: under 1 GB alone).  Elsewhere ru_maxrss (macOS: bytes; Linux fallback: kB).
PEAK_RSS = r'''
def peak_rss():
    """Peak resident set of this process [bytes]: VmHWM (Linux; reset by exec, unlike ru_maxrss,
    which a child inherits from the parent it was forked from)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    import resource, sys
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * (1 if sys.platform == "darwin" else 1024)
'''


def output_dir(script: str, out_dir=None) -> Path:
    """``out_dir``, or ``studies/out/<name>/`` beside ``script`` (a study's ``__file__``); created."""
    here = Path(script).resolve()
    out = Path(out_dir) if out_dir else here.parent / "out" / here.stem
    out.mkdir(parents=True, exist_ok=True)
    return out


def save_figure(fig, script: str, out: Path, name: str, fast: bool, readme_name: str | None = None,
                dpi: int = 110) -> None:
    """Write ``fig`` to ``out/<name>.png``; in full mode also to ``studies/figures/<readme_name or name>.png``.

    The figure is closed afterwards.
    """
    import matplotlib.pyplot as plt

    fig.savefig(out / f"{name}.png", dpi=dpi)
    if not fast:
        figures = Path(script).resolve().parent / "figures"
        figures.mkdir(exist_ok=True)
        fig.savefig(figures / f"{readme_name or name}.png", dpi=dpi)
    plt.close(fig)


def cli(main, doc: str, show=None) -> None:
    """``python studies/<name>.py [--fast] [--out DIR]``: run ``main`` and print ``show(result)``.

    ``show`` defaults to the result's ``to_string()``.
    """
    parser = argparse.ArgumentParser(description=(doc or "").strip().splitlines()[0] if doc else None)
    parser.add_argument("--fast", action="store_true", help="a few points: seconds (what CI runs)")
    parser.add_argument("--out", default=None, help="output folder (default studies/out/<name>/)")
    args = parser.parse_args()
    result = main(args.out, args.fast)
    if result is not None:
        print(show(result) if show else result.to_string())
