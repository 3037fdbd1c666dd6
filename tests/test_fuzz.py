"""A fuzz of every command: bad inputs fail cleanly, inputs at the edges of the valid give a sound result.

The cases change one thing in a command line that succeeds (its base, ``_fuzz.BASES``):

* ``tests/_fuzz.py``, ``tests/_fuzz_cli.py`` — bad inputs: the scene file (binary, empty, not UTF-8,
  broken TOML, tables and values of the wrong kind, every parameter of each command's scene and of every
  model outside its range or of a bad kind, unknown names, bad ``[numerics]``), an option (wrong types,
  zero/negative/huge counts, repeated and unknown names, bare numbers for dimensional values), a data
  file (points and identification data: empty, ragged, binary, Latin-1, UTF-16, corrupt Parquet, a
  directory, booleans, NaN, headers without units, loads beyond the unwrap limit) or an output path (a
  directory, under a regular file, a missing directory, an unwritable place, an unknown suffix);
* ``tests/_fuzz_edges.py`` — every input of every command's scene (used or not) at both ends of its
  physical domain, read from its Quantity, and just outside; every input at once at each end;
* ``tests/_fuzz_flags.py`` — every option of every command, read from the parser: alone at the edges of
  its values, and every pair of options used validly;
* ``tests/_fuzz_classes.py`` — the classes an independent fuzz found mishandled (issue 22): output paths
  too long, with a NUL, read-only, on a disk that fills; values outside their domain where unused and
  1e308 with a unit; work above its budget; empty and contradictory flags, data with no information, a
  rope slack at rest; a UTF-8 byte-order mark; messages naming the actual fix; valid inputs refused.

Each runs in-process through :func:`ropemodel.cli.main` with the process's file descriptors captured
(``capfd``: C-level output of CasADi or IPOPT is caught too).  A bad input must end with exit status 2
(bad input) or 1 (no valid solution, or work that could not be completed) as the case says; nothing on
stdout; on stderr, after any ``warning:`` lines of the scene, one message starting ``error: `` of at most
40 lines with no traceback and no solver log, holding the words the case names (the parameter, the
flag).  A valid input must end with exit 0 and a result without NaN or inf anywhere (stdout and the
files written), only ``warning:`` lines on stderr — or fail by the same contract.  A few cases run
through a real ``python -m ropemodel`` too, and the disk that fills in a real process with a file-size
limit (exit 1, one line, nothing left beside the inputs).

Counts (asserted by :func:`test_counts`; the README quotes them): see :data:`EXPECTED`.  The default
suite runs the issue's classes, the output paths and the corners, and a sample of the generated families
(every third bad input, every tenth valid one: :func:`_slow`); ``-m slow`` runs them all.  (A case that
fails in a file someone else is changing goes in ``OWNED_ELSEWHERE``: a strict xfail naming the fix it
needs.)  A new command gets every case once its base is in ``BASES``; a new parameter once its Quantity is
declared; a new option once ``_fuzz_flags.GOOD`` says how it is used.
"""

from __future__ import annotations

import os
import random
import re
import stat
import subprocess
import sys
from collections import Counter

import pytest

from ropemodel.cli import main
from _fuzz import BASES, DIR, SEED, scene_file_cases, scene_structure_cases, scene_value_cases
from _fuzz_classes import disk_full_cases, issue_cases
from _fuzz_cli import data_cases, option_cases, output_cases, points_cases
from _fuzz_edges import corner_cases, edge_cases
from _fuzz_flags import missing_good, pair_cases, single_cases

SOLVER_LOG = ("Traceback", "CasADi", "WARNING(", "Ipopt", "IPOPT", "EXIT:", "******", "Bonmin",
              "Exception", "Error in Function", "raise ")
MAX_LINES = 40
#: NaN or inf as a number prints it (a word of its own, not part of a name)
NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|-?inf|NaN|-?Infinity)(?![A-Za-z_])")


def all_cases():
    rng = random.Random(SEED)
    return (scene_file_cases() + scene_structure_cases() + scene_value_cases(rng) + option_cases()
            + points_cases() + data_cases() + output_cases() + edge_cases() + corner_cases() + issue_cases()
            + single_cases() + pair_cases())


CASES = all_cases()
DISK_FULL = disk_full_cases()
#: cases per command, per kind and per expectation (a change to the generator changes these on purpose)
EXPECTED = {"(none)": 5, "curve": 216, "identify": 210, "report": 309, "run": 794, "sensitivity": 388,
            "simulate": 315, "size": 300, "solve": 287, "sweep": 557, "trip": 311}
EXPECTED_KINDS = {"bom": 3, "budget": 4, "data": 65, "domain": 19, "edge": 1370, "flag": 303, "flag pair": 307,
                  "flags": 18, "koepe": 10, "message": 6, "option": 253, "output": 108, "output read-only": 8,
                  "scene": 1213, "valid": 5}
EXPECTED_OUTCOMES = {"fail": 2589, "sound": 1103}


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


