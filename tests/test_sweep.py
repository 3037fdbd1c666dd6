"""Sweeps: grids and tables of points against closed forms and direct solves; validation; CLI."""


import numpy as np
import pandas as pd
import pytest

import ropemodel as rm
from ropemodel.cli import main as cli
from ropemodel.sweeps import parse_axis


def f_c_up_closed_form(alpha, G_m, s):
    """docs/physics.md §1 (Krauze et al. 2025, eq. 13, upward, case 1), written out by hand in numpy."""
    p = s.parameters
    return (0.5 * p["F_nwl"] + (G_m + p["q_l"] * p["L_u"]) * np.sin(alpha)
            + p["mu_pm"] * G_m * np.cos(alpha) + p["mu_pl"] * p["q_l"] * p["L_u"] * np.cos(alpha))


@pytest.mark.parametrize("backend", ["casadi", "compiled"])
def test_grid_is_the_product_and_matches_closed_form(fig9, backend):
    df = rm.sweep(fig9, vary={"alpha_u": "0deg:40deg:9", "G_m": ["300 kN", "467 kN", 600e3]},
                  outputs=["F_C_up", "dF_up"], backend=backend, chunk_size=5)
    assert list(df.columns) == ["alpha_u [deg]", "G_m [kN]", "F_C_up [kN]", "dF_up [mm]"]
    assert len(df) == 27
    # first axis slowest, like itertools.product
    np.testing.assert_allclose(df["alpha_u [deg]"], np.repeat(np.linspace(0, 40, 9), 3), rtol=1e-15, atol=1e-14)
    assert df["G_m [kN]"].tolist()[:3] == [300.0, 467.0, 600.0]
    alpha = np.radians(df["alpha_u [deg]"].to_numpy())
    expected = f_c_up_closed_form(alpha, df["G_m [kN]"].to_numpy() * 1e3, fig9) / 1e3
    np.testing.assert_allclose(df["F_C_up [kN]"], expected, rtol=1e-13)


def test_spot_check_parquet_against_direct_solves(fig9, tmp_path):
    out = tmp_path / "s.parquet"
    rm.sweep(fig9, vary={"alpha_u": "4deg:44deg:200", "L_u": "500m:2000m:50"}, out=out, chunk_size=3000,
             collect=False)
    df = pd.read_parquet(out)
    assert len(df) == 10000 and not (tmp_path / "s.parquet.parts").exists()
    rng = np.random.default_rng(1)
    for i in rng.choice(len(df), 12, replace=False):
        row = df.iloc[i]
        direct = rm.run(fig9.with_values({"alpha_u": f"{float(row['alpha_u [deg]'])!r} deg",
                                          "L_u": float(row["L_u [m]"])})).to_series()
        for col in df.columns[2:]:
            assert row[col] == pytest.approx(direct[col], rel=1e-12, abs=1e-9), col


def test_chunk_size_and_backend_do_not_change_results(fig9):
    vary = {"alpha_u": np.linspace(-0.3, 0.6, 37), "mu_pm": (0.01, 0.2, 5)}  # slack ropes below ~0.1 rad
    a = rm.sweep(fig9, vary, chunk_size=1000, backend="casadi", errors="mark")
    b = rm.sweep(fig9, vary, chunk_size=7, backend="compiled", threads=2, errors="mark")
    assert 0 < a["solved"].sum() < len(a)
    pd.testing.assert_frame_equal(a, b, check_exact=False, rtol=1e-14, atol=1e-12)


def test_points_table_with_units_and_round_trip(fig9):
    pts = pd.DataFrame({"alpha_u [deg]": [10.0, 16.0, 30.0], "G_m [N]": [300e3, 467e3, 200e3]})
    df = rm.sweep(fig9, pts, outputs=["F_C_up"])
    assert list(df.columns) == ["alpha_u [deg]", "G_m [kN]", "F_C_up [kN]"]
    expected = f_c_up_closed_form(np.radians([10.0, 16.0, 30.0]), np.array([300e3, 467e3, 200e3]), fig9) / 1e3
    np.testing.assert_allclose(df["F_C_up [kN]"], expected, rtol=1e-13)
    again = rm.sweep(fig9, df[["alpha_u [deg]", "G_m [kN]"]], outputs=["F_C_up"])
    pd.testing.assert_frame_equal(df, again, check_exact=True, check_dtype=False)
    with pytest.raises(rm.InputError, match="unit 'kg' is not a unit of N"):
        rm.sweep(fig9, pd.DataFrame({"G_m [kg]": [1.0]}))


