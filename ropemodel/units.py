"""Units at the edges: read a value with its unit into SI, and express SI values in display units.

The symbolic core works in N, m, rad, s, W.  A value a person types (in a scene
file, on the command line, in a column header) carries its unit: ``"16 deg"``,
``"5.8 mm/kN"``, ``"1150.00 m"``, ``"16 °"``.  A bare number is accepted only
for a dimensionless quantity; for any other it is refused with the fix
(``G_m = 300 has no unit; write e.g. "300 kN"``), because guessing SI turns
``G_m = 300`` into 300 N and exits 0 with a wrong answer.  Angles count as
dimensional here: ``alpha_u = 16`` could mean 16 rad or 16 deg.

The Python API also takes SI floats where it says so (``bare="si"``) and pint
Quantities (duck-typed: pint itself is not imported).

Why not pint: importing pint and building its registry costs 1.5-2 times the
whole ``import casadi`` (``studies/startup.py`` measures it), which alone breaks the
start-up goal of the command line; the units a rope-drive engineer types form a
small closed set, parsed here in a few dozen lines.

Grammar: ``NUMBER [UNIT]`` with UNIT a product or quotient of names with an
optional SI prefix and an integer power (``kN/mm^2``, ``N·m``, ``kg/m³``, ``1/N``,
``MPa*s``, ``m/s**2``); a reciprocal may also be written as pint prints it, ``/ N`` (``"1e-5 / N"``);
``%`` is 0.01; an angle may be given in ``turn``/``turns`` (2π rad) or ``rev``.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache

from ropemodel.errors import InputError, suggest

# dimension vectors: (mass, length, time, angle, temperature)
_M, _L, _T, _A, _K = (1, 0, 0, 0, 0), (0, 1, 0, 0, 0), (0, 0, 1, 0, 0), (0, 0, 0, 1, 0), (0, 0, 0, 0, 1)
_ONE = (0, 0, 0, 0, 0)


def _dim(*pairs) -> tuple[int, ...]:
    out = [0, 0, 0, 0, 0]
    for base, power in pairs:
        for i, b in enumerate(base):
            out[i] += b * power
    return tuple(out)


_FORCE = _dim((_M, 1), (_L, 1), (_T, -2))
#: unit name → (factor to SI, dimension, takes an SI prefix)
UNITS: dict[str, tuple[float, tuple[int, ...], bool]] = {
    "m": (1.0, _L, True),
    "ft": (0.3048, _L, False),                               # international foot (US rules write lengths in ft)
    "g": (1e-3, _M, True),
    "t": (1e3, _M, False),                                   # tonne
    "s": (1.0, _T, True),
    "min": (60.0, _T, False),
    "h": (3600.0, _T, False),
    "N": (1.0, _FORCE, True),
    "kgf": (9.80665, _FORCE, False),
    "Pa": (1.0, _dim((_FORCE, 1), (_L, -2)), True),
    "bar": (1e5, _dim((_FORCE, 1), (_L, -2)), True),
    "J": (1.0, _dim((_FORCE, 1), (_L, 1)), True),
    "Wh": (3600.0, _dim((_FORCE, 1), (_L, 1)), True),
    "W": (1.0, _dim((_FORCE, 1), (_L, 1), (_T, -1)), True),
    "rad": (1.0, _A, True),
    "deg": (math.pi / 180.0, _A, False),
    "°": (math.pi / 180.0, _A, False),
    "rev": (2.0 * math.pi, _A, False),
    "turn": (2.0 * math.pi, _A, False),                      # a wrap angle: 1.5 turns = 540 deg
    "turns": (2.0 * math.pi, _A, False),
    "rpm": (2.0 * math.pi / 60.0, _dim((_A, 1), (_T, -1)), False),
    "%": (0.01, _ONE, False),
    "K": (1.0, _K, False),                                   # a temperature difference (kelvin)
    "Nm": (1.0, _dim((_FORCE, 1), (_L, 1)), True),           # torque, as catalogues print it
}
PREFIXES = {"p": 1e-12, "n": 1e-9, "u": 1e-6, "µ": 1e-6, "μ": 1e-6, "m": 1e-3, "c": 1e-2, "d": 1e-1,
            "da": 1e1, "h": 1e2, "k": 1e3, "M": 1e6, "G": 1e9, "T": 1e12}
_SUPERSCRIPT = {"²": "^2", "³": "^3", "⁻¹": "^-1", "⁻²": "^-2"}
_NUMBER = re.compile(r"^\s*(?P<num>[+-]?(?:(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?|(?:inf(?:inity)?|nan)(?![A-Za-z])))"
                     r"\s*(?P<unit>.*?)\s*$", re.I)
_TOKEN = re.compile(r"\s*(?:(?P<name>[A-Za-zµμ°%]+)|(?P<one>1)(?![\d.eE])|(?P<op>\*\*|[*·/^()])"
                    r"|(?P<num>\d+\.\d*(?:[eE][+-]?\d+)?|\d+[eE][+-]?\d+)|(?P<int>[+-]?\d+))")


class UnitError(ValueError):
    """A unit expression that cannot be read (message names the problem)."""


@lru_cache(maxsize=512)
def _name(name: str) -> tuple[float, tuple[int, ...]]:
    if name in UNITS:
        f, d, _ = UNITS[name]
        return f, d
    for p in sorted(PREFIXES, key=len, reverse=True):
        base = name[len(p):]
        if name.startswith(p) and base in UNITS and UNITS[base][2]:
            f, d, _ = UNITS[base]
            return PREFIXES[p] * f, d
    raise UnitError(f"unknown unit {name!r}{suggest(name, UNITS)}")


@lru_cache(maxsize=512)
def parse_unit(text: str) -> tuple[float, tuple[int, ...]]:
    """(factor to SI, dimension) of a unit expression such as ``"kN/mm^2"``, ``"N·m"`` or ``"/ N"`` (a
    reciprocal as pint prints it, ``1/N``).

    >>> parse_unit("/ N") == parse_unit("1/N")
    True
    """
    for sup, rep in _SUPERSCRIPT.items():
        text = text.replace(sup, rep)
    text = text.strip()
    if text.startswith("/"):            # "1e-5 / N": pint's way of writing a reciprocal unit
        text = "1" + text
    tokens, pos = [], 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos or m.lastgroup is None:
            raise UnitError(f"cannot read the unit {text!r} at {text[pos:]!r}")
        tokens.append((m.lastgroup, m.group(m.lastgroup)))
        pos = m.end()
    factor, dim, rest = _product(tokens, 0)
    if rest != len(tokens):
        raise UnitError(f"cannot read the unit {text!r}")
    return factor, dim


def _product(tokens, i):
    """product := power (('*' | '·' | '/' | juxtaposition) power)*"""
    factor, dim, i = _power(tokens, i)
    while i < len(tokens) and tokens[i] != ("op", ")"):
        op = tokens[i][1] if tokens[i][0] == "op" and tokens[i][1] in "*·/" else "*"
        if tokens[i][0] == "op" and tokens[i][1] in "*·/":
            i += 1
        f, d, i = _power(tokens, i)
        sign = -1 if op == "/" else 1
        factor *= f ** sign
        dim = tuple(a + sign * b for a, b in zip(dim, d))
    return factor, dim, i


def _power(tokens, i):
    if i >= len(tokens):
        raise UnitError("a unit expression ends too early")
    kind, val = tokens[i]
    if kind == "name":
        factor, dim = _name(val)
        i += 1
    elif kind in ("one", "int", "num"):      # a number inside a unit: kg/(100 m*mm^2)
        factor, dim = float(val), _ONE
        if factor <= 0:
            raise UnitError(f"a factor inside a unit must be positive, got {val}")
        i += 1
    elif (kind, val) == ("op", "("):
        factor, dim, i = _product(tokens, i + 1)
        if i >= len(tokens) or tokens[i] != ("op", ")"):
            raise UnitError("unbalanced parentheses in a unit")
        i += 1
    else:
        raise UnitError(f"unexpected {val!r} in a unit")
    if i < len(tokens) and tokens[i][0] == "op" and tokens[i][1] in ("^", "**"):
        if i + 1 >= len(tokens) or tokens[i + 1][0] not in ("int", "one"):
            raise UnitError("a power of a unit must be a whole number")
        n = int(tokens[i + 1][1])
        factor, dim, i = factor ** n, tuple(a * n for a in dim), i + 2
    return factor, dim, i


_NAMED = {
    _ONE: "a pure number", _M: "mass", _L: "length", _T: "time", _A: "angle", _FORCE: "force",
    _dim((_FORCE, 1), (_L, -2)): "pressure", _dim((_FORCE, 1), (_L, 1)): "energy or torque",
    _dim((_FORCE, 1), (_L, 1), (_T, -1)): "power", _dim((_L, 1), (_T, -1)): "speed",
    _dim((_L, 1), (_T, -2)): "acceleration", _dim((_A, 1), (_T, -1)): "angular speed",
    _dim((_L, 1), (_FORCE, -1)): "length per force", _dim((_FORCE, -1),): "1/force",
    _dim((_FORCE, 1), (_L, -1)): "force per length", _dim((_M, 1), (_L, -1)): "mass per length",
    _dim((_M, 1), (_L, -3)): "density", _dim((_L, 2),): "area", _dim((_FORCE, 1), (_L, -2), (_T, 1)): "viscosity",
    _dim((_T, -1),): "1/time", _K: "temperature difference", _dim((_K, -1),): "1/temperature",
}


def dimension_text(dim: tuple[int, ...]) -> str:
    """A readable name of a dimension: ``"force"``, ``"length per force"``, else base powers."""
    if dim in _NAMED:
        return _NAMED[dim]
    names = ("mass", "length", "time", "angle")
    num = [n if p == 1 else f"{n}^{p}" for n, p in zip(names, dim) if p > 0]
    den = [n if p == -1 else f"{n}^{-p}" for n, p in zip(names, dim) if p < 0]
    return ("·".join(num) or "1") + ("/" + "·".join(den) if den else "")


def is_dimensionless(si_unit: str) -> bool:
    """True for a quantity whose value is a pure number (an angle is not)."""
    return parse_unit(si_unit)[1] == _ONE


def split_value(text: str) -> tuple[float, str]:
    """``"5.8 mm/kN"`` → ``(5.8, "mm/kN")``; ``"16"`` → ``(16.0, "")``.  :class:`UnitError` otherwise."""
    m = _NUMBER.match(text)
    if not m:
        raise UnitError(f"cannot read {text!r} as a number with a unit (e.g. \"16 deg\")")
    return float(m["num"]), m["unit"]


def last_digit(text: str) -> float:
    """Place value of the last digit typed in the number of ``text`` (``"128.72 kN"`` → 0.01, ``"467"`` → 1)."""
    m = _NUMBER.match(str(text))
    if not m:
        return 0.0
    num = m["num"].lstrip("+-")
    mant, _, exp = num.lower().partition("e")
    decimals = len(mant.partition(".")[2]) if "." in mant else 0
    return 10.0 ** (-decimals + (int(exp) if exp else 0))


def _number(value) -> float | None:
    """A plain number (int, float, numpy scalar) as a float; None if ``value`` is not one."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)) or type(value).__module__ == "numpy" and hasattr(value, "dtype") \
            and getattr(value, "ndim", 1) == 0 and value.dtype.kind in "iuf":
        try:
            return float(value)
        except OverflowError:
            return math.inf
    return None


