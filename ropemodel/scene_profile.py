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

from ropemodel.errors import InputError, Problems
from ropemodel.units import to_si

#: the columns a profile may have, each pair with the SI unit of each column
FORMS = {("distance", "height"): ("m", "m"), ("length", "inclination"): ("m", "rad")}
_HEADER = re.compile(r"^\s*([A-Za-z_ ]+?)\s*\[\s*([^\]]*?)\s*\]\s*$")
#: at most this many problems are listed from one file (a wrong file lists one per row otherwise)
MAX_LISTED = 20


def read_profile(path: Path, found: Problems) -> tuple[list[float], list[float]]:
    """The segments of the profile file ``path``: (lengths [m], inclinations [rad]), from the drive.

    Every problem (unreadable file, header without units, a cell that is not a finite number, distances that
    do not increase, a step of zero length, too few points) is added to ``found``, naming the file, the line and
    the column; nothing is returned then (two empty lists).
    """
    name = f"route profile {path}"
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except FileNotFoundError:
        found.add(f"{name}: file not found (the path is relative to the scene file)")
        return [], []
    except (OSError, UnicodeDecodeError) as exc:
        found.add(f"{name}: cannot be read as UTF-8 text ({getattr(exc, 'strerror', None) or exc})")
        return [], []
    rows = [(n, r) for n, r in enumerate(csv.reader(text.splitlines()), start=1)
            if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")]
    if not rows:
        found.add(f"{name}: empty; expected a header such as 'distance [m],height [m]' and the points below it")
        return [], []
    mine = Problems()
    out: tuple[list[float], list[float]] = ([], [])
    form = _header(name, rows[0], mine)
    table = _numbers(name, rows[1:], form, mine) if form else []
    if form:    # rows with a bad cell are left out, so that every other problem is named too
        out = _segments(name, form, table, mine)
    for item in mine.items[:MAX_LISTED]:
        found.add(item)
    if len(mine.items) > MAX_LISTED:
        found.add(f"{name}: {len(mine.items) - MAX_LISTED} more problems like these")
    return ([], []) if mine else out


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


def _numbers(name: str, rows, form, found: Problems) -> list[tuple[int, float, float]]:
    """(line, first, second) in SI, in the order of :data:`FORMS`, of the rows whose cells are finite numbers
    (problems added for the others)."""
    key, names, factors = form
    order = sorted(range(2), key=lambda k: key.index(names[k]))    # the file's columns in the form's order
    out = []
    for line, cells in rows:
        if len(cells) != 2:
            found.add(f"{name}, line {line}: {len(cells)} columns, expected 2 ({', '.join(names)})")
            continue
        values = []
        for col, cell in enumerate(cells, start=1):
            try:
                x = float(cell)
            except ValueError:
                x = math.nan
            if not math.isfinite(x):
                found.add(f"{name}, line {line}, column {col} ({names[col - 1]}): {cell.strip()!r} is not a finite "
                          f"number")
            values.append(x * factors[col - 1])
        if all(math.isfinite(x) for x in values):
            out.append((line, values[order[0]], values[order[1]]))
    return out


def _segments(name: str, form, table, found: Problems) -> tuple[list[float], list[float]]:
    """Lengths [m] and inclinations [rad] of the segments (problems added)."""
    key, names, _ = form
    first, second = (f"column {names.index(c) + 1} ({c})" for c in key)
    if key == ("distance", "height"):
        if len(table) < 2:
            points = f"{len(table)} point{'' if len(table) == 1 else 's'}"
            found.add(f"{name}: {points}; a route needs at least 2 (distance, height) points")
            return [], []
        lengths, angles = [], []
        for (_, x0, h0), (line, x1, h1) in zip(table, table[1:]):
            if x1 <= x0:
                what = "a step of zero length" if x1 == x0 else "the distance decreases"
                found.add(f"{name}, line {line}, {first}: {what} ({x1:g} m after {x0:g} m); "
                          f"distances from the drive must increase strictly")
                continue
            lengths.append(math.hypot(x1 - x0, h1 - h0))
            angles.append(math.atan2(h0 - h1, x1 - x0))
        return lengths, angles
    if not table:
        found.add(f"{name}: no segment; a route needs at least one (length, inclination) row")
    for line, length, angle in table:
        if length <= 0.0:
            found.add(f"{name}, line {line}, {first}: {length:g} m; a segment's length must be > 0")
        if not -math.pi / 2 < angle < math.pi / 2:
            found.add(f"{name}, line {line}, {second}: {math.degrees(angle):g} deg; must be between "
                      f"-90 and 90 deg")
    return [t[1] for t in table], [t[2] for t in table]
