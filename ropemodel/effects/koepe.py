"""Koepe (friction) hoist (``model = "koepe"``): static tensions, traction, slip limits, checks.

Two conveyances hang from ``n_head`` head ropes over a friction wheel; ``n_tail`` tail (balance) ropes may
hang in a loop below them.  The physics is :mod:`ropemodel.papers.koepe` (statics),
:mod:`ropemodel.papers.koepe_slip` (rigid dynamics, braking window) and :mod:`ropemodel.papers.koepe_lining`
(Hajduk's lining on the wheel), stated with every assumption in docs/physics.md §7.

Every result is taken at its worst over the end states of the wind (:mod:`ropemodel.effects.koepe_states`):
the loaded conveyance at the bottom and at the top, and the empty hoist at both ends, with the loaded
conveyance in either compartment (the sheaves the ropes of each compartment run over may differ).  The
tensions are linear in the conveyances' positions, so the ends hold every extreme (docs/physics.md §7).
Each worst case says where it is (:meth:`~ropemodel.effects.base.Submodel.where`).

Effects and variants
--------------------
``hoist``       ``koepe`` — the static tensions: the largest rope pull T_max and tension difference dT_max.
``tail_ropes``  ``round`` (default) — n_tail ropes of q_tail each in a free loop; ``none``.
``head_ropes``  ``given`` (default) — q_head given; one variant per catalogue construction (q_head and the
                breaking force F_min_head from the diameter d_head, EN 12385-4).
``lining``      ``rigid`` (default) — Euler–Eytelwein on the wheel; ``voigt`` — Hajduk (1992) (koepe_wheel).
``checks``      ``none`` (default); ``design`` — rope safety, D/d, ratings, anti-slip factor (koepe_checks).
``brake``       ``none`` (default); ``window`` — the emergency brake's admissible deceleration (koepe_brake).

Valid ranges (each quantity's ``low``/``high``) are physical domains: an end from physics where there is
one (a count of ropes at least 1, a mass or length not negative), otherwise a factor of ten or more beyond
the field's largest installations: winding distance to 40 km (ten times the deepest shafts, about 4 km);
head-rope length and tail loop to 1 km; masses from 1 g to 1000 t (ten times the heaviest conveyances with
their payloads, about 100 t; the machine's equivalent mass to 10^4 t); 1 to 100 ropes (1 to 10 in use);
1 g/m to 1 t/m a rope (the heaviest hoisting and balance ropes weigh about 30 kg/m); friction 1e-3 to 10 and
wrap 1e-3 rad to ten turns (e^{μα} then stays a double); wheels 1 mm to 100 m (ten times the largest Koepe
wheels); speeds to 100 m/s (five times the fastest hoists); forces to 10^9 N; decelerations to 100 m/s² (ten
g); the lining's compliance to 1 /N and retardation time to 1000 s (Hajduk's linings: 1e-6 to 1e-4 /N,
milliseconds to seconds).
"""

from __future__ import annotations

import math
from typing import cast

from ropemodel._math import fabs, fmax
from ropemodel.effects import domains as dom
from ropemodel.effects import koepe_states as st
from ropemodel.effects.base import REGISTRY, Equation, Submodel, define_effect, register
from ropemodel.quantity import Quantity

MODEL = "koepe"
PRACTICE = "standard mine-hoisting practice (docs/physics.md §7)"
JUDGEMENT = "engineering judgement around the issue's example (905 m wind, 29.6 t conveyances, 22 t payload)"

def Q(name, unit, description, display=None, **kw) -> Quantity:
    """Shorthand for a Koepe quantity."""
    return Quantity(name, unit, description, display, **kw)


def usual(low, high, source) -> dict:
    """Keyword arguments of a usual range [low, high] (SI) and where it comes from."""
    return dict(warn_low=low, warn_high=high, usual_source=source)


def positive(low, high, source: str) -> dict:
    """A strictly positive quantity's domain (low, high] (an unknown solved for in log space) and its source."""
    return dict(low=low, high=high, low_open=low == 0.0, positive=True, range_source=source)


