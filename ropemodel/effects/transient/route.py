"""Loads along the haulage route: the one place the rope model asks for weights and resistances.

The lumped rope (:mod:`ropemodel.effects.transient.chain`) asks a *route* two questions, with s the
distance from the drive along the route (0 at the guiding sheave K_K, L_u at the return sheave K_ZN):

* ``rope(side, s0, s1)``: the rope of one side (``"winding"`` or ``"unwinding"``) between s0 and s1:
  its mass [kg], the component of its weight along the route pointing away from the drive (+s) [N],
  and its travel resistance in motion [N];
* ``load(x)``: the same three for the load at distance x.

:class:`Incline` is the route of Krauze et al. (2025): one incline α_u, the winding rope's resistance
μ_pl2 within L_ul of the drive (from point A to the drive) and μ_pl1 beyond, the unwinding rope's
μ_pl.  A route made of segments (length, inclination and resistance per segment) answers the same
two questions by summing over the segments between s0 and s1; setting ``setup.route`` in a variant's
``bind`` (ordered before the rope) is all the rope model needs.  Values may be CasADi symbols; the
geometry (L_u, L_ul, and the places asked about) are numbers.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, NamedTuple, Protocol

from ropemodel.effects.transient.base import G_N
from ropemodel.papers import krauze2025 as kr
from ropemodel.papers import route as rt


class Loads(NamedTuple):
    """Mass [kg], weight component along +s (away from the drive) [N], resistance in motion [N].
    Each a float, or a CasADi SX expression in the symbolic smooth mode."""

    mass: Any
    weight: Any
    resistance: Any


class Route(Protocol):
    def rope(self, side: str, s0: float, s1: float) -> Loads: ...

    def load(self, x: float) -> Loads: ...


@dataclass
class Incline:
    """Krauze et al. (2025): one incline; ``values`` SI (q_l, alpha_u, mu_pl, mu_pl1, mu_pl2, G_m, mu_pm),
    ``L_ul`` a number (point A, where the winding rope's resistance changes)."""

    values: dict
    L_ul: float

    def _mu(self, side: str, s0: float, s1: float):
        """Mean resistance coefficient of a side's rope over [s0, s1]: eq. (8)-(9) or (11)."""
        v = self.values
        if side == "unwinding":
            return v["mu_pl"]
        length = s1 - s0
        if length <= 0:
            return v["mu_pl2"]
        near = max(0.0, min(s1, self.L_ul) - s0)              # within L_ul of the drive: mu_pl2
        return (v["mu_pl2"] * near + v["mu_pl1"] * (length - near)) / length

    def rope(self, side: str, s0: float, s1: float) -> Loads:
        v = self.values
        length = s1 - s0
        return Loads(v["q_l"] * length / G_N,
                     kr.rope_weight_along_incline(v["q_l"], length, v["alpha_u"]),      # eq. (3), (4), (6)
                     kr.rope_resistance(self._mu(side, s0, s1), v["q_l"], length, v["alpha_u"]))   # eq. (8)-(11)

    def load(self, x: float) -> Loads:
        v = self.values
        return Loads(v["G_m"] / G_N, kr.load_weight_along_incline(v["G_m"], v["alpha_u"]),   # eq. (1)
                     kr.load_resistance(v["mu_pm"], v["G_m"], v["alpha_u"]))               # eq. (7)


def route_of(setup) -> Route:
    """The scene's route for the rope model: its ``route`` effect's (a route of segments), else the incline."""
    route = setup.submodels.get("route")
    transient = getattr(route, "transient_route", None)
    return transient(setup.values, setup.numbers) if transient else incline(setup.values, setup.numbers)


def incline(values: dict, numbers: dict) -> Incline:
    """The paper's route from the scene's values (L_ul taken as a number: it is geometry)."""
    return Incline(values, float(numbers["L_ul"]))


@dataclass
class Segments:
    """A route of straight segments (:mod:`ropemodel.papers.route`): ``lengths`` (numbers, from the drive),
    ``inclinations`` and ``mus`` (the winding rope's coefficient per segment) may be symbols; ``values``
    gives q_l, mu_pl, G_m, mu_pm.  A stretch of rope sums its parts of every segment it covers."""

    values: dict
    lengths: list
    inclinations: list
    mus: list
    #: (side, the parts of each segment a stretch covers) → its loads: the stretches of one span are equal
    _made: dict = field(default_factory=dict, repr=False, compare=False)

    def _parts(self, s0: float, s1: float):
        start = 0.0
        for i, (length, alpha, mu) in enumerate(zip(self.lengths, self.inclinations, self.mus)):
            part = max(0.0, min(start + length, s1) - max(start, s0))
            if part > 0.0:
                yield i, part, alpha, mu
            start += length

    def rope(self, side: str, s0: float, s1: float) -> Loads:
        """The loads of the rope on [s0, s1] (``side`` "winding" or "unwinding"); the same parts of the same
        segments give the same loads, made once (a span's elements are equal stretches, each one made element by
        element in symbols for the dynamic sizing)."""
        parts = list(self._parts(s0, s1))
        key = (side, tuple((i, part) for i, part, _, _ in parts))
        if key not in self._made:
            self._made[key] = self._rope(side, parts)
        return self._made[key]

    def _rope(self, side: str, parts) -> Loads:
        v, mass, weight, resistance = self.values, 0.0, 0.0, 0.0
        for _, part, alpha, mu in parts:
            coefficient = v["mu_pl"] if side == "unwinding" else mu
            mass = mass + v["q_l"] * part / G_N
            weight = weight + kr.rope_weight_along_incline(v["q_l"], part, alpha)          # eq. (2), (6) per segment
            resistance = resistance + kr.rope_resistance(coefficient, v["q_l"], part, alpha)   # eq. (10), (11)
        return Loads(mass, weight, resistance)

    def load(self, x: float) -> Loads:
        v = self.values
        return Loads(v["G_m"] / G_N, rt.load_weight_along_route(v["G_m"], x, self.lengths, self.inclinations),
                     rt.load_resistance_route(v["mu_pm"], v["G_m"], x, self.lengths, self.inclinations))