def test_si_columns(fig9):
    df = rm.sweep(fig9, vary={"alpha_u": [0.1, 0.2]}, outputs=["F_C_up", "mu_pl1"], si=True)
    assert list(df.columns) == ["alpha_u [rad]", "F_C_up [N]", "mu_pl1 [-]"]
    assert df["alpha_u [rad]"].tolist() == [0.1, 0.2]


def test_csv_and_parquet_hold_the_same_numbers(fig9, tmp_path):
    vary = {"alpha_u": "0deg:30deg:101", "F_nwl": "10kN:50kN:3"}  # slack ropes below ~3 deg
    rm.sweep(fig9, vary, out=tmp_path / "a.csv", collect=False, chunk_size=50, errors="mark")
    rm.sweep(fig9, vary, out=tmp_path / "a.parquet", collect=False, chunk_size=50, errors="mark")
    pd.testing.assert_frame_equal(pd.read_csv(tmp_path / "a.csv"), pd.read_parquet(tmp_path / "a.parquet"),
                                  check_exact=True, check_dtype=False)


def test_inverse_sweep_and_invalid_solutions(fig9):
    strokes = np.array([1.2, 1.4, 1.6])
    df = rm.sweep(fig9, vary={"dF_up": strokes}, given=["dF_up"], find=["G_m"], outputs=["G_m", "F_C_up"], si=True)
    for s, g in zip(strokes, df["G_m [N]"]):
        assert rm.solve(fig9, {"dF_up": s}, ["G_m"])["G_m"] == pytest.approx(g, rel=1e-12)
    # a stroke too short for any load: G_m < 0 is outside its range
    with pytest.raises(rm.SolveError, match=r"point 0 \(dF_up = 0\.1.*G_m found outside"):
        rm.sweep(fig9, vary={"dF_up": [0.1, 1.4]}, given=["dF_up"], find=["G_m"])
    marked = rm.sweep(fig9, vary={"dF_up": [0.1, 1.4]}, given=["dF_up"], find=["G_m"], errors="mark")
    assert marked["solved"].tolist() == [False, True]


@pytest.mark.parametrize("vary, match", [
    ({"alpha_u": "0deg:100deg:11"}, r"alpha_u = 90 deg \(value 9 of its axis\) is outside the valid range"),
    ({"mu_pm": [0.1, -0.2]}, r"mu_pm = -0\.2 .*point|mu_pm = -0\.2"),
    ({"L_ul": "0m:2000m:3"}, r"L_ul = 2000 m is beyond L_u"),
    ({"alpha_u": "0:1"}, r"START:STOP:N"),
    ({"alpha_u": "0deg:1deg:0"}, r"positive whole number"),
    ({"alpha_u": "0 kN:1 kN:3"}, r"alpha_u = '0 kN' has the dimension force, expected angle"),
    ({"alpha_u": "0:1deg:3"}, r'alpha_u = 0 has no unit; write e.g. "0 deg"'),
    ({"G_m": "300,467"}, r'G_m = 300 has no unit; write e.g. "300 kN"'),
    ({"alpah_u": [0.1]}, r"alpah_u"),
    ({"F_C_up": [1.0]}, r"F_C_up"),
])
def test_bad_points_are_refused_before_computing(fig9, vary, match):
    with pytest.raises(rm.InputError, match=match):
        rm.sweep(fig9, vary)


def test_bad_point_in_a_table_is_named(fig9):
    pts = pd.DataFrame({"L_u [m]": [1000.0, 400.0], "L_ul [m]": [500.0, 450.0]})
    with pytest.raises(rm.InputError, match=r"point 1: L_ul = 450 m is beyond L_u = 400 m"):
        rm.sweep(fig9, pts)


def test_parse_axis_units(fig9):
    q = fig9.built.quantities
    np.testing.assert_allclose(parse_axis("alpha_u", "0deg:45deg:4", q["alpha_u"]), np.radians([0, 15, 30, 45]))
    np.testing.assert_allclose(parse_axis("G_m", "300kN,467 kN", q["G_m"]), [300e3, 467e3])
    np.testing.assert_allclose(parse_axis("L_u", (1, 2, 3), q["L_u"]), [1, 1.5, 2])   # numbers: SI (Python API)