def check_clean(code: int, out: str, err: str, codes, words=(), typed: bool = True) -> None:
    """The contract of a failure (see the module docstring); ``words``: each must be in the message (a tuple
    of words: one of them); ``typed``: the input holds a NaN or an inf the message may quote."""
    assert code in codes, f"exit {code}, expected {sorted(codes)}\nstdout: {out[:2000]}\nstderr: {err[:2000]}"
    assert out == "", f"something printed on stdout: {out[:2000]}"
    lines = err.splitlines()
    while lines and lines[0].startswith("warning: "):
        lines.pop(0)
    assert lines and lines[0].startswith("error: "), f"stderr does not start with 'error: ':\n{err[:3000]}"
    assert len(lines) <= MAX_LINES, f"{len(lines)} lines on stderr:\n{err[:3000]}"
    for word in SOLVER_LOG:
        assert word not in err, f"{word!r} on stderr:\n{err[:3000]}"
    bad = None if typed else NON_FINITE.search("\n".join(lines))
    assert bad is None, f"{bad.group(0)!r} in the message:\n{err[:3000]}"
    for word in words:
        alternatives = word if isinstance(word, tuple) else (word,)
        assert any(w in err for w in alternatives), f"the message names none of {alternatives}:\n{err[:3000]}"


def _check_answer(out: str, err: str) -> None:
    """Exit 1 with something on stdout: no NaN or inf in it, only warnings and at most one error line on stderr,
    no solver log."""
    bad = NON_FINITE.search(out)
    assert bad is None, f"{bad.group(0)!r} in the answer:\n{out[max(0, bad.start() - 500):bad.end() + 200]}"
    others = [line for line in err.splitlines() if line and not line.startswith("warning: ")]
    assert len(others) <= 1 and all(line.startswith("error: ") for line in others), err[:3000]
    for word in SOLVER_LOG:
        assert word not in out + err, f"{word!r} printed:\n{(out + err)[:3000]}"


def check_sound(code: int, out: str, err: str, case, d) -> None:
    """The contract of a valid input: a result with no NaN or inf in it or in a file it wrote, only warnings
    on stderr; or a clean failure."""
    if code == 1 and out:     # an answer that there is none (size's diagnosis), or a report not complete
        _check_answer(out, err)
        return
    if code != 0:
        check_clean(code, out, err, case.codes - {0}, case.words, _typed(case))
        return
    assert out, f"exit 0 with nothing on stdout\nstderr: {err[:2000]}"
    bad = NON_FINITE.search(out)
    assert bad is None, f"{bad.group(0)!r} in the result:\n{out[max(0, bad.start() - 500):bad.end() + 200]}"
    others = [line for line in err.splitlines() if line and not line.startswith("warning: ")]
    assert not others, f"stderr besides warnings:\n{err[:3000]}"
    for path in d.iterdir():
        if path.suffix == ".csv" and path.name not in case.files:
            text = path.read_text(errors="replace")
            assert NON_FINITE.search(text) is None, f"NaN or inf in {path.name}"


#: cases that fail in files other engineers own; the fix they need is in the reason (strict: an xfail
#: that starts passing fails, so the mark is removed once the fix lands)
OWNED_ELSEWHERE: dict[tuple[str, str], str] = {}


#: the kinds of the issue's classes (tests/_fuzz_classes.py) and of the output paths: all in the default suite
DEFAULT_KINDS = ("output", "output read-only", "domain", "budget", "flags", "bom", "message", "valid", "koepe")


def _slow(i: int, case) -> bool:
    """A case outside the default sample: the default runs the issue's classes, the output paths, the corners,
    and every third bad input and every tenth valid one of the generated families; never dynamic sizing's
    valid inputs (minutes each).  ``-m slow`` runs the rest."""
    if "--dynamic" in case.argv and case.expect == "sound":
        return True
    if case.expect == "sound" and ("--pdf" in case.argv or "every input at its" in case.what):
        return True                                     # Chromium prints a PDF; every input at an edge sizes slowly
    if case.kind in DEFAULT_KINDS or "every input" in case.what:
        return False
    return i % (3 if case.expect == "fail" else 10) != 0


def _exhaustive(case) -> bool:
    """Dynamic sizing's valid inputs (one to four minutes each): ``-m exhaustive``, not CI's slow run."""
    return "--dynamic" in case.argv and case.expect == "sound"


def _param(i, case):
    reason = OWNED_ELSEWHERE.get((case.command, case.what))
    marks = [pytest.mark.xfail(reason=reason, strict=True)] if reason else []
    if _slow(i, case):
        marks.append(pytest.mark.slow)
    if _exhaustive(case):
        marks.append(pytest.mark.exhaustive)
    return pytest.param(case, id=f"{case.command}-{case.kind}-{i}-{case.what[:120]}", marks=marks)


