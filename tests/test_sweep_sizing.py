"""Sizing sweeps: each point equals a single sizing; warm starts change cost, never the answer."""

from importlib import resources

import numpy as np
import pytest

import ropemodel as rm

optimisation = pytest.importorskip("optimisation")


@pytest.fixture(scope="module")
def sizing_scene():
    return rm.load_scene(str(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml")))


def test_points_equal_single_sizings_and_warm_equals_cold(sizing_scene):
    from optimisation.sweep import sizing_sweep

    vary = {"alpha_u": "10deg:20deg:3", "G_m": ["400 kN", "467 kN"]}
    warm = sizing_sweep(sizing_scene, vary, warm=True, progress=False)
    cold = sizing_sweep(sizing_scene, vary, warm=False, progress=False)
    assert warm["feasible"].all() and cold["feasible"].all()
    for col in ("d [mm]", "F_nwl [kN]", "stroke [mm]"):
        np.testing.assert_allclose(warm[col], cold[col], rtol=1e-7)
    # the Fig. 9 point itself: the package's own size() (continuous optimum)
    row = warm[np.isclose(warm["alpha_u [deg]"], 15.0) & np.isclose(warm["G_m [kN]"], 467.0)].iloc[0]
    ref = optimisation.size(sizing_scene.with_values({"alpha_u": "15 deg"}), with_sensitivities=False).continuous
    assert row["d [mm]"] == pytest.approx(ref["d"] * 1e3, rel=1e-7)
    assert row["F_nwl [kN]"] == pytest.approx(ref["F_nwl"] / 1e3, rel=1e-6)


def test_infeasible_points_are_kept_and_marked(sizing_scene):
    from optimisation.sweep import sizing_sweep

    frame = sizing_sweep(sizing_scene, {"alpha_u": ["16 deg", "40 deg"]}, progress=False)
    assert frame["feasible"].tolist() == [True, False]
    assert np.isnan(frame["d [mm]"].iloc[1])
    assert not optimisation.size(sizing_scene.with_values({"alpha_u": "40 deg"}), with_sensitivities=False).feasible


def test_design_variables_cannot_be_swept(sizing_scene):
    from optimisation.sweep import sizing_sweep

    with pytest.raises(rm.InputError, match="design variable"):
        sizing_sweep(sizing_scene, {"d": [0.03]})


def test_cli_sizing_sweep(sizing_scene, tmp_path):
    import pandas as pd

    from ropemodel.cli import main as cli
    from optimisation.sweep import sizing_sweep

    path = str(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml"))
    out = tmp_path / "s.csv"
    assert cli(["sweep", path, "--sizing", "--vary", "L_u=800m:1600m:3", "-o", str(out), "--no-progress"]) == 0
    frame = pd.read_csv(out)
    api = sizing_sweep(sizing_scene, {"L_u": "800m:1600m:3"}, progress=False)
    np.testing.assert_allclose(frame["d [mm]"], api["d [mm]"], rtol=1e-12)
    assert cli(["sweep", path, "--sizing", "--vary", "L_u=800m:1600m:3", "--outputs", "F_C_up", "-o", str(out)]) == 2


def test_sobol_of_the_sizing_optimum(sizing_scene):
    """One varied input explains all the variance of the optimum: S1 = ST = 1 for d and F_nwl
    (exactly, up to the estimator's error); an input that does not enter leaves ST = 0."""
    from ropemodel.sensitivity import sobol_indices
    from optimisation.sweep import sizing_function

    res = sobol_indices(sizing_function(sizing_scene), {"alpha_u": (0.2, 0.3), "v_pj": (2.0, 3.0)}, n=16, seed=2)
    r = res.set_index(["output", "parameter"])
    # v_pj sets only the drive power, not d or F_nwl
    for out in ("d", "F_nwl"):
        assert r.loc[(out, "v_pj"), "ST"] == pytest.approx(0.0, abs=1e-9)
        assert r.loc[(out, "alpha_u"), "ST"] == pytest.approx(1.0, abs=max(2 * r.loc[(out, "alpha_u"), "ST_conf"], 0.05))
