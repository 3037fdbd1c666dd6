"""``sweep --sizing --dynamic`` in chunks on dask.distributed and resumable on disk (slow: a few dynamic
optima).  Truth: every row's design is simulated through the four manoeuvres at every place of the load and
judged by the test's own checks (``_dynamic_scene.simulated_failures``); a heavier load needs a thicker rope or
more pretension; a sweep killed after its first chunk resumes from the part on disk (the row is the part's,
byte for byte, not recomputed)."""

from __future__ import annotations

import os
import subprocess
import sys

import pandas as pd
import pytest
from _dynamic_scene import simulated_failures, write_scene

from optimisation.dynamic.sweep import dynamic_sizing_sweep
from optimisation.problem import load_sizing

#: four dynamic optima (two on the cluster, two through the killed and resumed command): minutes
pytestmark = [pytest.mark.slow, pytest.mark.exhaustive]

VARY = {"G_m": "440kN:480kN:2"}


@pytest.fixture(scope="module")
def path(tmp_path_factory):
    return write_scene(tmp_path_factory.mktemp("dynsweep"))


@pytest.fixture(scope="module")
def on_cluster(path, tmp_path_factory):
    """The map on a LocalCluster of one worker process (the scene and points travel pickled), written."""
    distributed = pytest.importorskip("dask.distributed")
    out = tmp_path_factory.mktemp("cluster") / "map.parquet"
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        frame = dynamic_sizing_sweep(load_sizing(path, emit=False), VARY, out=out, chunk_size=1, executor=client,
                                     progress=False)
    return frame, out


def test_cluster_rows_keep_every_check_in_simulation(path, on_cluster):
    frame, out = on_cluster
    assert len(frame) == 2 and frame["feasible"].all()
    pd.testing.assert_frame_equal(pd.read_parquet(out), frame)
    d, F = frame["d [mm]"].to_numpy(), frame["F_nwl [kN]"].to_numpy()
    assert d[1] > d[0] or (d[1] == d[0] and F[1] > F[0])
    scene = load_sizing(path, emit=False)
    for _, row in frame.iterrows():
        design = {"d": row["d [mm]"] / 1e3, "F_nwl": row["F_nwl [kN]"] * 1e3, "stroke": row["stroke [mm]"] / 1e3}
        assert simulated_failures(scene.with_values({"G_m": row["G_m [kN]"] * 1e3}), design) == []


def test_a_killed_sweep_resumes_from_its_parts(path, on_cluster, tmp_path):
    """Killed (SIGKILL) after committing the first chunk: the rerun computes only the second; the output is the
    cluster's map (the same optima; the first row's solve time is the killed run's, read from its part)."""
    out = tmp_path / "map.csv"
    cmd = [sys.executable, "-m", "ropemodel", "sweep", str(path), "--sizing", "--dynamic", "--vary",
           "G_m=440kN:480kN:2", "--chunk-size", "1", "-o", str(out), "--no-progress"]
    killed = subprocess.run(cmd, env={**os.environ, "ROPEMODEL_SWEEP_KILL_AFTER": "1"}, capture_output=True)
    assert killed.returncode != 0 and not out.exists()
    part = pd.read_feather(out.with_name(out.name + ".parts") / "part-000000.arrow")
    again = subprocess.run(cmd, capture_output=True, text=True)
    assert again.returncode == 0, again.stderr
    assert "wrote 2 points" in again.stdout
    frame = pd.read_csv(out)
    assert frame["seconds"].iloc[0] == part["seconds"].iloc[0]
    expected = on_cluster[0]
    for column in ("d [mm]", "F_nwl [kN]", "stroke [mm]"):
        assert frame[column].to_numpy() == pytest.approx(expected[column].to_numpy(), rel=1e-6), column
    assert not out.with_name(out.name + ".parts").exists()
