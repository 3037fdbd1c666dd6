"""Identification of mu and EA from (F_T, delta_alpha) points: synthetic data with known truth."""

import math
import re

import numpy as np
import pandas as pd
import pytest

import ropemodel as rm
from ropemodel.capstan.identify import identify, read_data
from ropemodel.numerics.capstan_rotation import rotation
from ropemodel.cli import main as cli
from ropemodel.errors import InputError

SCENE = "capstan_li_experiment"
TRUE = {"mu": 0.25, "EA": 5e4}
NOISE = 1e-5  # [rad] standard deviation of the synthetic encoder noise (0.0006 deg)


@pytest.fixture(scope="module")
def scene():
    return rm.load_scene(SCENE)


def synthetic(scene, seed, F=None, noise=NOISE):
    p = scene.parameters
    F = np.linspace(0.0, 100.0, 41) if F is None else F
    exact = rotation(F, TRUE["mu"], TRUE["EA"], p["R"], p["L"], p["alpha_0"], p["F_p"]) / p["R"]
    rng = np.random.default_rng(seed)
    return pd.DataFrame({"F_T [N]": F, "delta_alpha [rad]": exact + rng.normal(0.0, noise, F.size)})


def test_recovers_mu_and_EA_within_two_standard_errors(scene):
    start = scene.with_values({"mu": 0.4, "EA": 3e4})  # far from the truth
    res = identify(start, synthetic(scene, seed=0))
    assert res.ok, res.messages
    for k, v in TRUE.items():
        assert abs(res.estimates[k] - v) < 2 * res.standard_errors[k], (k, res.estimates[k], res.standard_errors[k])
    # the estimated noise is the one put in (chi-square with 39 dof: within 30 % at this size)
    assert math.sqrt(res.rss / (res.n_points - 2)) == pytest.approx(NOISE, rel=0.3)
    # the README's example, to the digits it shows: mu = 0.2577 +- 0.0061, EA = 49 915 +- 71 N
    assert (res.estimates["mu"], res.standard_errors["mu"]) == (pytest.approx(0.2577, abs=1e-4),
                                                                pytest.approx(0.0061, abs=1e-4))
    assert (res.estimates["EA"], res.standard_errors["EA"]) == (pytest.approx(49915, abs=1), pytest.approx(71, abs=1))


def test_recovers_the_preload_too(scene):
    start = scene.with_values({"mu": 0.3, "EA": 4e4, "F_p": 50.0})
    res = identify(start, synthetic(scene, seed=0), fit=("mu", "EA", "F_p"))
    assert res.ok, res.messages
    for k, v in {**TRUE, "F_p": scene.parameters["F_p"]}.items():
        assert abs(res.estimates[k] - v) < 2 * res.standard_errors[k], (k, res.estimates[k], res.standard_errors[k])
        assert res.standard_errors[k] < 0.05 * v, k     # the data determine it (2.6 % for mu, 0.2 % or less else)


@pytest.mark.slow
def test_standard_errors_cover_the_truth_over_seeds(scene):
    # 95 % nominal coverage of +-2 SE; with 10 seeds, fewer than 7 hits has probability < 0.2 %
    start = scene.with_values({"mu": 0.3, "EA": 4e4})
    hits = {k: 0 for k in TRUE}
    for seed in range(10):
        res = identify(start, synthetic(scene, seed=100 + seed))
        for k, v in TRUE.items():
            hits[k] += abs(res.estimates[k] - v) < 2 * res.standard_errors[k]
    assert min(hits.values()) >= 7, hits


def test_flags_mu_when_loads_are_too_small_to_slip(scene):
    # at loads of a thousandth of a newton the slip zones are ~1e-5 of the free span: mu has no influence
    data = synthetic(scene, seed=1, F=np.linspace(0.0, 1e-3, 10), noise=1e-12)
    res = identify(scene, data)
    assert not res.identifiable["mu"] and res.identifiable["EA"]
    assert not res.ok and any("mu" in m for m in res.messages)
    assert res.estimates["EA"] == pytest.approx(TRUE["EA"], abs=min(3 * res.standard_errors["EA"], 1e-3 * TRUE["EA"]))


@pytest.mark.parametrize("loads, words", [
    (np.zeros(5), "0 distinct loads F_T > 0 in 5 rows (0 repeat a load, 5 at F_T = 0"),   # no load applied
    (np.full(6, 40.0), "1 distinct load F_T > 0 in 6 rows (5 repeat a load, 0 at F_T = 0"),   # one row, repeated
    (np.array([0.0, 40.0, 40.0, 0.0]), "1 distinct load F_T > 0 in 4 rows (1 repeat a load, 2 at F_T = 0"),
])
def test_data_without_information_refused(scene, loads, words):
    """A rotation at F_T = 0 is 0 whatever mu and EA, and a repeated row repeats one equation: fewer distinct
    loads > 0 than parameters to fit cannot determine them (the least-squares normal matrix is singular)."""
    data = pd.DataFrame({"F_T [N]": loads, "delta_alpha [rad]": loads * 1e-4})
    with pytest.raises(InputError, match=re.escape(words)):
        identify(scene, data)


def test_csv_with_torque_and_degrees_equals_dataframe(scene, tmp_path):
    df = synthetic(scene, seed=2)
    R = scene.parameters["R"]
    csv = tmp_path / "test.csv"
    pd.DataFrame({"T [N*m]": 2 * R * df["F_T [N]"], "delta_alpha [deg]": np.degrees(df["delta_alpha [rad]"])}
                 ).to_csv(csv, index=False)
    F1, d1 = read_data(df)
    F2, d2 = read_data(csv, R)
    np.testing.assert_allclose(F2, F1, rtol=1e-14)
    np.testing.assert_allclose(d2, d1, rtol=1e-14)


@pytest.mark.parametrize("frame,match", [
    (pd.DataFrame({"F [N]": [1.0, 2.0], "delta_alpha [deg]": [0.1, 0.2]}), "columns"),
    (pd.DataFrame({"F_T [N]": [-1.0, 2.0, 3.0], "delta_alpha [deg]": [0.1, 0.2, 0.3]}), ">= 0"),
    (pd.DataFrame({"F_T [N]": [1.0, 2.0], "delta_alpha [deg]": [0.1, 0.2]}), "cannot determine"),
    (pd.DataFrame({"F_T [kg]": [1.0, 2.0, 3.0], "delta_alpha [deg]": [0.1, 0.2, 0.3]}), "convert"),
])
def test_bad_data_refused(scene, frame, match):
    with pytest.raises(InputError, match=match):
        identify(scene, frame)


def test_cli_identify(scene, tmp_path, capsys):
    csv = tmp_path / "d.csv"
    synthetic(scene, seed=0).to_csv(csv, index=False)
    assert cli(["identify", SCENE, str(csv), "--set", "mu=0.4", "--set", "EA=30kN"]) == 0
    out = capsys.readouterr().out
    assert "mu" in out and "EA" in out and "IPOPT" in out
    assert cli(["identify", SCENE, str(csv), "--fit", "nu"]) == 2
