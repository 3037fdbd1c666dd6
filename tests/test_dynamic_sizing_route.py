"""Dynamic sizing on the three-segment route of issue 21 (600 m at 12°, 700 m at 20°, 500 m at 6° from the
drive; 300 kN; 3 m/s; a 4 s ramp; 6x36-IWRC), from a scene with no transient in it (slow: one sizing with its
mesh control, minutes of CPU).

Truth: the hybrid simulator's histories judged by this test's own checks (``_dynamic_scene.simulated_failures``:
rope safety, slip, the dynamic slip factor, slack, stroke, taut rope), followed twice as long as the sizing
follows them, with the load on the steepest segment (its ends, its quarter points, which are no candidate of
the sizing, and its middle), and at every candidate place the sizing left out of its NLP; and under mesh
refinement (issue 23, items 1 and 2, ``_mesh_checks``): with 2x the scene's elements at every place, 4x with
the load where each manoeuvre is governed, 3 % less at the converged mesh.
"""

from __future__ import annotations

import json
import os

import pytest
import _route3 as route3
from _dynamic_scene import MANOEUVRES, N_SLIP_DYNAMIC, places, simulated_failures
from _mesh_checks import failures_with_elements, lighter_that_holds, mesh_record_problems

from optimisation.dynamic import size_dynamic
from optimisation.problem import load_sizing
from ropemodel.cli._size_dynamic import design_text
from ropemodel.papers import en12385

pytestmark = [pytest.mark.slow, pytest.mark.exhaustive]     # minutes each: not in CI (CONTRIBUTING, "Test tiers")


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    return load_sizing(route3.write(tmp_path_factory.mktemp("route")), emit=False)


@pytest.fixture(scope="module")
def sized(scene, tmp_path_factory):
    """The sizing, and what it wrote to the process's stdout and stderr (file descriptors 1 and 2: a solver
    writes there, not to Python's streams)."""
    log = tmp_path_factory.mktemp("fd") / "out.txt"
    with open(log, "w") as f:
        saved = [os.dup(1), os.dup(2)]
        try:
            os.dup2(f.fileno(), 1)
            os.dup2(f.fileno(), 2)
            design = size_dynamic(scene)
        finally:
            for fd, copy in zip((1, 2), saved):
                os.dup2(copy, fd)
                os.close(copy)
    return design, log.read_text()


@pytest.fixture(scope="module")
def design(sized):
    return sized[0]


@pytest.fixture(scope="module")
def scene_with(tmp_path_factory):
    """The route with ``n`` rope elements per span (the scene's: the default 8)."""
    tmp = tmp_path_factory.mktemp("mesh")
    return lambda n: load_sizing(route3.write(tmp, extra=f"[numerics]\nsegments = {n}\n", name=f"route{n}.toml"),
                                 emit=False)


def _horizon(design) -> float:
    """Twice as long after the ramp as the sizing followed each manoeuvre."""
    v = design.scene.parameters
    return v["t_ramp"] + 2 * (v["t_end"] - v["t_ramp"])


def test_a_catalogue_design_is_found(design):
    assert design.feasible
    assert design.design["d"] in en12385.diameters() and design.design["d"] >= design.continuous["d"]
    assert design.continuous["d"] >= design.static["d"]


def test_the_design_holds_with_the_load_on_the_steepest_segment(scene, design):
    """Starts and stops in both directions with the load anywhere on the 20° segment (600 m to 1300 m from the
    drive): at its ends, quarter points and middle."""
    steep = [600.001, 775.0, 950.0, 1125.0, 1300.0]
    assert simulated_failures(scene, design.design, where=steep, t_end=_horizon(design),
                              slip_factor=N_SLIP_DYNAMIC) == []


def test_design_holds_with_twice_the_rope_elements(scene_with, design):
    """The catalogue design keeps every check, the dynamic slip factor included, simulated with twice the
    scene's 8 elements per span, every manoeuvre at every place of the load."""
    assert failures_with_elements(scene_with, design, 16) == []


def test_design_holds_with_four_times_the_rope_elements(scene_with, design):
    """And with four times (32 per span), each manoeuvre with the load where it is governed (36 simulations of
    32 elements a span would be minutes of CPU: 4 here)."""
    assert failures_with_elements(scene_with, design, 32, everywhere=False) == []


def test_three_percent_less_fails_at_the_converged_mesh(scene_with, design):
    assert lighter_that_holds(scene_with(design.mesh["segments"]), design) == []


def test_mesh_and_factors_are_reported(design):
    assert mesh_record_problems(design, 8, n_slip=1.25) == []


def test_places_left_out_of_the_nlp_hold_in_simulation(scene, design):
    """The screening put only the cases governing a check into the NLP; at the returned design every other
    case (manoeuvre and place) keeps every check in simulation too."""
    inside = {(c["dynamics"], c["travel"], round(c["x_m"], 6)) for c in design.nlp_cases}
    assert 0 < len(inside) < len(MANOEUVRES) * len(places(scene))
    failures = []
    for dynamics, travel in MANOEUVRES:
        left_out = [x for x in places(scene) if (dynamics, travel, round(x, 6)) not in inside]
        failures += simulated_failures(scene, design.design, where=left_out, manoeuvres=[(dynamics, travel)],
                                       t_end=_horizon(design), slip_factor=N_SLIP_DYNAMIC)
    assert failures == []


def test_the_output_says_where_each_manoeuvre_is_governed(sized):
    """The JSON of ``size --dynamic`` on the route: each manoeuvre's governing place and all nine places of
    each, the defaults it took and the transient it built; the text names the places; no solver output."""
    design, written = sized
    assert written == ""
    res = json.loads(json.dumps(design.to_dict(), allow_nan=False))
    assert [m["manoeuvre"] for m in res["manoeuvres"]] == ["upward start", "upward stop", "downward start",
                                                          "downward stop"]
    for m in res["manoeuvres"]:
        assert len(m["positions"]) == 9 and m["ok"]
        assert m["x_m"] in [p["x_m"] for p in m["positions"]] and "x_m = " in m["where"]
        assert all("where" in least and "x_m" in least for least in m["least_margins"].values())
    assert "T_1" in res["defaults"]["t_end"] and res["transient"]["rope_elasticity"]["variant"] == "segments"
    text = design_text(design)
    assert "load at" in text and "segment 2" in text and "defaults used" in text
