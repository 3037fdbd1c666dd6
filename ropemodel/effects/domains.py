"""The physical domain of every input: the finite ends of each valid range, and where they come from.

A value outside its domain is an error wherever it stands, also in a parameter the scene does not use
(:mod:`ropemodel.scene_tables`); inside the domain but outside the range usual for the field it is a
warning (:meth:`ropemodel.quantity.Quantity.unusual`).  Each domain below is keyword arguments of a
:class:`~ropemodel.quantity.Quantity` (``low``, ``high``, their openness and ``range_source``, the reason
the README's parameter tables print beside the range).

An end comes from physics where physics has one (an inclination within ±90°, an efficiency at most 1, a
fill factor at most π/4).  Every other end is finite too, so that no valid input can drive a result out
of what a double holds or a solver resolves (a force times a speed, an elongation q_lw·F, the
Euler–Eytelwein ratio e^{μα}, a transient's time scales): it lies a factor of ten or more beyond the
largest (or smallest) installation of the field, with that installation named.  The fuzz
(``tests/_fuzz_edges.py``) runs every command at both ends of every domain and just outside them.
"""

from __future__ import annotations

import math

#: 10^9 N, ten times the heaviest loads hauled by rope (ship lifts of about 10^4 t, 10^8 N)
FORCE_MAX = 1e9
#: 100 km, ten times the longest rope haulages and ropeways (about 10 km)
ROUTE_MAX = 1e5
#: ten turns of wrap: with a friction coefficient of at most 10, e^{μα} < 1e273 stays a double
WRAP_MAX = 20 * math.pi
FRICTION_MAX = 10.0
#: 10^7 s (116 days): longer than a trip of the longest route at 1 cm/s
TIME_MAX = 1e7


def domain(low: float, high: float, source: str, *, low_open: bool = False, high_open: bool = False) -> dict:
    """Keyword arguments of a :class:`~ropemodel.quantity.Quantity`'s valid range [low, high] (SI) and its
    source; an ``*_open`` end is excluded."""
    return dict(low=low, high=high, low_open=low_open, high_open=high_open, range_source=source)


_FORCE = "10^9 N: ten times the heaviest rope-hauled loads (ship lifts, about 10^8 N)"
#: a force that may be zero (a pretension, a least tension, a load on a capstan)
FORCE = domain(0.0, FORCE_MAX, _FORCE)
#: a force that cannot be zero (a load, a breaking force, a drive's limit); 1 mN is below any of them
FORCE_POSITIVE = domain(1e-3, FORCE_MAX, f"1 mN to {_FORCE}")
#: a torque: a force of the domain above at a radius of up to 1 m
TORQUE = domain(0.0, FORCE_MAX, "a force of up to 10^9 N at 1 m")
_ROUTE = "100 km: ten times the longest rope haulages and ropeways (about 10 km)"
#: a length along a route; 1 mm is finer than any survey
ROUTE_LENGTH = domain(1e-3, ROUTE_MAX, f"1 mm to {_ROUTE}")
#: a position along a route, or a length that may be zero
ROUTE_POSITION = domain(0.0, ROUTE_MAX, _ROUTE)
#: an inclination: steeper than vertical is no incline
INCLINATION = domain(-math.pi / 2, math.pi / 2, "physics: an incline between falling and rising vertically",
                     low_open=True, high_open=True)
#: a coefficient of resistance: a rolling or sliding resistance per normal force, at most the force itself
RESISTANCE = domain(0.0, 1.0, "Krauze et al. 2025, eq. (7)-(11): a resistance per normal force, 0 to 1")
#: a friction coefficient of rope on drum, sheave or capstan
FRICTION = domain(1e-3, FRICTION_MAX, "1e-3 (below lubricated steel, 0.05) to 10 (above soft rubber, about 4), "
                                      "so that e^{mu alpha} stays a double over ten turns")
#: a wrap angle
WRAP = domain(1e-3, WRAP_MAX, "ten turns (a friction drum wraps a quarter turn to five turns); with mu <= 10, "
                              "e^{mu alpha} < 1e273 stays a double")
#: a radius or diameter of a drum, sheave or capstan
WHEEL = domain(1e-4, 100.0, "0.1 mm to 100 m: ten times the largest friction drums and Koepe wheels (about 10 m)")
#: a speed of haulage
SPEED = domain(1e-3, 100.0, "1 mm/s to 100 m/s, five times the fastest mine hoists (20 m/s): the quasi-static "
                            "rope needs speeds far below its wave speed (about 3 km/s)")
#: a duration of a transient
DURATION = domain(1e-3, TIME_MAX, "1 ms to 10^7 s (116 days): longer than a trip of 100 km at 1 cm/s")
#: a required safety factor
FACTOR = domain(1.0, 1e3, "at least 1 (physics); rules ask 2 to 10 (EN 12385-4, mining rules), 1000 bounds them")
#: a modulus of a rope or lining material
MODULUS = domain(1e3, 1e12, "1 kPa (a foam) to 1 TPa (diamond)")
#: a strength of rope wire
STRENGTH = domain(1e6, 1e10, "1 MPa to 10 GPa: beyond the strongest drawn steel wire (about 3 GPa)")
#: a retardation time of a visco-elastic material
RETARDATION = domain(0.0, 1e3, "0 to 1000 s: polymers' retardation times are milliseconds to seconds")
#: a fraction of a whole (an efficiency, a breaking force factor)
FRACTION = domain(1e-2, 1.0, "physics: a fraction is at most 1; below 1 % it is no longer a design value")
#: a compliance of a lining per unit tension (Hajduk 1992's Q: the lining yields Q·S of its thickness)
COMPLIANCE = domain(0.0, 1.0, "0 (rigid) to 1 1/N: Hajduk's linings are 1e-6 to 1e-4 1/N")
