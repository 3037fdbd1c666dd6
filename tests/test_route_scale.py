"""Routes at survey scale (issue 22, item 4): a profile of a thousand points through ``trip`` and the array evaluator
with its constants folded in, equal to the same route written as ``[[route]]`` tables and to the exact trip
written out in numpy.

Truths: the trip integrated in the distance travelled, in closed form on each stretch (``test_trip._by_distance``,
numpy only, docs/physics.md §4); the same route as ``[[route]]`` tables (a second way in); CasADi's map with the
constants passed at every point (a second method of the same evaluation).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_trip import LOAD, _by_distance

import ropemodel as rm
from ropemodel.core import evaluate as ev
from ropemodel.problem import Problem
from ropemodel.trips import trip

F_NWL = 400e3   # keeps both ropes taut through the ramps on every segment of the route below


def _segments(n: int, seed: int = 3) -> list[tuple[float, float, float | None]]:
    """n segments of 1 to 3 m at 2 to 25 deg (a surveyed incline, the survey's noise included), lengths [m],
    inclinations [deg], the winding rope's coefficient (None: mu_pl)."""
    rng = np.random.default_rng(seed)
    return [(float(L), float(a), None) for L, a in zip(rng.uniform(1.0, 3.0, n), rng.uniform(2.0, 25.0, n))]


def _scene_files(tmp_path, segments) -> tuple:
    """The route as a profile file (``length [m],inclination [deg]``) and as ``[[route]]`` tables."""
    (tmp_path / "route.csv").write_text("length [m],inclination [deg]\n"
                                        + "".join(f"{L!r},{a!r}\n" for L, a, _ in segments))
    head = ('[effects]\nroute = "segments"\ndynamics = "trip"\ninertia = "rigid"\npower = "drive"\n'
            'rope_elasticity = "rigid"\n')
    params = ("[parameters]\n" + "".join(f"{k} = {v!r}\n" for k, v in LOAD.items() if k in ("mu_pm", "mu_pl", "eta"))
              + f'G_m = "{LOAD["G_m"]!r} N"\nq_l = "{LOAD["q_l"]!r} N/m"\nq_lw = "5.8 mm/kN"\n'
              f'v_pj = "{LOAD["v_pj"]!r} m/s"\nt_ramp = "{LOAD["t_ramp"]!r} s"\nF_nwl = "{F_NWL!r} N"\n')
    profile, tables = tmp_path / "profile.toml", tmp_path / "tables.toml"
    profile.write_text(head + '[route_profile]\nfile = "route.csv"\n' + params)
    tables.write_text(head + "".join(f'[[route]]\nlength = "{L!r} m"\ninclination = "{a!r} deg"\n'
                                     for L, a, _ in segments) + params)
    return profile, tables


@pytest.fixture(scope="module")
def thousand(tmp_path_factory):
    """1000 segments as a profile and as tables: (segments, profile scene, tables scene)."""
    segments = _segments(1000)
    files = _scene_files(tmp_path_factory.mktemp("thousand"), segments)
    return (segments, *(rm.load_scene(str(p)) for p in files))


@pytest.mark.parametrize("direction", ["up", "down"])
def test_a_thousand_segment_trip_equals_its_tables_and_the_exact_trip(thousand, direction):
    """1000 segments (the trip's pieces evaluated with the route's constants folded in: 2000 constants at 1000
    pieces, above ev.FOLD_MIN): the summary equals the same route as [[route]] tables to 1e-12 and the trip
    integrated in the distance in numpy to the rounding of a thousand-term sum."""
    segments, profile, tables = thousand
    assert 2 * len(segments) * len(segments) > ev.FOLD_MIN
    got, same = trip(profile, direction).summary, trip(tables, direction).summary
    assert set(got) == set(same)
    for k, v in same.items():
        assert got[k] == pytest.approx(v, rel=1e-12, abs=1e-9), k
    ref = _by_distance(direction, segments, LOAD["t_ramp"], F_NWL)
    for k in ("t_trip", "F_C_max", "F_S_min", "P_max", "P_brake_max", "P_rms", "E_trip", "W_drum", "stroke_needed"):
        assert got[k] == pytest.approx(ref[k], rel=1e-9, abs=1e-6), k
    assert got["E_regen"] == pytest.approx(ref["E_brake"], rel=1e-9, abs=1e-6)


def test_folded_constants_give_what_the_map_gives(monkeypatch):
    """The model of a 200-segment route at 500 places of the load, with its constants folded into the Function
    (FOLD_MIN lowered to 0) and passed to CasADi's map at every point (FOLD_MIN above the work): the same
    numbers to the last bit; an output that does not vary with the place is one number repeated."""
    raw = dict(rm.load_scene("route_segments").raw)
    raw["route"] = [{"length": f"{L!r} m", "inclination": f"{a!r} deg"} for L, a, _ in _segments(200, seed=5)]
    raw["parameters"] = {**raw["parameters"], "F_nwl": "400 kN"}
    problem = Problem(rm.from_dict(raw, emit=False))
    x = np.linspace(0.0, sum(L for L, _, _ in _segments(200, seed=5)), 500)
    columns = {"x_m": x, "a_h": np.where(x < 150.0, 0.5, -0.5)}
    monkeypatch.setattr(ev, "FOLD_MIN", math.inf)
    mapped = problem.evaluate(columns)
    monkeypatch.setattr(ev, "FOLD_MIN", 0)
    folded = problem.evaluate(columns)
    assert set(folded) == set(mapped)
    for k, v in mapped.items():
        np.testing.assert_array_equal(folded[k], v, err_msg=k)
    assert np.ptp(folded["G_l"]) == 0.0 and np.ptp(folded["F_C_up"]) > 0.0
