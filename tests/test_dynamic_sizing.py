"""Dynamic sizing (issue 15): the four manoeuvres, and every check judged by the hybrid simulator."""

from __future__ import annotations

import pytest

from optimisation.dynamic.manoeuvres import manoeuvres
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.verify import verify
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, load_sizing
from ropemodel.errors import InputError
from _dynamic_scene import write_scene


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    return load_sizing(write_scene(tmp_path_factory.mktemp("dyn")), emit=False)


def test_natural_places_of_the_manoeuvres(scene):
    """No x_m: an upward trip starts at the return sheave (x_m = L_u) and stops at the drive (x_m = 0), a
    downward trip the other way round."""
    got = {(m.dynamics, m.travel): m.x_m for m in manoeuvres(scene)}
    assert got == {("start", "up"): 1150.0, ("stop", "up"): 0.0, ("start", "down"): 0.0, ("stop", "down"): 1150.0}
    assert all("trip" in m.source for m in manoeuvres(scene))


def test_given_place_is_used_for_all_four(scene):
    ms = manoeuvres(scene.with_values({"x_m": 300.0}))
    assert [m.x_m for m in ms] == [300.0] * 4 and all(m.source == "given" for m in ms)


def test_a_scene_without_transient_is_refused(tmp_path):
    text = write_scene(tmp_path).read_text().replace('dynamics = "start"\n', "")
    (tmp_path / "static.toml").write_text(text)
    with pytest.raises(InputError, match="transient"):
        DynamicSizingProblem(load_sizing(tmp_path / "static.toml", emit=False))


def test_static_optimum_slips_or_overloads_in_a_start(scene):
    """The static optimum (every static check met) fails in the simulated upward start: the reason for
    dynamic sizing.  The simulator names the failure."""
    static = SizingProblem(scene)
    sol = solve_continuous(static)
    assert sol.feasible
    problem = DynamicSizingProblem(scene)
    verdicts = verify(problem, sol.xs)
    up_start = verdicts[0]
    assert up_start.manoeuvre == "upward start" and not up_start.ok
    assert any(f.startswith(("slip", "safety")) for f in up_start.failures)
