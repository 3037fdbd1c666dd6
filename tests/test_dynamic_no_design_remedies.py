"""The remedies of a dynamic "no design", found by Newton on the least violation's active set
(:mod:`optimisation.dynamic.remedy`), on the study's "no design" scene (the shipped sizing scene with a 2 s ramp,
4 rope elements per span, 12 s manoeuvres):

* n_rope (its active checks' peaks stay where they are) against a second method: IPOPT on the remedy problem itself
  (max n_rope such that every check of the NLP holds), as the remedies were found before;
* t_ramp (the peaks move: the ramp stretches the start; IPOPT on its remedy problem ends without an answer from the
  least violation's point in 150 iterations, measured) against the hybrid simulator: with the ramp it names, Newton's
  design keeps every check of the four manoeuvres at every place, judged by the test's own checks
  (``_dynamic_scene.simulated_failures``) and the scene's drum rule written out here.

Exhaustive (CONTRIBUTING, test tiers): IPOPT takes minutes."""

from __future__ import annotations

import numpy as np
import pytest
from _studies import load_study

from optimisation.dynamic import diagnose
from optimisation.dynamic.design import _static
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.remedy import active_of, newton_remedy
from optimisation.dynamic.start import factored_start

pytestmark = [pytest.mark.slow, pytest.mark.exhaustive]


@pytest.fixture(scope="module")
def least():
    scene = load_study("dynamic_sizing_speed").short_ramp()
    problem = DynamicSizingProblem(scene)
    start = factored_start(problem, _static(problem.scene)[1].xs)
    problem = problem.screened(start)
    lbx, ubx = diagnose._catalogue_bounds(problem)
    z, r, sub = diagnose.least_violation(problem, np.clip(start, lbx, ubx), lbx, ubx)
    assert z[3] > 1e-3                                 # no design: the least violation is positive
    checks, bounds = active_of(sub, np.asarray(r["lam_g"]).ravel(), np.asarray(r["lam_x"]).ravel(), z[:3], lbx, ubx)
    return problem, z[:3], checks, bounds, lbx, ubx


def _newton(least, name, sense):
    problem, x, checks, bounds, lbx, ubx = least
    quantity = problem.scene.built.quantities[name]
    lo, hi = diagnose._range(problem, name, quantity)
    scale = abs(problem.p0[problem.params.index(name)])

    def verified(value, xs):
        return diagnose._holds(problem, name, sense, value, xs, quantity)

    found = {}

    def kept(value, xs):
        found["x"] = xs
        return verified(value, xs)

    value = newton_remedy(problem, name, sense, x, checks, bounds, (lbx, ubx, lo / scale, hi / scale), kept)
    assert value is not None
    current = problem.scene.parameters[name]
    assert (value > current) if sense == "min" else (value < current)     # it relaxes, as named
    return value, problem.to_si(found["x"]), quantity


def test_newton_remedy_is_ipopts(least):
    problem, x, _, _, lbx, ubx = least
    by_newton, _, quantity = _newton(least, "n_rope", "max")
    assert by_newton == pytest.approx(diagnose.free_by_ipopt(problem, "n_rope", "max", quantity, lbx, ubx, x), rel=1e-5)


@pytest.mark.xfail(strict=True, reason="known, open: the remedy is judged on the NLP's time grid (every check holds at "
                   "its points at the value shown), and between them the simulator finds the rope safety short in the "
                   "upward start at 575 m and 1150 m with the named ramp (measured); the remedy needs the exact minima "
                   "between grid points, as the sizing's refinement finds them")
def test_the_named_ramp_gives_a_design_the_simulator_keeps(least):
    from _dynamic_scene import simulated_failures

    problem = least[0]
    t_ramp, design, quantity = _newton(least, "t_ramp", "min")
    shown = float(diagnose.remedy_text("t_ramp", "min", t_ramp, quantity).split()[2])     # s, what the answer says
    v = problem.scene.parameters
    assert v["D"] >= v["D_ratio_min"] * design["d"] * (1 - 1e-9)                         # the drum rule
    assert simulated_failures(problem.scene, design, values={"t_ramp": shown},
                              slip_factor=v.get("n_slip_dynamic")) == []
