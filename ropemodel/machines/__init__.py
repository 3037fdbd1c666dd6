"""Machines: what each machine (a ``model`` of the effect registry) declares for the generic drivers.

A machine's physics is its effects (:mod:`ropemodel.effects`); its *declaration* (:class:`Machine`) says what
the generic drivers do with it: what sizing chooses and minimises, which checks it keeps and in which order,
the manoeuvres dynamic sizing takes it through, how its transient is assembled and what it returns, whether it
makes trips, and the report sections its scenes may show.  The drivers (:mod:`optimisation`,
:mod:`ropemodel.dynamics`, :mod:`ropemodel.trips`, :mod:`ropemodel.reports`, :mod:`ropemodel.cli`) read the
declaration of ``scene.model`` from :func:`machine_of` and name no machine themselves.

Importing this package imports every subpackage in it, and each registers its declaration with
:func:`register`.  A new machine is a new subpackage here (CONTRIBUTING.md, "Adding a machine").
"""

from __future__ import annotations

import importlib
import pkgutil

from ropemodel.machines.base import MACHINES, Machine, Transient, default, machine_of, register

__all__ = ["MACHINES", "Machine", "Transient", "default", "machine_of", "register"]

for _mod in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    if _mod.ispkg:
        importlib.import_module(f"{__name__}.{_mod.name}")
