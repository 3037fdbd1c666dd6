"""Sweeps: a scene evaluated over grids or tables of points, in chunks, resumable.

::

    import ropemodel as rm
    scene = rm.load_scene()
    df = rm.sweep(scene, vary={"alpha_u": "5deg:45deg:1000", "G_m": [300e3, 467e3]},
                  outputs=["F_C_up", "dF_up"])
    df.columns   # ['alpha_u [deg]', 'G_m [kN]', 'F_C_up [kN]', 'dF_up [mm]']
    rm.sweep(scene, vary={...}, out="big.parquet", collect=False)   # chunked, resumable

The package module itself is callable (``ropemodel.sweep(...)`` is
:func:`ropemodel.sweep.runner.sweep`).  Layout: :mod:`.points` (grids and
tables of points), :mod:`.validate` (every point checked before computing),
:mod:`.chunk` (one chunk evaluated by :mod:`ropemodel.core.evaluate` and
checked), :mod:`.store` (chunks on disk, resume), :mod:`.runner` (the
loop, executors, progress bar).
"""

from __future__ import annotations

import sys
import types

from ropemodel.sweep.points import Grid, Table, grid, parse_axis, read_points, table
from ropemodel.sweep.runner import CHUNK, sweep

__all__ = ["CHUNK", "Grid", "Table", "grid", "parse_axis", "read_points", "sweep", "table"]


class _CallableModule(types.ModuleType):
    """``ropemodel.sweep(...)`` calls :func:`sweep`; the package stays importable as a package."""

    def __call__(self, *args, **kwargs):
        return sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
