"""Start-up and braking transients of a winch scene: one module per effect, each variant a
:class:`~ropemodel.effects.transient.base.TransientSubmodel` that owns its behaviour.

Importing this package imports every module in it (each registers its effects and variants), so a
new transient variant is a new module here; :func:`ropemodel.dynamics.simulate` finds it through the
registry.  The effects build **no algebraic equation**: the static model (Krauze et al. 2025,
:mod:`ropemodel.effects.winch`) stays exactly as it is, and ``ropemodel run`` on a dynamic scene still
gives the static forces.  Moving masses: the load G_m/g, the rope q_l·L_u/g of each side (lumped on
the nodes), the return sheave's carriage m_t (constant-force tensioner) and, with a torque-limited
drive, the drum, gearing and motor m_drive (reduced to the rim); with a speed drive the drum's speed
is prescribed and its inertia does not enter the rope forces.

Modules: :mod:`.base` (the protocol), :mod:`.profile` (``dynamics``), :mod:`.ramp`, :mod:`.travel`,
:mod:`.rope` (``rope_elasticity``; the loop in :mod:`.chain`, its loads from :mod:`.route`),
:mod:`.tensioner`, :mod:`.drive`, :mod:`.contact` and :mod:`.capstan` (``drum_contact``),
:mod:`.options` (``[numerics]``).
"""

from __future__ import annotations

import importlib
import pkgutil

import ropemodel.effects.winch  # noqa: F401 - the static effects first (they keep their order in every scene)

for _mod in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    importlib.import_module(f"{__name__}.{_mod.name}")
