"""The transient studies run in --fast mode and their results hold their physics."""

from __future__ import annotations

import pytest
from _studies import load_study


def test_dynamic_factor_study_fast(tmp_path):
    df = load_study("dynamic_factor").main(tmp_path, fast=True)
    assert (tmp_path / "dynamic_factor.csv").exists() and (tmp_path / "dynamic_factor.png").exists()
    assert (tmp_path / "dynamic_start.png").exists()
    for _, d in df.groupby("case"):
        d = d.sort_values("t_ramp [s]")
        # the peak falls as the ramp gets longer, and never below the inextensible rope's value
        assert d["dynamic_factor [-]"].iloc[0] > d["dynamic_factor [-]"].iloc[-1]
        assert (d["dynamic_factor [-]"] >= d["rigid_factor [-]"] - 1e-9).all()
        assert d["dynamic_factor [-]"].iloc[-1] == pytest.approx(d["rigid_factor [-]"].iloc[-1], rel=0.25)


def test_dynamics_accuracy_study_fast(tmp_path):
    df = load_study("dynamics_accuracy").main(tmp_path, fast=True)
    assert (tmp_path / "dynamics_accuracy.csv").exists() and (tmp_path / "dynamic_accuracy.png").exists()
    cv = df[(df["integrator"] == "cvodes") & (df["rtol"] == df["rtol"].min())].sort_values("segments")
    assert cv["err_F_C_max [-]"].iloc[-1] < cv["err_F_C_max [-]"].iloc[0]     # converges with segments
    loose = df[(df["integrator"] == "cvodes") & (df["rtol"] == df["rtol"].max())]
    assert (loose["energy_residual [-]"].to_numpy() > cv["energy_residual [-]"].to_numpy()).all()


def test_drum_contact_study_fast(tmp_path):
    df = load_study("drum_contact").main(tmp_path, fast=True)
    assert (tmp_path / "drum_contact.csv").exists() and (tmp_path / "drum_contact.png").exists()
    d = df.sort_values("D [m]")
    # Li et al. eq. (12): K_1 = mu EA F_C / (R (F_C - F_S)) is inversely proportional to the drum radius
    D, K = d["D [m]"].to_numpy(), d["K_1 [N/m]"].to_numpy()
    assert K[0] * D[0] == pytest.approx(K[-1] * D[-1], rel=1e-12)
    # a softer contact (larger drum) changes the transient more
    assert d["max_dF_C_history [-]"].iloc[-1] > d["max_dF_C_history [-]"].iloc[0] > 0


def test_dynamics_events_study_fast(tmp_path):
    df = load_study("dynamics_events").main(tmp_path, fast=True)
    assert (tmp_path / "dynamics_events.csv").exists() and (tmp_path / "dynamics_events.png").exists()
    # the slip is found at every output step, also when it lies inside one, at the same times
    assert df["found"].all() and df["inside_one_output_step"].any()
    assert df["err_t_start [s]"].max() < 1e-9
    assert df["err_t_end [s]"].max() < 1e-6
