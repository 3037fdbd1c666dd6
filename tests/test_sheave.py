"""Sheave scenes (model = "sheave"): outputs, distribution, methods, limits, inverse questions, bad input."""

import json
import math
import subprocess
import sys
from importlib import resources

import numpy as np
import pytest
from scipy.special import lambertw

import ropemodel as rm
from ropemodel.cli import main as cli_main
from ropemodel.errors import InputError
from ropemodel.sheave import distribution

FIG5 = str(resources.files("ropemodel.data").joinpath("sheave_hajduk_fig5.toml"))
THIRION = str(resources.files("ropemodel.data").joinpath("sheave_thirion.toml"))


def sheave(lining="voigt", friction="constant", numerics=None, **params):
    p = {"S_0": "10 kN", "mu": 0.2, "alpha": "360 deg", "omega": math.pi}
    if lining == "voigt":
        p.update({"Q": 1e-5, "lambda": 0.01})
    elif lining == "voigt_anisotropic":
        p.update({"Q_R": 2e-6, "Q_T": 8e-6, "lambda_R": 0.001, "lambda_T": 0.3})
    elif lining == "rigid":
        del p["omega"]
    p.update(params)
    return rm.from_dict({"scene": {"model": "sheave"}, "effects": {"lining": lining, "friction": friction},
                         "parameters": p, "numerics": numerics or {}}, bare="si")


def test_example_scene_reproduces_the_table():
    r = rm.run(rm.load_scene(FIG5))
    assert round(r["S_ratio"], 6) == 2.685966
    assert r["S"] == pytest.approx(10e3 * r["S_ratio"], rel=1e-15)


