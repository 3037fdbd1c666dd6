"""Quantities: a name (the paper's symbol in ASCII), an SI unit, a description, a valid and a usual range."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ropemodel.errors import InputError
from ropemodel.units import factor, to_si

#: the extremes an output's worst case can be (:attr:`Quantity.worst`)
SENSES = ("least", "largest")


@dataclass(frozen=True)
class Quantity:
    """One physical quantity of a model, declared once (the effect registry enforces it).

    Attributes
    ----------
    name: the paper's symbol in ASCII (``F_C``, ``alpha_u``).
    unit: SI unit string (``"N"``, ``"m/N"``, ``"rad"``, ``"1"`` for a pure number).
    description: one line for tables and error messages.
    display: unit for human-readable tables (the paper's unit, e.g. ``"kN"``).
    low, high: valid range in SI; ``low_open``/``high_open`` make an end exclusive.  Outside it a
        value is an error, even where it is not used.  Every input has finite ends
        (:mod:`ropemodel.effects.domains`), with ``range_source`` saying where they come from.
    warn_low, warn_high: the range *usual for the field* (SI); outside it a valid value gets a warning
        that states this range and ``usual_source``, where the range comes from.
    usual_source: where the usual range comes from (documented in the README's scene section).
    unlimited: ``math.inf`` is a valid value, meaning "no limit" (e.g. a tensioner's stroke not given),
        shown as ``unlimited_text``.
    equation: where the quantity is defined (``"Krauze et al. 2025, eq. (13)"``).
    positive: strictly positive unknown; nonlinear blocks solve for it in log space.
    guess: starting value for Newton when the quantity is an unknown of a nonlinear block.
    default: value used when a scene leaves the parameter out (``None``: required), with
        ``default_note`` saying why that value (reported wherever the default is used).
    signs: what a negative and a positive value mean, for a signed quantity (``("braking", "motoring")``
        of a drive power); tables print it next to the number (:meth:`sign_text`).
    symbol: the symbol formulas show, plain Unicode with ``_`` before a subscript (``"m_safety,up"``);
        ``""``: made from the name (:func:`symbol_of`: ``alpha_u`` → ``α_u``, ``F_C_up`` → ``F_C,up``).
    worst: which extreme of an output is its worst case where the load's place or the manoeuvre varies
        (:mod:`ropemodel.envelope`): ``("least",)`` (a margin, a least tension), ``("largest",)`` (a rope
        force, a stroke), or both (a signed power: largest motoring and largest braking); ``()``: none
        (an intermediate quantity, given only at one place).
    """

    name: str
    unit: str
    description: str
    display: str | None = None
    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    range_source: str = ""
    warn_low: float = -math.inf
    warn_high: float = math.inf
    usual_source: str = ""
    unlimited: bool = False
    unlimited_text: str = "unlimited"
    equation: str = ""
    positive: bool = False
    guess: float = 1.0
    default: float | None = None
    default_note: str = ""
    signs: tuple[str, ...] = ()
    symbol: str = ""
    worst: tuple[str, ...] = ()

    def __post_init__(self):
        if not set(self.worst) <= set(SENSES):
            raise ValueError(f"{self.name}: worst must be among {SENSES}, got {self.worst}")

    @property
    def typeset(self) -> str:
        """The symbol a formula shows (:attr:`symbol`, or :func:`symbol_of` the name)."""
        return self.symbol or symbol_of(self.name)

    @property
    def display_unit(self) -> str:
        return self.display or self.unit

    @property
    def dimensionless(self) -> bool:
        """True for a pure number (its value may be typed without a unit)."""
        return self.unit in ("1", "")

    def to_display(self, value):
        """Convert an SI value to the display unit."""
        return value * factor(self.unit, self.display_unit)

    def sign_text(self, value: float) -> str:
        """What the sign of ``value`` means (``"braking"``), or ``""`` for an unsigned quantity or 0."""
        if not self.signs or not value or not math.isfinite(value):
            return ""
        return self.signs[value > 0]

    def to_si(self, value, bare: str = "refuse") -> float:
        """``value`` (string with unit, pint Quantity or number) in SI; see :func:`ropemodel.units.to_si`.
        The float ``math.inf`` is accepted for an ``unlimited`` quantity (its "not given")."""
        if self.unlimited and isinstance(value, float) and value == math.inf:
            return value
        return to_si(self.name, value, self.unit, self.display_unit, bare)

    @property
    def unit_text(self) -> str:
        """The display unit as shown after a number: ``" kN"``, or ``""`` for a pure number."""
        return "" if self.display_unit in ("1", "") else f" {self.display_unit}"

    def show(self, value: float) -> str:
        """``value`` (SI) as text in the display unit: ``"467 kN"``, ``"unlimited"``."""
        if self.unlimited and value == math.inf:
            return self.unlimited_text
        return f"{_fmt(self.to_display(value))}{self.unit_text}"

    def range_text(self) -> str:
        """The valid range as text in display units, e.g. ``(0, inf] m``."""
        f = factor(self.unit, self.display_unit)
        lo = "(" if self.low_open or self.low == -math.inf else "["
        hi = ")" if self.high_open or self.high == math.inf else "]"
        return f"{lo}{_fmt(self.low * f)}, {_fmt(self.high * f)}{hi}{self.unit_text}"

    def usual_text(self) -> str:
        """The usual range in display units, e.g. ``0.1 to 1000 mm/kN``."""
        f = factor(self.unit, self.display_unit)
        if self.warn_low == -math.inf:
            return f"up to {_fmt(self.warn_high * f)}{self.unit_text}"
        if self.warn_high == math.inf:
            return f"from {_fmt(self.warn_low * f)}{self.unit_text}"
        return f"{_fmt(self.warn_low * f)} to {_fmt(self.warn_high * f)}{self.unit_text}"

    def in_range(self, value: float) -> bool:
        if self.unlimited and value == math.inf:
            return True
        if not math.isfinite(value):
            return False
        if value < self.low or (self.low_open and value == self.low):
            return False
        if value > self.high or (self.high_open and value == self.high):
            return False
        return True

    def range_problem(self, value: float, what: str = "") -> str | None:
        """The message for a value outside the valid range, or None."""
        if self.in_range(value):
            return None
        return (f"{what or self.name} = {_fmt(self.to_display(value))}{self.unit_text} is outside the valid range "
                f"{self.range_text()} ({self.description})")

    def check(self, value: float, what: str = "") -> float:
        """Return ``value`` if valid, else raise :class:`InputError` naming the quantity and its range."""
        problem = self.range_problem(value, what)
        if problem:
            raise InputError(problem)
        return value

    def unusual(self, value: float) -> str | None:
        """A warning for a valid value outside the range usual for the field, or None."""
        if not (value < self.warn_low or value > self.warn_high) or value == math.inf:
            return None
        source = f"; {self.usual_source}" if self.usual_source else ""
        return (f"{self.name} = {self.show(value)} is outside the range usual for the field, "
                f"{self.usual_text()} ({self.description}{source}): check the value and its unit")


#: names written out in ASCII → their Greek letters
GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "eps": "ε", "eta": "η",
         "theta": "θ", "lambda": "λ", "mu": "μ", "nu": "ν", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ",
         "omega": "ω", "dF": "ΔF"}
#: suffixes of a direction of travel, joined to the subscript (``F_C_up`` → ``F_C,up``)
DIRECTIONS = ("up", "down")


def symbol_of(name: str, base: str = "") -> str:
    """The symbol of a quantity's ``name`` (Greek words as letters, ``dF`` as ΔF, a direction joined to the
    subscript), or of its ``base`` symbol with the name's direction.

    Examples
    --------
    >>> symbol_of("alpha_u"), symbol_of("mu_pl1"), symbol_of("F_C_up"), symbol_of("dF_CS_down"), symbol_of("c_mu")
    ('α_u', 'μ_pl1', 'F_C,up', 'ΔF_CS,down', 'c_μ')
    >>> symbol_of("slip_margin_up", base="m_slip")
    'm_slip,up'
    """
    head, *rest = name.split("_")
    if base:
        rest = [rest[-1]] if rest and rest[-1] in DIRECTIONS else []
        head, sep = base, "," if "_" in base else "_"
        return f"{head}{sep}{rest[0]}" if rest else head
    letters = [GREEK.get(part, part) for part in rest]
    head = GREEK.get(head, head)
    return f"{head}_{','.join(letters)}" if letters else head


def _fmt(x: float) -> str:
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:.6g}"


def positive(name: str, unit: str, description: str, display: str | None = None, **kw: Any) -> Quantity:
    """A strictly positive quantity: valid range (0, ∞); as an unknown of a nonlinear block it is
    solved for in log space.  Other fields as :class:`Quantity`."""
    return Quantity(name, unit, description, display, low=0.0, low_open=True, positive=True, **kw)


def non_negative(name: str, unit: str, description: str, display: str | None = None, **kw: Any) -> Quantity:
    """A quantity with valid range [0, ∞).  Other fields as :class:`Quantity`."""
    return Quantity(name, unit, description, display, low=0.0, **kw)
