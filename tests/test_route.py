"""Routes of several segments: the paper as a special case, the sums by hand, bad routes refused.

Truths: Krauze et al. (2025) Fig. 9 as printed (one segment), the paper's case 2 evaluated by
hand from its eq. (17)-(18) (two segments of equal inclination), and the sums of docs/physics.md §4
written out in numpy here (several segments, the load on each).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from test_krauze2025 import _check_fig9

import ropemodel as rm

G = 9.80665
BASE = {"mu_pm": 0.05, "mu_pl": 0.05, "G_m": "467 kN", "F_nwl": "20 kN", "q_l": "0.08 kN/m", "q_lw": "5.8 mm/kN"}


def route_scene(segments, x_m="1000 m", **params):
    return rm.from_dict({"effects": {"route": "segments"}, "route": segments,
                         "parameters": {**BASE, "x_m": x_m, **params}})


def test_one_segment_is_the_paper():
    """One segment of 1150 m at 16 deg, point A at 500 m: every one of Fig. 9's 25 values."""
    r = rm.run(route_scene([{"length": "1150 m", "inclination": "16 deg"}], L_ul="500 m"))
    _check_fig9(r.values)


def test_two_segments_of_equal_inclination_are_case_2():
    """Point A at the joint: the drive-side segment (L_ul) has mu_pl2, the other mu_pl1 (paper, eq. 17-18)."""
    L_u, L_ul, a, mu1, mu2 = 1150.0, 500.0, math.radians(16), 0.04, 0.07
    r = rm.run(route_scene([{"length": "500 m", "inclination": "16 deg", "mu_winding": mu2},
                            {"length": "650 m", "inclination": "16 deg", "mu_winding": mu1}]))
    # eq. (18), first line, by hand (kN, m)
    G_m, q_l, F_nwl, mu_pm, mu_pl = 467.0, 0.08, 20.0, 0.05, 0.05
    T_l = q_l * math.cos(a) * (mu1 * (L_u - L_ul) + mu2 * L_ul)
    F_C_up = 0.5 * F_nwl + (G_m + q_l * L_u) * math.sin(a) + G_m * mu_pm * math.cos(a) + T_l
    F_C_down = 0.5 * F_nwl + (G_m + q_l * L_u) * math.sin(a) - G_m * mu_pm * math.cos(a) - T_l
    F_S_up = 0.5 * F_nwl + q_l * L_u * math.sin(a) - mu_pl * q_l * L_u * math.cos(a)
    assert r["F_C_up"] / 1e3 == pytest.approx(F_C_up, rel=1e-13)
    assert r["F_C_down"] / 1e3 == pytest.approx(F_C_down, rel=1e-13)
    assert r["F_S_up"] / 1e3 == pytest.approx(F_S_up, rel=1e-13)
    # and the straight route's case 2 agrees to rounding
    straight = rm.run(rm.from_dict({"effects": {"resistance": "case2"}, "parameters": {
        **BASE, "L_u": "1150 m", "L_ul": "500 m", "alpha_u": "16 deg", "mu_pl1": mu1, "mu_pl2": mu2}}))
    for k in ("F_C_up", "F_C_down", "F_S_up", "F_S_down", "dF_up", "dF_down"):
        assert r[k] == pytest.approx(straight[k], rel=1e-13)


SEGMENTS = [(400.0, 22.0, 0.06), (650.0, 9.0, None), (300.0, -4.0, 0.03), (250.0, 30.0, None)]


def _by_hand(x, direction):
    """docs/physics.md §4, written out: F_C, F_S [N] with the load at x [m] from the drive."""
    q_l, G_m, F_nwl, mu_pm, mu_pl = 80.0, 467e3, 20e3, 0.05, 0.05
    s = 1.0 if direction == "up" else -1.0
    L = np.array([seg[0] for seg in SEGMENTS])
    a = np.radians([seg[1] for seg in SEGMENTS])
    mu = np.array([mu_pl if seg[2] is None else seg[2] for seg in SEGMENTS])
    j = int(np.searchsorted(np.cumsum(L), x, side="left"))
    weight = q_l * np.sum(L * np.sin(a))
    F_S = 0.5 * F_nwl + weight - s * mu_pl * q_l * np.sum(L * np.cos(a))
    F_C = 0.5 * F_nwl + weight + G_m * math.sin(a[j]) + s * (mu_pm * G_m * math.cos(a[j])
                                                             + q_l * np.sum(mu * L * np.cos(a)))
    return F_C, F_S


