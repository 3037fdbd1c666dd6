"""Winch drum traction (effect ``lining``): no-slip check and least pretension.

Truth: hand calculations. With F_S = c_S F_nwl + a and F_C = c_C F_nwl + b
(eq. (12)-(13) written out below: c_S = c_C = 1/2), the rigid no-slip limit
(c_S F_nwl + a)·e^{μα} = n·(c_C F_nwl + b) gives
F_nwl = (n b − a e^{μα}) / (c_S e^{μα} − n c_C).
"""

import json
import math
import subprocess
import sys

import pytest

import ropemodel as rm
from _toml import parameters_toml
from ropemodel.errors import InputError


def winch(lining="rigid", **params):
    base = rm.load_scene()
    p = dict(base.parameters)
    p.update({"mu_d": 0.2, "alpha_d": "200 deg"})
    p.update(params)
    return rm.from_dict({"scene": {"model": "winch"}, "effects": {"lining": lining, "power": "drive"},
                         "parameters": p}, bare="si")


def affine_parts(scene, d):
    """(c_S, a, c_C, b) with F_S = c_S F_nwl + a, F_C = c_C F_nwl + b: Krauze et al. (2025) eq. (12)-(13),
    case 1 (one μ_pl), written out.  Upward (s = +1): F_S = F_nwl/2 + q_l L_u sin α − μ_pl q_l L_u cos α,
    F_C = F_nwl/2 + (G_m + q_l L_u) sin α + μ_pm G_m cos α + μ_pl q_l L_u cos α; downward: s = −1."""
    p = scene.parameters
    s = 1.0 if d == "up" else -1.0
    sin, cos = math.sin(p["alpha_u"]), math.cos(p["alpha_u"])
    rope = p["q_l"] * p["L_u"]
    a = rope * sin - s * p["mu_pl"] * rope * cos
    b = (p["G_m"] + rope) * sin + s * (p["mu_pm"] * p["G_m"] + p["mu_pl"] * rope) * cos
    return 0.5, a, 0.5, b


def least_pretension(c_S, a, c_C, b, t, n):
    """Hand calculation of the no-slip limit for traction t, safety n."""
    return (n * b - a * t) / (c_S * t - n * c_C)


@pytest.mark.parametrize("n_slip", [1.0, 1.5])
def test_rigid_margin_by_hand(n_slip):
    scene = winch(n_slip=n_slip)
    r = rm.run(scene)
    t = math.exp(0.2 * math.radians(200))
    for d in ("up", "down"):
        assert r[f"traction_{d}"] == pytest.approx(t, rel=1e-14)
        hand = r[f"F_S_{d}"] * t / (n_slip * r[f"F_C_{d}"]) - 1
        assert r[f"slip_margin_{d}"] == pytest.approx(hand, rel=1e-13)


@pytest.mark.parametrize("d", ["up", "down"])
@pytest.mark.parametrize("n_slip", [1.0, 1.3])
def test_rigid_least_pretension_by_hand(d, n_slip):
    scene = winch(n_slip=n_slip)
    t = math.exp(0.2 * math.radians(200))
    hand = least_pretension(*affine_parts(scene, d), t, n_slip)
    r = rm.solve(scene, {f"slip_margin_{d}": 0.0}, ["F_nwl"])
    assert r["F_nwl"] == pytest.approx(hand, rel=1e-10)
    # and the forward check at that pretension is exactly at the onset of slip
    assert rm.run(scene.with_values({"F_nwl": r["F_nwl"]}))[f"slip_margin_{d}"] == pytest.approx(0.0, abs=1e-10)


