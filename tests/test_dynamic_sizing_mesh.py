"""Dynamic sizing under mesh refinement (issue 23, items 1 and 2), on the dynamic-sizing test scene (Fig. 9,
4 rope elements per span) and on the three-segment route of issue 21 (the default 8 per span).  Slow: one
sizing with its mesh control is minutes of CPU.

Truth: the hybrid simulator (what ``ropemodel simulate`` runs) with 2x and 4x the scene's rope elements and at
the mesh the sizing chose, its histories judged by the tests' own checks (``_dynamic_scene.simulated_failures``)
plus the dynamic slip reserve written here in numpy: e^{mu_d alpha_d} F_slack >= n_slip_dynamic F_tight at
every sample (a rigid lining).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import _route3 as route3
from _dynamic_scene import N_SLIP_DYNAMIC, simulated_failures, write_scene

from optimisation.dynamic import size_dynamic
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.problem import VARIABLES, load_sizing
from ropemodel.cli import main

pytestmark = pytest.mark.slow


def _test_scene(tmp, n=None):
    return write_scene(tmp, name=f"dyn{n}.toml", segments=n or 4)


def _route(tmp, n=None):
    return route3.write(tmp, extra=f"[numerics]\nsegments = {n}\n" if n else "", name=f"route{n}.toml")


SCENES = {"test scene": (_test_scene, 4), "three-segment route": (_route, 8)}


@pytest.fixture(scope="module", params=list(SCENES))
def case(request, tmp_path_factory):
    write, n = SCENES[request.param]
    tmp = tmp_path_factory.mktemp("mesh")
    return write, n, tmp, size_dynamic(load_sizing(write(tmp), emit=False))


def _at(case, n):
    write, _, tmp, _ = case
    return load_sizing(write(tmp, n), emit=False)


@pytest.mark.parametrize("times", [2, 4])
def test_design_holds_with_more_rope_elements(case, times):
    """The catalogue design keeps every check, the dynamic slip factor included, simulated with 2x and 4x the
    scene's elements."""
    _, n, _, design = case
    assert design.feasible, design.message
    assert simulated_failures(_at(case, times * n), design.design, slip_factor=N_SLIP_DYNAMIC) == []


def test_three_percent_less_fails_at_the_converged_mesh(case):
    """3 % less d, F_nwl or stroke (the others kept) than the continuous optimum fails some check in a simulated
    manoeuvre at the mesh the sizing converged to (the load where each manoeuvre is governed), or — where the
    static stroke check is the active one — that static check."""
    _, _, _, design = case
    scene = _at(case, design.mesh["segments"])
    where = sorted({m["x_m"] for m in design.manoeuvres_continuous})
    x = design.continuous
    for k in VARIABLES:
        lighter = {**x, k: 0.97 * x[k]}
        failures = simulated_failures(scene, lighter, where=where, slip_factor=N_SLIP_DYNAMIC)
        if not failures:
            problem = DynamicSizingProblem(scene)
            margins = problem.margins(np.array([lighter[v] for v in VARIABLES]) / problem.x_scale)
            failures = [c for c in problem.static_constraints if margins[c] < 0]
        assert failures, f"3 % less {k} still keeps every check"


def test_mesh_and_factors_are_reported(case):
    """The mesh chosen is at least the scene's, every check active through a manoeuvre has its error estimated,
    the force errors are within the tolerance, each back-off at least the unsafe part of its check's error; the
    slip factors are the scene's static one and the default dynamic one."""
    _, n, _, design = case
    mesh = design.mesh
    assert mesh["segments_scene"] == n and mesh["segments"] >= n and mesh["tolerance"] == 1000.0
    active = {a.split(" @ ")[0].split("[")[0] for a in design.active_continuous if " @ " in a and ", t = " in a}
    assert active and active <= set(mesh["errors"])          # every check active through a manoeuvre estimated
    assert all(e <= 1000.0 for c, e in mesh["errors"].items() if mesh["units"][c] == "N")
    assert all(mesh["backoffs"][c] >= u and u <= mesh["errors"][c] for c, u in mesh["unsafe"].items())
    assert design.slip_factors["n_slip"]["value"] == 1.25
    assert design.slip_factors["n_slip_dynamic"]["value"] == N_SLIP_DYNAMIC


def test_json_reports_the_mesh(tmp_path, capsys):
    """``size --dynamic --json`` on a scene that pins its load (one place: quick) reports the mesh and the
    two slip factors."""
    path = write_scene(tmp_path, 'x_m = "575 m"')
    assert main(["size", str(path), "--dynamic", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["mesh"]["segments"] >= 4 and out["mesh"]["tolerance"] == 1000.0
    assert set(out["mesh"]["errors"]) == set(out["mesh"]["backoffs"])
    assert out["slip_factors"]["n_slip_dynamic"]["value"] == N_SLIP_DYNAMIC
