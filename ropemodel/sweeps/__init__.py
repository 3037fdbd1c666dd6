"""Sweeps: a scene evaluated over grids or tables of points, in chunks, resumable.

::

    import ropemodel as rm
    scene = rm.load_scene()
    df = rm.sweep(scene, vary={"alpha_u": "5deg:45deg:1000", "G_m": [300e3, 467e3]},
                  outputs=["F_C_up", "dF_up"])
    df.columns   # ['alpha_u [deg]', 'G_m [kN]', 'F_C_up [kN]', 'dF_up [mm]']
    rm.sweep(scene, vary={...}, out="big.parquet", collect=False)   # chunked, resumable

``ropemodel.sweep`` is :func:`ropemodel.sweeps.runner.sweep`.  Layout: :mod:`.points` (grids and
tables of points), :mod:`.validate` (every point checked before computing),
:mod:`.chunk` (one chunk evaluated by :mod:`ropemodel.core.evaluate` and
checked), :mod:`.store` (chunks on disk, resume), :mod:`.runner` (the
loop, executors, progress bar).
"""

from __future__ import annotations

from ropemodel.sweeps.points import Grid, Table, grid, parse_axis, read_points, table
from ropemodel.sweeps.runner import CHUNK, sweep

__all__ = ["CHUNK", "Grid", "Table", "grid", "parse_axis", "read_points", "sweep", "table"]
