"""A fuzz of every command with generated bad inputs: each fails cleanly, never with a result.

The cases (``tests/_fuzz.py``, ``tests/_fuzz_cli.py``) change one thing in a command line that
succeeds: the scene file (binary, empty, not UTF-8, broken TOML, tables and values of the wrong
kind, every parameter of each command's scene and of every model outside its range or of a bad
kind, unknown names, bad ``[numerics]``), an option (wrong types, zero/negative/huge counts,
repeated and unknown names, bare numbers for dimensional values), a data file (points and
identification data: empty, ragged, binary, Latin-1, UTF-16, corrupt Parquet, a directory,
booleans, NaN, headers without units, loads beyond the unwrap limit) or an output path (a
directory, under a regular file, a missing directory, an unwritable place, an unknown suffix).

Each runs in-process through :func:`ropemodel.cli.main` with the process's file descriptors
captured (``capfd``: C-level output of CasADi or IPOPT is caught too), and must end with
exit status 2 (bad input) or 1 (no valid solution, or work that could not be completed) as the
case says; nothing on stdout; on stderr, after any ``warning:`` lines of the scene, one message
starting ``error: `` of at most 40 lines with no traceback and no solver log.  A few cases run
through a real ``python -m ropemodel`` too.

Counts (asserted by :func:`test_counts`; the README quotes them): 1521 cases — run 237, solve 132,
size 129, curve 128, identify 144, simulate 133, sweep 201, sensitivity 155, trip 125, report 132,
no command or an unknown one 5; scene files 1143, options 253, data files 65, output paths 60.
Outcomes: exit 2 for 1519, exit 1 for 2 (a ``solve --given`` out of reach, identification data
whose rotations fall with the load); 0 tracebacks, 0 accepted (exit 0), 0 results printed, 0 solver
logs.  (A case that fails in a file someone else is changing goes in ``OWNED_ELSEWHERE``: a strict
xfail naming the fix it needs.)  A new command gets every scene case
once its base is in ``BASES``.
"""

from __future__ import annotations

import os
import random
import subprocess
import sys
from collections import Counter

import pytest

from ropemodel.cli import main
from _fuzz import BASES, DIR, SEED, scene_file_cases, scene_structure_cases, scene_value_cases
from _fuzz_cli import data_cases, option_cases, output_cases, points_cases

SOLVER_LOG = ("Traceback", "CasADi", "WARNING(", "Ipopt", "IPOPT", "EXIT:", "******", "Bonmin",
              "Exception", "Error in Function", "raise ")
MAX_LINES = 40


def all_cases():
    rng = random.Random(SEED)
    return (scene_file_cases() + scene_structure_cases() + scene_value_cases(rng) + option_cases()
            + points_cases() + data_cases() + output_cases())


CASES = all_cases()
#: cases per command and per kind, and exit statuses (a change to the generator changes these on purpose)
EXPECTED = {"run": 237, "solve": 132, "size": 129, "curve": 128, "identify": 144, "simulate": 133, "sweep": 201,
            "sensitivity": 155, "trip": 125, "report": 132, "(none)": 5}
EXPECTED_KINDS = {"scene": 1143, "option": 253, "data": 65, "output": 60}


def write_files(d, files: dict) -> None:
    for name, content in files.items():
        path = d / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if content is DIR:
            path.mkdir()
        else:
            path.write_bytes(content)


def argv_of(case, d) -> list[str]:
    return [a.replace("{d}", str(d)) for a in case.argv]


def check_clean(code: int, out: str, err: str, codes) -> None:
    """The contract of a failure (see the module docstring)."""
    assert code in codes, f"exit {code}, expected {sorted(codes)}\nstdout: {out[:2000]}\nstderr: {err[:2000]}"
    assert out == "", f"something printed on stdout: {out[:2000]}"
    lines = err.splitlines()
    while lines and lines[0].startswith("warning: "):
        lines.pop(0)
    assert lines and lines[0].startswith("error: "), f"stderr does not start with 'error: ':\n{err[:3000]}"
    assert len(lines) <= MAX_LINES, f"{len(lines)} lines on stderr:\n{err[:3000]}"
    for word in SOLVER_LOG:
        assert word not in err, f"{word!r} on stderr:\n{err[:3000]}"


#: cases that fail in files other engineers own; the fix they need is in the reason (strict: an xfail
#: that starts passing fails, so the mark is removed once the fix lands)
OWNED_ELSEWHERE: dict[tuple[str, str], str] = {}


def _param(i, case):
    reason = OWNED_ELSEWHERE.get((case.command, case.what))
    marks = [pytest.mark.xfail(reason=reason, strict=True)] if reason else []
    return pytest.param(case, id=f"{case.command}-{case.kind}-{i}-{case.what}", marks=marks)


@pytest.mark.parametrize("case", [_param(i, c) for i, c in enumerate(CASES)])
def test_bad_input_fails_cleanly(case, tmp_path, capfd, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_files(tmp_path, case.files)
    code = main(argv_of(case, tmp_path))
    out, err = capfd.readouterr()
    check_clean(code, out, err, case.codes)


@pytest.mark.parametrize("command", list(BASES))
def test_each_base_succeeds(command, tmp_path, capfd):
    """The invocation every case of a command starts from succeeds: the one change is what fails."""
    from _fuzz import base_case

    argv, files = base_case(command)
    write_files(tmp_path, files)
    code = main(argv_of(type("C", (), {"argv": argv})(), tmp_path))
    out, err = capfd.readouterr()
    assert code == 0, err
    assert out and "error" not in err


def counts():
    by_command = Counter(c.command for c in CASES)
    by_kind = Counter(c.kind for c in CASES)
    return len(CASES), dict(sorted(by_command.items())), dict(sorted(by_kind.items()))


def test_counts():
    total, by_command, by_kind = counts()
    assert set(BASES) <= set(by_command), "every command is fuzzed"
    assert (total, by_command, by_kind) == (1521, dict(sorted(EXPECTED.items())), dict(sorted(EXPECTED_KINDS.items())))
    assert Counter(tuple(c.codes) for c in CASES) == {(2,): 1519, (1,): 2}
    assert not OWNED_ELSEWHERE


#: one case of each of these, through a real process
THROUGH_A_PROCESS = ("file binary", "file TOML: huge nesting", "model = 3", "--find twice", "--threads -1",
                     "--samples 3", "points csv: ragged", "data: Latin-1", "-o under a regular file",
                     "--plot suffix .xyz")
SUBPROCESS = [next(c for c in CASES if c.what == what) for what in THROUGH_A_PROCESS]


@pytest.mark.parametrize("case", SUBPROCESS, ids=[f"{c.command}-{c.what}" for c in SUBPROCESS])
def test_console_entry(case, tmp_path):
    """Through the real console entry: no traceback from ``python -m ropemodel`` either."""
    write_files(tmp_path, case.files)
    env = {**os.environ, "PYTHONWARNINGS": "default"}
    p = subprocess.run([sys.executable, "-m", "ropemodel", *argv_of(case, tmp_path)], capture_output=True,
                       text=True, env=env, cwd=tmp_path, timeout=300)
    check_clean(p.returncode, p.stdout, p.stderr, case.codes)
