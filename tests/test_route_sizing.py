"""Sizing on a route of segments: every check with the load anywhere on the route and through a trip's ramps.

Truth: a one-dimensional search written here (docs/physics.md §4 written out in numpy in tests/_route_truth.py:
the forces at the drum, the least tension along each side by brute force; the least pretension for no slip and
taut ropes everywhere in the loop over every place of the load, manoeuvre and direction, then the diameter
where the rope safety of the worst case is exactly met), as in tests/test_sizing.py for the paper's straight
route.  The places are many points along the route and both sides of every joint, not the library's list.

Changed with the worst case by default: the checks were made with the load in the middle of each segment in
steady motion and at a trip's start and stop only where the trip starts and stops; a start (or a stop) can
happen with the load anywhere, and the tension must hold everywhere in the loop, not only at the drum.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from _route_truth import Route, places, rope
from scipy.optimize import brentq

import ropemodel as rm
from optimisation.design import size
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, load_sizing

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


def _route(d, segments=SEGMENTS) -> Route:
    """The haulage at diameter d with no pretension: each force is then its part beyond F_nwl/2."""
    return Route(tuple(g[0] for g in segments), tuple(g[1] for g in segments), tuple(g[2] for g in segments),
                 G_m=P["G_m"], q_l=rope(d)["q_l"], F_nwl=0.0, mu_pm=P["mu_pm"], mu_pl=P["mu_pl"])


def _cases(d, segments=SEGMENTS):
    """(F_C part, F_S part, least tension part of either side) [N] of every place, manoeuvre and direction."""
    r, a = _route(d, segments), P["v_pj"] / P["t_ramp"]
    out = []
    for x in places(r, 20):
        for acc in (0.0, a, -a):
            for s in (1.0, -1.0):
                F_C, F_S = r.drum(float(x), acc, s)
                least = min(r.least(side, float(x), acc, s, n=201) for side in ("winding", "unwinding"))
                out.append((F_C, F_S, least))
    return out


def _least_F(d, segments):
    r, n = math.exp(P["mu_d"] * P["alpha_d"]), P["n_slip"]
    need = [2 * P["F_S_min"]]                              # the return sheave: F_nwl/2 >= F_S_min
    for c, s, least in _cases(d, segments):
        need += [2 * (n * c - r * s) / (r - n), 2 * (P["F_S_min"] - least)]
    return max(need)


def _safety(d, segments):
    F = _least_F(d, segments)
    return min(rope(d)["F_min"] / (P["n_rope"] * (0.5 * F + c)) - 1 for c, _, _ in _cases(d, segments))


def _hand(segments=SEGMENTS):
    d = brentq(_safety, 0.005, 0.2, args=(segments,), xtol=1e-15, rtol=1e-15)
    F = _least_F(d, segments)
    q_lw = sum(g[0] for g in segments) / (P["rope_E"] * 0.460 * d * d)
    stroke = max(q_lw * (2 * F + c + s) for c, s, _ in _cases(d, segments))
    return {"d": d, "F_nwl": F, "stroke": stroke}


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    f = tmp_path_factory.mktemp("route") / "size.toml"
    f.write_text(TOML, encoding="utf-8")
    return load_sizing(f, emit=False)


def test_route_sizing_checks_every_place_and_manoeuvre(scene):
    """Every check with the load at the return-sheave end of each segment and at the drive, in steady motion,
    a start and a stop; each check only in the cases it can differ in (the unwinding rope's does not depend
    on where the load is, the return sheave's on nothing)."""
    problem = SizingProblem(scene)
    labels = {c.split(" @ ")[1] for c in problem.constraints if c.startswith("safety_margin_up @ ")}
    places = ["segment 1, x_m = 400 m", "segment 2, x_m = 1050 m", "segment 3, x_m = 1350 m",
              "segment 1, x_m = 0 m"]
    assert labels == {f"{p}, {m}" for p in places for m in ("steady", "start", "stop")}
    assert {c for c in problem.constraints if c.startswith("slack_margin_up")} == {
        f"slack_margin_up @ {m}" for m in ("steady", "start", "stop")}
    assert "sheave_margin" in problem.constraints


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
    assert "segment 1, x_m = 400 m, start" in active     # a start with the load on the steep segment at the drive


def _without_ramps(raw):
    raw = dict(raw)
    raw["effects"] = {k: v for k, v in raw["effects"].items() if k not in ("dynamics", "inertia", "checks", "power")}
    raw["parameters"] = {k: v for k, v in raw["parameters"].items() if k not in ("t_ramp", "v_pj")}
    return rm.from_dict(raw, optional=("d", "F_nwl", "stroke", "D"), emit=False)


def test_a_start_on_the_steep_end_needs_more_rope(tmp_path):
    """Steep at the return sheave's end: a start with the load there sets the rope (the same route without
    ramps needs less), and the one-dimensional search agrees."""
    f = tmp_path / "reversed.toml"
    segments = TOML.split("[[route]]")
    f.write_text(segments[0] + "[[route]]" + segments[3].split("[parameters]")[0] + "[[route]]" + segments[2]
                 + "[[route]]" + segments[1] + "[parameters]" + TOML.split("[parameters]")[1], encoding="utf-8")
    scene = load_sizing(f, emit=False)
    assert [scene.parameters[f"alpha_{i}"] for i in (1, 2, 3)] == pytest.approx([math.radians(a) for a in (3, 9, 22)])
    design = size(scene, with_sensitivities=False)
    active = {c.split(" @ ")[1] for c in design.active_continuous if " @ " in c}
    assert "segment 3, x_m = 1350 m, start" in active
    lighter = size(_without_ramps(scene.raw), with_sensitivities=False)
    assert lighter.continuous["d"] < 0.99 * design.continuous["d"]
    assert design.continuous["d"] == pytest.approx(_hand(list(reversed(SEGMENTS)))["d"], rel=1e-8)


def _profile_toml(segments) -> str:
    head, params = TOML.split("[parameters]\n")
    head = head.split("[[route]]")[0]
    return head + "".join(f'[[route]]\nlength = "{L!r} m"\ninclination = "{a!r} deg"\nmu_winding = {mu!r}\n'
                          for L, a, mu in segments) + "[parameters]\n" + params


@pytest.mark.slow      # 2 to 8 s: the one-dimensional search over many places in numpy
def test_constraint_generation_equals_every_candidate_and_the_one_dimensional_search(tmp_path):
    """A 12-segment route that rises, dips and rises again (the least tension inside the route moves with the
    rope's weight): ``size`` (the NLP holds the cases where each check can be least, more added while a design
    leaves a candidate below zero) gives the optimum of the NLP of every candidate (a second method) to 1e-10
    and of the one-dimensional search over many places in numpy to 1e-8, and holds fewer cases than it checks."""
    rng = np.random.default_rng(7)
    segments = [(float(L), float(a), float(mu)) for L, a, mu in
                zip(rng.uniform(50.0, 200.0, 12), np.concatenate([rng.uniform(8.0, 25.0, 5), rng.uniform(-6.0, 2.0, 3),
                                                                   rng.uniform(5.0, 20.0, 4)]),
                    rng.uniform(0.04, 0.07, 12))]
    f = tmp_path / "size.toml"
    f.write_text(_profile_toml(segments), encoding="utf-8")
    design = size(str(f), with_sensitivities=False)
    every = SizingProblem(load_sizing(str(f), emit=False))
    whole = solve_continuous(every)
    assert design.feasible and whole.feasible
    assert design.load_cases["in_nlp"] < len(every.cases)
    for k, v in every.to_si(whole.xs).items():
        assert design.continuous[k] == pytest.approx(v, rel=1e-10), k
    hand = _hand(segments)
    for k in ("d", "F_nwl", "stroke"):
        assert design.continuous[k] == pytest.approx(hand[k], rel=1e-8), k


def test_a_rope_below_the_catalogue_is_the_optimum_over_every_place_that_can_govern(tmp_path):
    """A light load (3 kN): the continuous optimum is a rope thinner than the catalogue's smallest, outside the
    rope weights the places are first found for (``size`` then finds them again for every rope); its optimum is
    that of the NLP of every place that can govern for every rope (a second method) to 1e-10."""
    from ropemodel.papers import en12385 as ropes

    rng = np.random.default_rng(3)
    segments = [(float(L), float(a), 0.05) for L, a in zip(rng.uniform(20.0, 80.0, 30), rng.uniform(-5.0, 25.0, 30))]
    f = tmp_path / "size.toml"
    f.write_text(_profile_toml(segments).replace('G_m = "467 kN"', 'G_m = "3 kN"')
                 .replace('F_S_min = "5 kN"', 'F_S_min = "0.1 kN"'), encoding="utf-8")
    design = size(str(f), with_sensitivities=False)
    every = SizingProblem(load_sizing(str(f), emit=False))
    whole = solve_continuous(every)
    assert design.feasible and design.continuous["d"] < ropes.diameters()[0]
    for k, v in every.to_si(whole.xs).items():
        assert design.continuous[k] == pytest.approx(v, rel=1e-10), k


@pytest.mark.slow      # about 20 s: three sizings and the diagnosis of every candidate
def test_no_design_on_a_long_route_names_what_makes_one(tmp_path):
    """The 12-segment route that rises, dips and rises with a rope safety factor of 40: no design.  The
    least-violation problem over the cases ``size`` holds gives the least maximum violation of the NLP of every
    candidate (a second method) to 1e-9, and the named remedy is right: with the n_rope it names a design exists,
    with 0.5 % more none does (bisection truth around the named value)."""
    from optimisation.infeasibility import diagnose

    rng = np.random.default_rng(7)
    segments = [(float(L), float(a), float(mu)) for L, a, mu in
                zip(rng.uniform(50.0, 200.0, 12), np.concatenate([rng.uniform(8.0, 25.0, 5), rng.uniform(-6.0, 2.0, 3),
                                                                   rng.uniform(5.0, 20.0, 4)]),
                    rng.uniform(0.04, 0.07, 12))]
    text = _profile_toml(segments)

    def sized(n_rope):
        f = tmp_path / f"size_{n_rope!r}.toml"
        f.write_text(text.replace("n_rope = 4.5", f"n_rope = {n_rope!r}"), encoding="utf-8")
        return f, size(str(f), with_sensitivities=False)

    f, design = sized(40.0)
    assert not design.feasible
    whole = diagnose(SizingProblem(load_sizing(str(f), emit=False)))
    assert design.diagnosis.max_violation == pytest.approx(whole.max_violation, rel=1e-9)
    (need,) = [n for n in design.diagnosis.needs if n.startswith("n_rope <=")]
    n_rope = float(need.split()[2])
    assert sized(n_rope)[1].feasible
    assert not sized(1.005 * n_rope)[1].feasible
