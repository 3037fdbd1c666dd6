"""The places of the load that can govern (ropemodel.envelope.prune) against a brute-force search.

Truth: docs/physics.md §4 written out in numpy (tests/_route_truth.py), the least tension of the winding rope
searched at 2001 points along the route for the load at every place of a fine grid (not only the joints), and
the drum force F_C likewise, for ropes from very light to very heavy (the pruning must hold for every q_l a
sizing tries) and every manoeuvre.  The worst over the grid must be at a joint the pruning keeps.  And sizing
with the pruned places equals sizing with every place.
"""

from __future__ import annotations

import numpy as np
import pytest
from _route_truth import Route, places

import ropemodel as rm
from optimisation import design as sizing
from optimisation.problem import D_OPTIONAL, SIZED, SizingProblem, load_sizing
from ropemodel.envelope.prune import governing_places

ACCELERATIONS = (0.0, 0.5, -0.5, -1.2)


def _route(seed: int, n: int = 25) -> Route:
    rng = np.random.default_rng(seed)
    return Route(tuple(rng.uniform(20.0, 200.0, n)), tuple(rng.uniform(-8.0, 25.0, n)),
                 tuple(rng.uniform(0.02, 0.08, n)), G_m=467e3, q_l=80.0, F_nwl=30e3)


def _params(route: Route) -> dict:
    out = {"G_m": route.G_m, "mu_pm": route.mu_pm, "mu_pl": route.mu_pl}
    for i, (L, a, mu) in enumerate(zip(route.lengths, route.alphas, route.mus), start=1):
        out.update({f"L_{i}": L, f"alpha_{i}": a, f"mu_w{i}": mu})
    return out


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_worst_place_is_a_kept_joint(seed):
    route = _route(seed)
    keep = governing_places(_params(route), ACCELERATIONS)
    assert len(keep) < len(route.lengths) + 1          # it prunes
    joints = np.concatenate([[0.0], route.ends])
    kept = joints[sorted(keep)]
    grid = places(route, 60)
    for q_l in (2.0, 80.0, 2000.0):
        r = route.with_(q_l=q_l)
        for a in ACCELERATIONS:
            for s in (1.0, -1.0):
                least = [r.least("winding", float(x), a, s, 1001) for x in grid]
                least_kept = min(r.least("winding", float(x), a, s, 1001) for x in kept)
                assert least_kept == pytest.approx(min(least), rel=1e-12, abs=1e-6), (q_l, a, s)
                F_C = [r.drum(float(x), a, s)[0] for x in grid]
                F_C_kept = [r.drum(float(x), a, s)[0] for x in kept]
                assert max(F_C_kept) == pytest.approx(max(F_C), rel=1e-12)
                assert min(F_C_kept) == pytest.approx(min(F_C), rel=1e-12)


def test_sizing_on_the_pruned_places_equals_sizing_on_every_place():
    """12 segments with a dip: the design, every margin and where each governs are those of the NLP over every
    place (a second method: the unpruned NLP)."""
    route = _route(7, 12)
    scene = load_sizing(rm.from_dict({
        "effects": {"route": "segments", "rope": "6x36-IWRC", "lining": "rigid", "dynamics": "trip"},
        "route": [{"length": f"{float(L)!r} m", "inclination": f"{float(a)!r} deg"}
                  for L, a in zip(route.lengths, route.degrees)],
        "parameters": {"mu_pm": 0.05, "mu_pl": 0.05, "G_m": "467 kN", "v_pj": "2.5 m/s", "t_ramp": "5 s",
                       "rope_grade": "1770 N/mm^2", "rope_E": "100 kN/mm^2", "mu_d": 0.2, "alpha_d": "540 deg",
                       "n_slip": 1.25, "n_rope": 4.5, "F_S_min": "5 kN"}}, optional=SIZED + D_OPTIONAL), emit=False)
    pruned = SizingProblem(scene)
    assert len(pruned.cases) < len(pruned.all_cases)
    a = sizing.size(scene, with_sensitivities=False)
    every = sizing.SizingProblem
    try:
        sizing.SizingProblem = lambda s, **_: every(s, prune_places=False)   # every place, in one NLP
        b = sizing.size(scene, with_sensitivities=False)
    finally:
        sizing.SizingProblem = every
    assert a.design == b.design
    for k, v in b.continuous.items():
        assert a.continuous[k] == pytest.approx(v, rel=1e-9)
    for k, v in b.margins.items():
        assert a.margins[k] == pytest.approx(v, rel=1e-9, abs=1e-9)
    assert a.governing == b.governing


