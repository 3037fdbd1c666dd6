"""Sweep output files: locked, atomic, checked before any work, never reported done unless whole.

The truths these tests compare against are independent of the code under test: pandas reading the
file, a reference sweep computed in memory, byte equality with an uninterrupted run, the kernel's
``flock`` taken by the test itself, and the processes' exit codes and stderr.
"""

import errno
import fcntl
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import ropemodel as rm
import ropemodel.sweeps.files as files
import ropemodel.sweeps.schedule as schedule
import ropemodel.sweeps.store as store
from ropemodel.cli import main as cli
from ropemodel.sweeps.files import available_memory

ROOT = Path(__file__).resolve().parents[1]
VARY = {"alpha_u": "4deg:40deg:60", "G_m": "200kN:600kN:25"}
OUTPUTS = ["F_C_up", "dF_up"]
ARGS = ["sweep", "example", "--vary", "alpha_u=4deg:40deg:60", "--vary", "G_m=200kN:600kN:25",
        "--outputs", "F_C_up,dF_up", "--chunk-size", "100", "--no-progress"]  # 1500 points, 15 chunks


def _env():
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    env.pop(store.KILL_HOOK, None)
    return env


def _start(args, **kwargs):
    """The console entry, ``python -m ropemodel ...``, as a separate process."""
    kwargs.setdefault("stdout", subprocess.PIPE)
    kwargs.setdefault("stderr", subprocess.PIPE)
    return subprocess.Popen([sys.executable, "-m", "ropemodel", *args], env=_env(), **kwargs)


def _read(path):
    return pd.read_csv(path) if path.suffix == ".csv" else pd.read_parquet(path)


@pytest.fixture(scope="module")
def reference():
    """The sweep computed in memory: what every output file must hold."""
    return rm.sweep(rm.load_scene(), VARY, OUTPUTS, progress=False)


@pytest.fixture
def no_compute(monkeypatch):
    """Fail the test if any chunk is evaluated."""
    def refuse(*args):
        raise AssertionError("a chunk was computed")

    monkeypatch.setattr(schedule, "run_chunk", refuse)


@pytest.fixture
def count_chunks(monkeypatch):
    """The first point of every chunk computed."""
    calls = []
    real = schedule.run_chunk
    monkeypatch.setattr(schedule, "run_chunk",
                        lambda job, start, inputs: calls.append(start) or real(job, start, inputs))
    return calls


def _one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


# -- locking ------------------------------------------------------------------------------------------

def test_second_writer_is_refused_before_computing(tmp_path, capsys, no_compute):
    out = tmp_path / "s.parquet"
    with open(tmp_path / "s.parquet.lock", "w") as held:  # another writer holds the documented lock
        fcntl.flock(held, fcntl.LOCK_EX)
        assert cli(ARGS + ["-o", str(out)]) == 2
        line = _one_error_line(capsys.readouterr().err)
        assert line.startswith(f"error: {out} is being written by another process") and "wait" in line
        with pytest.raises(rm.InputError, match="being written by another process"):
            rm.sweep(rm.load_scene(), VARY, OUTPUTS, out=out, collect=False)
    assert not out.exists() and not (tmp_path / "s.parquet.parts").exists()


