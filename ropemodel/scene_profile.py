"""A route read from a surveyed profile: a CSV file of two columns with their units in the header.

A scene with ``[effects] route = "segments"`` gives its segments either as ``[[route]]`` tables or as
``[route_profile] file = "incline.csv"`` (a path relative to the scene file).  The file holds one of:

* ``distance [m],height [m]``: points of the route from the drive (the first row, at the guiding sheave
  K_K) toward the return sheave; ``distance`` is the horizontal distance from the drive (chainage, as a
  survey gives it), strictly increasing, ``height`` the elevation.  Each step between two points is a
  straight segment of length L_i = √(Δx² + Δh²) and inclination α_i = atan2(h_{i−1} − h_i, Δx) (> 0:
  rising toward the drive, the convention of ``[[route]]``).  At least 2 points.
* ``length [m],inclination [deg]``: one row per segment, from the drive, as ``[[route]]`` tables would
  give them (length > 0, −90° < inclination < 90°).  At least 1 row.

Units are any of length (``m``, ``km``, ``ft``) and angle (``deg``, ``rad``; a grade in % is not an angle and
is refused).  Blank lines and lines starting with ``#`` are skipped; a UTF-8 byte-order mark is accepted.
Every problem of the file is named at once, with its line and column (:func:`read_profile`).  The segments
become the parameters ``L_i``, ``alpha_i`` of ``[[route]]`` segment i, so every command takes them alike.
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import numpy as np

from ropemodel.errors import InputError, Problems
from ropemodel.units import to_si

#: the columns a profile may have, each pair with the SI unit of each column
FORMS = {("distance", "height"): ("m", "m"), ("length", "inclination"): ("m", "rad")}
_HEADER = re.compile(r"^\s*([A-Za-z_ ]+?)\s*\[\s*([^\]]*?)\s*\]\s*$")
#: at most this many problems are listed from one file (a wrong file lists one per row otherwise)
MAX_LISTED = 20
#: no segment (the file's problems are said)
_NONE = (np.empty(0), np.empty(0))


def read_profile(path: Path, found: Problems) -> tuple[np.ndarray, np.ndarray]:
    """The segments of the profile file ``path``: (lengths [m], inclinations [rad]), from the drive.

    Every problem (unreadable file, header without units, a cell that is not a finite number or is beyond the
    largest float once in SI, distances that do not increase, a step of zero length, too few points) is added to
    ``found``, naming the file, the line and the column; nothing is returned then (two empty arrays).  Each column
    is converted to SI at once, and the segments' checks run on the arrays.
    """
    name = f"route profile {path}"
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except FileNotFoundError:
        found.add(f"{name}: file not found (the path is relative to the scene file)")
        return _NONE
    except (OSError, UnicodeDecodeError) as exc:
        found.add(f"{name}: cannot be read as UTF-8 text ({getattr(exc, 'strerror', None) or exc})")
        return _NONE
    rows = [(n, r) for n, r in enumerate(csv.reader(text.splitlines()), start=1)
            if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")]
    if not rows:
        found.add(f"{name}: empty; expected a header such as 'distance [m],height [m]' and the points below it")
        return _NONE
    mine = Problems()
    out = _NONE
    form = _header(name, rows[0], mine)
    if form:    # rows with a bad cell are left out, so that every other problem is named too
        out = _segments(name, form, _numbers(name, rows[1:], form, mine), mine)
    for item in mine.items[:MAX_LISTED]:
        found.add(item)
    if len(mine.items) > MAX_LISTED:
        found.add(f"{name}: {len(mine.items) - MAX_LISTED} more problems like these")
    return _NONE if mine else out


def _header(name: str, row: tuple[int, list[str]], found: Problems):
    """(the form, a key of :data:`FORMS`; the column names in the file's order; the factor to SI of each
    column) from the header row, or None (problems added)."""
    line, cells = row
    parsed = [_HEADER.match(c) for c in cells]
    names = tuple(m.group(1).strip().lower() if m else c.strip().lower() for m, c in zip(parsed, cells))
    form = next((f for f in FORMS if sorted(f) == sorted(names)), None)
    if form is None:
        found.add(f"{name}, line {line}: header {','.join(cells)!r}; expected two columns with their units, "
                  f"'distance [m],height [m]' or 'length [m],inclination [deg]'")
        return None
    factors = []
    for col, (m, column) in enumerate(zip(parsed, names), start=1):
        si = FORMS[form][form.index(column)]
        if m is None or not m.group(2):
            found.add(f"{name}, line {line}, column {col} ({column}): no unit; write e.g. "
                      f"'{column} [{'m' if si == 'm' else 'deg'}]'")
            continue
        try:
            factors.append(to_si(column, f"1 {m.group(2)}", si))
        except InputError:
            what = ("a length (m, km, ft)" if si == "m" else
                    "an angle (deg or rad; a grade in % is not one: alpha = atan(grade/100))")
            found.add(f"{name}, line {line}, column {col} ({column}): unit [{m.group(2)}] is not {what}")
    return (form, names, tuple(factors)) if len(factors) == 2 else None


def _numbers(name: str, rows, form, found: Problems) -> tuple[list[int], np.ndarray, np.ndarray]:
    """(lines, first, second): the rows whose cells are finite numbers, their lines and their two columns in SI, in
    the order of :data:`FORMS`, each column converted at once (problems added for the other rows)."""
    key, names, factors = form
    lines: list[int] = []
    columns: tuple[list[float], list[float]] = ([], [])
    for line, cells in rows:
        if len(cells) != 2:
            found.add(f"{name}, line {line}: {len(cells)} columns, expected 2 ({', '.join(names)})")
            continue
        values = [_finite(cell) for cell in cells]
        for col, (cell, x) in enumerate(zip(cells, values), start=1):
            if x is None:
                found.add(f"{name}, line {line}, column {col} ({names[col - 1]}): {cell.strip()!r} is not a finite "
                          f"number")
        first, second = values
        if first is not None and second is not None:
            lines.append(line)
            columns[0].append(first)
            columns[1].append(second)
    with np.errstate(over="ignore"):      # a value beyond the largest float in SI is named below
        si = [np.array(c, dtype=float) * f for c, f in zip(columns, factors)]     # one conversion per column
    order = sorted(range(2), key=lambda k: key.index(names[k]))    # the file's columns in the form's order
    kept = np.isfinite(si[0]) & np.isfinite(si[1])
    for k in np.flatnonzero(~kept):
        for col in (0, 1):
            if not math.isfinite(si[col][k]):
                found.add(f"{name}, line {lines[k]}, column {col + 1} ({names[col]}): {columns[col][k]!r} is beyond "
                          f"the largest float once in SI")
    return [line for line, ok in zip(lines, kept) if ok], si[order[0]][kept], si[order[1]][kept]


def _finite(cell: str) -> float | None:
    """The number in ``cell``, or None where it is not a finite one."""
    try:
        x = float(cell)
    except ValueError:
        return None
    return x if math.isfinite(x) else None


def _segments(name: str, form, table, found: Problems) -> tuple[np.ndarray, np.ndarray]:
    """Lengths [m] and inclinations [rad] of the segments (problems added)."""
    key, names, _ = form
    lines, a, b = table        # the two columns in the order of FORMS (distance, height or length, inclination)
    first, second = (f"column {names.index(c) + 1} ({c})" for c in key)
    if key == ("distance", "height"):
        if len(lines) < 2:
            points = f"{len(lines)} point{'' if len(lines) == 1 else 's'}"
            found.add(f"{name}: {points}; a route needs at least 2 (distance, height) points")
            return _NONE
        dx, fall = a[1:] - a[:-1], b[:-1] - b[1:]
        for k in np.flatnonzero(dx <= 0.0):
            what = "a step of zero length" if dx[k] == 0.0 else "the distance decreases"
            found.add(f"{name}, line {lines[k + 1]}, {first}: {what} ({a[k + 1]:g} m after {a[k]:g} m); "
                      f"distances from the drive must increase strictly")
        # math's hypot and atan2, not numpy's: numpy's differ in the last bit at a few points in 10 000
        return (np.array(list(map(math.hypot, dx.tolist(), fall.tolist()))),
                np.array(list(map(math.atan2, fall.tolist(), dx.tolist()))))
    if not lines:
        found.add(f"{name}: no segment; a route needs at least one (length, inclination) row")
    for k in np.flatnonzero((a <= 0.0) | ~((-math.pi / 2 < b) & (b < math.pi / 2))):
        if a[k] <= 0.0:
            found.add(f"{name}, line {lines[k]}, {first}: {a[k]:g} m; a segment's length must be > 0")
        if not -math.pi / 2 < b[k] < math.pi / 2:
            found.add(f"{name}, line {lines[k]}, {second}: {math.degrees(b[k]):g} deg; must be between "
                      f"-90 and 90 deg")
    return a, b
