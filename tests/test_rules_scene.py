"""A scene with ``[rules] set = "..."``: its factors from the rule at the suspended length, each check naming
its rule (run, size text and JSON, report), overrides marked, other machines refused, every mistake at once.

Truths: the cited formula written out here (30 CFR § 57.19021(b): 7.0 − 0.0005 L, L in ft, for L < 4000 ft;
5.0 beyond); the same scene with that factor typed by hand in [parameters] (a second way to the same
design); central differences for the derivatives through the rule.
"""

from __future__ import annotations

import json
import math
import re
from importlib import resources

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main as cli
from ropemodel.errors import InputError
from ropemodel.scene import from_toml

FT = 0.3048


def cfr_friction(L_m: float) -> float:
    """30 CFR § 57.19021(b), typed from W. Va. Code R. § 36-1-35.3.1.b (L in ft); 5.0 at 4000 ft or more."""
    L = L_m / FT
    return 7.0 - 0.0005 * L if L < 4000 else 5.0


def fig9_text(rules: str = "", n_rope: bool = False, extra: str = "") -> str:
    """The built-in sizing scene of the Fig. 9 route, without its n_rope line (unless ``n_rope``), with
    ``rules`` as its [rules] table."""
    text = resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml").read_text()
    if not n_rope:
        text = re.sub(r"(?m)^n_rope = .*$", "", text)
    text = text.replace("[parameters]\n", "[parameters]\n" + extra)
    return text + ("\n[rules]\n" + rules if rules else "")


def scene_of(rules: str = "", **kw):
    return from_toml(fig9_text(rules, **kw), "test scene", emit=False)


US = 'set = "us-30cfr-57"\n'


def test_the_factor_is_the_rule_at_the_route_length():
    s = scene_of(US)
    assert s.parameters["n_rope"] == pytest.approx(cfr_friction(1150.0), rel=1e-12)    # 5.1135
    assert s.origin["n_rope"] == "rules"
    assert s.check_basis("safety_margin_up") == "n_rope: us-30cfr-57 § 57.19021(b) (to verify)"
    assert s.with_values({"L_u": "600 m"}).parameters["n_rope"] == pytest.approx(cfr_friction(600.0), rel=1e-12)
    assert s.with_values({"L_u": "2000 m"}).parameters["n_rope"] == 5.0                # beyond 4000 ft