def _race(tmp_path, reference, trials, extra=()):
    """Two processes on one output, ``trials`` times; every outcome checked; the outcomes counted."""
    outcomes = {"wrote": 0, "already complete": 0, "refused": 0}
    for i in range(trials):
        out = tmp_path / f"race{i}{'.csv' if i % 2 else '.parquet'}"
        restart = ["--restart"] if i % 2 else []
        if restart:  # both recompute a finished output and replace it
            assert cli(ARGS + ["-o", str(out)]) == 0
        procs = [_start([*ARGS, *extra, *restart, "-o", str(out)], text=True) for _ in range(2)]
        for p in procs:
            stdout, stderr = p.communicate(timeout=300)
            if p.returncode == 2:
                line = _one_error_line(stderr)
                assert re.fullmatch(rf"error: {re.escape(str(out))} is being written by another process"
                                    r"( \(pid \d+\))?; wait for it to finish, or write to another file", line), line
                assert stdout == ""
                outcomes["refused"] += 1
            else:
                assert p.returncode == 0 and stderr == "", (p.returncode, stderr)
                kind = "wrote" if stdout.startswith("wrote ") else "already complete"
                assert stdout in (f"wrote 1500 points x 4 columns to {out}\n",
                                  f"already complete: {out} (1500 points)\n"), stdout
                outcomes[kind] += 1
        pd.testing.assert_frame_equal(_read(out), reference, check_exact=True, check_dtype=False)
        assert not out.with_name(out.name + ".lock").exists() and not out.with_name(out.name + ".parts").exists()
    return outcomes


def test_two_sweep_processes_on_one_output(tmp_path, reference):
    outcomes = _race(tmp_path, reference, trials=2)
    assert sum(outcomes.values()) == 4 and outcomes["wrote"] >= 2


@pytest.mark.slow
def test_two_sweep_processes_on_one_output_many_times(tmp_path, reference):
    outcomes = _race(tmp_path, reference, trials=12, extra=["--backend", "casadi"])
    print(outcomes)
    assert sum(outcomes.values()) == 24 and outcomes["wrote"] >= 12


# -- failures before any work -------------------------------------------------------------------------

def _unwritable(tmp_path):
    if os.geteuid() != 0:
        d = tmp_path / "ro"
        d.mkdir(mode=0o555)
        return d / "x.csv", "no permission"
    if not Path("/sys").is_dir():
        pytest.skip("no read-only place for root")
    return Path("/sys/ropemodel-test.csv"), "ermission denied"  # sysfs refuses new files, even to root


@pytest.mark.parametrize("case", ["directory", "under a file", "deep under a file", "missing directory",
                                  "unknown suffix", "unwritable"])
def test_unwritable_outputs_are_refused_before_work(tmp_path, capsys, no_compute, case):
    (tmp_path / "adir.csv").mkdir()
    (tmp_path / "afile").write_text("")
    path, words = {
        "directory": (tmp_path / "adir.csv", "is a directory"),
        "under a file": (tmp_path / "afile" / "x.csv", f"{tmp_path / 'afile'} is a file, not a directory"),
        "deep under a file": (tmp_path / "afile" / "a" / "x.csv", f"{tmp_path / 'afile'} is a file, not a directory"),
        "missing directory": (tmp_path / "nowhere" / "x.csv", f"directory {tmp_path / 'nowhere'} does not exist"),
        "unknown suffix": (tmp_path / "x.xlsx", "must end in .parquet, .pq, .csv"),
        "unwritable": None,
    }.get(case) or _unwritable(tmp_path)
    before = sorted(tmp_path.rglob("*"))
    assert cli(ARGS + ["-o", str(path)]) == 2
    line = _one_error_line(capsys.readouterr().err)
    assert line.startswith("error: ") and str(path) in line and words in line, line
    assert sorted(tmp_path.rglob("*")) == before  # nothing created
    with pytest.raises(rm.InputError):
        rm.sweep(rm.load_scene(), VARY, OUTPUTS, out=path, collect=False)


@pytest.mark.parametrize("vary, words", [  # the size and the limit named; nothing allocated for them
    (["alpha_u=4deg:40deg:100000000000"], r"100000000000 points on one axis; at most 100000000"),
    (["alpha_u=4deg:40deg:100000", "G_m=200kN:600kN:1000000"],
     r"the grid has 1e\+11 points \(100000 x 1000000\); at most 1e\+10 points per sweep"),
    (["alpha_u=4deg:40deg:100000", "G_m=200kN:600kN:100000"],
     r"10,000,000,000 points x 4 columns need at least 298\.0 GiB of disk for the sweep's parts beside "
     r".*big\.parquet; [\d,.]+ GiB is free there"),
])
def test_impossible_work_is_refused_with_its_size(tmp_path, capsys, no_compute, vary, words):
    if shutil.disk_usage(tmp_path).free > 320e9:
        pytest.skip("this disk could hold 1e10 points")
    args = ["sweep", "example", *[a for v in vary for a in ("--vary", v)], "--outputs", "F_C_up,dF_up"]
    assert cli(args + ["-o", str(tmp_path / "big.parquet")]) == 2
    line = _one_error_line(capsys.readouterr().err)
    assert re.search(words, line), line
    assert sorted(tmp_path.iterdir()) == []


