"""The points of a sweep: grids (the product of axes) and tables of points.

A sweep varies some *inputs* of a :class:`~ropemodel.problem.Problem` (scene
parameters, or given outputs of an inverse problem).  Its points come from

* a **grid** — ``{name: axis}``; the points are the Cartesian product of the
  axes, first axis slowest (like ``itertools.product``).  An axis is a
  sequence of values (SI numbers or strings with a unit), a ``(start, stop,
  n)`` tuple, or the text ``"START:STOP:N"`` (``"0deg:45deg:1000"``).  The
  grid is never materialised: a chunk of points is computed from its indices,
  so a 1e7-point grid costs no memory up front;
* a **table** — a :class:`pandas.DataFrame` whose columns are input names
  (SI values) or labels with a unit (``"alpha_u [deg]"``, any pint unit of the
  right dimension), one row per point.  A sweep's own output frame can be fed
  back as points.

:func:`check_points` validates every varied input before anything is
computed: its range (vectorised over all values) and the submodels'
cross-parameter rules, naming the parameter, the value and the point.
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ropemodel.errors import InputError
from ropemodel.units import factor, to_si

_LABEL = re.compile(r"^\s*(?P<name>[^\[\]]+?)\s*\[(?P<unit>[^\]]*)\]\s*$")


def parse_axis(name: str, spec, unit: str) -> np.ndarray:
    """One grid axis of quantity ``name`` (SI ``unit``) as an array of SI values.

    ``spec`` is ``"START:STOP:N"`` (START/STOP may carry units, N ≥ 1 points,
    ends included), a ``(start, stop, n)`` tuple, a comma-separated text
    ``"1,2,5"`` or a sequence of values (numbers are SI, strings carry units).
    """
    if isinstance(spec, str):
        text = spec.strip()
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise InputError(f"--vary {name}={spec}: expected START:STOP:N, e.g. {name}=0:1:11")
            return _linspace(name, parts[0], parts[1], parts[2], unit, spec)
        return _values(name, [p for p in text.split(",") if p.strip()], unit, spec)
    if isinstance(spec, tuple) and len(spec) == 3 and not isinstance(spec[2], (str, float)):
        return _linspace(name, spec[0], spec[1], spec[2], unit, spec)
    if np.isscalar(spec):
        return _values(name, [spec], unit, spec)
    return _values(name, list(spec), unit, spec)


def _number(name, value, unit):
    if isinstance(value, str):
        value = value.strip()
        try:
            value = float(value)
        except ValueError:
            pass
    return to_si(name, value, unit)


def _linspace(name, start, stop, n, unit, spec) -> np.ndarray:
    try:
        count = int(str(n).strip())
    except ValueError:
        raise InputError(f"{name}={spec}: the number of points N must be an integer, got {n!r}") from None
    if count < 1:
        raise InputError(f"{name}={spec}: the number of points N must be a positive integer, got {n!r}")
    return np.linspace(_number(name, start, unit), _number(name, stop, unit), count)


def _values(name, values, unit, spec) -> np.ndarray:
    if not values:
        raise InputError(f"{name}={spec!r}: no values")
    out = []
    for v in values:
        if isinstance(v, (np.floating, np.integer)):
            v = float(v)
        out.append(_number(name, v, unit))
    return np.asarray(out, dtype=float)


def split_label(label: str) -> tuple[str, str | None]:
    """``"alpha_u [deg]"`` → ``("alpha_u", "deg")``; ``"alpha_u"`` → ``("alpha_u", None)``."""
    m = _LABEL.match(label)
    if not m:
        return label.strip(), None
    unit = m["unit"].strip()
    return m["name"], ("1" if unit in ("-", "", "1") else unit)


class Points:
    """An ordered set of points: ``n`` points, ``chunk(start, stop)`` → {name: SI array}."""

    names: list[str]
    n: int

    def chunk(self, start: int, stop: int) -> dict[str, np.ndarray]:
        raise NotImplementedError

    def values_of(self, name: str) -> np.ndarray:
        """Every distinct value a varied input takes (for range checks)."""
        raise NotImplementedError

    def fingerprint(self) -> str:
        """A hash of the points (resuming a sweep needs the very same points)."""
        raise NotImplementedError


@dataclass
class Grid(Points):
    """The Cartesian product of ``axes`` (name → SI array), first axis slowest."""

    axes: dict[str, np.ndarray]

    def __post_init__(self):
        self.names = list(self.axes)
        self.shape = tuple(len(a) for a in self.axes.values())
        self.n = int(math.prod(self.shape))

    def chunk(self, start, stop):
        idx = np.unravel_index(np.arange(start, stop, dtype=np.int64), self.shape)
        return {k: a[i] for (k, a), i in zip(self.axes.items(), idx)}

    def values_of(self, name):
        return self.axes[name]

    def index_of(self, name):
        return self.names.index(name)

    def fingerprint(self):
        h = hashlib.sha256(b"grid")
        for k, a in self.axes.items():
            h.update(k.encode())
            h.update(np.ascontiguousarray(a, dtype=float).tobytes())
        return h.hexdigest()


@dataclass
class Table(Points):
    """Explicit points: name → SI array, all of one length."""

    columns: dict[str, np.ndarray]

    def __post_init__(self):
        self.names = list(self.columns)
        lengths = {len(v) for v in self.columns.values()}
        if len(lengths) > 1:
            raise InputError(f"point columns have different lengths: {sorted(lengths)}")
        self.n = lengths.pop() if lengths else 0

    def chunk(self, start, stop):
        return {k: v[start:stop] for k, v in self.columns.items()}

    def values_of(self, name):
        return self.columns[name]

    def fingerprint(self):
        h = hashlib.sha256(b"table")
        for k, a in self.columns.items():
            h.update(k.encode())
            h.update(np.ascontiguousarray(a, dtype=float).tobytes())
        return h.hexdigest()


def grid(vary: dict, quantities: dict) -> Grid:
    """A :class:`Grid` from ``{name: axis spec}`` (see :func:`parse_axis`)."""
    if not vary:
        raise InputError("nothing to vary: give at least one NAME=START:STOP:N or a table of points")
    axes = {}
    for name, spec in vary.items():
        if name not in quantities:
            raise InputError(f"cannot vary {name!r}: not an input of this problem")
        axes[name] = parse_axis(name, spec, quantities[name].unit)
    return Grid(axes)


def table(frame: pd.DataFrame, quantities: dict) -> Table:
    """A :class:`Table` from a DataFrame with input names or ``"name [unit]"`` labels as columns.

    Columns that are not inputs of the problem (e.g. the outputs of an earlier
    sweep fed back) are ignored only if they carry a unit label of a known
    output; any other unknown column is an error, so a typo is not dropped.
    """
    cols = {}
    for col in frame.columns:
        name, unit = split_label(str(col))
        if name not in quantities:
            raise InputError(f"points column {col!r}: {name!r} is not an input of this problem; "
                             f"inputs: {', '.join(quantities)}")
        if name in cols:
            raise InputError(f"points give {name} twice")
        raw = pd.to_numeric(frame[col], errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(raw))
        if bad.size:
            raise InputError(f"points column {col!r}: row {int(bad[0])} is not a finite number "
                             f"({frame[col].iloc[int(bad[0])]!r})")
        si_unit = quantities[name].unit
        f = 1.0 if unit is None else _factor_to_si(col, unit, si_unit)
        cols[name] = raw * f
    return Table(cols)


def _factor_to_si(col, unit, si_unit) -> float:
    try:
        return 1.0 / factor(si_unit, unit)
    except Exception as exc:  # pint raises several types for unknown or incompatible units
        raise InputError(f"points column {col!r}: unit {unit!r} is not a unit of {si_unit} ({exc})") from None


def read_points(path) -> pd.DataFrame:
    """A points table from a CSV or Parquet file."""
    from pathlib import Path

    p = Path(path)
    if not p.exists():
        raise InputError(f"points file not found: {p}")
    if p.suffix.lower() in (".parquet", ".pq"):
        return pd.read_parquet(p)
    if p.suffix.lower() in (".csv", ".txt"):
        return pd.read_csv(p)
    raise InputError(f"points file {p}: expected .csv or .parquet")
