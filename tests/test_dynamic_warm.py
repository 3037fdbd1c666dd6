"""Re-solves on the previous optimum's active set (optimisation.dynamic.warm) against IPOPT (a second method)
on the static sizing NLP of the Fig. 9 scene: a nearby load keeps the active set, and Newton on it lands on
IPOPT's optimum; a far one changes it, and the active set is refused (never a point that is not a KKT point)."""

import numpy as np
import pytest

import ropemodel as rm
from optimisation.dynamic.warm import on_active_set
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, prepare


@pytest.fixture(scope="module")
def problem():
    return SizingProblem(prepare(rm.load_scene("winch_sizing_fig9")))


@pytest.fixture(scope="module")
def optimum(problem):
    sol = solve_continuous(problem)
    assert sol.feasible and sol.polished
    return sol


def test_a_nearby_point_is_solved_on_the_same_active_set(problem, optimum):
    p = problem.p_of({"G_m": 470e3})
    newton = on_active_set(problem, optimum, problem, p)
    ipopt = solve_continuous(problem, p=p, x0=optimum.xs)
    assert newton is not None and ipopt.feasible
    assert newton.xs == pytest.approx(ipopt.xs, rel=1e-9, abs=1e-12)
    assert sorted(newton.active) == sorted(ipopt.active)
    assert np.all(newton.g >= -1e-8)


def test_a_fixed_diameter_drops_one_active_check(problem, optimum):
    """d fixed at a catalogue size above the optimum (37.2 mm): the rope safety leaves the active set, slip and
    stroke fix F_nwl and stroke; Newton finds which of the three to drop."""
    newton = on_active_set(problem, optimum, problem, None, fix_d=0.044)
    ipopt = solve_continuous(problem, x0=optimum.xs, fix_d=0.044)
    assert ipopt.feasible and len(optimum.active) == 3 and len(ipopt.active) == 2
    assert newton is not None and sorted(newton.active) == sorted(ipopt.active)
    assert newton.xs == pytest.approx(ipopt.xs, rel=1e-9, abs=1e-12)


def test_a_far_point_that_changes_the_active_set_is_refused(problem, optimum):
    """A light load on a shallow route: the sheave's check replaces slip in the active set (IPOPT); the old active
    set gives no KKT point there, so it is refused."""
    p = problem.p_of({"G_m": 150e3, "alpha_u": np.radians(4.0)})
    ipopt = solve_continuous(problem, p=p, x0=optimum.xs)
    assert ipopt.feasible and sorted(ipopt.active) != sorted(optimum.active)
    assert on_active_set(problem, optimum, problem, p) is None
