"""Sizing sweeps: each point equals a single sizing; warm starts change cost, never the answer."""

from importlib import resources

import numpy as np
import pandas as pd
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


def _grid_indices(func, ranges, fixed, m):
    """First-order and total Sobol indices of a function of two inputs by brute force: the output on an
    m x m midpoint grid of the uniform ranges, its variance split by the law of total variance
    (S1_a = Var(E[y|a]) / Var y, ST_a = E[Var(y|b)] / Var y); a second method, independent of SALib's
    sampling and estimators."""
    (a, (a_lo, a_hi)), (b, (b_lo, b_hi)) = ranges.items()
    mid = (np.arange(m) + 0.5) / m
    A, B = np.meshgrid(a_lo + (a_hi - a_lo) * mid, b_lo + (b_hi - b_lo) * mid, indexing="ij")
    y = func({a: A.ravel(), b: B.ravel(), **{k: np.full(A.size, v) for k, v in fixed.items()}})
    out = {}
    for name, values in y.items():
        Y = values.reshape(m, m)
        V = Y.var()
        out[name] = {a: (Y.mean(axis=1).var() / V, Y.var(axis=0).mean() / V),
                     b: (Y.mean(axis=0).var() / V, Y.var(axis=1).mean() / V)}
    return out


def test_sobol_of_the_sizing_optimum(sizing_scene):
    """Sobol indices of the optimum (d, F_nwl, stroke) over the inclination and the load against the same
    indices by brute force on a grid; an input that does not enter (v_pj sets only the drive power) has
    exactly zero.  The grid's own error is below 1e-3 (64 against 32 points a side); the estimator's is within
    twice its 95 % bootstrap half-width, which the sample makes small (< 0.05).  The truth is not trivial
    (d: 0.45 alpha_u, 0.55 G_m; F_nwl: 0.035 and 0.965; the stroke: alpha_u alone), so swapped, dropped or
    mis-scaled inputs fail."""
    from ropemodel.sensitivities import sobol_indices
    from optimisation.sweep import sizing_function

    func = sizing_function(sizing_scene)
    ranges = {"alpha_u": (0.2, 0.3), "G_m": (350e3, 500e3)}
    truth = _grid_indices(func, ranges, {"v_pj": 2.5}, 64)
    coarse = _grid_indices(func, ranges, {"v_pj": 2.5}, 32)
    res = sobol_indices(func, {**ranges, "v_pj": (2.0, 3.0)}, n=2 ** 12, seed=2)
    r = res.set_index(["output", "parameter"])
    for out in ("d", "F_nwl", "stroke"):
        assert r.loc[(out, "v_pj"), "ST"] == pytest.approx(0.0, abs=1e-9)
        for par in ranges:
            row = r.loc[(out, par)]
            for i, index in enumerate(("S1", "ST")):
                exact = truth[out][par][i]
                assert exact == pytest.approx(coarse[out][par][i], abs=1e-3), (out, par, index)
                conf = row[f"{index}_conf"]
                # 1e-12: rounding, where an input does not enter (the stroke does not depend on G_m)
                assert conf < 0.05 and abs(row[index] - exact) <= 2 * conf + 1e-12, (out, par, index, row[index],
                                                                                      exact)
    # the inputs' shares differ by far more than the tolerance: a swap of the inputs would fail
    assert abs(truth["F_nwl"]["alpha_u"][0] - truth["F_nwl"]["G_m"][0]) > 0.5


def _scaled_diff(a, b, problem):
    """|a - b| per design column, relative to max(|b|, the variable's scale in the NLP)."""
    scale = {"d [mm]": problem.x_scale[0] * 1e3, "F_nwl [kN]": problem.x_scale[1] / 1e3,
             "stroke [mm]": problem.x_scale[2] * 1e3}
    return {c: np.abs(a[c] - b[c]) / np.maximum(np.abs(b[c]), s) for c, s in scale.items()}


def test_active_set_map_equals_cold_ipopt_across_active_set_changes(sizing_scene):
    """The fast path (neighbours' active sets, batched Newton, accepted by multipliers) against IPOPT from the
    scene's design at every point: the same feasibility, the same optima.  The grid crosses three active sets
    (slip, slack of the winding rope, pretension at its bound) and the edge of the feasible region."""
    from optimisation.design import solve_best
    from optimisation.problem import SizingProblem
    from optimisation.sweep import sizing_sweep

    vary = {"G_m": ["200 kN", "800 kN"], "alpha_u": "2deg:30deg:5", "L_u": "600m:3000m:5"}
    fast = sizing_sweep(sizing_scene, vary, progress=False)
    cold = sizing_sweep(sizing_scene, vary, warm=False, progress=False)
    problem = SizingProblem(sizing_scene)
    polished, active = [], set()
    for _, row in cold.iterrows():
        p = problem.p_of({"G_m": row["G_m [kN]"] * 1e3, "alpha_u": np.radians(row["alpha_u [deg]"]),
                          "L_u": row["L_u [m]"]})
        sol = solve_best(problem, p)      # cold IPOPT, active set identified and polished by Newton
        polished.append([v * f for v, f in zip(problem.to_si(sol.xs).values(), (1e3, 1e-3, 1e3))] if sol.feasible
                        else [np.nan] * 3)
        if sol.feasible:
            active.add((tuple(sol.active), tuple(sol.active_bounds)))
    assert len(active) >= 3 and 0 < (~cold["feasible"]).sum() < len(cold)
    assert (fast["feasible"] == cold["feasible"]).all()
    ok = cold["feasible"].to_numpy()
    ref = pd.DataFrame(polished, columns=["d [mm]", "F_nwl [kN]", "stroke [mm]"])
    for col, diff in _scaled_diff(fast[ok], ref[ok], problem).items():
        assert diff.max() <= 1e-12, col          # the same vertex, to rounding
    for col, diff in _scaled_diff(fast[ok], cold[ok], problem).items():
        assert diff.max() <= 1e-7, col           # IPOPT's raw answer, to its tolerance (bounds relaxed by 1e-8)
    assert fast.loc[~ok, ["d [mm]", "F_nwl [kN]", "stroke [mm]"]].isna().all().all()
    assert (fast["iterations"] == 0).mean() >= 0.8    # most points solved on a neighbour's active set


def test_active_set_map_on_random_points_and_the_voigt_lining():
    """Points in random order (no neighbour is near) and a lining whose traction is implicit (a rootfinder
    in the NLP): still IPOPT's answers."""
    from optimisation.sweep import sizing_sweep

    scene = rm.load_scene(str(resources.files("ropemodel.data").joinpath("winch_sizing_voigt.toml")))
    rng = np.random.default_rng(3)
    pts = pd.DataFrame({"alpha_u": np.radians(rng.uniform(2, 30, 12)), "L_u": rng.uniform(600, 3000, 12)})
    fast = sizing_sweep(scene, pts, progress=False)
    cold = sizing_sweep(scene, pts, warm=False, progress=False)
    assert (fast["feasible"] == cold["feasible"]).all() and fast["feasible"].any()
    ok = cold["feasible"].to_numpy()
    from optimisation.problem import SizingProblem

    for col, diff in _scaled_diff(fast[ok], cold[ok], SizingProblem(scene)).items():
        assert diff.max() <= 1e-7, col


def test_unknown_method_is_refused(sizing_scene):
    from optimisation.sweep import sizing_sweep

    with pytest.raises(rm.InputError, match="valid methods"):
        sizing_sweep(sizing_scene, {"alpha_u": ["16 deg"]}, method="newton")
