"""Units at the edges: parse user values into SI and format SI values for display.

The symbolic core works in N, m, rad, s, W.  A scene or command-line value may be
a bare number (taken as SI) or a string with a unit (``"16 deg"``,
``"5.8 mm/kN"``), parsed with pint and checked against the quantity's dimension.
"""

from __future__ import annotations

import math
from functools import lru_cache

import pint

from ropemodel.errors import InputError

ureg = pint.UnitRegistry()
ureg.formatter.default_format = "~P"


@lru_cache(maxsize=None)
def _unit(unit: str) -> pint.Unit:
    return ureg.Quantity(1.0, unit)


def to_si(name: str, value, si_unit: str) -> float:
    """Return ``value`` of quantity ``name`` as a float in ``si_unit``.

    ``value`` may be a number (already SI), a string such as ``"16 deg"`` or a
    pint Quantity.  Raises :class:`InputError` naming the parameter on a wrong
    dimension, an unparsable string, NaN or inf.
    """
    if isinstance(value, bool):
        raise InputError(f"{name}: expected a number or a value with a unit, got {value!r}")
    if isinstance(value, (int, float)):
        out = float(value)
    else:
        if isinstance(value, str):
            try:
                q = ureg.Quantity(value.strip())
            except Exception as exc:  # pint raises several unrelated types
                raise InputError(f"{name}: cannot read {value!r} as a value with a unit ({exc})") from None
        elif isinstance(value, pint.Quantity):
            q = value
        else:
            raise InputError(f"{name}: expected a number or a value with a unit, got {value!r}")
        target = _unit(si_unit)
        if not isinstance(q, pint.Quantity):  # a bare number in a string
            q = ureg.Quantity(float(q))
        if q.dimensionality != target.dimensionality:
            expected = "a dimensionless number or an angle" if target.dimensionless else str(target.dimensionality)
            raise InputError(f"{name}: {value!r} has dimension {q.dimensionality}, expected {expected} "
                             f"(a value in {si_unit})")
        out = float(q.to(si_unit).magnitude)
    if not math.isfinite(out):
        raise InputError(f"{name}: value must be finite, got {value!r}")
    return out


def factor(si_unit: str, display_unit: str) -> float:
    """Multiply a value in ``si_unit`` by this to express it in ``display_unit``."""
    if si_unit == display_unit:
        return 1.0
    return float(ureg.Quantity(1.0, si_unit).to(display_unit).magnitude)


def label(name: str, unit: str) -> str:
    """Column label with the unit in brackets, e.g. ``F_C [kN]``."""
    return f"{name} [{unit}]" if unit not in ("", "1") else f"{name} [-]"
