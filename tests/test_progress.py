"""Signs of life: commands that can run long show progress on a terminal, and nothing elsewhere.

A pseudo-terminal stands in for the person watching: stderr is attached to it, stdout to a pipe.
"""

from __future__ import annotations

import os
import pty
import select
import subprocess
import sys

import pytest

LONG = [
    (["size", "winch_sizing_fig9"], "rope, pretension and stroke"),
    (["sensitivity", "example", "--sobol", "G_m=300kN:500kN", "--sobol", "alpha_u=10deg:20deg",
      "--samples", "64", "--outputs", "F_C_up"], "computing the Sobol indices"),
    (["simulate", "winch_start"], "building the transient"),
    (["trip", "route_segments"], "trip of"),
    (["identify", "capstan_li_experiment", "{tmp}/data.csv"], "identifying mu, EA"),
    (["report", "example", "-o", "{tmp}/report.html"], "report of"),
]
#: commands that show a bar over their work (the units it counts)
BARS = [
    (["simulate", "winch_start"], "/60.0 s"),
    (["sweep", "example", "--vary", "alpha_u=5deg:45deg:400", "--vary", "G_m=300kN:500kN:500", "-o",
      "{tmp}/sweep.parquet"], "pt/s"),
]


def _argv(argv, tmp):
    if any("{tmp}/data.csv" in a for a in argv):   # identification data: a curve of the scene's own drive
        import ropemodel as rm
        from ropemodel.capstan.curves import load_curve

        curve = load_curve(rm.load_scene("capstan_li_experiment"), 50.0, 10, 5.0)
        curve[["F_T [N]", "delta_alpha [rad]"]].to_csv(tmp / "data.csv", index=False)
    return [a.replace("{tmp}", str(tmp)) for a in argv]


def _run_with_terminal(argv, env=None):
    """(exit status, what the terminal on stderr showed, stdout) of ``python -m ropemodel argv``."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "ropemodel", *argv], stdout=subprocess.PIPE, stderr=slave,
                            env={**os.environ, **(env or {})})
    os.close(slave)
    shown = b""
    while True:
        ready, _, _ = select.select([master], [], [], 0.1)
        if ready:
            try:
                chunk = os.read(master, 4096)
            except OSError:
                break
            if not chunk:
                break
            shown += chunk
        elif proc.poll() is not None:
            break
    out = proc.stdout.read()
    proc.wait()
    os.close(master)
    return proc.returncode, shown.decode(errors="replace"), out.decode()


@pytest.mark.parametrize("argv, text", LONG)
def test_progress_on_a_terminal(argv, text, tmp_path):
    code, shown, out = _run_with_terminal(_argv(argv, tmp_path))
    assert code == 0 and text in shown and " s)" in shown      # the status line with its elapsed time
    assert text not in out                                      # never mixed into the results


@pytest.mark.parametrize("argv, text", BARS)
def test_a_bar_over_the_work(argv, text, tmp_path):
    code, shown, out = _run_with_terminal(_argv(argv, tmp_path))
    assert code == 0 and text in shown and "100%" in shown
    assert "100%" not in out


@pytest.mark.parametrize("argv, text", LONG[:1])
def test_quiet_and_pipes_show_nothing(argv, text):
    code, shown, _ = _run_with_terminal([*argv, "--quiet"])
    assert code == 0 and text not in shown
    p = subprocess.run([sys.executable, "-m", "ropemodel", *argv], capture_output=True, text=True)
    assert p.returncode == 0 and p.stderr == ""
