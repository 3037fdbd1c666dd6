"""Ctrl-C at any moment: a real ``python -m ropemodel`` process gets SIGINT and exits 130 with one
line on stderr, no traceback, nothing on stdout, and leaves no process behind.

The moments are found from the outside, not guessed from timings (the machine may be loaded):
start-up is seen in the process's memory map (numpy's, then CasADi's library loaded), a solver at
work by its plugin's library (IPOPT) or by the child process bonmin runs in, a sweep at work by
the first finished chunk in its parts directory.  SIGINT goes to the whole process group, as a
terminal sends it, or to the main process alone (``kill -INT``).

Not covered: the interpreter's own first milliseconds (its ``site`` import), where no code of this
package runs yet and Python prints its own traceback.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

WAIT = 120.0   # seconds to reach a moment; far more than it takes


def _maps(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return ""


def _children(pid: int) -> list[int]:
    try:
        return [int(c) for c in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        return []


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_text()
    except OSError:
        return ""


def _library(name):
    return lambda p, d: name in _maps(p.pid)


def _bonmin_child(p, d):
    return any("ropemodel" in _cmdline(c) for c in _children(p.pid))


def _first_part(p, d):
    return any((d / "out.parquet.parts").glob("part-*.arrow"))


def interrupt(argv, moment, tmp_path, group=True, after=0.0):
    """Start ``ropemodel argv``, wait for ``moment(process, dir)``, send SIGINT; (status, stdout, stderr)."""
    p = subprocess.Popen([sys.executable, "-m", "ropemodel", *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, cwd=tmp_path, start_new_session=True, env={**os.environ, "ROPEMODEL_QUIET": "1"})
    t0 = time.monotonic()
    try:
        while not moment(p, tmp_path):
            assert p.poll() is None, f"ended before the moment: {p.returncode}\n{p.stderr.read()}"
            assert time.monotonic() - t0 < WAIT, "the moment never came"
            time.sleep(0.002)
        children = _children(p.pid)
        time.sleep(after)
        if group:
            os.killpg(p.pid, signal.SIGINT)
        else:
            p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=WAIT)
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.communicate()
    time.sleep(0.2)
    left = [c for c in children if Path(f"/proc/{c}").exists() and "ropemodel" in _cmdline(c)]
    assert not left, f"processes left running: {left}"
    return p.returncode, out, err


def check(status, out, err, line="interrupted"):
    assert status == 130, (status, out[-2000:], err[-2000:])
    assert out == "", out[-2000:]
    assert "Traceback" not in err and "CasADi" not in err and "WARNING" not in err, err[-3000:]
    assert len(err.splitlines()) == 1 and err.startswith(line), err[-3000:]


SIZING = ["size", "winch_sizing_fig9"]


@pytest.mark.parametrize("argv, moment, group, after", [
    (["run"], _library("_multiarray_umath"), True, 0.0),     # start-up: numpy loading
    (["run"], _library("libcasadi.so"), True, 0.0),          # start-up: CasADi loading
    (["run"], _library("libcasadi.so"), False, 0.05),        # start-up: the model being built
    (SIZING, _library("nlpsol_ipopt"), True, 0.0),           # size: IPOPT at work
    (SIZING, _library("nlpsol_ipopt"), False, 0.02),
    (SIZING + ["--discrete", "bonmin"], _bonmin_child, True, 0.1),    # size: bonmin in its child process
    (SIZING + ["--discrete", "bonmin"], _bonmin_child, False, 0.1),
    (["simulate", "winch_start"], _library("integrator_cvodes"), True, 0.1),   # a transient: CVODES at work
], ids=["numpy", "casadi", "building", "ipopt", "ipopt-main", "bonmin", "bonmin-main", "cvodes"])
def test_ctrl_c_exits_130_with_one_line(argv, moment, group, after, tmp_path):
    check(*interrupt(argv, moment, tmp_path, group, after))


@pytest.mark.parametrize("group", [True, False], ids=["group", "main"])
def test_ctrl_c_during_a_sweep_keeps_its_parts(group, tmp_path):
    argv = ["sweep", "example", "--vary", "alpha_u=0deg:45deg:4000000", "--outputs", "F_C_up",
            "--chunk-size", "20000", "-o", "out.parquet"]
    status, out, err = interrupt(argv, _first_part, tmp_path, group)
    check(status, out, err, line="interrupted: ")
    assert "resume" in err
    assert not (tmp_path / "out.parquet").exists()   # a part file, never a torn output
    assert any((tmp_path / "out.parquet.parts").glob("part-*.arrow"))


def _ipopt_interrupted_at_its_third_evaluation():
    """A real IPOPT solve during which Ctrl-C comes (SIGINT sent from inside the objective, so it lands
    there every time): CasADi's interrupt check stops IPOPT and consumes the KeyboardInterrupt."""
    import casadi as ca

    class Objective(ca.Callback):
        def __init__(self):
            ca.Callback.__init__(self)
            self.calls = 0
            self.construct("f", {"enable_fd": True})

        def get_n_in(self):
            return 1

        def get_n_out(self):
            return 1

        def get_sparsity_in(self, i):
            return ca.Sparsity.dense(2, 1)

        def eval(self, arg):
            self.calls += 1
            if self.calls == 3:
                os.kill(os.getpid(), signal.SIGINT)
            return [ca.sumsqr(arg[0] - 1)]

    f, x = Objective(), ca.MX.sym("x", 2)
    solver = ca.nlpsol("s", "ipopt", {"x": x, "f": f(x)},
                       {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
                        "ipopt.hessian_approximation": "limited-memory"})
    solver(x0=[5.0, 5.0])
    return solver.stats()["return_status"]


def test_an_interrupt_consumed_by_casadi_still_ends_the_command(monkeypatch, capfd):
    """Before: IPOPT returned (status NonIpopt_Exception_Thrown), CasADi printed its WARNING, and the
    command printed its result with exit 0.  The command below prints a result after such a solve."""
    import ropemodel.envelope
    from ropemodel.cli import main

    statuses = []

    class Result:
        def table(self):
            return "A RESULT"

    def run(scene):
        statuses.append(_ipopt_interrupted_at_its_third_evaluation())
        return Result()

    monkeypatch.setattr(ropemodel.envelope, "run", run)     # what `ropemodel run` calls
    code = main(["run"])
    out, err = capfd.readouterr()
    assert statuses == ["NonIpopt_Exception_Thrown"]   # IPOPT was stopped and returned: the interrupt consumed
    assert (code, out, err) == (130, "", "interrupted\n")
