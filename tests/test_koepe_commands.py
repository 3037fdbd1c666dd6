"""Every command that takes a scene, on the Koepe hoist: run, solve, sweep, sensitivity, report; exit codes.

Truths: the closed forms of tests/_koepe_truth.py (the inverse solve by brentq on them, the elasticity by a
central difference of them), and, for bad input, the list of mistakes typed into the scene.
"""

from __future__ import annotations

import html
import json
import math
import subprocess
import sys

import pytest
from scipy.optimize import brentq

import ropemodel as rm
from ropemodel.cli import main
from _koepe_truth import ISSUE, coasting, rel, slips, statics

NO_TAIL_DEEP = '''[scene]
name = "deep, no tail ropes"
model = "koepe"
[effects]
tail_ropes = "none"
[parameters]
H = "1000 m"
H_head = "50 m"
m_conveyance = "20 t"
m_payload = "15 t"
n_head = 4
q_head = "8.6 kg/m"
mu = 0.25
alpha = "180 deg"
D = "4 m"
v_max = "10 m/s"
'''


def test_a_hoist_that_slips_at_rest_exits_1(tmp_path):
    f = tmp_path / "deep.toml"
    f.write_text(NO_TAIL_DEEP, encoding="utf-8")
    p = subprocess.run([sys.executable, "-m", "ropemodel", "run", str(f)], capture_output=True, text=True)
    assert p.returncode == 1 and p.stdout == ""
    assert p.stderr.count("\n") == 1 and "Traceback" not in p.stderr
    assert "the ropes slip on the wheel at rest (loaded at the bottom): T_1/T_2 = 3.274 exceeds the traction " \
           "limit 2.193" in p.stderr


