"""Design checks (effect checks = "design"): margins against the paper's Fig. 9 and hand calculation."""

import json
import math

import pytest

from ropemodel.cli import main as cli
from ropemodel.effects.winch_checks import margin_names
from ropemodel.problem import run, solve
from ropemodel.scene import from_dict, load

# Krauze et al. (2025) Fig. 9: F_C, F_S and the least stroke dF for both directions [kN, mm]
FIG9 = {"F_C_up": 190.95, "F_C_down": 137.21, "F_S_up": 30.94, "F_S_down": 39.78,
        "dF_up": 1402.94, "dF_down": 1142.57}


def paper_scene(**params):
    base = load()
    values = {**base.parameters, "d": "42 mm", "F_min": "1100 kN", "n_rope": 4.0, "D": "1.4 m",
              "stroke": "1000 mm", **params}
    return from_dict({"scene": {"name": "Fig. 9 + checks"},
                      "effects": {**base.effects, "checks": "design"}, "parameters": values}, bare="si")


def test_paper_rope_stroke_is_403_mm_short():
    """The paper's conclusion: the installed 1000 mm stroke is 403 mm short (1402.94 - 1000)."""
    res = run(paper_scene())
    assert res["stroke_margin_up"] * 1e3 == pytest.approx(1000 - FIG9["dF_up"], abs=0.01)
    assert res["stroke_margin_down"] * 1e3 == pytest.approx(1000 - FIG9["dF_down"], abs=0.01)
    table = res.frames["design checks"]
    row = table[(table["check"].str.contains("stroke")) & (table["direction"] == "up")].iloc[0]
    assert row["pass"] == "NO" and row["margin"] == pytest.approx(-402.94, abs=0.01)
    assert "NO" in res.table()


def test_margins_by_hand_from_the_paper_forces():
    res = run(paper_scene(F_S_min="35 kN"))
    for d in ("up", "down"):
        assert res[f"safety_margin_{d}"] == pytest.approx(1100 / (4 * FIG9[f"F_C_{d}"]) - 1, abs=2e-4)
        assert res[f"slack_margin_{d}"] / 1e3 == pytest.approx(FIG9[f"F_S_{d}"] - 35, abs=0.01)
    assert res["slack_margin_up"] < 0 < res["slack_margin_down"]     # 30.94 kN < 35 kN < 39.78 kN
    assert res["drum_margin"] == pytest.approx(1.4 / (30 * 0.042) - 1, rel=1e-14)
    assert res["drum_margin"] > 0 and run(paper_scene(D="1.2 m"))["drum_margin"] < 0


def test_every_check_in_both_directions():
    names = margin_names(run(paper_scene()).values)
    for base in ("safety_margin", "slack_margin", "stroke_margin"):
        assert f"{base}_up" in names and f"{base}_down" in names
    assert "drum_margin" in names


def test_checks_solve_backwards_largest_load():
    """Acausal: safety_margin_up = 0 gives the largest load; check it forward by eq. (13)."""
    res = solve(paper_scene(), {"safety_margin_up": 0.0}, ["G_m"])
    a = math.radians(16)
    q_l, L = 80.0, 1150.0
    F_C = 0.5 * 20e3 + (res["G_m"] + q_l * L) * math.sin(a) + 0.05 * res["G_m"] * math.cos(a) \
        + 0.05 * q_l * L * math.cos(a)
    assert F_C == pytest.approx(1100e3 / 4, rel=1e-12)


def test_run_json_carries_margins(tmp_path, capsys):
    p = tmp_path / "s.toml"
    p.write_text("""
[effects]
power = "drive"
checks = "design"
[parameters]
L_u = "1150 m"
L_ul = "500 m"
alpha_u = "16 deg"
mu_pm = 0.05
mu_pl = 0.05
G_m = "467 kN"
F_nwl = "20 kN"
v_pj = "2.5 m/s"
eta = 1.0
q_l = "0.08 kN/m"
q_lw = "5.8 mm/kN"
d = "42 mm"
F_min = "1100 kN"
n_rope = 4
D = "1.4 m"
stroke = "1000 mm"
""")
    assert cli(["run", str(p), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["stroke_margin_up"] == pytest.approx(-0.40294, abs=1e-5)


def test_shipped_paper_scene_flags_the_stroke(capsys):
    assert cli(["run", "winch_sizing_paper_rope", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["stroke_margin_up"] * 1e3 == pytest.approx(1000 - FIG9["dF_up"], abs=0.01)
    assert out["F_C_up"] / 1e3 == pytest.approx(FIG9["F_C_up"], abs=0.01)
    # the 6x36-IWRC 1770 rope of 42 mm: F_min = K d^2 R_r (EN 12385-4)
    assert out["safety_margin_up"] == pytest.approx(0.356 * 42**2 * 1770 / 1e3 / (4.5 * FIG9["F_C_up"]) - 1,
                                                    abs=2e-4)