# --- the domains' sources (the module docstring; ropemodel/effects/domains.py for those shared with the winch)
SHAFT = "40 km: ten times the deepest shafts (about 4 km)"
#: a head rope above a conveyance, a tail loop below it
SPAN = dom.domain(0.0, 1e3, "0 to 1 km: ten times the tallest headframes and the deepest tail loops (about 100 m)")
MASS = "1000 t: ten times the heaviest conveyances with their payloads (about 100 t)"
#: a count of ropes
COUNT = dom.domain(1.0, 100.0, "physics: at least one rope; 100 is ten times the most a friction hoist hangs (10)")
ROPE_MASS = "1 g/m to 1 t/m: the heaviest hoisting and balance ropes weigh about 30 kg/m"
WHEEL = "ten times the largest Koepe wheels (about 10 m)"


# --- quantities several effects share, declared once (the registry refuses a second declaration)
H = Q("H", "m", "winding distance: between a conveyance's upper and lower positions", "m", guess=905.0,
      **positive(0.0, 4e4, SHAFT), **usual(20.0, 3000.0, JUDGEMENT))
H_HEAD = Q("H_head", "m", "head-rope length from the wheel's tangent point to a conveyance at its upper position",
           "m", **SPAN, guess=56.7, **usual(5.0, 200.0, JUDGEMENT))
M_CONVEYANCE = Q("m_conveyance", "kg", "mass of each conveyance with its attachments", "t", guess=3e4, symbol="m_c",
                 **positive(1e-3, 1e6, f"1 g to {MASS}"), **usual(500.0, 1.5e5, JUDGEMENT))
M_PAYLOAD = Q("m_payload", "kg", "payload of the loaded conveyance", "t", guess=2e4, symbol="m_p",
              **positive(0.0, 1e6, MASS), **usual(100.0, 1e5, JUDGEMENT))
N_HEAD = Q("n_head", "1", "number of head ropes (a whole number)", guess=4.0, **COUNT, symbol="n_h",
           **usual(1.0, 10.0, "multi-rope friction hoists carry 1 to 10 head ropes (judgement)"))
Q_HEAD = Q("q_head", "kg/m", "mass per metre of one head rope", "kg/m", guess=8.6, symbol="q_h",
           **positive(1e-3, 1e3, ROPE_MASS),
           **usual(0.5, 40.0, "EN 12385-4 ropes of 10 to 90 mm (W d², W about 4000 kg/m³)"))
MU = Q("mu", "1", "friction coefficient of the head ropes on the wheel's lining", guess=0.25, **dom.FRICTION,
       **usual(0.15, 0.4, "BPVS § 27(5): a lining of at least 0.25, not below 0.18 wet; polymer linings 0.2-0.3 "
                          "(judgement)"))
ALPHA = Q("alpha", "rad", "wrap of the head ropes on the wheel", "deg", guess=math.pi, **dom.WRAP,
          **usual(math.radians(150), math.radians(400), "tower Koepes wrap 180°-200°, with a deflection sheave or a "
                                                         "double wrap more (judgement)"))
D_WHEEL = Q("D", "m", "diameter of the friction wheel at the rope centre", "m", guess=4.5,
            **positive(1e-3, 100.0, f"1 mm to 100 m: {WHEEL}"),
            **usual(0.8, 10.0, "Koepe wheels of 1 to 9 m (judgement)"))
V_MAX = Q("v_max", "m/s", "largest rope speed: the hoisting speed", "m/s", guess=10.0,
            **positive(0.0, 100.0, "100 m/s: five times the fastest mine hoists (20 m/s)"),
          **usual(1.0, 20.0, "mine hoists run at 1 to 20 m/s (judgement)"))
F_R = Q("F_r", "N", "shaft resistance (guides, air) on the loaded conveyance, against its velocity", "kN",
        **dom.FORCE, guess=1e3, default=0.0, default_note="not given: no shaft resistance")
M_SHEAVE = tuple(
    Q(f"m_sheave_{c}", "kg", f"mass equivalent to the sheaves compartment {c}'s head ropes run over between the "
      f"wheel and the conveyance, J/r² (moment of inertia over radius squared)", "t",
      **dom.domain(0.0, 1e6, f"0 to {MASS}; a sheave's equivalent mass is far less"), guess=1e3,
      default=0.0, default_note="not given: no sheave, the ropes hang from the wheel (a tower Koepe)")
    for c in st.COMPARTMENTS)
