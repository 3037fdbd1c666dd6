"""Simulate the transient of a Koepe scene (``dynamics = "braking"`` or ``"start"``, issue 25 item 3).

The scene's transient variants (:mod:`ropemodel.effects.koepe_transient`, found through the effect registry)
are bound to a :class:`~ropemodel.effects.transient.base.Setup` and assembled by the same
:class:`~ropemodel.dynamics.system.TransientSystem` and :class:`~ropemodel.dynamics.hybrid.HybridIntegrator` as
the winch's: CasADi's BDF integrator (cvodes) between events at ``[numerics] sim_rtol`` (default 1e-8), the slip
and stick events located by root finding (:mod:`ropemodel.dynamics.hybrid`).  The static model
(:func:`ropemodel.problem.run`) gives the values the transient starts from.
"""

from __future__ import annotations

from collections.abc import Mapping

from ropemodel.dynamics.assemble import chosen
from ropemodel.dynamics.koepe_history import KoepeSimulation
from ropemodel.dynamics.simulate import SIMULATORS, integrate
from ropemodel.dynamics.system import TransientSystem
from ropemodel.effects.koepe_transient.profile import KoepeProfile
from ropemodel.effects.transient.base import Setup, TransientSubmodel
from ropemodel.errors import InputError
from ropemodel.problem import run
from ropemodel.scene import SceneLike, as_scene


def build(scene) -> TransientSystem:
    """The transient system of a Koepe ``scene`` at its numbers."""
    submodels = chosen(scene)
    parts = sorted((sm for sm in submodels.values() if isinstance(sm, TransientSubmodel)), key=lambda p: p.order)
    if not any(isinstance(p, KoepeProfile) for p in parts):
        raise InputError(f'scene {scene.name!r} has no transient: set [effects] dynamics = "braking" or "start"')
    static = run(scene)
    values = {k: float(v) for k, v in static.values.items()}
    setup = Setup(values, dict(values), dict(scene.numerics), {p.effect: p for p in parts}, submodels)
    setup.v_scale = max(float(values["v_max"]), 1e-6)
    setup.f_scale = max(float(values["T_max"]), 1.0)
    for p in parts:
        p.bind(setup)
    return TransientSystem(setup, parts)


def simulate(scene: SceneLike, values: Mapping | None = None, progress: bool | None = None) -> KoepeSimulation:
    """Simulate the braking or start of a Koepe scene; arguments as :func:`ropemodel.dynamics.simulate`.

    The absolute tolerance of the integrator is sim_rtol/10 of the least steady stretch of a head-rope element
    (the states are lengths, speeds and energies; the stretch is the smallest length that matters).

    Examples
    --------
    >>> sim = simulate("koepe_braking", progress=False)
    >>> sim.summary["slip"], sim.summary["dynamics"], sim.summary["brake_control"]
    (False, 'braking', 'torque')
    """
    from ropemodel.progress import status

    scene = as_scene(scene)
    if values:
        scene = scene.with_values(values)
    with status(f"simulating {scene.name}: building the transient", progress):
        system = build(scene)
        x0, mode = system.initial()
    num = scene.numerics
    mesh = system.setup.part("head_elasticity").mesh
    atol = num["sim_rtol"] * 0.1 * max(float(mesh.e0.min()), 1e-9)
    return integrate(KoepeSimulation(scene, system), system, x0, mode, atol, progress)


SIMULATORS["koepe"] = simulate
