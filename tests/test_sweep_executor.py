"""Sweeps on executors give the same DataFrame as a local run: dask LocalCluster, process and thread pools."""

import pickle
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import pandas as pd
import pytest

import ropemodel as rm

VARY = {"alpha_u": "4deg:40deg:30", "L_u": "500m:2000m:20"}


@pytest.fixture(scope="module")
def local(fig9):
    return rm.sweep(fig9, VARY, chunk_size=50)


def test_compiled_function_pickles(fig9):
    f = rm.Problem(fig9).function
    g = pickle.loads(pickle.dumps(f))
    x = rm.Problem(fig9).inputs()
    assert float(g(**x)["F_C_up"]) == float(f(**x)["F_C_up"])


def test_dask_local_cluster_equals_local(fig9, local, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        remote = rm.sweep(fig9, VARY, chunk_size=50, executor=client)
        written = rm.sweep(fig9, VARY, chunk_size=50, executor=client, out=tmp_path / "d.parquet", collect=False)
    pd.testing.assert_frame_equal(remote, local, check_exact=True)
    pd.testing.assert_frame_equal(pd.read_parquet(written), local, check_exact=True)


def test_process_pool_equals_local(fig9, local):
    with ProcessPoolExecutor(2) as pool:
        remote = rm.sweep(fig9, VARY, chunk_size=50, executor=pool, backend="casadi")
    pd.testing.assert_frame_equal(remote, local, check_exact=False, rtol=1e-14, atol=1e-12)


def test_thread_pool_equals_local(fig9, local):
    with ThreadPoolExecutor(2) as pool:
        remote = rm.sweep(fig9, VARY, chunk_size=50, executor=pool)
    pd.testing.assert_frame_equal(remote, local, check_exact=True)


def test_worker_errors_reach_the_caller(fig9):
    with ThreadPoolExecutor(2) as pool, pytest.raises(rm.SolveError, match="G_m found outside"):
        rm.sweep(fig9, {"dF_up": [1.4, 0.1]}, given=["dF_up"], find=["G_m"], executor=pool, chunk_size=1)


@pytest.mark.slow
def test_dask_worker_processes_equal_local(fig9, local):
    """Worker processes: the compiled Function travels pickled and is compiled there once."""
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        remote = rm.sweep(fig9, VARY, chunk_size=50, executor=client)
    pd.testing.assert_frame_equal(remote, local, check_exact=True)