def test_cli_sweep_csv(tmp_path, capsys):
    out = tmp_path / "cli.csv"
    code = cli(["sweep", "example", "--vary", "alpha_u=5deg:45deg:4", "--vary", "G_m=300kN,467kN",
                "--outputs", "F_C_up,dF_up", "-o", str(out), "--no-progress"])
    assert code == 0
    df = pd.read_csv(out)
    assert list(df.columns) == ["alpha_u [deg]", "G_m [kN]", "F_C_up [kN]", "dF_up [mm]"]
    api = rm.sweep(rm.load_scene(), {"alpha_u": "5deg:45deg:4", "G_m": "300kN,467kN"}, ["F_C_up", "dF_up"])
    pd.testing.assert_frame_equal(df, api, check_exact=True, check_dtype=False)


def test_cli_sweep_points_file_and_errors(tmp_path, capsys):
    pts = tmp_path / "pts.csv"
    pd.DataFrame({"alpha_u [deg]": [5.0, 16.0], "q_l [kN/m]": [0.08, 0.1]}).to_csv(pts, index=False)
    out = tmp_path / "o.parquet"
    assert cli(["sweep", "example", "--points", str(pts), "--outputs", "F_S_up", "-o", str(out)]) == 0
    df = pd.read_parquet(out)
    expected = rm.run(rm.load_scene().with_values({"alpha_u": "16 deg", "q_l": "0.1 kN/m"}))["F_S_up"] / 1e3
    assert df["F_S_up [kN]"].iloc[1] == pytest.approx(expected, rel=1e-13)
    assert cli(["sweep", "example", "--vary", "alpha_u=0deg:95deg:3", "-o", str(out)]) == 2
    assert "alpha_u = 95 deg" in capsys.readouterr().err
    assert cli(["sweep", "example", "--vary", "alpha_u=0:1:3", "-o", str(tmp_path / "x.xlsx")]) == 2


def _voigt_winch():
    base = rm.load_scene()
    p = dict(base.parameters)
    p.update({"mu_d": 0.25, "alpha_d": "200 deg", "Q": 5e-7, "lambda": 0.05, "D": "3000 mm"})
    return rm.from_dict({"scene": {"model": "winch"}, "effects": {"lining": "voigt", "power": "drive"},
                         "parameters": p}, bare="si")


def test_inverse_sweep_through_newton_catches_non_convergence():
    """Least pretension for no slip on a Voigt-lined drum (a Newton block).  For Q = 2e-6 1/N no
    pretension prevents slip (tests/test_winch_lining.py shows it by bracketing): the sweep
    must refuse that point, not return Newton's last iterate; the other points equal single solves."""
    scene = _voigt_winch()
    qs = [3e-7, 5e-7, 2e-6]
    kwargs = dict(given={"slip_margin_up": 0.0}, find=["F_nwl"], outputs=["F_nwl"], si=True)
    with pytest.raises(rm.SolveError, match=r"point 2 \(Q = 2e-06.*does not reproduce the given slip_margin_up"):
        rm.sweep(scene, {"Q": qs}, **kwargs)
    marked = rm.sweep(scene, {"Q": qs}, errors="mark", **kwargs)
    assert marked["solved"].tolist() == [True, True, False]
    for q, f in zip(qs[:2], marked["F_nwl [N]"][:2]):
        direct = rm.solve(scene.with_values({"Q": q}), {"slip_margin_up": 0.0}, ["F_nwl"])["F_nwl"]
        assert f == pytest.approx(direct, rel=1e-9)


