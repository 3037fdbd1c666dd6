"""The remedies of a dynamic "no design", found by Newton on the least violation's active set
(:mod:`optimisation.dynamic.remedy`), on the study's "no design" scene (the shipped sizing scene with a 2 s ramp,
4 rope elements per span, 12 s manoeuvres):

* n_rope (its active checks' peaks stay where they are) against a second method: IPOPT on the remedy problem itself
  (max n_rope such that every check of the NLP holds), as the remedies were found before;
* t_ramp (the peaks move: the ramp stretches the start; IPOPT on its remedy problem ends without an answer from the
  least violation's point in 150 iterations, measured) against the hybrid simulator: with the ramp the answer names
  (``diagnose.remedy``: Newton, the checks' exact minima between grid points added), its design keeps every check of
  the four manoeuvres at every place (judged at the grid points only, the named ramp 2.184 s left the upward start's
  rope safety short at 575 m and its dynamic slip reserve at 1150 m, measured), judged by the test's own checks
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
    """Newton's remedy on the NLP's grid: (value [SI], its design [SI], the parameter's quantity)."""
    problem, x, checks, bounds, lbx, ubx = least
    quantity = problem.scene.built.quantities[name]
    lo, hi = diagnose._range(problem, name, quantity)
    scale = abs(problem.p0[problem.params.index(name)])
    found = newton_remedy(problem, name, sense, x, checks, bounds, (lbx, ubx, lo / scale, hi / scale),
                          lambda value, xs: diagnose._holds(problem, name, sense, value, xs, quantity))
    assert found is not None
    value, xs = found
    return _relaxes(problem, name, sense, value), problem.to_si(xs), quantity


def _relaxes(problem, name, sense, value):
    current = problem.scene.parameters[name]
    assert (value > current) if sense == "min" else (value < current)     # it relaxes, as named
    return value


def test_newton_remedy_is_ipopts(least):
    problem, x, _, _, lbx, ubx = least
    by_newton, _, quantity = _newton(least, "n_rope", "max")
    by_ipopt = diagnose.free_by_ipopt(problem, "n_rope", "max", quantity, lbx, ubx, x)
    assert by_ipopt is not None and by_newton == pytest.approx(by_ipopt[0], rel=1e-5)


def _simulated(problem, t_ramp, design, quantity):
    """The hybrid simulator's failures (the test's own checks) with the ramp the answer shows for ``t_ramp``."""
    from _dynamic_scene import simulated_failures

    shown = float(diagnose.remedy_text("t_ramp", "min", t_ramp, quantity).split()[2])     # s, what the answer says
    v = problem.scene.parameters
    assert v["D"] >= v["D_ratio_min"] * design["d"] * (1 - 1e-9)                         # the drum rule
    return simulated_failures(problem.scene, design, values={"t_ramp": shown}, slip_factor=v.get("n_slip_dynamic"))


def test_the_named_ramp_gives_a_design_the_simulator_keeps(least):
    problem, x, checks, bounds, lbx, ubx = least
    quantity = problem.scene.built.quantities["t_ramp"]
    found = diagnose.remedy(problem, "t_ramp", "min", quantity, (checks, bounds, x), (lbx, ubx))
    assert found is not None
    assert _simulated(problem, _relaxes(problem, "t_ramp", "min", found[0]), problem.to_si(found[1]), quantity) == []


def test_a_ramp_judged_at_the_grid_points_alone_is_short_between_them(least):
    """Why the remedy adds the checks' exact minima: Newton's ramp on the NLP's grid alone leaves checks of the upward
    start short between its points (the simulator's verdict; measured: the rope safety at 575 m, the dynamic slip
    reserve at 1150 m), so the test above can fail."""
    t_ramp, design, quantity = _newton(least, "t_ramp", "min")
    failures = _simulated(least[0], t_ramp, design, quantity)
    assert failures and all(" in the up start at " in f for f in failures), failures
