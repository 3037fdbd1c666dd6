"""The worst case by default, on the three-segment route of issue 21 (600 m at 12°, 700 m at 20°, 500 m at 6° from
the drive; 300 kN; 3 m/s; 4 s ramps; a 6x36-IWRC rope): every number against docs/physics.md §4 written out in
numpy (tests/_route_truth.py), the worst taken there by brute force over the load's places and the manoeuvres.

Before: without x_m the load sat at the start of an upward trip (the gentle 6° end), so `solve --given
safety_margin_up=0 --find G_m` answered 2.5x the load the 20° segment allows, `size` took the drive power from
segment 1 and checked starts only at the route's ends, and its text output crashed.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from _route3 import SCENE as ROUTE3
from _route_truth import C, Route, places, rope

import ropemodel as rm
from ropemodel.cli import main

LENGTHS, DEGREES = (600.0, 700.0, 500.0), (12.0, 20.0, 6.0)
V, ETA, A = 3.0, 0.85, 3.0 / 4.0          # v_pj [m/s], eta, the linear ramp's v_pj/t_ramp [m/s^2]
MU_D, ALPHA_D, N_SLIP, N_ROPE = 0.2, math.radians(540.0), 1.25, 5.0
#: a fixed design for run / solve / sensitivity / sweep (the sizing's d and F_nwl before this change)
DESIGN = {"d": "36 mm", "F_nwl": "24.7 kN", "D": "1.08 m"}


def route(d: float, F_nwl: float, G_m: float = 300e3, degrees=DEGREES) -> Route:
    return Route(LENGTHS, degrees, (0.05, 0.05, 0.05), G_m=G_m, q_l=rope(d)["q_l"], F_nwl=F_nwl)


def power_up(r: Route, x_m: float, a: float) -> float:
    """The drive's power hauling up [W]: (F_C − F_S) v_pj / η (motoring)."""
    F_C, F_S = r.drum(x_m, a, 1.0)
    return (F_C - F_S) * V / ETA


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("route3")
    sized = d / "route3.toml"
    sized.write_text(ROUTE3, encoding="utf-8")
    fixed = d / "route3_design.toml"
    fixed.write_text(ROUTE3 + "".join(f'{k} = "{v}"\n' for k, v in DESIGN.items()), encoding="utf-8")
    return sized, fixed


@pytest.fixture(scope="module")
def sized(files):
    from optimisation.design import size

    return size(str(files[0]), with_sensitivities=False)