def test_results_beyond_memory_are_refused_with_collect(no_compute):
    mem = available_memory()
    if mem is None:
        pytest.skip("available memory unknown here")
    n = 2 * int(mem // (8 * 3))  # 3 columns of 8 bytes: twice what memory holds (it moves while tests run)
    axis = {"alpha_u": f"4deg:40deg:{n // 1000 + 1}", "G_m": "200kN:600kN:1000"}
    with pytest.raises(rm.InputError, match=r"collect=True keeps every result in memory: [\d,]+ points x 3 columns"):
        rm.sweep(rm.load_scene(), axis, ["F_C_up"])


# -- failures while writing ---------------------------------------------------------------------------

def _enospc(*args):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_disk_full_at_the_end_keeps_the_parts_and_resumes(tmp_path, capsys, monkeypatch, suffix):
    whole = tmp_path / f"whole{suffix}"
    assert cli(ARGS + ["-o", str(whole)]) == 0
    out = tmp_path / f"full{suffix}"

    def full(tables, schema, path):  # a real start, then the disk is full
        Path(path).write_bytes(b"PAR1 half a file")
        _enospc()

    monkeypatch.setitem(store.FORMATS, suffix, full)
    assert cli(ARGS + ["-o", str(out)]) == 1
    line = _one_error_line(capsys.readouterr().err)
    assert line == (f"error: cannot write {out}: No space left on device; 1500 of 1500 points are done and kept "
                    f"in {out}.parts: rerun the same command to resume")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([whole.name, whole.name + ".sweep.json"] * (
        suffix == ".csv") + [whole.name] * (suffix != ".csv") + [out.name + ".parts"])
    monkeypatch.undo()
    calls = []
    real = schedule.run_chunk
    monkeypatch.setattr(schedule, "run_chunk",
                        lambda job, start, inputs: calls.append(start) or real(job, start, inputs))
    assert cli(ARGS + ["-o", str(out)]) == 0 and calls == []
    assert out.read_bytes() == whole.read_bytes()


@pytest.mark.parametrize("fail_at, kept", [(0, 0), (3, 300)])
def test_disk_full_while_computing(tmp_path, tmp_path_factory, capsys, monkeypatch, count_chunks, fail_at, kept):
    whole = tmp_path_factory.mktemp("whole") / "whole.parquet"
    assert cli(ARGS + ["-o", str(whole)]) == 0
    out = tmp_path / "p.parquet"
    real = store._write_part
    written = []

    def part(table, path):
        if len(written) == fail_at:
            Path(path).write_bytes(b"ARROW1 torn")
            _enospc()
        written.append(path)
        real(table, path)

    monkeypatch.setattr(store, "_write_part", part)
    assert cli(ARGS + ["-o", str(out)]) == 1
    line = _one_error_line(capsys.readouterr().err)
    parts = tmp_path / "p.parquet.parts"
    assert line.startswith(f"error: cannot write {parts}/part-{fail_at:06d}.arrow: No space left on device; ")
    if kept:
        assert line.endswith(f"{kept} of 1500 points are done and kept in {parts}: rerun the same command to resume")
        assert sorted(p.name for p in parts.iterdir()) == ["manifest.json"] + [f"part-{k:06d}.arrow" for k in range(3)]
    else:
        assert line.endswith("nothing was written") and not parts.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == (["p.parquet.parts"] if kept else [])
    monkeypatch.setattr(store, "_write_part", real)
    count_chunks.clear()
    assert cli(ARGS + ["-o", str(out)]) == 0
    assert count_chunks == list(range(kept, 1500, 100))
    assert out.read_bytes() == whole.read_bytes()


def test_a_file_that_does_not_read_back_is_not_reported(tmp_path, capsys, monkeypatch):
    """A writer that ends without an error but leaves a torn file: caught by reading it back."""
    out = tmp_path / "t.parquet"
    real = store.FORMATS[".parquet"]

    def torn(tables, schema, path):
        real(tables, schema, path)
        with open(path, "r+b") as f:
            f.truncate(f.seek(0, 2) // 2)

    monkeypatch.setitem(store.FORMATS, ".parquet", torn)
    assert cli(ARGS + ["-o", str(out)]) == 1
    line = _one_error_line(capsys.readouterr().err)
    assert line.startswith(f"error: cannot write {out}: the file written cannot be read back (")
    assert line.endswith("rerun the same command to resume") and capsys.readouterr().out == ""
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.parquet.parts"]


def test_sizing_output_is_written_atomically(tmp_path, monkeypatch):
    frame = pd.DataFrame({"a [m]": [1.0, 2.0], "b, c [-]": [3.0, None]})
    out = tmp_path / "f.csv"
    out.write_text("old,file\n1,2\n")
    def full(self, path, **kwargs):
        Path(path).write_text("a,")
        _enospc()

    monkeypatch.setattr(pd.DataFrame, "to_csv", full)
    with pytest.raises(files.OutputError, match=f"cannot write {re.escape(str(out))}: No space left on device; "
                                                f"nothing was written"):
        files.write_frame(frame, out)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.csv"] and out.read_text() == "old,file\n1,2\n"
    monkeypatch.undo()
    assert files.write_frame(frame, out) == (2, ["a [m]", "b, c [-]"])
    pd.testing.assert_frame_equal(pd.read_csv(out), frame)


# -- interrupts ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_ctrl_c_keeps_the_finished_chunks_and_resumes(tmp_path, capsys, monkeypatch, suffix):
    whole = tmp_path / f"whole{suffix}"
    assert cli(ARGS + ["-o", str(whole)]) == 0
    out = tmp_path / f"cut{suffix}"
    real = schedule.run_chunk

    def ctrl_c(job, start, inputs):
        if start == 500:
            raise KeyboardInterrupt
        return real(job, start, inputs)

    monkeypatch.setattr(schedule, "run_chunk", ctrl_c)
    assert cli(ARGS + ["-o", str(out)]) == 130
    err = capsys.readouterr().err
    assert err == "interrupted: 500 of 1500 points done; rerun the same command to resume\n"
    assert not out.exists() and len(list(tmp_path.glob(f"cut{suffix}.parts/part-*.arrow"))) == 5
    calls = []
    monkeypatch.setattr(schedule, "run_chunk",
                        lambda job, start, inputs: calls.append(start) or real(job, start, inputs))
    assert cli(ARGS + ["-o", str(out)]) == 0
    assert calls == list(range(500, 1500, 100))
    assert out.read_bytes() == whole.read_bytes()


def test_sigint_to_a_sweep_process(tmp_path):
    """A real Ctrl-C (SIGINT) to ``python -m ropemodel sweep``: one line, exit 130, chunks kept."""
    import signal
    import time

    out = tmp_path / "big.parquet"
    args = ["sweep", "example", "--vary", "alpha_u=4deg:40deg:1000", "--vary", "G_m=200kN:600kN:1000",
            "--outputs", "F_C_up", "--backend", "casadi", "--chunk-size", "10000", "-o", str(out)]
    proc = _start(args, text=True)
    parts = tmp_path / "big.parquet.parts"
    deadline = time.monotonic() + 120
    while not (parts / "part-000001.arrow").exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 130 and stdout == "", (proc.returncode, stderr)
    m = re.fullmatch(r"interrupted: (\d+) of 1000000 points done; rerun the same command to resume\n", stderr)
    assert m, stderr
    assert int(m[1]) == 10000 * len(list(parts.glob("part-*.arrow"))) >= 20000
    assert not out.exists()


# -- finished sweeps ----------------------------------------------------------------------------------

@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_rerun_of_a_finished_sweep_says_complete(tmp_path, capsys, monkeypatch, reference, suffix):
    out = tmp_path / f"done{suffix}"
    assert cli(ARGS + ["-o", str(out)]) == 0
    assert capsys.readouterr().out == f"wrote 1500 points x 4 columns to {out}\n"
    first = out.read_bytes()
    stamp = out.stat().st_mtime_ns
    real = schedule.run_chunk
    calls = []
    monkeypatch.setattr(schedule, "run_chunk",
                        lambda job, start, inputs: calls.append(start) or real(job, start, inputs))
    assert cli(ARGS + ["-o", str(out)]) == 0 and calls == []
    assert capsys.readouterr().out == f"already complete: {out} (1500 points)\n"
    assert cli(ARGS + ["-o", str(out), "--json"]) == 0 and calls == []
    info = json.loads(capsys.readouterr().out)
    assert info == {"output": str(out), "rows": 1500, "columns": list(reference.columns), "status": "complete"}
    assert out.stat().st_mtime_ns == stamp
    # the API finds it too, and gives back the frame it holds
    frame = rm.sweep(rm.load_scene(), VARY, OUTPUTS, out=out, chunk_size=100)
    pd.testing.assert_frame_equal(frame, reference, check_exact=True)
    assert calls == []
    written = rm.sweep(rm.load_scene(), VARY, OUTPUTS, out=out, chunk_size=100, collect=False)
    assert (os.fspath(written), written.rows, written.columns, written.status) == (
        str(out), 1500, list(reference.columns), "complete")
    # --restart recomputes it
    assert cli(ARGS + ["-o", str(out), "--restart"]) == 0 and calls == list(range(0, 1500, 100))
    assert out.read_bytes() == first
    calls.clear()
    written = rm.sweep(rm.load_scene(), VARY, OUTPUTS, out=out, chunk_size=100, collect=False, restart=True)
    assert (written.rows, written.status, len(calls)) == (1500, "written", 15)
    # other settings: not this sweep's output, so it is computed (and replaced)
    calls.clear()
    assert cli(ARGS[:-3] + ["--chunk-size", "500", "-o", str(out)]) == 0 and calls == [0, 500, 1000]
    capsys.readouterr()


def test_an_edited_csv_is_not_taken_as_complete(tmp_path, capsys, monkeypatch, reference):
    out = tmp_path / "e.csv"
    assert cli(ARGS + ["-o", str(out)]) == 0
    first = out.read_bytes()
    out.write_bytes(first.replace(b"\n", b"\n0,", 1))  # one value changed, same size or not
    real = schedule.run_chunk
    calls = []
    monkeypatch.setattr(schedule, "run_chunk",
                        lambda job, start, inputs: calls.append(start) or real(job, start, inputs))
    assert cli(ARGS + ["-o", str(out)]) == 0 and len(calls) == 15
    assert out.read_bytes() == first
    assert capsys.readouterr().out.endswith(f"wrote 1500 points x 4 columns to {out}\n")
    # the signature is beside the CSV, not in it: pandas reads it with no options
    pd.testing.assert_frame_equal(pd.read_csv(out), reference, check_exact=True, check_dtype=False)
    assert json.loads((tmp_path / "e.csv.sweep.json").read_text())["rows"] == 1500


def test_killed_sweep_leaves_no_stale_lock(tmp_path):
    out = tmp_path / "k.parquet"
    killed = subprocess.run([sys.executable, "-m", "ropemodel", *ARGS, "-o", str(out)], capture_output=True,
                            env={**_env(), store.KILL_HOOK: "2"})
    assert killed.returncode < 0  # SIGKILL: no cleanup ran
    assert (tmp_path / "k.parquet.lock").exists()  # the file stays, its lock went with the process
    assert cli(ARGS + ["-o", str(out)]) == 0
    assert not (tmp_path / "k.parquet.lock").exists() and len(pd.read_parquet(out)) == 1500


# -- signs of life --------------------------------------------------------------------------------------

def _stderr_on_pty(args):
    """Run the CLI with stderr on a pseudo-terminal of 24 x 100 characters; its stderr and exit code."""
    import pty
    import select
    import struct
    import termios

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    proc = _start(args, stderr=slave, stdout=subprocess.DEVNULL)
    os.close(slave)
    data = b""
    while True:
        ready, _, _ = select.select([master], [], [], 1.0)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # EIO: the child closed the terminal
                break
            if not chunk:
                break
            data += chunk
        elif proc.poll() is not None:
            break
    os.close(master)
    return proc.wait(timeout=60), data.decode(errors="replace")


def test_progress_bar_on_a_terminal_only(tmp_path):
    args = ARGS[:-1] + ["-o", str(tmp_path / "t.parquet")]  # without --no-progress
    code, err = _stderr_on_pty(args)
    assert code == 0
    assert "sweep: compiling" in err  # the status line, shown before any chunk is computed
    assert err.index("sweep: compiling") < err.index("sweep:   0%|")
    assert re.search(r"sweep: 100%\|[^\r\n]*\| 1\.50k/1\.50k", err), err
    for quiet in ("--no-progress", "--quiet"):
        code, err = _stderr_on_pty(args + ["--restart", quiet])
        assert code == 0 and err == ""
    proc = _start(args + ["--restart"], text=True)  # stderr a pipe, not a terminal
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 0 and stderr == "" and stdout.startswith("wrote 1500 points")


# -- summaries -------------------------------------------------------------------------------------------

def test_csv_shape_with_quoted_headers(tmp_path):
    path = tmp_path / "q.csv"
    path.write_text('"a, b [m]","c ""x"" [-]",d,"e\nf",g\n1,2,3,4,5\n6,7,8,9,10\n"1,5",2,3,4,5\n')
    frame = pd.read_csv(path)  # the independent reader
    assert files.table_shape(path) == (len(frame), list(frame.columns)) == (3, ["a, b [m]", 'c "x" [-]', "d",
                                                                               "e\nf", "g"])
    path.write_text(path.read_text() + "1,2\n")  # a ragged last row: not a readable table
    with pytest.raises(Exception, match="Expected 5 columns, got 2"):
        files.table_shape(path)


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_sizing_sweep_summary_counts_seven_columns(tmp_path, capsys, suffix):
    pytest.importorskip("optimisation")
    from importlib import resources

    scene = str(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml"))
    out = tmp_path / f"s{suffix}"
    args = ["sweep", scene, "--sizing", "--vary", "L_u=800m:1600m:2", "-o", str(out), "--no-progress"]
    assert cli(args) == 0
    frame = _read(out)
    assert frame.shape == (2, 7)
    assert capsys.readouterr().out == f"wrote 2 points x 7 columns to {out}\n"
    assert cli(args + ["--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert (info["rows"], info["columns"]) == (2, list(frame.columns))
    assert not (tmp_path / f".s{suffix}.tmp").exists() and not (tmp_path / f"s{suffix}.lock").exists()


def test_sizing_sweep_is_locked(tmp_path, capsys):
    pytest.importorskip("optimisation")
    out = tmp_path / "s.csv"
    with open(tmp_path / "s.csv.lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        assert cli(["sweep", "example", "--sizing", "--vary", "L_u=800m:1600m:2", "-o", str(out)]) == 2
    assert "is being written by another process" in _one_error_line(capsys.readouterr().err)
    assert not out.exists()
