"""The sizing studies run end to end in fast mode and their numbers are consistent."""


import pandas as pd
import pytest
from _studies import load_study


def test_sizing_benchmark_fast(tmp_path):
    summary = load_study("sizing_benchmark").main(tmp_path, fast=True)
    df = pd.read_csv(tmp_path / "sizing_benchmark.csv")
    assert len(df) == summary["scenes"] >= 5
    assert (tmp_path / "sizing_benchmark.png").stat().st_size > 0
    # IPOPT solved every (feasible by construction) scene and met every check
    assert summary["ipopt_success_rate"] == 1.0
    # where both converged to feasible points, SLSQP (finite differences) found the same rope
    both = df[df["ipopt_ok"] & df["slsqp_converged"] & df["slsqp_feasible"]]
    assert (both["rel_diff_d"] <= 1e-4).all()
    assert summary["time_ratio_slsqp_over_ipopt"] == pytest.approx(
        df["slsqp_s"].median() / df["ipopt_s"].median(), rel=1e-12)


def test_discrete_design_fast(tmp_path):
    summary = load_study("discrete_design").main(tmp_path, fast=True)
    df = pd.read_csv(tmp_path / "discrete_design.csv")
    assert len(df) == summary["scenes"] >= 1
    # the next size up is a catalogue size >= the continuous optimum
    found = df[df["next_up_found"]]
    assert (found["d_next_up"] >= found["d_continuous"] - 1e-12).all()
    assert (tmp_path / "discrete_design.png").stat().st_size > 0