def test_size_text_and_json_succeed_and_the_power_is_the_routes_largest(files, sized, capsys):
    """size (text and JSON) on the route: the drive power is the largest hauling up over every place and
    manoeuvre, computed by hand at the recommended design: a start with the load on the 20° segment (of the
    steady powers too, the 20° segment's is the largest); the old output's, segment 1 in steady motion, is
    more than 20 % short of it."""
    assert main(["size", str(files[0])]) == 0
    text = capsys.readouterr().out
    assert "design found" in text and "drive motoring" in text and "segment 2, x_m = 1300 m, start" in text
    assert main(["size", str(files[0]), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    d, F_nwl = out["d"], out["F_nwl"]
    r = route(d, F_nwl)
    steady = [power_up(r, float(x), 0.0) for x in r.ends]
    assert np.argmax(steady) == 1                          # the 20° segment
    truth, x, a = max((power_up(r, float(x), a), float(x), a) for a in (0.0, A, -A) for x in places(r))
    assert out["N_p_up"] == pytest.approx(truth, rel=1e-12)
    assert out["drive_power"]["motoring"]["value"] == pytest.approx(truth, rel=1e-12)
    assert out["drive_power"]["motoring"]["where"] == {"segment": 2, "x_m": 1300.0, "direction": "up",
                                                       "manoeuvre": "start"}
    assert r.segment(x) == 1 and a == A
    assert truth > 1.2 * steady[0]          # what the old output reported (segment 1, steady) was far too small
    assert set(out["margins"]) == set(out["governing"]) and min(out["margins"].values()) >= 0.0


def test_the_restart_on_the_steepest_segment_is_inside_the_design(sized):
    """A start (and a stop) with the load anywhere on the 20° segment, both directions: the rope's safety
    F_min/F_C >= n_rope and no slip F_S e^(mu_d alpha_d) >= n_slip F_C, with the ramp's rigid-body inertia, by
    hand at the recommended design.  The old sizing's design (36 mm, 24.7 kN) fails the upward restart."""
    def ok(d, F_nwl):
        r, F_min = route(d, F_nwl), rope(d)["F_min"]
        worst_safety = worst_slip = math.inf
        for x_m in (600.0 + 1e-6, 950.0, 1300.0):
            for a in (A, -A):
                for s in (1.0, -1.0):
                    F_C, F_S = r.drum(x_m, a, s)
                    worst_safety = min(worst_safety, F_min / (N_ROPE * F_C) - 1)
                    worst_slip = min(worst_slip, F_S * math.exp(MU_D * ALPHA_D) / (N_SLIP * F_C) - 1)
        return worst_safety, worst_slip

    safety, slip = ok(sized.design["d"], sized.design["F_nwl"])
    assert safety >= -1e-12 and slip >= -1e-12
    safety, slip = ok(0.036, 24.7e3)
    assert safety < -0.1 and slip < -0.3       # safety factor 4.4, slip margin -37 %: the finding


def _largest_load(d: float, F_nwl: float, accelerations, x_ms) -> float:
    """The largest G_m with F_min/(n_rope F_C_up) >= 1 at every place and acceleration: F_C is linear in G_m."""
    F_min = rope(d)["F_min"]
    best = math.inf
    for a in accelerations:
        for x_m in x_ms:
            r0, r1 = route(d, F_nwl, G_m=0.0), route(d, F_nwl, G_m=1.0)
            F0, F1 = r0.drum(x_m, a, 1.0)[0], r1.drum(x_m, a, 1.0)[0]
            best = min(best, (F_min / N_ROPE - F0) / (F1 - F0))
    return best


def test_solve_answers_at_the_worst_place_and_manoeuvre(files, capsys):
    """--given safety_margin_up=0 --find G_m: the largest load that passes everywhere (a start on the 20°
    segment); pinned to steady motion the 20° segment's (the '387 kN' class of the issue); pinned at the old
    default place, the start of an upward trip on the 6° segment, 2.5x that."""
    fixed = str(files[1])
    ends = list(np.cumsum(LENGTHS))
    args = ["solve", fixed, "--given", "safety_margin_up=0", "--find", "G_m", "--json"]
    answers = {}
    for extra in ([], ["--at", "a_h=0m/s^2"], ["--at", "a_h=0m/s^2", "--at", "x_m=1800m"]):
        assert main(args + extra) == 0
        answers[len(extra)] = json.loads(capsys.readouterr().out)
    d, F = 0.036, 24.7e3
    assert answers[0]["G_m"] == pytest.approx(_largest_load(d, F, (0.0, A, -A), ends), rel=1e-9)
    assert answers[2]["G_m"] == pytest.approx(_largest_load(d, F, (0.0,), ends), rel=1e-9)
    assert answers[4]["G_m"] == pytest.approx(_largest_load(d, F, (0.0,), [1800.0]), rel=1e-9)
    assert answers[4]["G_m"] > 2.4 * answers[2]["G_m"] > 2.4 * answers[0]["G_m"]
    assert answers[0]["worst_case"]["governing_case"] == {"segment": 2, "x_m": 1300.0, "manoeuvre": "start"}
    assert answers[0]["given"] == {"safety_margin_up": 0.0}


def test_a_given_output_without_a_worst_needs_a_place(files, capsys):
    assert main(["solve", str(files[1]), "--given", "G_ml=100kN", "--find", "G_m"]) == 2
    err = capsys.readouterr().err
    assert "G_ml changes with x_m" in err and "--at x_m=..." in err


def test_no_solution_because_a_rope_goes_slack_says_so(capsys):
    """Before: a "no solution" whose cause was a slack rope at every case's answer said "at none of them is it
    the worst", as if the worst lay elsewhere.  The second method: ``run`` at each answer shown fails as slack."""
    import re

    assert main(["solve", "route_segments", "--given", "dF_up=3000 mm", "--find", "G_m"]) == 1
    err = capsys.readouterr().err
    assert "at none of them is it the worst" not in err
    assert "none of them holds" in err and "slack" in err
    answers = re.findall(r"G_m = ([0-9.]+) kN", err)
    assert len(answers) >= 6
    for g in answers[:6]:
        assert main(["run", "route_segments", "--set", f"G_m={g} kN"]) == 1
        assert "slack" in capsys.readouterr().err


def test_no_solution_with_answers_out_of_range_says_so(capsys):
    """A negative drum force: each case's answer is a negative load, outside G_m's range (the second method: the
    same question pinned to one case says it is out of reach)."""
    assert main(["solve", "route_segments", "--given", "F_C_up=-10 kN", "--find", "G_m"]) == 1
    err = capsys.readouterr().err
    assert "none of them holds" in err and "is outside its valid range" in err
    assert main(["solve", "route_segments", "--given", "F_C_up=-10 kN", "--find", "G_m", "--at", "x_m=400 m",
                 "--at", "a_h=0 m/s^2"]) == 1
    assert "is out of reach" in capsys.readouterr().err


def test_run_prints_each_result_at_its_worst_and_where(files, capsys):
    """run: the envelope (value and where of each result's worst) against the brute force; --at pins a point;
    --worst is refused with what replaced it."""
    assert main(["run", str(files[1]), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    r = route(0.036, 24.7e3)
    F_C, x, a = max((r.drum(float(x), a, 1.0)[0], float(x), a) for a in (0.0, A, -A) for x in places(r))
    assert out["F_C_up"] == pytest.approx(F_C, rel=1e-12)
    assert out["worst_case"]["outputs"]["F_C_up"]["where"] == {"segment": 2, "x_m": 1300.0, "direction": "up",
                                                              "manoeuvre": "start"}
    assert "G_ml" not in out and "G_ml" in out["worst_case"]["no_worst"]
    assert main(["run", str(files[1])]) == 0
    text = capsys.readouterr().out
    assert "worst case over 4 places of the load x 3 manoeuvres (steady, start, stop)" in text
    assert main(["run", str(files[1]), "--json", "--at", "x_m=1800m", "--at", "a_h=0m/s^2"]) == 0
    one = json.loads(capsys.readouterr().out)
    assert "worst_case" not in one and one["F_C_up"] == pytest.approx(r.drum(1800.0, 0.0, 1.0)[0], rel=1e-12)
    assert main(["run", str(files[1]), "--worst"]) == 2
    assert "--worst is gone" in capsys.readouterr().err
    assert main(["run", "example", "--at", "x_m=100m"]) == 2
    assert "do not depend on x_m" in capsys.readouterr().err


def _worst_F_C_up(degrees) -> float:
    r = route(0.036, 24.7e3, degrees=degrees)
    return max(r.drum(float(x), a, 1.0)[0] for a in (0.0, A, -A) for x in places(r, 50))


def test_sensitivity_is_that_of_the_worst(files):
    """The elasticity of F_C_up's worst to each segment's inclination against central differences of the
    brute-force worst; the 20° segment's inclination ranks first (the tornado's order)."""
    scene = rm.load_scene(str(files[1]))
    e = rm.elasticities(scene, outputs=["F_C_up"], parameters=["alpha_1", "alpha_2", "alpha_3", "G_m"])
    h = 1e-4
    for i in range(3):
        up, dn = list(DEGREES), list(DEGREES)
        up[i] += math.degrees(h)
        dn[i] -= math.degrees(h)
        fd = (_worst_F_C_up(tuple(up)) - _worst_F_C_up(tuple(dn))) / (2 * h)      # N/rad
        row = e[e["parameter"] == f"alpha_{i + 1}"].iloc[0]
        assert row["dy_dp"] * 1e3 * math.degrees(1.0) == pytest.approx(fd, rel=1e-7)
        assert row["where"] == "segment 2, x_m = 1300 m, start"
    alphas = e[e["parameter"].str.startswith("alpha")]
    assert alphas.loc[alphas["elasticity"].abs().idxmax(), "parameter"] == "alpha_2"


def test_sweep_of_a_route_is_the_brute_force_worst_point_by_point(files):
    scene = rm.load_scene(str(files[1]))
    df = rm.sweep(scene, vary={"alpha_3": ["6 deg", "24 deg"], "G_m": ["200 kN", "300 kN"]},
                  outputs=["F_C_up", "N_p_up", "taut_margin_down", "F_C_least_down"], si=True, progress=False)
    for _, row in df.iterrows():
        degrees = (12.0, 20.0, math.degrees(row["alpha_3 [rad]"]))
        r = route(0.036, 24.7e3, G_m=row["G_m [N]"], degrees=degrees)
        F_C, x, a = max((r.drum(float(x), a, 1.0)[0], float(x), a) for a in (0.0, A, -A) for x in places(r, 50))
        assert row["F_C_up [N]"] == pytest.approx(F_C, rel=1e-12)
        assert r.segment(row["F_C_up@x_m [m]"]) == r.segment(x) and row["F_C_up@a_h [m/s^2]"] == a
        P = max(power_up(r, float(x), a) for a in (0.0, A, -A) for x in places(r, 50))
        assert row["N_p_up [W]"] == pytest.approx(P, rel=1e-12)
        least = min(r.least("winding", float(x), a, -1.0, n=2001) for a in (0.0, A, -A) for x in places(r, 50))
        # the winding rope's least anywhere: at the drum (taut_margin + F_S_min), along the route, at the sheave
        got = min(row["taut_margin_down [N]"] + 500.0, row["F_C_least_down [N]"], 0.5 * 24.7e3)
        assert got == pytest.approx(least, rel=1e-9)
    steep = df[df["alpha_3 [rad]"] > 0.3]
    assert (steep["F_C_up@x_m [m]"] == 1800.0).all()       # the 24° end segment governs there


def test_the_report_lists_each_check_with_where_it_governs(files):
    """The report of the sizing scene: at the recommended design, every check with where it is least, the
    place and manoeuvre of each the brute force's (the rope's safety: a start on the 20° segment)."""
    from test_report import Page

    from optimisation.design import size
    from ropemodel.reports import build, load

    report = build(load(str(files[0])))
    html = report.html
    assert "where it is least" in html and "All 14 checks pass." in html
    design = size(str(files[0]), with_sensitivities=False)
    r, F_min = route(design.design["d"], design.design["F_nwl"]), rope(design.design["d"])["F_min"]
    _, x, a = min((F_min / (N_ROPE * r.drum(float(x), a, 1.0)[0]) - 1, float(x), a)
                  for a in (0.0, A, -A) for x in places(r))
    assert r.segment(x) == 1 and a == A
    rows = {r["margin"]: r for r in Page(html).table("checks", 1)}        # the sizing section's checks
    assert len(rows) == 13 and all(r["where it is least"] for r in rows.values())     # no D: the least drum
    assert rows["safety_margin_up"]["where it is least"] == "segment 2, x_m = 1300 m, start"
    assert rows["sheave_margin"]["where it is least"] == "the same in every case"


def test_q_lw_of_the_catalogue_rope_is_the_routes(sized):
    """The stroke the design needs follows eq. (19)-(23) with q_lw = L_u/(E C d^2) of the whole route."""
    d, F_nwl = sized.design["d"], sized.design["F_nwl"]
    q_lw = sum(LENGTHS) / (100e9 * C * d * d)
    r = route(d, F_nwl)
    need = max(q_lw * (sum(r.drum(float(x), a, s)) + F_nwl) for s in (1.0, -1.0) for a in (0.0, A, -A)
               for x in places(r, 50))
    assert need - 1e-9 <= sized.design["stroke"] <= need + 1e-3        # rounded up to 1 mm


@pytest.mark.parametrize("ramp, peak", [("linear", 1.0), ("cosine", math.pi / 2)])
def test_starts_and_stops_are_at_the_ramps_peak_acceleration(files, ramp, peak):
    """The start's and the stop's acceleration: the largest of the ramp shape, v_pj/t_ramp for the linear ramp
    and (π/2) v_pj/t_ramp for the cosine one (its acceleration (π/2)(v_pj/t_ramp) sin(π t/t_ramp))."""
    from ropemodel.envelope import load_cases, with_ramps

    scene = with_ramps(rm.from_toml(ROUTE3.replace('route = "segments"', f'route = "segments"\nramp = "{ramp}"')
                                    .replace('[parameters]', '[parameters]\nd = "36 mm"\nF_nwl = "25 kN"\nD = "1.1 m"'),
                                    emit=False))
    acc = {c.manoeuvre: c.values(scene.parameters)["a_h"] for c in load_cases(scene)}
    assert acc["start"] == pytest.approx(peak * A, rel=1e-9) and acc["stop"] == pytest.approx(-peak * A, rel=1e-9)
    assert acc["steady"] == 0.0 and "emergency stop" not in acc
    braked = scene.with_values({"a_e": "2 m/s^2"})
    assert {c.manoeuvre: c.values(braked.parameters)["a_h"] for c in load_cases(braked)}["emergency stop"] == -2.0
