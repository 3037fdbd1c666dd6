"""The report's sections, one module per group; the page shows them in the order of :data:`MODULES`.

A new section is a module here with one or more functions decorated by
:func:`ropemodel.reports.registry.section`, and its name in :data:`MODULES` where it belongs.
"""

from __future__ import annotations

import importlib

#: section modules in page order
MODULES = ("document", "scene", "inputs", "rules", "basis", "equations", "results", "sizing", "transient", "trip",
           "dynamic_sizing", "sensitivity", "references")


def load_all() -> None:
    """Import every section module (each registers its sections once)."""
    for name in MODULES:
        importlib.import_module(f"{__name__}.{name}")
