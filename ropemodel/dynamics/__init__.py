"""Time-domain transients of a winch scene: start-up and braking (issue 6).

``simulate(scene)`` builds the lumped model of the rope loop from the effects the scene
picks (:mod:`ropemodel.effects.winch_dynamics`), integrates it with a CasADi BDF
integrator, locates slip/stick and stroke-limit events, and returns a
:class:`Simulation` with the history and a summary (peak force, dynamic factor, slip,
stroke used).  Modules: :mod:`.chain` (masses, weights, resistances, elements),
:mod:`.profile` (drive speed), :mod:`.system` (equations of motion per mode),
:mod:`.hybrid` (event location), :mod:`.history` (results).
"""

from ropemodel.dynamics.history import Simulation
from ropemodel.dynamics.simulate import simulate

__all__ = ["Simulation", "simulate"]
