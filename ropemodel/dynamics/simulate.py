"""Simulate the transient of a winch scene: assemble it from the variants the scene picks, integrate it."""

from __future__ import annotations

from ropemodel.dynamics.assemble import build
from ropemodel.dynamics.history import Simulation
from ropemodel.dynamics.hybrid import HybridIntegrator


def simulate(scene, values: dict | None = None) -> Simulation:
    """Simulate the transient of a scene with a transient (``dynamics = "start"`` or ``"stop"``).

    ``values`` override scene parameters (SI numbers or unit strings).  Returns a
    :class:`~ropemodel.dynamics.history.Simulation` (history DataFrame, summary, events).
    Raises :class:`~ropemodel.errors.InputError` for a scene without a transient or one that cannot
    start (e.g. a slack rope), :class:`~ropemodel.errors.SolveError` if the integration fails.
    """
    if values:
        scene = scene.with_values(values)
    system = build(scene)
    x0, mode = system.initial()
    num, nums = scene.numerics, system.setup.numbers
    atol = num["sim_rtol"] * 1e-1 * max(nums["L_u"] * nums["q_lw"] * system.setup.f_scale, 1e-9)
    sim = Simulation(scene, system)
    events = HybridIntegrator(system, num["sim_rtol"], num["sim_dt"], num["sim_integrator"], atol).run(
        x0, mode, sim.record)
    sim.finish(events)
    return sim