@pytest.mark.parametrize("x", [0.0, 10.0, 399.0, 400.0, 401.0, 1050.0, 1300.0, 1349.9, 1350.1, 1600.0])
def test_four_segments_load_on_each_by_hand(x):
    segs = [{"length": f"{L} m", "inclination": f"{a} deg", **({"mu_winding": mu} if mu is not None else {})}
            for L, a, mu in SEGMENTS]
    r = rm.run(route_scene(segs, x_m=f"{x} m", F_nwl="100 kN"))   # every rope taut on the -4 deg segment
    for d in ("up", "down"):
        F_C, F_S = _by_hand(x, d)
        F_C += 40e3   # F_nwl 100 kN here, 20 kN in the hand sums
        F_S += 40e3
        assert r[f"F_C_{d}"] == pytest.approx(F_C, rel=1e-12)
        assert r[f"F_S_{d}"] == pytest.approx(F_S, rel=1e-12)
    assert r["L_u"] == pytest.approx(1600.0, rel=1e-15)


@pytest.mark.parametrize("route, params, message", [
    (None, {}, r'route = "segments" needs the segments'),
    ([], {}, r"\[\[route\]\] must be a list of tables.*an empty route has no segment"),
    ([{"length": "0 m", "inclination": "5 deg"}], {}, r"L_1 = 0 m is outside the valid range \[0.001, 100000\] m"),
    ([{"length": "-40 m", "inclination": "5 deg"}], {}, r"L_1 = -40 m is outside the valid range"),
    ([{"length": "400 m", "inclination": "90 deg"}], {}, r"alpha_1 = 90 deg is outside the valid range \(-90, 90\)"),
    ([{"length": "400 m", "inclination": "-95 deg"}], {}, r"alpha_1 = -95 deg is outside the valid range"),
    ([{"length": "400 m", "inclination": "5 deg"}], {"x_m": "500 m"}, r"x_m = 500 m is beyond the route.*L_u = 400 m"),
    ([{"length": "400 m", "inclination": "5 deg"}], {"L_u": "400 m"}, r"L_u is the sum of the \[\[route\]\] segments"),
    ([{"length": "400", "inclination": "5 deg"}], {},
     r'\[\[route\]\] segment 1: length = 400 has no unit; write e.g. "400 m"'),
    ([{"lenght": "400 m", "inclination": "5 deg"}], {},
     r"(?s)unknown key 'lenght'.*did you mean 'length'.*segment 1 has no length"),
])
def test_bad_routes_are_refused(route, params, message):
    data = {"effects": {"route": "segments"}, "parameters": {**BASE, "x_m": "100 m", **params}}
    if route is not None:
        data["route"] = route
    with pytest.raises(rm.InputError, match=message):
        rm.from_dict(data)


def test_a_route_without_the_effect_is_refused():
    with pytest.raises(rm.InputError, match=r'set \[effects\] route = "segments"'):
        rm.from_dict({"route": [{"length": "400 m", "inclination": "5 deg"}],
                      "parameters": {**BASE, "L_u": "400 m", "L_ul": "0 m", "alpha_u": "5 deg"}})


def test_route_parameters_sweep_and_differentiate():
    """A segment's inclination is a parameter like any other: swept, and its elasticity exact."""
    scene = route_scene([{"length": "400 m", "inclination": "22 deg"}, {"length": "650 m", "inclination": "9 deg"}])
    df = rm.sweep(scene, vary={"alpha_2": ["5 deg", "9 deg", "12 deg"]}, outputs=["F_C_up"], si=True)
    hand = [_two(math.radians(a)) for a in (5, 9, 12)]
    np.testing.assert_allclose(df["F_C_up [N]"], hand, rtol=1e-12)
    e = rm.elasticities(scene, outputs=["F_C_up"], parameters=["alpha_2"])
    a = math.radians(9)
    dF = (467e3 * (math.cos(a) - 0.05 * math.sin(a)) + 80 * 650 * (math.cos(a) - 0.05 * math.sin(a)))
    assert float(e["elasticity"].iloc[0]) == pytest.approx(dF * a / _two(a), rel=1e-10)