def test_run_on_the_kept_places_equals_run_on_every_place(tmp_path):
    """``run`` evaluates only the places that can govern: on a 300-point surveyed profile with the ramps' starts
    and stops, every output's worst and where it governs equal those of the envelope over every place (a second
    method), and far fewer places are evaluated.  A scene whose elongation reads the place otherwise (as built:
    the load's pull times x_m) is not pruned."""
    from ropemodel.envelope import load_cases, with_ramps
    from ropemodel.envelope.prune import prunable, prune
    from ropemodel.core.model import Model
    from ropemodel.envelope.worst import envelope
    from ropemodel.problem import Problem

    x = np.linspace(0.0, 2000.0, 300)
    h = 500.0 - x * np.tan(np.radians(10.0)) - 15.0 * np.sin(2.0 * np.pi * x / 700.0)
    L, a = np.hypot(np.diff(x), np.diff(h)), np.arctan2(-np.diff(h), np.diff(x))
    scene = with_ramps(rm.from_dict({
        "effects": {"route": "segments", "dynamics": "trip"},
        "route": [{"length": f"{float(length)!r} m", "inclination": f"{float(angle)!r} rad"}
                  for length, angle in zip(L, a)],
        "parameters": {"G_m": "467 kN", "F_nwl": "40 kN", "q_l": "0.08 kN/m", "q_lw": "5.8 mm/kN", "mu_pm": 0.05,
                       "mu_pl": 0.05, "v_pj": "2.5 m/s", "t_ramp": "5 s"}}))
    result = rm.run(scene)
    every = envelope(Problem(scene), load_cases(scene))
    assert result.envelope.spanned == every.cases and len(result.envelope.cases) < len(every.cases) / 5
    assert result.values.keys() >= every.values().keys()
    for k, v in every.values().items():
        assert result.values[k] == v, k
    assert result.where == every.where()
    asbuilt = Model("winch", {**scene.effects, "elongation": "asbuilt"}, scene.built.options)
    assert prunable(scene.built) and not prunable(asbuilt)
    assert prune(load_cases(scene), scene.parameters, asbuilt) == load_cases(scene)


@pytest.mark.slow      # 2 to 5 s each: the least tension searched along the route at every place of a fine grid
@pytest.mark.parametrize("seed", [4, 5])
def test_a_range_of_rope_weights_keeps_the_worst_place_of_each(seed):
    """For the rope weights of a range only (a sizing's catalogue: q_l from 20 to 150 N/m), fewer places are kept,
    and for ropes at both ends of the range and inside it the least tension of the winding rope over a fine grid
    of places (searched at 1001 points along the route, numpy) is still at a kept joint."""
    route = _route(seed, 60)
    every = governing_places(_params(route), ACCELERATIONS)
    keep = governing_places(_params(route), ACCELERATIONS, (20.0, 150.0))
    assert keep < every
    joints = np.concatenate([[0.0], route.ends])
    kept, grid = joints[sorted(keep)], places(route, 20)
    for q_l in (20.0, 61.0, 150.0):
        r = route.with_(q_l=q_l)
        for a in ACCELERATIONS:
            for s in (1.0, -1.0):
                least = min(r.least("winding", float(x), a, s, 1001) for x in grid)
                least_kept = min(r.least("winding", float(x), a, s, 1001) for x in kept)
                assert least_kept == pytest.approx(least, rel=1e-12, abs=1e-6), (q_l, a, s)
