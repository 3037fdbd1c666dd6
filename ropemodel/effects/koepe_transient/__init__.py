"""Braking and starting of a Koepe hoist with elastic head ropes (issue 25, item 3): one module per effect.

Each variant is a :class:`~ropemodel.effects.transient.base.TransientSubmodel` registered for
``model = "koepe"``; :func:`ropemodel.dynamics.simulate` finds them through the registry and assembles them with
the same machinery as the winch's transients (:class:`~ropemodel.dynamics.system.TransientSystem`, the hybrid
integrator).  The effects build **no algebraic equation**: ``ropemodel run`` on a Koepe scene with a transient
still gives the static results.

Modules: :mod:`.profile` (``dynamics``, ``travel``: what the transient is, where it starts, its phases),
:mod:`.control` (``brake_control``: the brake's law; the drive ramp of a start), :mod:`.mesh` (the head ropes
cut into elements, the tail loop), :mod:`.ropes` (``head_elasticity``: the elastic head ropes and the tail
ropes' mass), :mod:`.wheel` (``wheel_contact``: stick and slip on the wheel, the wheel's inertia).
The physics, with every assumption, is docs/physics.md §7, elastic ropes.
"""

from __future__ import annotations

import importlib
import pkgutil

import ropemodel.effects.koepe  # noqa: F401 - the static effects first (they keep their order in every scene)

for _mod in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    importlib.import_module(f"{__name__}.{_mod.name}")