def _two(a2):
    """F_C_up of the two-segment route with the load (at 1000 m) on segment 2 inclined at a2."""
    a1 = math.radians(22)
    return (10e3 + 80 * (400 * math.sin(a1) + 650 * math.sin(a2)) + 467e3 * math.sin(a2)
            + 0.05 * 467e3 * math.cos(a2) + 0.05 * 80 * (400 * math.cos(a1) + 650 * math.cos(a2)))


def test_run_takes_each_result_at_its_worst_place_by_default(capsys):
    """No x_m: each result at its own worst place (and manoeuvre: route_segments has 5 s ramps), by hand
    (docs/physics.md §4: the load term G_m (sin α_j + μ_pm cos α_j + a/g), the ramps' inertia on both sides);
    the old --worst is refused and says what replaced it (the change of default: the old default, the start of
    a trip, gave the forces of the 3° segment)."""
    from ropemodel.cli import main

    assert main(["run", "route_segments", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    q_l, G_m, F_nwl, L = 80.0, 467e3, 30e3, [400.0, 650.0, 300.0]
    al = np.radians([22.0, 9.0, 3.0])
    mu = np.array([0.06, 0.05, 0.05])
    a = 2.5 / 5.0
    m_C = (G_m + q_l * sum(L)) / G

    def F_C_up(j, acc):
        return (0.5 * F_nwl + q_l * np.sum(L * np.sin(al)) + G_m * math.sin(al[j])
                + 0.05 * G_m * math.cos(al[j]) + q_l * np.sum(mu * L * np.cos(al)) + m_C * acc)

    truth = max(F_C_up(j, acc) for j in range(3) for acc in (0.0, a, -a))
    assert out["F_C_up"] == pytest.approx(truth, rel=1e-12) and truth == F_C_up(0, a)
    assert out["worst_case"]["outputs"]["F_C_up"]["where"] == {"segment": 1, "x_m": 400.0, "direction": "up",
                                                              "manoeuvre": "start"}
    assert main(["run", "route_segments", "--worst"]) == 2
    assert "--worst is gone" in capsys.readouterr().err


def test_the_readme_envelope_of_route_segments_by_hand():
    """The documentation's `ropemodel run route_segments` excerpt (the winch page, "The worst case by default"),
    each printed number (6 digits) by hand: lowering, the drive brakes hardest stopping on the 22° segment and
    motors starting on the 3° one."""
    from _docs_text import section

    text = section("The worst case by default")
    block = text.split("$ ropemodel run route_segments\n", 1)[1].split("```", 1)[0]
    q_l, G_m, F, L, eta, v, a = 80.0, 467e3, 30e3, np.array([400.0, 650.0, 300.0]), 0.85, 2.5, 0.5
    al = np.radians([22.0, 9.0, 3.0])
    mu = np.array([0.06, 0.05, 0.05])
    L_u = L.sum()

    def forces(j, acc, s=1.0):
        F_S = 0.5 * F + q_l * np.sum(L * np.sin(al)) - s * (0.05 * q_l * np.sum(L * np.cos(al)) + q_l * L_u / G * acc)
        F_C = (0.5 * F + q_l * np.sum(L * np.sin(al)) + G_m * math.sin(al[j])
               + s * (0.05 * G_m * math.cos(al[j]) + q_l * np.sum(mu * L * np.cos(al)) + (G_m + q_l * L_u) / G * acc))
        return F_C, F_S

    def drive(F_C, F_S, s):
        """The drive's power: the drum's s (F_C − F_S) v, /η motoring, ·η braking (four quadrants)."""
        P = s * (F_C - F_S) * v
        return (P / eta if P > 0 else P * eta) / 1e3

    start, stop = forces(0, a), forces(2, -a)
    lowered_stop, lowered_start = forces(0, -a, -1.0), forces(2, a, -1.0)
    hand = {("F_S_up", "largest"): stop[1] / 1e3, ("F_S_up", "least"): start[1] / 1e3,
            ("F_C_up", "largest"): start[0] / 1e3, ("dF_up", "largest"): 5.8 * (start[0] + start[1] + F) / 1e3,
            ("N_p_up", "largest"): drive(*start, 1.0), ("N_p_up", "least"): drive(*stop, 1.0),
            ("N_p_down", "least"): drive(*lowered_stop, -1.0), ("N_p_down", "largest"): drive(*lowered_start, -1.0)}
    for (name, sense), value in hand.items():
        line = next(ln for ln in block.splitlines() if ln.split()[:2] == [name, sense])
        assert float(line.split()[2]) == pytest.approx(value, rel=5e-6), line
