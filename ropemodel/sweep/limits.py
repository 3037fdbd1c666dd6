"""What a sweep needs, checked before it starts: work that cannot fit is refused, naming its size.

* **Points**: a grid's points are numbered by int64 indices (``Grid.chunk``): at most 2**63 - 1.
* **Axes**: a ``START:STOP:N`` axis is an array of N values; its N is read first
  (:func:`axis_counts`), so an axis of 1e11 values is refused instead of allocated.
* **Memory**: ``collect=True`` keeps every result (8 bytes a value) in memory.
* **Disk**: a sweep to a file keeps its finished chunks as uncompressed Arrow parts until
  it ends: 8 bytes a value at least, beside the output.

Each limit is a lower bound of the need, so nothing that could fit is refused.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np

from ropemodel.errors import InputError
from ropemodel.sweep.points import grid

INDEX_MAX = int(np.iinfo(np.int64).max)


def axis_counts(vary: dict, quantities: dict) -> dict[str, int]:
    """Number of values of every grid axis, counted before any axis is made: a ``START:STOP:N`` or
    ``(start, stop, n)`` axis is read for its N only (its values are made later, by
    :func:`~ropemodel.sweep.points.grid`, once the size is known to fit)."""
    counts = {}
    for name, spec in vary.items():
        n = _linspace_count(spec)
        if n is None:
            n = len(grid({name: spec}, quantities).axes[name]) if name in quantities else 1
        counts[name] = n
    return counts


def _linspace_count(spec) -> int | None:
    """N of a ``"START:STOP:N"`` or ``(start, stop, n)`` axis (None for other forms, or an N that
    :func:`~ropemodel.sweep.points.parse_axis` will refuse with its own message)."""
    if isinstance(spec, str) and spec.count(":") == 2:
        n = spec.split(":")[2].strip()
    elif isinstance(spec, tuple) and len(spec) == 3 and not isinstance(spec[2], (str, float)):
        n = spec[2]
    else:
        return None
    try:
        n = int(n)
    except (TypeError, ValueError):
        return None
    return n if n >= 1 else None


def _gib(nbytes: float) -> str:
    return f"{nbytes / 2**30:,.1f} GiB"


def available_memory() -> int | None:
    """Bytes of memory this process can still take (Linux: MemAvailable, within a cgroup limit)."""
    avail = None
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    avail = int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    try:
        limit = Path("/sys/fs/cgroup/memory.max").read_text().strip()
        used = int(Path("/sys/fs/cgroup/memory.current").read_text())
        if limit != "max" and avail is not None:
            avail = min(avail, int(limit) - used)
    except (OSError, ValueError):
        pass
    return avail


def check_size(n: int, columns: int, *, axes: dict | None = None, out=None, collect: bool = True) -> None:
    """:class:`InputError` for work that cannot fit, before it starts: more points than an int64
    index, grid axes beyond memory, or ``collect`` results (8 bytes a value) beyond memory."""
    if n > INDEX_MAX:
        raise InputError(f"the grid has {n:,} points, more than an int64 index can number ({INDEX_MAX:,}); "
                         f"sweep fewer points at once")
    mem = available_memory()
    if mem is None:
        return
    for name, count in (axes or {}).items():
        if 16 * count > mem:  # the axis and numpy's temporary while making it
            raise InputError(f"axis {name} has {count:,} values: {_gib(16 * count)} to make it, "
                             f"{_gib(mem)} of memory is available")
    if collect and n * columns * 8 > mem:
        where = "" if out is None else f"; its file {out} is written either way, collect=False returns only its path"
        raise InputError(f"collect=True keeps every result in memory: {n:,} points x {columns} columns need "
                         f"{_gib(n * columns * 8)}, {_gib(mem)} of memory is available{where}")


def check_disk(todo: int, columns: int, out: Path) -> None:
    """:class:`InputError` if ``todo`` points still to compute cannot fit on the disk of ``out``."""
    need = todo * 8 * columns  # the parts alone (uncompressed Arrow, 8 bytes a value): a lower bound
    free = shutil.disk_usage(out.parent).free
    if need > free:
        raise InputError(f"{todo:,} points x {columns} columns need at least {_gib(need)} of disk "
                         f"for the sweep's parts beside {out}; {_gib(free)} is free there")