def test_rigid_cli_solve(tmp_path):
    scene = winch()
    t = math.exp(0.2 * math.radians(200))
    hand = least_pretension(*affine_parts(scene, "up"), t, 1.0)
    toml = tmp_path / "w.toml"
    params = parameters_toml(scene)
    toml.write_text(f'[scene]\nmodel = "winch"\n[effects]\nlining = "rigid"\npower = "drive"\n'
                    f"[parameters]\n{params}\n")
    out = subprocess.run([sys.executable, "-m", "ropemodel", "solve", str(toml), "--given", "slip_margin_up=0",
                          "--find", "F_nwl", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["F_nwl"] == pytest.approx(hand, rel=1e-10)


@pytest.mark.parametrize("bad", [{"mu_d": 0.0}, {"mu_d": -0.1}, {"alpha_d": 0.0}, {"n_slip": 0.9}])
def test_rigid_bad_input(bad):
    with pytest.raises(InputError):
        winch(**bad)


def test_none_is_default_and_builds_nothing():
    r = rm.run(rm.load_scene())
    assert "slip_margin_up" not in r.values


# --- Voigt drum lining: truth from scipy's Lambert W and a bracketing root finder ---

from scipy.optimize import brentq, minimize_scalar  # noqa: E402
from scipy.special import lambertw  # noqa: E402

VOIGT = {"mu_d": 0.25, "alpha_d": "200 deg", "Q": 5e-7, "lambda": 0.05, "D": "3000 mm"}


def voigt_ratio(F_S, mu=0.25, alpha=math.radians(200), Q=5e-7, lam=0.05, v=2.5, D=3.0):
    """s = W(c e^{μα})/c, c = Q F_S (1 − e^{−α/k}), k = λ·2v/D (Hajduk eq. (19), independent solve)."""
    c = Q * F_S * -math.expm1(-alpha / (lam * 2 * v / D))
    return lambertw(c * math.exp(mu * alpha)).real / c


def test_voigt_traction_and_margin_against_lambert_w():
    r = rm.run(winch("voigt", **VOIGT))
    for d in ("up", "down"):
        s = voigt_ratio(r[f"F_S_{d}"])
        assert r[f"traction_{d}"] == pytest.approx(s, rel=1e-12)
        assert r[f"slip_margin_{d}"] == pytest.approx(r[f"F_S_{d}"] * s / r[f"F_C_{d}"] - 1, rel=1e-12)
        # the compliant lining transmits less than a rigid one
        assert r[f"traction_{d}"] < math.exp(0.25 * math.radians(200))


def voigt_margin(scene, d, n_slip, Q=5e-7):
    """slip margin as a function of F_nwl, from the affine forces and the Lambert-W ratio."""
    c_S, a, c_C, b = affine_parts(scene, d)

    def margin(F):
        F_S = c_S * F + a
        return F_S * voigt_ratio(F_S, Q=Q) / (n_slip * (c_C * F + b)) - 1

    return margin


@pytest.mark.parametrize("d", ["up", "down"])
@pytest.mark.parametrize("n_slip", [1.0, 1.2])
def test_voigt_least_pretension_against_bracketing_solve(d, n_slip):
    scene = winch("voigt", n_slip=n_slip, **VOIGT)
    margin = voigt_margin(scene, d, n_slip)

    # with a compliant lining F_S·s(F_S) grows only like ln F_S: the margin rises, peaks and
    # falls again with F_nwl; the least pretension is the root below the peak
    peak = minimize_scalar(lambda F: -margin(F), bounds=(0.0, 1e8), method="bounded").x
    assert margin(peak) > 0 > margin(0.0)
    truth = brentq(margin, 0.0, peak, xtol=1e-9, rtol=1e-14)
    r = rm.solve(scene, {f"slip_margin_{d}": 0.0}, ["F_nwl"])
    assert r["F_nwl"] == pytest.approx(truth, rel=1e-9)


def test_voigt_uses_the_haulage_speed_of_the_drive():
    """ω = 2 v_pj/D: the same v_pj quantity as the drive power (one definition, one value)."""
    from ropemodel.effects.winch import DrivePower
    from ropemodel.effects.winch_lining import V_PJ, VoigtDrumLining

    assert V_PJ is next(q for q in DrivePower.quantities if q.name == "v_pj")
    assert V_PJ in VoigtDrumLining.quantities
    slow = rm.run(winch("voigt", **VOIGT).with_values({"v_pj": 0.5}))["traction_up"]
    fast = rm.run(winch("voigt", **VOIGT).with_values({"v_pj": 10.0}))["traction_up"]
    assert slow < fast < math.exp(0.25 * math.radians(200))


@pytest.mark.parametrize("bad", [{"Q": -1e-7}, {"lambda": -0.01}, {"D": 0.0}])
def test_voigt_bad_input(bad):
    with pytest.raises(InputError):
        winch("voigt", **{**VOIGT, **bad})


def test_voigt_no_pretension_prevents_slip_is_a_solve_error():
    """With a very compliant lining F_S·s(F_S) grows only like ln F_S: for Q = 2e-6 1/N no
    pretension stops the rope slipping upward (the margin's maximum over F_nwl is < 0);
    the inverse solve must say so, not return a number."""
    scene = winch("voigt", **{**VOIGT, "Q": 2e-6})
    margin = voigt_margin(scene, "up", 1.0, Q=2e-6)
    peak = minimize_scalar(lambda F: -margin(F), bounds=(0.0, 1e8), method="bounded").x
    assert margin(peak) < 0
    with pytest.raises(rm.SolveError, match="slip_margin_up"):
        rm.solve(scene, {"slip_margin_up": 0.0}, ["F_nwl"])


def test_voigt_cli_solve(tmp_path, capsys):
    from ropemodel.cli import main as cli_main

    scene = winch("voigt", **VOIGT)
    margin = voigt_margin(scene, "up", 1.0)
    peak = minimize_scalar(lambda F: -margin(F), bounds=(0.0, 1e8), method="bounded").x
    truth = brentq(margin, 0.0, peak, xtol=1e-9, rtol=1e-14)
    params = parameters_toml(scene)
    toml = tmp_path / "w.toml"
    toml.write_text(f'[scene]\nmodel = "winch"\n[effects]\nlining = "voigt"\npower = "drive"\n[parameters]\n{params}\n')
    assert cli_main(["solve", str(toml), "--given", "slip_margin_up=0", "--find", "F_nwl", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["F_nwl"] == pytest.approx(truth, rel=1e-9)
