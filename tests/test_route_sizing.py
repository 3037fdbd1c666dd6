"""Sizing on a route of segments: every check with the load on every segment and through a trip's ramps.

Truth: a one-dimensional search written here (docs/physics.md §4 sums and inertia written out, the
least pretension for no slip / taut ropes over every state, then the diameter where the rope safety
of the worst state is exactly met), as in tests/test_sizing.py for the paper's straight route.
"""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq

import ropemodel as rm
from optimisation.design import size
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, load_sizing

G = 9.80665
K, W, C = 0.356, 4090.0, 0.460        # 6x36-IWRC, EN 12385-4
SEGMENTS = [(400.0, 22.0, 0.06), (650.0, 9.0, 0.05), (300.0, 3.0, 0.05)]
P = dict(G_m=467e3, mu_pm=0.05, mu_pl=0.05, v_pj=2.5, t_ramp=5.0, mu_d=0.2, alpha_d=math.radians(540),
         n_slip=1.25, n_rope=4.5, F_S_min=5e3, rope_grade=1770e6, rope_E=100e9)

TOML = '''
[effects]
route = "segments"
rope = "6x36-IWRC"
lining = "rigid"
dynamics = "trip"
[[route]]
length = "400 m"
inclination = "22 deg"
mu_winding = 0.06
[[route]]
length = "650 m"
inclination = "9 deg"
[[route]]
length = "300 m"
inclination = "3 deg"
[parameters]
mu_pm = 0.05
mu_pl = 0.05
G_m = "467 kN"
rope_grade = "1770 N/mm^2"
rope_E = "100 kN/mm^2"
mu_d = 0.2
alpha_d = "540 deg"
n_slip = 1.25
n_rope = 4.5
F_S_min = "5 kN"
v_pj = "2.5 m/s"
t_ramp = "5 s"
'''


def _states():
    """(load's segment, acceleration, direction) of every state: each segment in steady motion, and the
    start and stop of each direction's trip where they happen (an upward trip starts at the last segment)."""
    a = P["v_pj"] / P["t_ramp"]
    out = [(j, 0.0, d) for j in range(3) for d in ("up", "down")]
    return out + [(2, a, "up"), (0, -a, "up"), (0, a, "down"), (2, -a, "down")]


def _parts(d, j, acc, direction, segments=SEGMENTS):
    """(constant part of F_S, constant part of F_C) [N]: F_S = F_nwl/2 + s, F_C = F_nwl/2 + c."""
    q = G * W * d * d
    L = [g[0] for g in segments]
    al = [math.radians(g[1]) for g in segments]
    mu = [g[2] for g in segments]
    L_u = sum(L)
    sgn = 1.0 if direction == "up" else -1.0
    weight = sum(q * Li * math.sin(ai) for Li, ai in zip(L, al))
    s = weight - sgn * (P["mu_pl"] * sum(q * Li * math.cos(ai) for Li, ai in zip(L, al)) + q * L_u / G * acc)
    c = (weight + P["G_m"] * math.sin(al[j])
         + sgn * (P["mu_pm"] * P["G_m"] * math.cos(al[j])
                  + sum(m * q * Li * math.cos(ai) for m, Li, ai in zip(mu, L, al))
                  + (P["G_m"] + q * L_u) / G * acc))
    return s, c


def _least_F(d, segments):
    r, n = math.exp(P["mu_d"] * P["alpha_d"]), P["n_slip"]
    need = [0.0]
    for st in _states():
        s, c = _parts(d, *st, segments)
        need += [2 * (n * c - r * s) / (r - n), 2 * (P["F_S_min"] - s), 2 * (P["F_S_min"] - c)]
    return max(need)


def _safety(d, segments):
    F = _least_F(d, segments)
    F_min = K * d * d * P["rope_grade"]
    return min(F_min / (P["n_rope"] * (0.5 * F + _parts(d, *st, segments)[1])) - 1 for st in _states())


def _hand(segments=SEGMENTS):
    d = brentq(_safety, 0.005, 0.2, args=(segments,), xtol=1e-15, rtol=1e-15)
    F = _least_F(d, segments)
    q_lw = sum(g[0] for g in segments) / (P["rope_E"] * C * d * d)
    stroke = max(q_lw * (2 * F + sum(_parts(d, *st, segments))) for st in _states())
    return {"d": d, "F_nwl": F, "stroke": stroke}


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    f = tmp_path_factory.mktemp("route") / "size.toml"
    f.write_text(TOML, encoding="utf-8")
    return load_sizing(f, emit=False)


def test_route_sizing_checks_every_segment_and_the_ramps(scene):
    problem = SizingProblem(scene)
    labels = {c.split(" @ ")[1] for c in problem.constraints if " @ " in c}
    assert labels == {"segment 1", "segment 2", "segment 3", "start of an upward trip", "stop of an upward trip",
                      "start of a downward trip", "stop of a downward trip"}


def test_route_sizing_equals_the_one_dimensional_search(scene):
    problem = SizingProblem(scene)
    sol = solve_continuous(problem)
    assert sol.feasible
    got, hand = problem.to_si(sol.xs), _hand()
    for k in ("d", "F_nwl", "stroke"):
        assert got[k] == pytest.approx(hand[k], rel=1e-8), k


def test_route_catalogue_design_passes_its_checks_in_every_state(scene):
    design = size(scene, with_sensitivities=False)
    assert design.feasible and min(design.margins.values()) >= 0.0
    assert design.design["d"] >= _hand()["d"]
    active = {c.split(" @ ")[1] for c in design.active_continuous if " @ " in c}
    assert "segment 1" in active     # the steep segment at the drive, in steady motion, sets the rope


def _without_ramps(raw):
    raw = dict(raw)
    raw["effects"] = {k: v for k, v in raw["effects"].items() if k not in ("dynamics", "inertia", "checks", "power")}
    raw["parameters"] = {k: v for k, v in raw["parameters"].items() if k not in ("t_ramp", "v_pj")}
    return rm.from_dict(raw, optional=("d", "F_nwl", "stroke", "D"), emit=False)


def test_a_start_on_the_steep_end_needs_more_rope(tmp_path):
    """Steep at the return sheave's end, where an upward trip starts: the start's inertia there sets the rope
    (the same route without ramps needs less), and the one-dimensional search agrees."""
    f = tmp_path / "reversed.toml"
    segments = TOML.split("[[route]]")
    f.write_text(segments[0] + "[[route]]" + segments[3].split("[parameters]")[0] + "[[route]]" + segments[2]
                 + "[[route]]" + segments[1] + "[parameters]" + TOML.split("[parameters]")[1], encoding="utf-8")
    scene = load_sizing(f, emit=False)
    assert [scene.parameters[f"alpha_{i}"] for i in (1, 2, 3)] == pytest.approx([math.radians(a) for a in (3, 9, 22)])
    design = size(scene, with_sensitivities=False)
    active = {c.split(" @ ")[1] for c in design.active_continuous if " @ " in c}
    assert "start of an upward trip" in active
    lighter = size(_without_ramps(scene.raw), with_sensitivities=False)
    assert lighter.continuous["d"] < 0.99 * design.continuous["d"]
    assert design.continuous["d"] == pytest.approx(_hand(list(reversed(SEGMENTS)))["d"], rel=1e-8)
