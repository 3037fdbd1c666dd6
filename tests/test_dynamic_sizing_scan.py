"""A "no design" verdict of dynamic sizing backed by a brute-force search (slow: a few hundred simulations).

The test scene with a 2 s ramp (its 4 s ramp has a design): the scan of the design box
(:func:`optimisation.dynamic.scan.scan_box`) finds no design, and says how fine it was.  Truth, independent of
the sizing package: a grid of its own over the same box — every catalogue diameter, pretensions offset from the
scan's, a 100 m stroke — each point judged by the scene's drum rule (D >= D_ratio_min d, the scene's numbers),
then simulated by the hybrid simulator in the upward start at each place (then the other manoeuvres, if it
survives) and judged by the test's own checks (``_dynamic_scene.simulated_failures``): every point fails a
check.  And on the 4 s ramp the scan finds the catalogue design size dynamic sizing returns."""

from __future__ import annotations

import numpy as np
import pytest
from _dynamic_scene import MANOEUVRES, places, simulated_failures, write_scene

from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.scan import scan_box
from optimisation.problem import load_sizing
from ropemodel.papers import en12385

pytestmark = pytest.mark.slow

STROKE = 100.0           # [m]
F_GRID = np.linspace(5e3, 245e3, 13)       # [N], between the scan's pretensions (8 kN apart from 0)


def scene_with_ramp(tmp_path, ramp: str):
    path = write_scene(tmp_path)
    path.write_text(path.read_text().replace('t_ramp = "4 s"', f't_ramp = "{ramp}"'))
    return load_sizing(path, emit=False)


def keeps_every_check(scene, design: dict) -> bool:
    """Whether ``design`` (SI) keeps every check of ``scene``: the drum rule D >= D_ratio_min d (a static check
    the simulator does not see: the scene's D and rule factor), then the upward start's first 4 s at each place
    (its peaks follow the 2 s ramp: a failure there is a failure; far end first, only to fail sooner), then the
    four manoeuvres in full."""
    v = scene.parameters
    if v["D"] < v["D_ratio_min"] * design["d"]:
        return False
    for x in reversed(places(scene)):
        if simulated_failures(scene, design, manoeuvres=(("start", "up"),), where=[x], t_end=4.0):
            return False
    return not simulated_failures(scene, design, manoeuvres=MANOEUVRES)


@pytest.mark.exhaustive       # 390 points, most simulated: about 3 minutes
def test_no_design_verdict_is_backed_by_a_brute_force_search(tmp_path):
    scene = scene_with_ramp(tmp_path, "2 s")
    scan = scan_box(DynamicSizingProblem(scene))
    assert scan.designs == [] and scan.points == len(en12385.diameters()) * len(scan.grid)
    text = scan.text()
    assert "30 catalogue diameters 8-60 mm" in text and "none keeps every check" in text
    grid = [{"d": d, "F_nwl": float(F), "stroke": STROKE} for d in en12385.diameters() for F in F_GRID]
    assert [design for design in grid if keeps_every_check(scene, design)] == []


def test_the_scan_finds_the_design_that_exists(tmp_path):
    """4 s ramp: the lightest point the scan keeps is the catalogue diameter of the returned design (48 mm,
    ``test_dynamic_sizing_design``), and it holds in the simulator by the test's own checks."""
    scene = scene_with_ramp(tmp_path, "4 s")
    problem = DynamicSizingProblem(scene)
    scan = scan_box(problem)
    assert scan.designs
    best = problem.to_si(scan.designs[0])
    assert best["d"] == pytest.approx(0.048)
    assert simulated_failures(scene, best) == []