def _run(case, tmp_path, capfd, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_files(tmp_path, case.files)
    if case.kind == "output read-only":
        for name in case.files:
            (tmp_path / name).chmod(stat.S_IRUSR | stat.S_IRGRP | stat.S_IROTH)
    code = main(argv_of(case, tmp_path))
    out, err = capfd.readouterr()
    return code, out, err


@pytest.mark.parametrize("case", [_param(i, c) for i, c in enumerate(CASES) if c.expect == "fail"])
def test_bad_input_fails_cleanly(case, tmp_path, capfd, monkeypatch):
    code, out, err = _run(case, tmp_path, capfd, monkeypatch)
    check_clean(code, out, err, case.codes, case.words, _typed(case))


def _typed(case) -> bool:
    """Whether the case's own input holds a NaN or an inf (a message may quote it)."""
    given = " ".join([*case.argv, *(v.decode(errors="replace") for v in case.files.values() if isinstance(v, bytes))])
    return NON_FINITE.search(given) is not None or "1e999" in given or "1" * 400 in given


@pytest.mark.parametrize("case", [_param(i, c) for i, c in enumerate(CASES) if c.expect == "sound"])
def test_valid_input_is_sound(case, tmp_path, capfd, monkeypatch):
    code, out, err = _run(case, tmp_path, capfd, monkeypatch)
    check_sound(code, out, err, case, tmp_path)


def _fill(limit: int):
    def set_limit():
        import resource

        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))   # Python ignores SIGXFSZ: writes fail, EFBIG
    return set_limit


@pytest.mark.parametrize("case", [pytest.param(c, id=f"{c.command}-{c.what}", marks=[] if i % 3 == 0 else
                                               [pytest.mark.slow]) for i, c in enumerate(DISK_FULL)])
def test_disk_that_fills(case, tmp_path):
    """A disk that fills while the output is written (a file-size limit of 200 bytes in a real process): exit
    1 in one line, and nothing left beside the inputs (no partial output, no temporary file, no lock)."""
    write_files(tmp_path, case.files)
    p = subprocess.run([sys.executable, "-m", "ropemodel", *argv_of(case, tmp_path)], capture_output=True,
                       text=True, cwd=tmp_path, timeout=600, preexec_fn=_fill(200))
    check_clean(p.returncode, p.stdout, p.stderr, case.codes, case.words, _typed(case))
    assert sorted(x.name for x in tmp_path.iterdir()) == sorted(case.files), list(tmp_path.iterdir())


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
    by_command = Counter(c.command for c in CASES + DISK_FULL)
    by_kind = Counter(c.kind for c in CASES + DISK_FULL)
    by_outcome = Counter(c.expect for c in CASES + DISK_FULL)
    return len(CASES) + len(DISK_FULL), dict(sorted(by_command.items())), dict(sorted(by_kind.items())), \
        dict(sorted(by_outcome.items()))


def test_counts():
    total, by_command, by_kind, by_outcome = counts()
    assert set(BASES) <= set(by_command), "every command is fuzzed"
    assert not missing_good(), "every option says how it is used (_fuzz_flags.GOOD)"
    assert (by_command, by_kind, by_outcome) == (EXPECTED, EXPECTED_KINDS, EXPECTED_OUTCOMES)
    assert total == sum(EXPECTED.values())


def test_readme_states_the_count():
    """The README and the documentation's "Clean failure, always" (the scene reference, "Writing a scene")
    quote the fuzz's size: its cases, bad and valid (issue 22: the fuzz keeps its count in the README)."""
    from _docs_text import README, section

    total, _, _, by_outcome = counts()
    quoted = (f"{total:,} cases ({by_outcome['fail']:,} bad inputs, {by_outcome['sound']:,} valid inputs at the "
              f"edges)")
    for text in (section("Writing a scene"), README.read_text(encoding="utf-8")):
        assert quoted in " ".join(text.split())


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


#: the commands whose closed pipe the default suite tries (the rest with -m slow: each a process of its own)
PIPED = ("run", "curve", "trip")


def _piped(command: str):
    return pytest.param(command, marks=[] if command in PIPED else [pytest.mark.slow])


@pytest.mark.parametrize("command", [_piped(c) for c in BASES])
def test_a_reader_that_stops_early(command, tmp_path):
    """``ropemodel COMMAND ... | head -c0``: the reader closes the pipe before the command prints; the command ends
    quietly with exit 0, as ``git log | head`` does (nothing on stderr)."""
    from _fuzz import base_case

    argv, files = base_case(command)
    write_files(tmp_path, files)
    argv = [a.replace("{d}", str(tmp_path)) for a in argv]
    read, write = os.pipe()
    p = subprocess.Popen([sys.executable, "-m", "ropemodel", *argv], stdout=write, stderr=subprocess.PIPE,
                         cwd=tmp_path)
    os.close(write)
    os.close(read)        # the reader is gone before the command prints anything
    err = p.stderr.read().decode(errors="replace")
    code = p.wait(timeout=600)
    assert (code, err) == (0, "")
