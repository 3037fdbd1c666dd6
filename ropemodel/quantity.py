"""Quantities: a name (the paper's symbol in ASCII), an SI unit, a description and a valid range."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ropemodel.errors import InputError
from ropemodel.units import factor


@dataclass(frozen=True)
class Quantity:
    """One physical quantity of a model.

    Attributes
    ----------
    name: the paper's symbol in ASCII (``F_C``, ``alpha_u``).
    unit: SI unit string as pint reads it (``"N"``, ``"m/N"``, ``"rad"``, ``"1"``).
    description: one line for tables and error messages.
    display: unit for human-readable tables (the paper's unit, e.g. ``"kN"``).
    low, high: valid range in SI; ``low_open``/``high_open`` make an end exclusive.
    warn_low, warn_high: outside these the value is valid but beyond the source's range (a warning).
    equation: where the quantity is defined (``"Krauze et al. 2025, eq. (13)"``).
    positive: strictly positive unknown; nonlinear blocks solve for it in log space.
    guess: starting value for Newton when the quantity is an unknown of a nonlinear block.
    default: value used when a scene leaves the parameter out (``None``: required).
    """

    name: str
    unit: str
    description: str
    display: str | None = None
    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False
    warn_low: float = -math.inf
    warn_high: float = math.inf
    equation: str = ""
    positive: bool = False
    guess: float = 1.0
    default: float | None = None

    @property
    def display_unit(self) -> str:
        return self.display or self.unit

    def to_display(self, value):
        """Convert an SI value to the display unit."""
        return value * factor(self.unit, self.display_unit)

    @property
    def unit_text(self) -> str:
        """The display unit as shown after a number: ``" kN"``, or ``""`` for a pure number."""
        return "" if self.display_unit in ("1", "") else f" {self.display_unit}"

    def range_text(self) -> str:
        """The valid range as text in display units, e.g. ``(0, inf] m``."""
        f = factor(self.unit, self.display_unit)
        lo = "[" if not self.low_open else "("
        hi = "]" if not self.high_open else ")"
        return f"{lo}{_fmt(self.low * f)}, {_fmt(self.high * f)}{hi}{self.unit_text}"

    def in_range(self, value: float) -> bool:
        if not math.isfinite(value):
            return False
        if value < self.low or (self.low_open and value == self.low):
            return False
        if value > self.high or (self.high_open and value == self.high):
            return False
        return True

    def check(self, value: float, what: str = "") -> float:
        """Return ``value`` if valid, else raise :class:`InputError` naming the quantity and its range."""
        if not self.in_range(value):
            shown = self.to_display(value)
            raise InputError(
                f"{what or self.name} = {_fmt(shown)}{self.unit_text} is outside the valid range "
                f"{self.range_text()} ({self.description})"
            )
        return value

    def beyond_source(self, value: float) -> bool:
        """True where ``value`` is valid but outside the range the source covers."""
        return value < self.warn_low or value > self.warn_high


def _fmt(x: float) -> str:
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:.6g}"