def test_bad_input_names_every_problem(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text(NO_TAIL_DEEP.replace('H = "1000 m"', 'H = "-1000 m"').replace('"20 t"', "20")
                 .replace("n_head = 4", "n_head = 4.5").replace('v_max = "10 m/s"\n', "")
                 .replace('tail_ropes = "none"', 'tail_ropes = "nonne"\nlining = "voigt"'), encoding="utf-8")
    assert main(["run", str(f)]) == 2
    err = capsys.readouterr().err
    for problem in ("H = -1000 m is outside the valid range (0, 40000] m", 'm_conveyance = 20 has no unit; write e.g. '
                    '"20 t"', "n_head = 4.5 is not a whole number of ropes", "missing parameter v_max",
                    "tail_ropes = 'nonne' is not a variant; valid variants: none, round (did you mean 'none'?)",
                    "missing parameter Q_R", "missing parameter lambda_R"):
        assert problem in err, problem
    assert "Traceback" not in err


def test_run_prints_display_units_and_json_si(capsys):
    assert main(["run", "koepe_example"]) == 0
    table = capsys.readouterr().out
    for line in ("T_1                       830.451  kN", "sigma_static              2.83631  -",
                 "a_slip_lower_decel        2.07375  m/s^2", "m_payload                      22  t"):
        assert line in table, line
    assert "where each worst case is" in table and "static states at the wheel" in table
    assert main(["run", "koepe_example", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    s = statics(ISSUE)
    assert rel(out["T_1"], s["worst"]["T_1"]) < 1e-12 and rel(out["T_max"], s["T_max"]) < 1e-12
    assert out["where"]["T_1"] == "loaded at the bottom, the loaded side high"
    assert out["where"]["a_slip_hoist_decel"] == "hoisting, slowing down: empty, conveyance L at the top"
    assert out["rules"]["set"] == "us-30cfr-57"
    # the example's window, against the closed forms (ISSUE with the example's brake data)
    h = dict(ISSUE, a_brake_min=1.5)
    assert rel(out["a_brake_low_hoist"], coasting(h, +1)) < 1e-12
    assert rel(out["a_brake_high_lower"], slips(h)["lower_decel"][0]) < 1e-12
    # the numbers the README quotes, to its digits
    quoted = {"T_1": (830.451, 1e-3), "ratio_static": (1.4207, 1), "traction_limit": (2.1933, 1),
              "sigma_static": (2.836, 1), "a_slip_hoist_accel": (2.074, 1), "a_slip_lower_decel": (2.074, 1),
              "a_slip_hoist_decel": (3.423, 1), "a_brake_low_hoist": (1.702, 1), "a_brake_high_hoist": (3.423, 1),
              "a_brake_low_lower": (1.5, 1), "a_brake_high_lower": (2.074, 1)}
    for key, (value, scale) in quoted.items():
        digits = len(str(value).split(".")[1])
        assert round(out[key] * scale, digits) == value, key
    assert out["where"]["a_brake_low_hoist"] == "the deceleration without brake (loaded at the bottom)"


def test_the_readmes_voigt_numbers():
    import tomllib
    from importlib import resources

    data = tomllib.loads(resources.files("ropemodel.data").joinpath("koepe_example.toml").read_text())
    data["effects"]["lining"] = "voigt"
    data["parameters"].update(Q_R="2e-7 1/N", lambda_R="0.5 s")
    r = rm.run(rm.from_dict(data, emit=False))
    assert (round(r["traction_limit"], 4), round(r["traction_limit_run"], 4)) == (2.0648, 2.094)
    assert round(r["a_slip_lower_decel"], 3) == 1.864


def test_solve_the_largest_payload_for_an_anti_slip_factor(capsys):
    assert main(["solve", "koepe_example", "--given", "sigma_static=1.75", "--find", "m_payload", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    truth = brentq(lambda m: statics(dict(ISSUE, m_payload=m))["worst"]["sigma"] - 1.75, 1e3, 1e5, xtol=1e-9)
    assert out["m_payload"] == pytest.approx(truth, rel=1e-9)          # 37.566 t
    assert round(out["m_payload"] / 1e3, 3) == 37.566


def test_sweep_over_the_payload(tmp_path):
    out = tmp_path / "k.csv"
    assert main(["sweep", "koepe_example", "--vary", "m_payload=10t:40t:4", "--outputs",
                 "sigma_static,a_slip_lower_decel", "-o", str(out), "--no-progress"]) == 0
    import pandas as pd

    frame = pd.read_csv(out)
    for _, row in frame.iterrows():
        h = dict(ISSUE, m_payload=row["m_payload [t]"] * 1e3)
        assert rel(row["sigma_static [-]"], statics(h)["worst"]["sigma"]) < 1e-12
        assert rel(row["a_slip_lower_decel [m/s^2]"], slips(h)["lower_decel"][0]) < 1e-12


def test_sensitivity_is_the_derivative_of_the_closed_form(capsys):
    assert main(["sensitivity", "koepe_example", "--outputs", "sigma_static", "--parameters", "m_payload",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (row,) = out
    e = row["elasticity"]
    m, dm = ISSUE["m_payload"], 1.0
    sigma = [statics(dict(ISSUE, m_payload=x))["worst"]["sigma"] for x in (m - dm, m, m + dm)]
    assert e == pytest.approx((sigma[2] - sigma[0]) / (2 * dm) * m / sigma[1], rel=1e-7)


def test_the_report_carries_the_koepes_checks():
    r = rm.report("koepe_example")
    assert r.incomplete == []
    from ropemodel.reports.registry import sections

    assert {"scene", "inputs", "rules", "equations", "results", "checks", "sensitivity"} <= set(r.shown)
    not_here = {"dynamic_sizing", "trip", "transient"}       # no manoeuvres, no trips, no transient in this scene
    assert not_here <= {s.name for s in sections()} and not not_here & set(r.shown)
    assert "sizing" in r.shown and "sizing: design n_head = 2, d_head = 58 mm" in " ".join(r.verdicts)
    for name in ("head_safety_margin", "tail_safety_margin", "wheel_margin", "brake_margin_hoist", "pull_margin"):
        assert name in r.html
    assert "us-30cfr-57 § 57.19021(b)" in r.html and "loaded at the bottom, the loaded side high" in r.html
    assert "checks at the scene's values: all 9 pass" in r.verdicts


@pytest.mark.slow
def test_the_report_shows_a_braking_through_the_machines_transient_section():
    """The one transient section shows the Koepe's braking as the Koepe declares it: its words, its summary (the
    simulation's own report) and the history's columns it names, drawn in two panels (N, m/s)."""
    from ropemodel.dynamics import simulate

    r = rm.report("koepe_braking")
    assert "transient" in r.shown and "trip" not in r.shown and r.incomplete == []
    assert "the head ropes elastic, slip judged at every instant" in r.html
    first = simulate(rm.load_scene("koepe_braking")).report().splitlines()[0]
    assert html.escape(first, quote=False) in r.html
    assert 'alt="histories of the transient"' in r.html and "the margin against slip (kN)" in r.html


def test_the_tonne_is_a_unit():
    assert rm.load_scene("koepe_example").parameters["m_conveyance"] == 29.6e3
    assert math.isclose(rm.run(rm.load_scene("koepe_example"), {"m_payload": "0.5 t"})["T_1"],
                        statics(dict(ISSUE, m_payload=500.0))["worst"]["T_1"], rel_tol=1e-12)


def test_the_result_shows_itself():
    """Jupyter's table carries where each worst case is; the picture's ratio at the bottom of the wind is the
    loaded hoist's worst static ratio (the closed form), and its dashed line the traction limit."""
    import matplotlib

    matplotlib.use("Agg")
    r = rm.run(rm.load_scene("koepe_example"))
    assert "worst case: loaded at the bottom, the loaded side high" in r._repr_html_()
    assert r.to_frame().loc["T_1", "source"].endswith("worst case: loaded at the bottom, the loaded side high")
    ax = r.plot()
    y, ratio = ax.lines[0].get_data()
    w = statics(ISSUE)["worst"]
    assert y[-1] == ISSUE["H"] and rel(ratio[-1], w["T_1"] / w["T_2"]) < 1e-12
    assert ax.lines[2].get_data()[1][0] == pytest.approx(math.exp(0.25 * math.pi), rel=1e-14)
