"""A "no design" verdict of dynamic sizing backed by a brute-force search (slow: a few hundred simulations).

The test scene with a 2 s ramp (its 4 s ramp has a design): the scan of the design box
(:func:`optimisation.dynamic.scan.scan_box`) finds no design, and says how fine it was.  Truth, independent of
the sizing package: a grid of its own over the same box — every catalogue diameter, pretensions offset from the
scan's, a 100 m stroke — each point simulated by the hybrid simulator in the upward start (then the other
manoeuvres, if it survives) and judged by the test's own checks (``_dynamic_scene.simulated_failures``): every
point fails a check.  And on the 4 s ramp the scan finds the catalogue design size dynamic sizing returns."""

from __future__ import annotations

import numpy as np
import pytest
from _dynamic_scene import MANOEUVRES, simulated_failures, write_scene

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


def test_no_design_verdict_is_backed_by_a_brute_force_search(tmp_path):
    scene = scene_with_ramp(tmp_path, "2 s")
    scan = scan_box(DynamicSizingProblem(scene))
    assert scan.designs == [] and scan.points == len(en12385.diameters()) * len(scan.F_nwl)
    text = scan.text()
    assert "30 catalogue diameters 8-60 mm" in text and "none keeps every check" in text
    survivors = []
    for d in en12385.diameters():
        for F in F_GRID:
            design = {"d": d, "F_nwl": float(F), "stroke": STROKE}
            # a failure within the first 4 s is a failure: the full manoeuvres only for a point that survives them
            failed = simulated_failures(scene, design, manoeuvres=(("start", "up"),), where=[0.0], t_end=4.0)
            if not failed:
                failed = simulated_failures(scene, design, manoeuvres=MANOEUVRES)
            if not failed:
                survivors.append(design)
    assert survivors == []


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
