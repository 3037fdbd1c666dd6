"""Winch drum traction (effect ``lining``): no-slip check and least pretension.

Truth: hand calculations. With F_S = c_S F_nwl + a and F_C = c_C F_nwl + b
(eq. (12)-(13) are affine in F_nwl; the coefficients are read from two forward
runs), the rigid no-slip limit (c_S F_nwl + a)·e^{μα} = n·(c_C F_nwl + b) gives
F_nwl = (n b − a e^{μα}) / (c_S e^{μα} − n c_C).
"""

import json
import math
import subprocess
import sys

import pytest

import ropemodel as rm
from ropemodel.errors import InputError


def winch(lining="rigid", **params):
    base = rm.load_scene()
    p = dict(base.parameters)
    p.update({"mu_d": 0.2, "alpha_d": "200 deg"})
    p.update(params)
    return rm.from_dict({"scene": {"model": "winch"}, "effects": {"lining": lining, "power": "drive"},
                         "parameters": p})


def affine_parts(scene, d):
    """(c_S, a, c_C, b) with F_S = c_S F_nwl + a, F_C = c_C F_nwl + b, from two forward runs."""
    r0 = rm.run(scene.with_values({"F_nwl": 0.0}))
    r1 = rm.run(scene.with_values({"F_nwl": 1000.0}))
    c_S = (r1[f"F_S_{d}"] - r0[f"F_S_{d}"]) / 1000.0
    c_C = (r1[f"F_C_{d}"] - r0[f"F_C_{d}"]) / 1000.0
    return c_S, r0[f"F_S_{d}"], c_C, r0[f"F_C_{d}"]


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
    params = "\n".join(f"{k} = {v!r}" for k, v in scene.parameters.items())
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