T_MAX = Q("T_max", "N", "largest static tension at the wheel (all head ropes of a side): the largest rope pull",
          "kN", equation=f"{PRACTICE}: T = g (m + n_head q_head L_h + n_tail q_tail L_t)")
DT_MAX = Q("dT_max", "N", "largest static tension difference across the wheel", "kN", symbol="ΔT_max",
           equation=f"{PRACTICE}: abs(T_L − T_E)")

define_effect(MODEL, "hoist", "koepe", "the static tensions at the ends of the wind, loaded and empty")
define_effect(MODEL, "tail_ropes", "round", "tail (balance) ropes hanging in a free loop, or none")
define_effect(MODEL, "head_ropes", "given", "head ropes: q_head given, or from a catalogue construction and d_head")
define_effect(MODEL, "lining", "rigid", "traction of the wheel: static, anti-slip factor, slip accelerations")
define_effect(MODEL, "checks", "none", "design checks: rope safety, D/d, ratings, anti-slip factor")
define_effect(MODEL, "brake", "none", "the emergency brake's admissible deceleration, both directions")


class TailRopes(Submodel):
    """What a variant of ``tail_ropes`` gives the others: its terms of the side tensions, its safety check."""

    def terms(self, v) -> tuple:
        """(n_tail, q_tail, h_loop) for :func:`ropemodel.papers.koepe.side_tensions`."""
        raise NotImplementedError

    def safety_equations(self, v) -> list[Equation]:
        """The tail ropes' safety check of ``checks = "design"`` (none without tail ropes)."""
        raise NotImplementedError


def partner(sm: Submodel, effect: str) -> Submodel:
    """The submodel of the scene's variant of ``effect`` (through the registry; the default variant when the
    scene's effects are not known)."""
    spec = REGISTRY[MODEL][effect]
    return spec.variants[sm.effects.get(effect, spec.default)](sm.options, sm.effects)


def tail_terms(sm: Submodel, v):
    """(n_tail, q_tail, h_loop) of the scene's tail ropes (zeros without): floats, arrays or symbols."""
    return cast(TailRopes, partner(sm, "tail_ropes")).terms(v)


def static_states(sm: Submodel, v) -> list[st.Sides]:
    """The static end states (no shaft resistance, no sheave) with their tensions."""
    return [st.sides(v, tail_terms(sm, v), s) for s in st.STATIC]


@register(MODEL, "hoist", "koepe")
class KoepeHoist(Submodel):
    """The static tensions at the wheel at the ends of the wind: the largest rope pull and difference.

    T_L, T_E of :func:`ropemodel.papers.koepe.side_tensions` (loaded side and the other) at each static
    end state; T_max = max(T_L, T_E) and dT_max = abs(T_L − T_E) at their worst.  The ratings and rope safety
    (``checks = "design"``) read them.
    """

    description = "static tensions of both sides at the ends of the wind, loaded and empty"
    citations = ("delavergne2003", "edwards1992")
    quantities = (H, H_HEAD, M_CONVEYANCE, M_PAYLOAD, N_HEAD, Q_HEAD, T_MAX, DT_MAX)

    def equations(self, v):
        states = static_states(self, v)
        every = "over the static end states (loaded at the bottom, at the top, empty), each a closed form"
        return [Equation("T_max", v["T_max"] - st.largest([fmax(s.T_L, s.T_E) for s in states]),
                         f"{PRACTICE}: the largest T_L or T_E at an end of the wind", method=f"the largest {every}"),
                Equation("dT_max", v["dT_max"] - st.largest([fabs(s.T_L - s.T_E) for s in states]),
                         f"{PRACTICE}: the largest abs(T_L − T_E) at an end of the wind",
                         method=f"the largest {every}")]

    def where(self, values):
        states = static_states(self, values)
        top = st.argleast([-max(s.T_L, s.T_E) for s in states])
        diff = st.argleast([-abs(s.T_L - s.T_E) for s in states])
        return {"T_max": st.describe(states[top], high=True), "dT_max": st.describe(states[diff], high=True)}

    def rules(self, values):
        return whole_ropes(values, "n_head")


def whole_ropes(values, name: str) -> list[str]:
    """A number of ropes that is not a whole number, named (an empty list otherwise)."""
    n = values.get(name)
    if n is not None and n != round(n):
        return [f"{name} = {n:g} is not a whole number of ropes: give how many ropes there are"]
    return []
