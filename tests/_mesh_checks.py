"""Dynamic sizing under mesh refinement (issue 23, items 1 and 2): the checks the test scene's slow tests
(``test_dynamic_sizing_design``) and the three-segment route's (``test_dynamic_sizing_route``) make of the
design each module sizes once (a sizing with its mesh control is minutes of CPU: sizing each scene again
here would double it).

Truth: the hybrid simulator (what ``ropemodel simulate`` runs) with more rope elements than the scene's and at
the mesh the sizing chose, its histories judged by the tests' own checks (``_dynamic_scene.simulated_failures``)
plus the dynamic slip reserve written there in numpy: e^{mu_d alpha_d} F_slack >= n_slip_dynamic F_tight at
every sample (a rigid lining).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from _dynamic_scene import MANOEUVRES, N_SLIP_DYNAMIC, simulated_failures

from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.problem import VARIABLES


def failures_with_elements(scene_with: Callable[[int], object], design, n: int, everywhere: bool = True) -> list[str]:
    """The catalogue design simulated with ``n`` rope elements per span (``scene_with(n)``: the scene so
    meshed): what fails, the dynamic slip factor included.  ``everywhere``: every manoeuvre at every place of
    the load, else each manoeuvre with the load where it is governed at the scene's mesh (a fine mesh on a
    long route costs ~10 CPU-s a simulation).  Each manoeuvre is followed as long as the sizing followed it (a
    scene without a transient gives no ``t_end``: the sizing's default)."""
    scene, t_end = scene_with(n), design.scene.parameters["t_end"]
    if everywhere:
        return simulated_failures(scene, design.design, t_end=t_end, slip_factor=N_SLIP_DYNAMIC)
    labels = [f"{'upward' if travel == 'up' else 'downward'} {dynamics}" for dynamics, travel in MANOEUVRES]
    assert [m["manoeuvre"] for m in design.manoeuvres] == labels
    return [f for m, manoeuvre in zip(design.manoeuvres, MANOEUVRES)
            for f in simulated_failures(scene, design.design, where=[m["x_m"]], manoeuvres=[manoeuvre],
                                        t_end=t_end, slip_factor=N_SLIP_DYNAMIC)]


def lighter_that_holds(scene, design) -> list[str]:
    """The design variables of which 3 % less than the continuous optimum (the others kept) still keeps every
    check: simulated on ``scene`` (at the mesh the sizing converged to) with the load where each manoeuvre
    is governed, or, where no manoeuvre fails, the static checks (the static stroke check can be the active
    one).  [] for a tight optimum."""
    where = sorted({m["x_m"] for m in design.manoeuvres_continuous})
    x, holds = design.continuous, []
    for k in VARIABLES:
        lighter = {**x, k: 0.97 * x[k]}
        failures = simulated_failures(scene, lighter, where=where, t_end=design.scene.parameters["t_end"],
                                      slip_factor=N_SLIP_DYNAMIC)
        if not failures:
            problem = DynamicSizingProblem(scene)
            margins = problem.margins(np.array([lighter[v] for v in VARIABLES]) / problem.x_scale)
            failures = [c for c in problem.static_constraints if margins[c] < 0]
        if not failures:
            holds.append(k)
    return holds


def mesh_record_problems(design, n: int, n_slip: float) -> list[str]:
    """What is wrong with the design's record of its mesh and slip factors (scene's ``n`` elements per span,
    static slip factor ``n_slip``): the mesh at least the scene's, every check active through a manoeuvre
    estimated, the force errors within the default tolerance, each back-off at least the unsafe part of its
    check's error, the slip factors the scene's static one and the default dynamic one."""
    mesh, out = design.mesh, []
    if not (mesh["segments_scene"] == n and mesh["segments"] >= n and mesh["tolerance"] == 1000.0):
        out.append(f"mesh {mesh['segments']} from {mesh['segments_scene']} at tolerance {mesh['tolerance']}")
    active = {a.split(" @ ")[0].split("[")[0] for a in design.active_continuous if " @ " in a and ", t = " in a}
    if not active or not active <= set(mesh["errors"]):
        out.append(f"active checks {active} not all estimated: {set(mesh['errors'])}")
    out += [f"{c}: error {e} N above 1 kN" for c, e in mesh["errors"].items() if mesh["units"][c] == "N" and e > 1e3]
    out += [f"{c}: back-off {mesh['backoffs'][c]} below the unsafe part {u} of {mesh['errors'][c]}"
            for c, u in mesh["unsafe"].items() if not mesh["backoffs"][c] >= u or u > mesh["errors"][c]]
    factors = {k: v["value"] for k, v in design.slip_factors.items()}
    if factors != {"n_slip": n_slip, "n_slip_dynamic": N_SLIP_DYNAMIC}:
        out.append(f"slip factors {factors}")
    return out