def test_cli_json_reports_S_and_ratio(capsys):
    assert cli_main(["run", FIG5, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert round(d["S_ratio"], 6) == 2.685966 and d["S"] == pytest.approx(26859.66, rel=1e-6)


def test_table_shows_the_distribution(capsys):
    assert cli_main(["run", FIG5]) == 0
    out = capsys.readouterr().out
    assert "tension along the arc" in out and "S/S_0 [-]" in out


@pytest.mark.parametrize("method", ["closed", "ode"])
def test_distribution_frame_matches_table(method):
    scene = sheave(numerics={"method": method, "points": 9})
    frames = rm.run(scene).frames
    df = frames["tension along the arc"]
    assert list(df.columns) == ["alpha [deg]", "S [kN]", "S/S_0 [-]", "e^(mu alpha) [-]"]
    by_angle = dict(zip(df["alpha [deg]"].round(6), df["S/S_0 [-]"]))
    for deg, ref in ((90.0, 1.212743), (180.0, 1.597677), (360.0, 2.685966)):
        assert by_angle[deg] == pytest.approx(ref, abs=5e-7)
    api = distribution(scene, points=9)
    np.testing.assert_allclose(api["S/S_0 [-]"], df["S/S_0 [-]"], rtol=1e-12)


@pytest.mark.parametrize("integrator", ["rk4", "cvodes"])
def test_ode_method_agrees_with_closed(integrator):
    closed = rm.run(sheave(Q=1e-1, **{"lambda": 1e-5}))["S_ratio"]
    ode = rm.run(sheave(Q=1e-1, **{"lambda": 1e-5}, numerics={"method": "ode", "integrator": integrator}))
    assert ode["S_ratio"] == pytest.approx(closed, rel=1e-6)


def test_anisotropic_scene_against_lambert_w():
    r = rm.run(sheave("voigt_anisotropic"))
    a, w = 2 * math.pi, math.pi
    c = 1e4 * (2e-6 * -math.expm1(-a / (0.001 * w)) + 8e-6 * -math.expm1(-a / (0.3 * w)))
    assert r["S_ratio"] == pytest.approx(lambertw(c * math.exp(0.2 * a)).real / c, rel=1e-12)


def test_physical_lining_data_by_hand():
    """Hajduk eq. (6) and (1) by hand at R = 1.5 m (R² and R differ there), then eq. (19) by Lambert W:
    ln s + q s (1 − e^{−α/k}) = μα gives s = W(c e^{μα})/c with c = q (1 − e^{−α/k})."""
    p = {"R": "1.5 m", "a": "30 mm", "h": "20 mm", "E": "50 MPa", "G": "17 MPa", "eta_R": "0.5 MPa*s",
         "eta_T": "0.17 MPa*s"}
    r = rm.run(sheave("voigt_physical", **p))
    Q_R, Q_T = 0.02 / (5e7 * 1.5**2 * 0.03), 0.2 / (1.7e7 * 1.5 * 0.03)
    assert r["Q_R"] == pytest.approx(Q_R, rel=1e-14)
    assert r["Q_T"] == pytest.approx(Q_T, rel=1e-14)
    assert r["lambda_R"] == pytest.approx(0.01, rel=1e-14) and r["lambda_T"] == pytest.approx(0.01, rel=1e-14)
    a, k = 2 * math.pi, 0.01 * math.pi
    c = (Q_R + Q_T) * 1e4 * -math.expm1(-a / k)
    assert r["S_ratio"] == pytest.approx(lambertw(c * math.exp(0.2 * a)).real / c, rel=1e-13)


def test_rigid_scene_is_euler_eytelwein():
    for method in ("closed", "ode"):
        r = rm.run(sheave("rigid", numerics={"method": method}))
        assert r["S_ratio"] == pytest.approx(math.exp(0.2 * 2 * math.pi), rel=1e-12 if method == "closed" else 1e-6)


@pytest.mark.parametrize("method", ["closed", "ode"])
@pytest.mark.parametrize("zero", ["omega", "lambda"])
def test_zero_lambda_omega_is_a_limit_not_an_error(method, zero):
    r = rm.run(sheave(numerics={"method": method}, **{zero: 0.0}))
    q, mu_a = 0.1, 0.2 * 2 * math.pi
    assert r["S_ratio"] == pytest.approx(lambertw(q * math.exp(mu_a)).real / q, rel=1e-6)


@pytest.mark.parametrize("method", ["closed", "ode"])
def test_inverse_friction_from_ratio(method):
    """Given S/S_0, find mu: round trip through the acausal core (Newton through the integrator for ode)."""
    scene = sheave(numerics={"method": method})
    r = rm.solve(scene, {"S_ratio": 2.0}, ["mu"])
    assert rm.run(scene.with_values({"mu": r["mu"]}))["S_ratio"] == pytest.approx(2.0, rel=1e-6)
    # independent: ln 2 + q·2·(1 − e^{−α/k}) = μα
    c = 0.1 * -math.expm1(-2 * math.pi / (0.01 * math.pi))
    assert r["mu"] == pytest.approx((math.log(2.0) + 2.0 * c) / (2 * math.pi), rel=1e-6)


def test_thirion_scene_runs_and_needs_ode(tmp_path):
    r = rm.run(rm.load_scene(THIRION))
    assert r["c_mu"] == pytest.approx(1 / (3e6 * 1.0 * 0.03))
    text = open(THIRION).read().replace('method = "ode"', 'method = "closed"')
    bad = tmp_path / "t.toml"
    bad.write_text(text)
    with pytest.raises(InputError, match="no closed form"):
        rm.load_scene(bad)


@pytest.mark.parametrize("name,value", [("mu", 0.0), ("mu", -0.2), ("Q", -1e-6), ("lambda", -0.1),
                                        ("S_0", 0.0), ("S_0", -5.0), ("alpha", 0.0), ("alpha", -1.0),
                                        ("omega", -1.0)])
def test_bad_input_refused(name, value, capsys):
    with pytest.raises(InputError, match=name):
        sheave(**{name: value})
    assert cli_main(["run", FIG5, "--set", f"{name}={value}"]) == 2
    assert name in capsys.readouterr().err


def test_bad_input_cli_exit_2_subprocess():
    out = subprocess.run([sys.executable, "-m", "ropemodel", "run", FIG5, "--set", "mu=0"],
                         capture_output=True, text=True)
    assert out.returncode == 2 and "mu" in out.stderr and "Traceback" not in out.stderr


def test_bad_numerics_refused():
    for numerics in ({"method": "euler"}, {"integrator": "rk45"}, {"rtol": 0.5}):
        with pytest.raises(InputError):
            sheave(numerics=numerics)


def test_distribution_api_uses_derived_data():
    """Thirion friction (c_mu) and physical lining data (Q_R, ...) are outputs: the API solves first.
    Truth: the chained-segment distribution ends at the scene's own S (one integration over the arc)."""
    scene = rm.load_scene(THIRION)
    df = distribution(scene, points=7)
    r = rm.run(scene)
    assert df["S/S_0 [-]"].iloc[-1] == pytest.approx(r["S_ratio"], rel=1e-6)
    assert df["S [kN]"].iloc[0] == pytest.approx(20.0)


def test_thirion_inverse_pressure_by_hand():
    """Rigid lining with Thirion friction: ds/dα = μ s/(1 + β s), β = S_0/(p_c R a), separates to
    ln s + β (s − 1) = μα, so the p_c giving a ratio s is S_0 (s − 1)/((μα − ln s) R a)."""
    scene = rm.from_dict({"scene": {"model": "sheave"}, "effects": {"lining": "rigid", "friction": "thirion"},
                          "parameters": {"S_0": "20 kN", "mu": 0.3, "alpha": "180 deg", "R": "1 m", "a": "30 mm",
                                         "p_c": "2 MPa"},
                          "numerics": {"method": "ode"}}, bare="si")
    s = 2.2
    hand = 2e4 * (s - 1) / ((0.3 * math.pi - math.log(s)) * 1.0 * 0.03)
    r = rm.solve(scene, {"S_ratio": s}, ["p_c"])
    assert r["p_c"] == pytest.approx(hand, rel=1e-6)
    # and forward at the scene's p_c against the same separable solution (Lambert W)
    beta = 2e4 / (2e6 * 0.03)
    truth = lambertw(beta * math.exp(beta + 0.3 * math.pi)).real / beta
    assert rm.run(scene)["S_ratio"] == pytest.approx(truth, rel=1e-6)