@pytest.mark.parametrize("scene", ["fig9", "voigt"])
def test_evaluate_columns_equals_problem_evaluate(fig9, scene):
    """The chunked engine offered as the body of Problem.evaluate gives Problem.evaluate's numbers."""
    from ropemodel.core.evaluate import evaluate_columns

    s = fig9 if scene == "fig9" else _voigt_winch()
    problem = rm.Problem(s)
    alpha = np.linspace(0.05, 0.5, 301)
    ref = problem.evaluate({"alpha_u": alpha})
    x = problem.inputs()
    got = evaluate_columns(problem.function, {"alpha_u": alpha}, {k: v for k, v in x.items() if k != "alpha_u"},
                           threads=2, chunk=64)
    assert set(got) == set(ref)
    for k in ref:
        np.testing.assert_allclose(got[k], ref[k], rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_cli_sweep_summary(tmp_path, capsys, suffix):
    import json

    out = tmp_path / f"o{suffix}"
    assert cli(["sweep", "example", "--vary", "alpha_u=1deg:9deg:9", "--vary", "mu_pm=0.01,0.02",
                "--outputs", "F_C_up", "-o", str(out), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["rows"] == 18 and info["columns"] == ["alpha_u [deg]", "mu_pm [-]", "F_C_up [kN]"]


@pytest.mark.parametrize("backend", ["casadi", "compiled"])
def test_constants_are_not_cached_with_the_compiled_function(fig9, backend):
    """Two sweeps of one Function with different constant inputs (one evaluator shared by both)."""
    alpha = np.radians([5.0, 20.0])
    for G_m in (300e3, 600e3):
        df = rm.sweep(fig9.with_values({"G_m": G_m}), {"alpha_u": alpha}, ["F_C_up"], si=True, backend=backend)
        np.testing.assert_allclose(df["F_C_up [N]"], f_c_up_closed_form(alpha, G_m, fig9), rtol=1e-13)
        out = rm.Problem(fig9).evaluate({"alpha_u": alpha, "G_m": G_m})
        np.testing.assert_allclose(out["F_C_up"], f_c_up_closed_form(alpha, G_m, fig9), rtol=1e-13)


def test_a_slack_rope_is_no_result(fig9):
    """Horizontal route (closed form, docs/physics.md §1): F_C_down = F_nwl/2 − μ_pm G_m − μ_pl q_l L_u and
    F_S_up = F_nwl/2 − μ_pl q_l L_u.  Where one is <= 0 that rope would have to push: the point has no
    result (NaN, solved False, the reason named), never a negative force."""
    p = fig9.parameters
    f_nwl = np.linspace(0.0, 120e3, 25)
    c_down = 0.5 * f_nwl - p["mu_pm"] * p["G_m"] - p["mu_pl"] * p["q_l"] * p["L_u"]
    s_up = 0.5 * f_nwl - p["mu_pl"] * p["q_l"] * p["L_u"]
    df = rm.sweep(fig9.with_values({"alpha_u": 0.0}), {"F_nwl": f_nwl}, ["F_C_down", "F_S_up"], si=True,
                  errors="mark")
    taut = (c_down > 0) & (s_up > 0)
    assert 0 < taut.sum() < len(f_nwl)
    assert df["solved"].tolist() == taut.tolist()
    np.testing.assert_allclose(df["F_C_down [N]"][taut], c_down[taut], rtol=1e-13)
    assert df["F_C_down [N]"][~taut].isna().all() and df["F_S_up [N]"][~taut].isna().all()
    assert set(df["invalid"][~taut]) <= {
        "outside the model: F_S_up <= 0: the unwinding rope is slack (upward travel)",
        "outside the model: F_C_down <= 0: the winding rope is slack (downward travel)"}
    assert df["invalid"][taut].isna().all()
    with pytest.raises(rm.SolveError, match=r"point 0 \(F_nwl = 0, SI\): outside the model: F_S_up <= 0"):
        rm.sweep(fig9.with_values({"alpha_u": 0.0}), {"F_nwl": f_nwl}, ["F_C_down", "F_S_up"])
    # hauling up only: the slack rope of lowering does not spoil F_C_up (the winding rope pulls up)
    up = rm.sweep(fig9.with_values({"alpha_u": 0.0}), {"F_nwl": f_nwl[s_up > 0]}, ["F_C_up"], errors="mark")
    assert up["solved"].all()


def test_a_sweeps_own_marked_output_is_a_points_file(fig9, tmp_path):
    from ropemodel.sweeps import read_points

    out = tmp_path / "marked.csv"
    first = rm.sweep(fig9, {"alpha_u": "0 deg:8 deg:5"}, ["F_C_down"], errors="mark", out=out)
    p, alpha = fig9.parameters, np.radians(np.linspace(0, 8, 5))
    c_down = (0.5 * p["F_nwl"] + (p["G_m"] + p["q_l"] * p["L_u"]) * np.sin(alpha)   # eq. (13), lowering
              - (p["mu_pm"] * p["G_m"] + p["mu_pl"] * p["q_l"] * p["L_u"]) * np.cos(alpha))
    assert first["solved"].tolist() == (c_down > 0).tolist() and 0 < (c_down > 0).sum() < 5
    again = rm.sweep(fig9, points=read_points(out), outputs=["F_C_down"], errors="mark")
    pd.testing.assert_frame_equal(first, again)
