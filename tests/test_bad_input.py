"""Bad input gets a clear error naming the parameter, never a wrong number; the CLI exits 2."""

import math
import subprocess
import sys

import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.scene import SceneWarning

BASE = {
    "L_u": "1150 m", "L_ul": "500 m", "alpha_u": "16 deg", "mu_pm": 0.05, "mu_pl": 0.05,
    "G_m": "467 kN", "F_nwl": "20 kN", "q_l": "0.08 kN/m", "q_lw": "5.8 mm/kN",
}


def scene(**changes):
    p = {**BASE, **changes}
    return rm.from_dict({"scene": {"name": "t"}, "parameters": {k: v for k, v in p.items() if v is not None}})


@pytest.mark.parametrize("changes, pattern", [
    ({"alpa_u": "16 deg"}, r"unknown parameter 'alpa_u'.*did you mean 'alpha_u'"),
    ({"G_m": None}, r"missing parameter G_m .*e\.g\. G_m = \"\d+ kN\""),
    ({"alpha_u": "16 kN"}, r"alpha_u = '16 kN' has the dimension force, expected angle \(a value in deg\)"),
    ({"L_u": "3 s"}, r"L_u = '3 s' has the dimension time, expected length"),
    ({"G_m": float("nan")}, r"G_m: value must be finite"),
    ({"G_m": math.inf}, r"G_m: value must be finite"),
    ({"G_m": "inf kN"}, r"G_m: value must be finite"),
    ({"G_m": 10 ** 400}, r"G_m: 1000.*\.\.\. is too large to be a number"),
    ({"L_u": "-5 m"}, r"L_u = -5 m is outside the valid range \[0.001, 100000\] m"),
    ({"L_u": "0 m"}, r"L_u = 0 m is outside the valid range"),
    ({"L_ul": "-1 m"}, r"L_ul = -1 m is outside"),
    ({"L_ul": "1200 m"}, r"L_ul = 1200 m is beyond L_u = 1150 m"),
    ({"alpha_u": "90 deg"}, r"alpha_u = 90 deg is outside the valid range \(-90, 90\) deg"),
    ({"alpha_u": "-95 deg"}, r"alpha_u = -95 deg is outside"),
    ({"q_lw": "0 mm/kN"}, r"q_lw = 0 mm/kN is outside the valid range"),
    ({"q_lw": "-5.8 mm/kN"}, r"q_lw = -5.8 mm/kN is outside"),
    ({"mu_pm": "abc"}, r"mu_pm = 'abc' is not a number \(e\.g\. \"0\.5\"\)"),
    ({"G_m": True}, r"G_m = True: expected a number or a value with a unit"),
    ({"G_m": [1, 2]}, r"G_m = \[1, 2\]: expected a number or a value with a unit"),
    ({"G_m": 300}, r'G_m = 300 has no unit; write e\.g\. "300 kN"'),
    ({"G_m": "300"}, r'G_m = 300 has no unit; write e\.g\. "300 kN"'),
    ({"alpha_u": 16}, r'alpha_u = 16 has no unit; write e\.g\. "16 deg"'),
    ({"mu_pl1": 0.04},
     r"mu_pl1 = 0.04 disagrees with the value this scene computes, 0.05 .*choose resistance = 'case2'"),
    ({"F_C_up": "100 kN"}, r"F_C_up = 100 kN disagrees with the value this scene computes, 190.949 kN"),
    ({"lining": "rigid"}, r"lining is an effect of model 'winch': move it to \[effects\]"),
    ({"segments": 8}, r"segments is a numerics option of model 'winch': move it to \[numerics\]"),
])
def test_scene_errors(changes, pattern):
    with pytest.raises(rm.InputError, match=pattern):
        scene(**changes)


def test_known_but_unused_is_a_warning_and_a_check_that_agrees_is_accepted():
    """v_pj without the power effect is named with the variant that uses it; mu_pl1 = mu_pl (case 1) passes."""
    with pytest.warns(SceneWarning, match=r"v_pj is not used: it belongs to power = 'drive' or lining = 'voigt'"):
        sc = scene(v_pj="2.5 m/s", mu_pl1=0.05, mu_pl2="0.050")
    assert sc.unused == {"v_pj": "power = 'drive' or lining = 'voigt'"} and set(sc.checks) == {"mu_pl1", "mu_pl2"}


