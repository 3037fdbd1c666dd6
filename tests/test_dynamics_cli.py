"""``ropemodel simulate``: JSON contract, history files with units, exit codes."""

from __future__ import annotations

import json
from importlib import resources

import pandas as pd
import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.dynamics import simulate

START = str(resources.files("ropemodel.data").joinpath("winch_start.toml"))
STROKE = str(resources.files("ropemodel.data").joinpath("winch_start_stroke.toml"))


def test_json_has_the_contract_keys_and_agrees_with_the_api(capsys):
    assert main(["simulate", START, "--json", "--set", "t_end=10s"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("F_C_max", "F_C_end", "F_S_min", "dynamic_factor", "slip", "stroke_used"):
        assert key in out
    sim = simulate(rm.load_scene(START).with_values({"t_end": "10 s"}))
    assert out["F_C_max"] == pytest.approx(sim.summary["F_C_max"], rel=1e-12)
    assert out["dynamic_factor"] == pytest.approx(out["F_C_max"] / rm.run(rm.load_scene())["F_C_up"], rel=1e-12)
    assert out["slip"] is False


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_history_file_has_units_in_its_columns(tmp_path, capsys, suffix):
    path = tmp_path / f"h{suffix}"
    assert main(["simulate", START, "-o", str(path), "--set", "t_end=6s"]) == 0
    frame = pd.read_csv(path) if suffix == ".csv" else pd.read_parquet(path)
    for col in ("t [s]", "v_load [m/s]", "F_C [N]", "F_S [N]", "take_up [m]", "slip_speed [m/s]"):
        assert col in frame.columns
    assert frame["t [s]"].iloc[-1] == pytest.approx(6.0)
    assert "dynamic factor" in capsys.readouterr().out


def test_stroke_run_out_in_the_report(capsys):
    assert main(["simulate", STROKE, "--set", "t_end=10s"]) == 0
    assert "RAN OUT OF STROKE" in capsys.readouterr().out


@pytest.mark.parametrize("argv", [
    ["simulate", START, "-o", "history.txt"],
    ["simulate", "example"],
    ["simulate", START, "--set", "t_ramp=-1s"],
])
def test_bad_input_exits_2(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and len(err.strip().splitlines()) == 1
