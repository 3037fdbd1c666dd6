"""The points of a sweep: grids (the product of axes) and tables of points.

A sweep varies some *inputs* of a :class:`~ropemodel.problem.Problem` (scene
parameters, or given outputs of an inverse problem).  Its points come from

* a **grid** — ``{name: axis}``; the points are the Cartesian product of the
  axes, first axis slowest (like ``itertools.product``).  An axis is a
  sequence of values (SI numbers or strings with a unit), a ``(start, stop,
  n)`` tuple, or the text ``"START:STOP:N"`` (``"5deg:45deg:1000"``).  The
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

from ropemodel.errors import InputError, Problems
from ropemodel.units import factor

#: columns a sweep writes besides inputs and outputs (ignored when its output is read back as points)
SWEEP_COLUMNS = ("solved", "invalid")
#: the most points one grid axis and one sweep may have (a sweep of more is several sweeps)
MAX_AXIS = 10**8
MAX_POINTS = 10**10

_LABEL = re.compile(r"^\s*(?P<name>[^\[\]]+?)\s*\[(?P<unit>[^\]]*)\]\s*$")


def parse_axis(name: str, spec, quantity, bare: str = "si") -> np.ndarray:
    """One grid axis of ``quantity`` (a :class:`~ropemodel.quantity.Quantity`) as an array of SI values.

    ``spec`` is ``"START:STOP:N"`` (START and STOP carry units where the quantity has one,
    N ≥ 1 points, ends included), a ``(start, stop, n)`` tuple, a comma-separated text
    ``"1 kN,2 kN,5 kN"`` or a sequence of values.  Text is read as a person typed it: a
    dimensional value needs its unit.  Numbers follow ``bare`` (``"si"``: SI numbers, the
    Python API; ``"refuse"``: only for pure numbers).
    """
    if isinstance(spec, str):
        text = spec.strip()
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise InputError(f"--vary {name}={spec}: expected START:STOP:N, e.g. {name}={_example_axis(quantity)}")
            return _linspace(name, parts[0], parts[1], parts[2], quantity, spec, "refuse")
        items = text.split(",")
        if len(items) > 1 and not all(p.strip() for p in items):
            raise InputError(f"--vary {name}={spec}: an empty value between its commas; list values as "
                             f"{name}=V1,V2,..., e.g. {name}={_example_list(quantity)}")
        return _values(name, [p for p in items if p.strip()], quantity, spec, "refuse")
    if isinstance(spec, tuple) and len(spec) == 3 and not isinstance(spec[2], (str, float)):
        return _linspace(name, spec[0], spec[1], spec[2], quantity, spec, bare)
    if np.isscalar(spec):
        return _values(name, [spec], quantity, spec, bare)
    return _values(name, list(spec), quantity, spec, bare)


def _example_axis(q) -> str:
    unit = "" if q.dimensionless else q.display_unit
    return f"1{unit}:2{unit}:11"


def _example_list(q) -> str:
    unit = "" if q.dimensionless else q.display_unit
    return f"1{unit},2{unit},5{unit}"


def _linspace(name, start, stop, n, quantity, spec, bare) -> np.ndarray:
    try:
        count = int(str(n).strip())
    except ValueError:
        raise InputError(f"{name}={spec}: the number of points N must be a whole number, got {n!r}") from None
    if count < 1:
        raise InputError(f"{name}={spec}: the number of points N must be a positive whole number, got {n!r}")
    if count > MAX_AXIS:
        raise InputError(f"{name}={spec}: {count} points on one axis; at most {MAX_AXIS}")
    lo, hi = (_si(quantity, v, bare) for v in (start, stop))
    return np.linspace(lo, hi, count)


def _values(name, values, quantity, spec, bare) -> np.ndarray:
    if not values:
        raise InputError(f"{name}={spec!r}: no values")
    out = []
    for v in values:
        if isinstance(v, (np.floating, np.integer)):
            v = float(v)
        out.append(_si(quantity, v, bare))
    return np.asarray(out, dtype=float)


def _si(quantity, value, bare) -> float:
    """Text is read as typed (a dimensional value needs its unit); numbers follow ``bare``."""
    return quantity.to_si(value.strip() if isinstance(value, str) else value, bare)


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
        return _digest(b"grid", self.axes)


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
        return _digest(b"table", self.columns)


def _digest(kind: bytes, arrays: dict[str, np.ndarray]) -> str:
    """SHA-256 of ``kind`` and each name with its values (as float64), in order."""
    h = hashlib.sha256(kind)
    for k, a in arrays.items():
        h.update(k.encode())
        h.update(np.ascontiguousarray(a, dtype=float).tobytes())
    return h.hexdigest()


def grid(vary: dict, quantities: dict, bare: str = "si") -> Grid:
    """A :class:`Grid` from ``{name: axis spec}`` (see :func:`parse_axis`); too many points are refused."""
    if not vary:
        raise InputError("nothing to vary: give at least one NAME=START:STOP:N or a table of points")
    axes = {}
    for name, spec in vary.items():
        if name not in quantities:
            raise InputError(f"cannot vary {name!r}: not an input of this problem")
        axes[name] = parse_axis(name, spec, quantities[name], bare)
    n = math.prod(len(a) for a in axes.values())
    if n > MAX_POINTS:
        raise InputError(f"the grid has {n:.3g} points ({' x '.join(str(len(a)) for a in axes.values())}); at most "
                         f"{MAX_POINTS:.0e} points per sweep: split it into several sweeps")
    return Grid(axes)


def table(frame: pd.DataFrame, quantities: dict, ignore=()) -> Table:
    """A :class:`Table` from a DataFrame whose columns are ``"name [unit]"`` labels of inputs.

    A dimensional column needs its unit in brackets (``F_T [N]``) in a file (a frame from
    :func:`read_points`); a pure number may go without (``mu`` or ``mu [-]``).  In a DataFrame
    built in Python, a column named without a unit holds SI values (the Python API's numbers).
    Columns named in ``ignore`` (the outputs of the problem, and the ``solved``/``invalid``
    columns a sweep writes) are left out, so a sweep's own output file is a valid points file.  Every
    problem of every column is listed at once.
    """
    cols, found = {}, Problems()
    if frame.shape[1] == 0 or len(frame) == 0:
        raise InputError("the points table is empty: it needs a header row and at least one row of values")
    for col in frame.columns:
        name, unit = split_label(str(col))
        if name in ignore or name in SWEEP_COLUMNS:
            continue
        if name not in quantities:
            found.add(f"points column {col!r}: {name!r} is not an input of this problem; inputs: "
                      f"{', '.join(quantities)}")
            continue
        if name in cols:
            found.add(f"points give {name} twice")
            continue
        q = quantities[name]
        if unit is None and not q.dimensionless and frame.attrs.get("source"):
            found.add(f"points column {col!r} has no unit: label it with its unit, e.g. "
                      f"\"{name} [{q.display_unit}]\"")
            continue
        with found.collect():
            cols[name] = finite_column(col, frame[col]) * (1.0 if unit is None else _factor_to_si(col, unit, q.unit))
    found.raise_if_any()
    if not cols:
        raise InputError("the points table has no input column")
    return Table(cols)


def finite_column(col, series: pd.Series, what: str = "points column") -> np.ndarray:
    """A column of finite numbers (booleans and text refused, naming the first bad row)."""
    if series.dtype == bool or series.map(lambda v: isinstance(v, (bool, np.bool_))).any():
        raise InputError(f"{what} {col!r} holds true/false values, not numbers")
    try:
        raw = pd.to_numeric(series, errors="coerce").to_numpy(dtype=float)
    except (OverflowError, TypeError, ValueError):  # e.g. a 400-digit integer, which no float holds
        raw = np.array([_float(v) for v in series], dtype=float)
    bad = np.flatnonzero(~np.isfinite(raw))
    if bad.size:
        raise InputError(f"{what} {col!r}: row {int(bad[0]) + 1} is not a finite number "
                         f"({_shown(series.iloc[int(bad[0])])})")
    return raw


def _shown(value) -> str:
    """A cell as a message shows it: an empty cell (read as NaN) as empty, the rest as written (40 characters)."""
    if isinstance(value, (float, np.floating)) and math.isnan(value):
        return "empty, or not a number"
    text = str(value) if isinstance(value, (float, np.floating, int, np.integer)) else repr(value)
    return text[:40] + "..." if len(text) > 40 else text


def _float(value) -> float:
    try:
        return float(value)
    except (OverflowError, TypeError, ValueError):
        return math.nan


def _factor_to_si(col, unit, si_unit) -> float:
    try:
        return 1.0 / factor(si_unit, unit)
    except Exception as exc:  # pint raises several types for unknown or incompatible units
        raise InputError(f"points column {col!r}: unit {unit!r} is not a unit of {si_unit} ({exc})") from None


def read_points(path, what: str = "points file") -> pd.DataFrame:
    """A points table (or another table a person wrote, named ``what`` in messages) from a CSV or
    Parquet file; any unreadable file is one clear error."""
    from pathlib import Path

    p = Path(path)
    try:
        kind = "directory" if p.is_dir() else "file" if p.exists() else None
    except OSError as exc:          # a name too long for the file system, a NUL, a folder that refuses access
        shown = str(p) if len(str(p)) <= 80 else str(p)[:60] + f"... ({len(str(p))} characters)"
        raise InputError(f"{what} {shown} cannot be read: {exc.strerror or exc}") from None
    if kind == "directory":
        raise InputError(f"{what} {p} is a directory")
    if kind is None:
        raise InputError(f"{what} not found: {p}")
    suffix = p.suffix.lower()
    if suffix not in (".parquet", ".pq", ".csv", ".txt"):
        raise InputError(f"{what} {p}: expected .csv or .parquet")
    try:
        frame = pd.read_parquet(p) if suffix in (".parquet", ".pq") else pd.read_csv(p, encoding="utf-8-sig",
                                                                                      on_bad_lines="error")
        frame.attrs["source"] = str(p)   # text a person wrote: dimensional columns need their units
        return frame
    except pd.errors.EmptyDataError:
        raise InputError(f"{what} {p} is empty: it needs a header row and at least one row") from None
    except UnicodeDecodeError:
        raise InputError(f"{what} {p} is not UTF-8 text (a binary file, or another encoding)") from None
    except (pd.errors.ParserError, ValueError, OSError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InputError(f"cannot read {what} {p}: {first}") from None
