"""A transient scene holds only what the physics needs: no lining, no stroke, no load position.

Truths: Newton's law for an inextensible rope (the rope fixed to the drum never slips, whatever the
forces), the continuum integral of the rope's elongation at rest (the take-up with the load at either
end of the route, where a span has zero length), and the static model of Krauze et al. (2025) that a
start-up from either end settles on.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.dynamics import simulate

G_N = 9.80665            # standard gravity [m/s²]

#: the Fig. 9 haulage with a start-up, nothing else: no lining, no stroke, no x_m
MINIMAL = {
    "scene": {"name": "minimal start-up"},
    "effects": {"dynamics": "start"},
    "parameters": {"L_u": "1150 m", "L_ul": "500 m", "alpha_u": "16 deg", "mu_pm": 0.05, "mu_pl": 0.05,
                   "G_m": "467 kN", "F_nwl": "20 kN", "v_pj": "2.5 m/s", "q_l": "0.08 kN/m", "q_lw": "5.8 mm/kN",
                   "t_ramp": "5 s", "t_end": "20 s"},
}


def minimal(effects=None, params=None, numerics=None):
    d = {k: dict(v) for k, v in MINIMAL.items()}
    d["effects"].update(effects or {})
    d["parameters"].update(params or {})
    d["numerics"] = dict(numerics or {})
    return rm.from_dict(d, bare="si")


def test_minimal_scene_needs_no_lining_stroke_or_position(tmp_path, capsys):
    path = tmp_path / "minimal.toml"
    lines = ["[scene]", 'name = "minimal"', "[effects]", 'dynamics = "start"', "[parameters]"]
    lines += [f"{k} = {json.dumps(v)}" for k, v in MINIMAL["parameters"].items()]
    path.write_text("\n".join(lines) + "\n")
    assert main(["simulate", str(path), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["x_m"] == 1150.0 and s["x_m_source"].startswith("default: the start of an upward trip")
    assert s["stroke"] is None and s["stroke_unlimited"] is True and s["stroke_used"] > 0
    assert s["stroke_events"] == [] and s["stroke_exhausted"] is False
    assert s["slip"] is False and s["traction_ratio"] is None and s["slip_events"] == []
    assert main(["simulate", str(path)]) == 0
    out = capsys.readouterr().out
    assert "stroke unlimited" in out and "rope fixed to the drum" in out and "default: the start" in out


def test_lining_is_asked_only_when_chosen():
    sc = minimal()
    assert "mu_d" not in sc.parameters and "alpha_d" not in sc.parameters
    with pytest.warns(rm.scene.SceneWarning, match="mu_d is not used"):
        minimal(params={"mu_d": 0.25})


def test_rope_fixed_to_the_drum_never_slips_and_is_newtons_law():
    """Forces a friction drum could not hold (the slip scene's traction: the rope slips there): without a
    lining the rope is fixed to the drum, F_C = F_C,static + (G_m + q_l L_u)/g · a through the ramp."""
    sc = minimal(effects={"rope_elasticity": "rigid"}, params={"t_end": "8 s"})
    v, st = sc.parameters, rm.run(sc)
    sim = simulate(sc)
    assert not sim.summary["slip"] and set(sim.history["drum"]) == {"stick"}
    assert math.exp(0.2 * 3 * math.pi) < sim.summary["F_C_max"] / sim.summary["F_S_min"]   # winch_start_slip's drum
    h = sim.history
    ramp = h[(h["t [s]"] > 0.5) & (h["t [s]"] < v["t_ramp"] - 1e-9)]
    a = v["v_pj"] / v["t_ramp"]
    np.testing.assert_allclose(ramp["F_C [N]"], st["F_C_up"] + (v["G_m"] + v["q_l"] * v["L_u"]) / G_N * a,
                               rtol=1e-9)


def test_unlimited_stroke_has_no_stroke_event():
    """No stroke given: the take-up goes where it must (here beyond the paper's installed 1000 mm, which a
    1000 mm stroke cannot hold: winch_start_stroke runs out)."""
    s = simulate(minimal(params={"x_m": "1100 m"})).summary
    assert s["stroke_unlimited"] and not s["stroke_exhausted"] and s["stroke_used"] > 1.0
    limited = simulate(minimal(params={"x_m": "1100 m", "stroke": "1000 mm"})).summary
    assert limited["stroke_exhausted"] and limited["stroke"] == 1.0


def _rest_take_up(v, x):
    """Take-up at rest = loop elongation = ∫T ds/EA of the continuum (no resistance at rest), the load at x."""
    s, L, h = math.sin(v["alpha_u"]), v["L_u"], v["F_nwl"] / 2
    w, C2 = v["q_l"] * s, L - x
    return (h * L + w * L ** 2 / 2                                  # unwinding rope
            + h * C2 + w * C2 ** 2 / 2                              # sheave → load
            + (h + w * C2 + v["G_m"] * s) * x + w * x ** 2 / 2) / (L / v["q_lw"])   # load → drum


@pytest.mark.parametrize("travel,x_m", [("up", 1150.0), ("down", 0.0)])
def test_default_position_is_the_start_of_a_trip(travel, x_m):
    """The load at either end of the route (a span of zero length): the take-up at rest converges to the
    continuum integral at second order in the element length, as with the load inside the route (measured
    errors at 4, 8, 16 segments: 4.6e-3, 1.1e-3, 2.8e-4 up; 3.5e-2, 8.7e-3, 2.2e-3 down)."""
    errs = []
    for n in (4, 8, 16):
        sc = minimal(effects={"travel": travel}, params={"t_end": "1 s", "t_ramp": "1 s"}, numerics={"segments": n})
        sim = simulate(sc)
        assert sim.summary["x_m"] == x_m and sim.summary["x_m_source"].startswith("default")
        exact = _rest_take_up(sc.parameters, x_m)
        errs.append(abs(sim.history["take_up [m]"].iloc[0] - exact) / exact)
    assert errs[-1] < 3e-3
    assert errs[2] < 0.3 * errs[1] < 0.09 * errs[0]


@pytest.mark.parametrize("travel", ["up", "down"])
def test_start_from_either_end_settles_on_the_static_forces(travel):
    """A start-up from the default position settles on Krauze eq. (12)-(13) of its direction to 1e-9."""
    sc = minimal(effects={"travel": travel}, params={"t_end": "200 s"})
    s = simulate(sc).summary
    st = rm.run(sc)
    assert not s["slack"]
    assert s["F_C_end"] == pytest.approx(st[f"F_C_{travel}"], rel=1e-9)
    assert s["F_S_end"] == pytest.approx(st[f"F_S_{travel}"], rel=1e-9)


def test_given_position_is_reported_as_given():
    s = simulate(minimal(params={"x_m": "700 m", "t_end": "5 s"})).summary
    assert s["x_m"] == 700.0 and s["x_m_source"] == "given"