def test_every_mistake_is_named_at_once():
    with pytest.raises(rm.InputError) as err:
        scene(G_m=300, alpa_u="16 deg", L_u="3 s", q_lw="-1 mm/kN", lining="rigid", mu_pl1=0.04)
    assert len(err.value.problems) == 6, err.value.problems
    assert str(err.value).startswith("6 problems")
@pytest.mark.parametrize("data, pattern", [
    ({"effects": {"elongaton": "none"}}, r"unknown effect 'elongaton'.*did you mean 'elongation'"),
    ({"effects": {"elongation": "off"}},
     r"elongation = 'off' is not a variant; valid variants: asbuilt, asbuilt_stress, krauze2025, none"),
    ({"scene": {"model": "winhc"}}, r"unknown model 'winhc'.*did you mean 'winch'"),
    ({"paramaters": {}}, r"unknown table \[paramaters\].*did you mean 'parameters'"),
    ({"scene": {"nmae": "x"}}, r"unknown key 'nmae' in \[scene\].*did you mean 'name'"),
    ({"numerics": {"rtol": 1e-6}}, r"unknown numerics option 'rtol' for model 'winch'"),
])
def test_structure_errors(data, pattern):
    with pytest.raises(rm.InputError, match=pattern):
        rm.from_dict({"parameters": BASE, **data})


def test_invalid_toml():
    with pytest.raises(rm.InputError, match="invalid TOML"):
        rm.from_toml("[scene\nname = 1")


def test_missing_file(tmp_path):
    with pytest.raises(rm.InputError, match="scene file not found"):
        rm.load_scene(tmp_path / "nope.toml")


@pytest.mark.parametrize("argv, pattern", [
    (["run", "--set", "alpha_u=16kN"], "alpha_u"),
    (["run", "--set", "alpa_u=3"], "did you mean 'alpha_u'"),
    (["run", "--set", "L_ul=2000m"], "L_ul"),
    (["run", "--set", "G_m"], "expected NAME=VALUE"),
    (["run", "missing.toml"], "scene file not found"),
    (["solve", "example", "--given", "F_C_up=200kN", "--find", "nope"], "unknown unknown to find 'nope'"),
    (["solve", "example", "--given", "F_C_up=200", "--find", "G_m"], 'F_C_up = 200 has no unit; write e.g. "200 kN"'),
    (["solve", "example"], "solve needs --given"),
    (["frobnicate"], "invalid choice"),
    ([], "no command given"),
])
def test_cli_exit_2_one_line(capsys, argv, pattern):
    assert main(argv) == 2
    cap = capsys.readouterr()
    assert cap.out == ""
    assert cap.err.count("\n") == 1 and cap.err.startswith("error: ") and pattern in cap.err


def test_cli_bad_toml_file(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text("[parameters\n")
    assert main(["run", str(f)]) == 2
    assert "invalid TOML" in capsys.readouterr().err


def test_console_script_no_traceback(tmp_path):
    p = subprocess.run([sys.executable, "-m", "ropemodel", "run", "--set", "alpha_u=95deg"],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr and "alpha_u = 95 deg" in p.stderr


def test_cli_warning_is_one_line(capsys):
    assert main(["run", "--set", "alpha_u=50deg", "--json"]) == 0
    err = capsys.readouterr().err
    assert err.startswith("warning: alpha_u = 50 deg") and err.count("\n") == 1


def test_missing_optional_package_names_the_extra(monkeypatch):
    import sys

    from ropemodel.errors import require

    for name in [m for m in sys.modules if m.split(".")[0] == "SALib"] + ["SALib"]:
        monkeypatch.setitem(sys.modules, name, None)  # as if SALib were not installed (nor imported before)
    with pytest.raises(rm.InputError, match=r'pip install "ropemodel\[sobol\]"'):
        require("SALib.analyze.sobol", "sobol")
