"""The wiring of effects: which submodels make up each model.

Importing this package imports every module in it, and each module registers its
effects and variants in :data:`ropemodel.effects.base.REGISTRY`.  A new effect is
a new module here; nothing else needs editing.
"""

from __future__ import annotations

import importlib
import pkgutil

from ropemodel.effects.base import (
    REGISTRY,
    Equation,
    Submodel,
    Symbols,
    all_quantities,
    choice,
    define_effect,
    define_numerics,
    effects_of,
    numerics_of,
    positive_number,
    misplaced,
    models,
    register,
    resolve_effects,
)

__all__ = [
    "REGISTRY",
    "Equation",
    "Submodel",
    "Symbols",
    "all_quantities",
    "choice",
    "define_effect",
    "define_numerics",
    "effects_of",
    "numerics_of",
    "positive_number",
    "models",
    "misplaced",
    "register",
    "resolve_effects",
]

for _mod in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    if _mod.name != "base":
        importlib.import_module(f"{__name__}.{_mod.name}")