def _pint_text(value) -> str | None:
    """``"12.5 kN/m"`` for a pint Quantity (duck-typed), else None."""
    if all(hasattr(value, a) for a in ("magnitude", "units", "to")):
        mag = _number(value.magnitude)
        if mag is not None:
            return f"{mag!r} {format(value.units, '~C')}"
    return None


def to_si(name: str, value, si_unit: str, display: str | None = None, bare: str = "refuse") -> float:
    """``value`` of quantity ``name`` as a float in ``si_unit``.

    value: a string with a unit (``"16 deg"``), a pint Quantity, or a number.  A number is taken
        as it is for a dimensionless quantity; for a dimensional one it is refused
        (``bare="refuse"``, files and command line) or taken as SI (``bare="si"``, the documented
        Python API).  A string is text a person typed: without a unit it is refused for a
        dimensional quantity whatever ``bare`` says.
    display: the quantity's display unit, used in the suggested fix.
    Raises :class:`InputError` naming the parameter: no unit, wrong dimension, an unreadable
    string, a wrong type, a value too large for a float, NaN or inf.
    """
    target_f, target_d = parse_unit(si_unit)
    shown = display if display not in (None, "1", "") else si_unit
    num = _number(value)
    text: str | None = None
    unit = ""
    if num is None:
        text = value if isinstance(value, str) else _pint_text(value)
        if text is None:
            raise InputError(f"{name} = {value!r}: expected a number or a value with a unit "
                             f"(e.g. \"1 {shown}\"), got {type(value).__name__}")
        try:
            num, unit = split_value(text)
        except UnitError:
            example = "0.5" if target_d == _ONE else f"1 {shown}"
            raise InputError(f"{name} = {text!r} is not a number{'' if target_d == _ONE else ' with a unit'} "
                             f"(e.g. \"{example}\")") from None
    if not math.isfinite(num):
        typed = text if text is not None else value
        if isinstance(value, int) or text is not None and not re.search(r"inf|nan", text, re.I):
            raise InputError(f"{name}: {str(typed)[:40]}{'...' if len(str(typed)) > 40 else ''} is too large "
                             f"to be a number")
        raise InputError(f"{name}: value must be finite, got {typed!r}")
    if unit and re.match(r"[\d.+-]", unit) and not re.match(r"1\s*/", unit):
        example = _plain(num) if target_d == _ONE else f"{_plain(num)} {shown}"
        raise InputError(f"{name} = {text!r} has a second number where its unit should be; write one number "
                         f"{'' if target_d == _ONE else 'and its unit '}(e.g. \"{example}\")")
    if unit:
        try:
            f, d = parse_unit(unit)
        except UnitError as exc:
            raise InputError(f"{name} = {text!r}: {exc}") from None
        if d != target_d:
            raise InputError(f"{name} = {text!r} has the dimension {dimension_text(d)}, expected "
                             f"{dimension_text(target_d)} (a value in {shown})")
        out = num * f / target_f
    elif target_d == _ONE or (bare == "si" and text is None):
        out = num
    else:
        typed = text.strip() if text is not None else _plain(num)
        raise InputError(f"{name} = {typed} has no unit; write e.g. \"{typed} {shown}\"")
    if not math.isfinite(out):
        raise InputError(f"{name} = {value!r} is too large to be a number")
    return out


def _plain(x: float) -> str:
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else repr(float(x))


def factor(si_unit: str, display_unit: str) -> float:
    """Multiply a value in ``si_unit`` by this to express it in ``display_unit`` (same dimension)."""
    if si_unit == display_unit:
        return 1.0
    f_si, d_si = parse_unit(si_unit)
    f_disp, d_disp = parse_unit(display_unit)
    if d_si != d_disp:
        raise UnitError(f"{display_unit!r} is not a unit of {si_unit!r}")
    return f_si / f_disp


def label(name: str, unit: str) -> str:
    """Column label with the unit in brackets, e.g. ``F_C [kN]``; ``[-]`` for a pure number."""
    return f"{name} [{unit}]" if unit not in ("", "1") else f"{name} [-]"
