"""An interrupted sweep resumes where it stopped: same file, nothing recomputed, no row lost."""

import os
import signal
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import ropemodel as rm
import ropemodel.sweeps.schedule as schedule
from ropemodel.cli import main as cli
from ropemodel.sweeps.store import KILL_HOOK

ROOT = Path(__file__).resolve().parents[1]
ARGS = ["sweep", "example", "--vary", "alpha_u=4deg:40deg:60", "--vary", "G_m=200kN:600kN:25",
        "--chunk-size", "100", "--no-progress"]  # 1500 points, 15 chunks


def _cli(args, env_extra=None):
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    env.pop(KILL_HOOK, None)
    env.update(env_extra or {})
    code = "import sys; from ropemodel.cli import main; sys.exit(main(sys.argv[1:]))"
    return subprocess.run([sys.executable, "-c", code, *args], env=env, capture_output=True, text=True)


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_killed_sweep_resumes_to_the_same_file(tmp_path, suffix, monkeypatch):
    whole = tmp_path / f"whole{suffix}"
    assert cli(ARGS + ["-o", str(whole)]) == 0  # uninterrupted, in this process

    cut = tmp_path / f"cut{suffix}"
    killed = _cli(ARGS + ["-o", str(cut)], {KILL_HOOK: "4"})
    assert killed.returncode == -signal.SIGKILL  # really killed, mid-write of the 5th chunk
    parts = cut.with_name(cut.name + ".parts")
    assert sorted(p.name for p in parts.glob("part-*.arrow")) == [f"part-{k:06d}.arrow" for k in range(4)]
    assert list(parts.glob("*.tmp")), "the half-written part is left as a temporary file"
    assert not cut.exists()

    # resume in-process to count the chunks computed: only the 11 missing ones
    calls = []
    real = schedule.run_chunk
    monkeypatch.setattr(schedule, "run_chunk",
                        lambda job, start, inputs: calls.append(start) or real(job, start, inputs))
    scene = rm.load_scene()
    rm.sweep(scene, {"alpha_u": "4deg:40deg:60", "G_m": "200kN:600kN:25"}, out=cut, chunk_size=100,
             collect=False, progress=False)
    assert sorted(calls) == list(range(400, 1500, 100))
    assert cut.read_bytes() == whole.read_bytes()
    assert not parts.exists()
    n = len(pd.read_parquet(cut) if suffix == ".parquet" else pd.read_csv(cut))
    assert n == 1500


def test_resume_refuses_other_settings(tmp_path, capsys, monkeypatch):
    out = tmp_path / "x.parquet"
    monkeypatch.setenv(KILL_HOOK, "2")
    monkeypatch.setattr("os.kill", lambda pid, sig: (_ for _ in ()).throw(KeyboardInterrupt()))
    assert cli(ARGS + ["-o", str(out)]) == 130  # stopped (here by an interrupt) after 2 chunks
    monkeypatch.delenv(KILL_HOOK)
    other = ["sweep", "example", "--vary", "alpha_u=4deg:40deg:61", "--chunk-size", "100", "-o", str(out)]
    assert cli(other) == 2
    err = capsys.readouterr().err
    assert "unfinished sweep with other settings" in err and "points" in err
    assert cli(other + ["--restart"]) == 0 and len(pd.read_parquet(out)) == 61
