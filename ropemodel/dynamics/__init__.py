"""Time-domain transients of a scene: start-up and braking (what each machine declares:
:class:`ropemodel.machines.Transient`).

``simulate(scene)`` assembles the transient from the variants the scene picks (each a
:class:`~ropemodel.effects.transient.base.TransientSubmodel` of :mod:`ropemodel.effects.transient`,
found through the effect registry), integrates it with a CasADi BDF integrator, locates its state
events (slip/stick, stroke limits, the motor's torque limit, a slack rope) and returns a
:class:`Simulation` with the history and a summary (peak force, dynamic factor, slip, stroke used).
``smooth_mode(scene, params)`` gives the smooth regime's ODE as CasADi Functions of symbolic
parameters (for dynamic sizing).  Modules: :mod:`.assemble` (the scene's variants),
:mod:`.system` (equations per mode, initial state, events), :mod:`.hybrid` and :mod:`.detect`
(integration and event location), :mod:`.history` (results), :mod:`.smooth` (the symbolic smooth mode).
"""

from ropemodel.dynamics.history import Simulation
from ropemodel.dynamics.simulate import simulate
from ropemodel.dynamics.smooth import SmoothMode, smooth_mode

__all__ = ["Simulation", "SmoothMode", "simulate", "smooth_mode"]