def test_a_sized_scene_names_each_check_s_rule(tmp_path, capsys):
    path = tmp_path / "us.toml"
    path.write_text(fig9_text(US))
    assert cli(["size", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    factors = out["rules"]["factors"]
    assert out["rules"]["set"] == "us-30cfr-57"
    assert factors["n_rope"]["value"] == pytest.approx(cfr_friction(1150.0), rel=1e-12)
    assert factors["n_rope"]["basis"] == "rule" and factors["n_rope"]["clause"] == "§ 57.19021(b)"
    assert factors["n_rope"]["status"] == "to verify"
    py = factors["n_rope"]["python"]
    assert eval(py, {"__builtins__": {}}, factors["n_rope"]["inputs"]) == pytest.approx(factors["n_rope"]["value"])
    assert factors["n_slip"]["basis"] == factors["F_S_min"]["basis"] == "user-given"
    assert factors["D_ratio_min"]["basis"] == "default"
    named = {c for f in factors.values() for c in f["checks"]}
    assert {m.rsplit("_", 1)[0] if m.endswith(("_up", "_down")) else m for m in out["margins"]} - named == \
        {"stroke_margin"}                # the stroke check has no factor: eq. (23) alone
    assert cli(["size", str(path)]) == 0
    text = capsys.readouterr().out
    for line in text.splitlines():
        if line.startswith(("safety_margin", "slip_margin", "slack_margin", "taut_margin", "drum_margin")):
            assert re.search(r"(us-30cfr-57 § 57\.19021\(b\) \(to verify\)|user-given|default)", line), line


def test_the_rule_set_design_is_the_design_with_the_factor_typed_by_hand():
    from optimisation.design import size

    ruled = size(scene_of(US, extra=""), with_sensitivities=False)
    typed = size(from_toml(fig9_text(extra=f"n_rope = {cfr_friction(1150.0)!r}\n"), emit=False),
                 with_sensitivities=False)
    assert ruled.feasible and typed.feasible
    assert ruled.design == typed.design
    assert ruled.continuous["d"] == pytest.approx(typed.continuous["d"], rel=1e-9)


def test_run_tables_and_json_name_the_rule(capsys, tmp_path):
    path = tmp_path / "us.toml"
    path.write_text(fig9_text(US))
    res = rm.run(rm.load_scene(str(path)))
    frame = res.frames["design checks"]
    safety = frame[frame["check"].str.startswith("rope safety")]
    assert list(safety["rule"]) == ["n_rope: us-30cfr-57 § 57.19021(b) (to verify)"] * 2
    assert set(frame[frame["check"].str.contains("stroke")]["rule"]) == {"-"}
    data = json.loads(res.to_json())
    assert data["rules"]["factors"]["n_rope"]["inputs"] == {"L": 1150.0}
    assert cli(["run", str(path), "--set", "L_u=2000m", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["rules"]["factors"]["n_rope"]["value"] == 5.0


def test_without_a_rule_set_the_factors_are_user_given():
    s = from_toml(fig9_text(n_rope=True), emit=False)
    assert s.rules is None
    assert s.check_basis("safety_margin_down") == "n_rope: user-given (scene file)"
    data = json.loads(rm.run(s).to_json())
    assert data["rules"]["set"] is None
    assert data["rules"]["factors"]["n_rope"] == {"value": 4.5, "basis": "user-given",
                                                  "text": "user-given (scene file)",
                                                  "checks": ["safety_margin", "safety_margin_S"]}


def test_an_override_is_marked_with_its_reason():
    s = scene_of(US + 'n_rope = { value = 6, reason = "the mine\'s own standard" }\n')
    assert s.parameters["n_rope"] == 6.0 and s.origin["n_rope"] == "rules override"
    assert s.check_basis("safety_margin_up") == ("n_rope: override of us-30cfr-57 § 57.19021(b): "
                                                 "the mine's own standard")
    entry = json.loads(rm.run(s).to_json())["rules"]["factors"]["n_rope"]
    assert entry["basis"] == "override" and entry["reason"] == "the mine's own standard"
    assert s.with_values({"L_u": "600 m"}).parameters["n_rope"] == 6.0          # an override does not follow L_u
    by_hand = s.with_values({"n_rope": 7.0}, origin="--set")                     # nor does a value set by hand
    assert by_hand.check_basis("safety_margin_up") == \
        "n_rope: user-given (--set), in place of us-30cfr-57 § 57.19021(b)"
    text = fig9_text(US + 'F_S_min = { value = "8 kN", reason = "the tensioner maker\'s least tension" }\n')
    with pytest.raises(InputError, match="F_S_min is given twice: in \\[parameters\\] and as an override"):
        from_toml(text, emit=False)
    s = from_toml(text.replace('F_S_min = "5 kN"', ""), emit=False)
    assert s.parameters["F_S_min"] == 8000.0 and s.origin["F_S_min"] == "rules override"


def test_a_rule_set_for_another_machine_is_refused():
    with pytest.raises(InputError) as info:
        scene_of('set = "at-bpvs"\ncarried = "persons"\n')
    msg = str(info.value)
    assert "written for drum-hoist, koepe" in msg and "not for this scene's model 'winch'" in msg
    assert "rule sets for winch: " in msg and "us-30cfr-57" in msg


def test_every_mistake_of_rules_at_once():
    bad = ('set = "iso-4308-1"\ngroup = "M9"\nn_rop = 4\nn_slip = 1.3\n'
           'F_S_min = { value = 5000, reason = "x" }\n')
    with pytest.raises(InputError) as info:
        from_toml(fig9_text(bad, extra='G_m = "-5 kN"\n').replace('G_m = "467 kN"\n', ""), emit=False)
    problems = info.value.problems
    text = "\n".join(problems)
    assert "group = 'M9'; valid: 'M1'" in text                          # a choice not in the set
    assert "unknown key 'n_rop'" in text and "did you mean" in text     # a typo, with the nearest name
    assert "n_slip: an override gives its value and its reason" in text
    assert "F_S_min = 5000 has no unit" in text                         # the override's value, as a scene's
    assert any(p.startswith("G_m") for p in problems)                   # and the scene's other mistakes
    assert not any("missing parameter n_rope" in p for p in problems)   # the set gives it, once the group is right
    with pytest.raises(InputError, match="needs group to choose its rule for n_rope"):
        scene_of('set = "iso-4308-1"\n')
    with pytest.raises(InputError, match="unknown rule set 'us-30cfr'.*did you mean"):
        scene_of('set = "us-30cfr"\n')
    with pytest.raises(InputError, match=r"\[rules\] needs set"):
        scene_of('n_rope = { value = 6, reason = "x" }\n')
    with pytest.raises(InputError, match="n_rope is set by rule set 'us-30cfr-57'.*remove it from"):
        from_toml(fig9_text(US, n_rope=True), emit=False)
    with pytest.raises(InputError, match="the override needs a reason"):
        scene_of(US + 'n_rope = { value = 6, reason = " " }\n')
    with pytest.raises(InputError, match=r"n_rope from rule .* out of range|n_rope = 0\.5"):
        scene_of(US + 'n_rope = { value = 0.5, reason = "x" }\n')


def test_a_chosen_mechanism_group_gives_its_factor():
    s = scene_of('set = "iso-4308-1"\ngroup = "M5"\n')
    assert s.parameters["n_rope"] == 4.5
    assert s.check_basis("safety_margin_up") == ("n_rope: iso-4308-1 ISO 4308-1, Zp for running ropes, group M5 "
                                                 "(to verify)")


def test_solve_refuses_to_free_a_length_a_rule_reads(capsys, tmp_path):
    path = tmp_path / "us.toml"
    path.write_text(fig9_text(US))
    assert cli(["solve", str(path), "--given", "safety_margin_up=0", "--find", "L_u"]) == 2
    err = capsys.readouterr().err
    assert "--find L_u: L_u sets n_rope through the scene's rule set" in err and "Traceback" not in err


def test_a_sweep_over_the_route_length_carries_the_rule():
    s = scene_of(US)
    lengths = [600.0, 1150.0, 1300.0, 2000.0]
    df = rm.sweep(s, vary={"L_u": lengths}, outputs=["safety_margin_up", "F_min", "F_C_up"], si=True, progress=False)
    truth = df["F_min [N]"] / (np.array([cfr_friction(L) for L in lengths]) * df["F_C_up [N]"]) - 1
    np.testing.assert_allclose(df["safety_margin_up [-]"], truth, rtol=1e-10)
    arrays = rm.Problem(s).evaluate({"L_u": np.array(lengths)})
    np.testing.assert_allclose(arrays["safety_margin_up"], truth, rtol=1e-10)


def test_elasticity_to_the_length_includes_the_rule():
    s = scene_of(US)
    e = rm.elasticities(s, outputs=["safety_margin_up"], parameters=["L_u", "n_rope"])
    h = 0.5
    up, down = (rm.run(s.with_values({"L_u": 1150.0 + d}))["safety_margin_up"] for d in (h, -h))
    dy_dL = (up - down) / (2 * h)
    assert e.set_index("parameter").loc["L_u", "dy_dp"] == pytest.approx(dy_dL, rel=1e-6)    # measured 3e-8
    n = s.parameters["n_rope"]
    m = rm.run(s)["safety_margin_up"]
    assert e.set_index("parameter").loc["n_rope", "dy_dp"] == pytest.approx(-(m + 1) / n, rel=1e-9)


def test_sizing_sensitivity_to_the_length_includes_the_rule():
    from optimisation.design import size

    s = scene_of(US)
    base = size(s)
    h = 2.0
    up, down = (size(s.with_values({"L_u": 1150.0 + d}), with_sensitivities=False) for d in (h, -h))
    fd = (up.continuous["d"] - down.continuous["d"]) / (2 * h)
    assert base.sensitivities["L_u"]["d"] == pytest.approx(fd, rel=1e-6)    # measured 4e-8 (h = 2 m)
    assert fd != pytest.approx(0.0, abs=1e-9)


def test_a_route_of_segments_takes_the_sum_of_its_lengths():
    text = fig9_text(US).replace('L_u = "1150 m"\n', "").replace('L_ul = "500 m"\n', "")
    text = text.replace('alpha_u = "16 deg"\n', "").replace("[effects]\n", '[effects]\nroute = "segments"\n')
    text += '\n'.join(f'[[route]]\nlength = "{L} m"\ninclination = "{a} deg"\n' for L, a in ((400, 22), (650, 9),
                                                                                            (300, 3)))
    s = from_toml(text, emit=False)
    assert s.parameters["n_rope"] == pytest.approx(cfr_friction(1350.0), rel=1e-12)
    assert s.with_values({"L_2": "1000 m"}).parameters["n_rope"] == pytest.approx(cfr_friction(1700.0), rel=1e-12)
    lengths = json.loads(rm.run(s).to_json())["rules"]["lengths"]["suspended"]
    assert lengths["value"] == 1350.0 and lengths["from"] == ["L_1", "L_2", "L_3"]
    assert lengths["status"] == "engineering judgement"


def test_the_report_names_the_rule_of_each_check(tmp_path):
    from ropemodel.reports import build, load

    path = tmp_path / "us.toml"
    text = fig9_text(US + 'n_slip = { value = 1.3, reason = "wet drum" }\n')
    path.write_text(re.sub(r"(?m)^n_slip = 1.25.*$", "", text))
    html = build(load(str(path))).html
    assert 'id="rules"' in html and "us-30cfr-57" in html and "7.0 − 0.0005·L for L &lt; 4000 ft" in html
    assert "override of rule set us-30cfr-57: wet drum" in html          # the set has no slip rule
    assert "n_rope: us-30cfr-57 § 57.19021(b) (to verify)" in html       # in the checks tables
    assert "engineering judgement" in html and "does not apply here (rope = winding-drum)" in html
    assert math.isfinite(float(re.search(r"1150 m \(([\d.]+) ft\)", html).group(1)))


def test_a_sizing_map_over_the_route_length_carries_the_rule():
    """A sizing sweep (shared active sets, and IPOPT at each point) against a sizing of each length alone."""
    from optimisation.design import size
    from optimisation.sweep import sizing_sweep

    s = scene_of(US)
    lengths = [900.0, 1150.0, 1400.0]
    alone = [size(s.with_values({"L_u": L}), with_sensitivities=False).continuous["d"] * 1e3 for L in lengths]
    for method in ("active-set", "ipopt"):
        df = sizing_sweep(s, {"L_u": lengths}, method=method, progress=False)
        np.testing.assert_allclose(df["d [mm]"], alone, rtol=1e-6)
        np.testing.assert_allclose(df["n_rope [-]"], [cfr_friction(L) for L in lengths], rtol=1e-12)
