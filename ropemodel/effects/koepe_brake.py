"""The emergency brake's admissible deceleration on a Koepe hoist (effect ``brake``), both directions.

``none``    (default) no window is built.
``window``  per direction ("hoist" moves the loaded conveyance up, "lower" down), the decelerations a brake
            may give in every end state without the ropes slipping (:func:`ropemodel.papers.koepe_slip.braking_window`):

    a_brake_low  = max(a_brake_min, d_free)     d_free: the deceleration with neither drive nor brake, the
                                                largest over the end states (a brake only adds to it)
    a_brake_high = min(a_slip_decel, a_brake_max)   the slip limit of the direction (effect ``lining``)
    brake_margin = a_brake_high − a_brake_low   [m/s²]   >= 0: a window exists

d_free = (s (T_L − T_E) + F_r)/M_total (:func:`~ropemodel.papers.koepe_slip.coasting_deceleration`, s = +1
hoisting, −1 lowering), M_total every mass that moves: both sides (T/g), the sheaves, the head ropes on the
wheel and the machine (wheel, rotor, brake discs) referred to the rope, m_machine.  A window that holds in
every end state is one constant deceleration a controlled brake may keep wherever it is tripped.  No rule
set shipped gives a least deceleration for an emergency stop (New Brunswick Reg. 96-105 s. 192 gives
1.5-3.7 m/s² for drum hoists carrying persons; none read for friction hoists): ``a_brake_min`` is the
scene's, or a rule set's where one gives it (``emergency_deceleration_min``).
"""

from __future__ import annotations

import math

from ropemodel._math import fmax, fmin
from ropemodel.effects import domains as dom
from ropemodel.effects import koepe_states as st
from ropemodel.effects.base import Equation, Submodel, register
from ropemodel.effects.koepe import ALPHA, D_WHEEL, F_R, M_SHEAVE, MODEL, Q, partner, tail_terms, usual
from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_slip as ks

SRC = "docs/physics.md §7, braking window"
DIRECTIONS = {"hoist": (+1.0, "hoisting"), "lower": (-1.0, "lowering")}
DECELERATION = dom.domain(0.0, 100.0, "0 to 100 m/s² (ten g): far beyond any brake a person survives")

QUANTITIES = (
    ALPHA, D_WHEEL, F_R, *M_SHEAVE,
    Q("a_brake_min", "m/s^2", "least deceleration of an emergency stop (the rule's or the mine's)", "m/s^2",
      guess=1.5, **DECELERATION, **usual(0.5, 5.0, "regulations ask 1 to 2 m/s² (e.g. New Brunswick Reg. 96-105 "
                                                      "s. 192: more than 1.5 m/s², drum hoists)")),
    Q("a_brake_max", "m/s^2", "largest deceleration allowed in an emergency stop", "m/s^2", guess=5.0,
      **{**DECELERATION, "low_open": True}, unlimited=True, default=math.inf,
      default_note="not given: no largest deceleration (the slip limit bounds the window)"),
    Q("m_machine", "kg", "mass equivalent to the wheel, the motor's rotor and the brake discs, J/R² (their moment "
      "of inertia about the wheel's axle over the wheel's radius squared)", "t",
      **dom.domain(0.0, 1e7, "0 to 10^4 t: far beyond a wheel, rotor and brake discs reduced to the rim "
                             "(tens of tonnes)"),
      guess=2e4, default=0.0,
      default_note="not given: left out; it can only lower the deceleration without brake, so the window's floor "
                   "is on the safe side"),
    *(q for d in DIRECTIONS for q in (
        Q(f"a_brake_low_{d}", "m/s^2", f"least admissible brake deceleration {DIRECTIONS[d][1]}", "m/s^2",
          equation=f"{SRC}: max(a_brake_min, d_free)"),
        Q(f"a_brake_high_{d}", "m/s^2", f"largest admissible brake deceleration {DIRECTIONS[d][1]}", "m/s^2",
          equation=f"{SRC}: min(a_slip_{d}_decel, a_brake_max)"),
        Q(f"brake_margin_{d}", "m/s^2", f"width of the emergency brake's window {DIRECTIONS[d][1]}, a_brake_high − "
          f"a_brake_low (>= 0 passes: an admissible deceleration exists)", "m/s^2", symbol=f"m_brake,{d}",
          equation=f"{SRC}"))),
)


@register(MODEL, "brake", "none")
class NoBrakeWindow(Submodel):
    """No braking window."""

    description = "no braking window"


@register(MODEL, "brake", "window")
class BrakeWindow(Submodel):
    """The admissible deceleration of the emergency brake per direction, or the conflict named."""

    description = "the emergency brake's admissible deceleration per direction (rigid ropes)"
    citations = ("delavergne2003",)
    quantities = QUANTITIES

    def coasting(self, v, sign) -> list:
        """(state, d_free) of each end state of the manoeuvres in the direction of ``sign``."""
        tail, out = tail_terms(self, v), []
        arc = kp.arc_rope_mass(v["n_head"], v["q_head"], v["D"] / 2.0, v["alpha"])
        for state in st.DYNAMIC[::2]:   # the sheaves' sum is the same with conveyance L in either compartment
            s = st.sides(v, tail, state)
            M_L, M_E = st.masses(v, s)
            out.append((s, ks.coasting_deceleration(s.T_L, s.T_E, M_L + M_E + arc + v["m_machine"], sign, v["F_r"])))
        return out

    def equations(self, v):
        eqs = []
        for d, (sign, _) in DIRECTIONS.items():
            free = st.largest([x for _, x in self.coasting(v, sign)])
            low, high = v[f"a_brake_low_{d}"], v[f"a_brake_high_{d}"]
            eqs += [Equation(f"a_brake_low_{d}", low - fmax(v["a_brake_min"], free),
                             f"{SRC}: the least deceleration asked, or the deceleration without brake",
                             method="max(a_brake_min, d_free), d_free = (s (T_L − T_E) + F_r)/M_total the largest "
                                    "over the end states (koepe_slip.coasting_deceleration, each a closed form)"),
                    Equation(f"a_brake_high_{d}", high - fmin(v[f"a_slip_{d}_decel"], v["a_brake_max"]),
                             f"{SRC}: the slip limit, or the largest deceleration allowed"),
                    Equation(f"brake_margin_{d}", v[f"brake_margin_{d}"] - (high - low), f"{SRC}: the window's width")]
        return eqs

    def where(self, values):
        out, slips = {}, partner(self, "lining").where(values)
        for d, (sign, name) in DIRECTIONS.items():
            rows = self.coasting(values, sign)
            i = st.argleast([-x for _, x in rows])
            w = ks.braking_window_verdict(name, values[f"a_slip_{d}_decel"], values["a_brake_min"],
                                          values["a_brake_max"], rows[i][1])
            texts = {"the rule's least deceleration": "a_brake_min", "the rule's largest deceleration": "a_brake_max",
                     "the deceleration without brake": f"the deceleration without brake ({rows[i][0].state.name})",
                     f"the slip limit (a_slip_{d}_decel)":
                         f"the slip limit a_slip_{d}_decel ({slips[f'a_slip_{d}_decel'].split(': ', 1)[-1]})"}
            low, high = texts.get(w.low_by, w.low_by), texts.get(w.high_by, w.high_by)
            out[f"a_brake_low_{d}"], out[f"a_brake_high_{d}"] = low, high
            out[f"brake_margin_{d}"] = (f"{name}: {w.low:.4g} to {w.high:.4g} m/s², from {low} to {high}"
                                        if w.admissible else f"{name}: no admissible brake deceleration: {low} "
                                                             f"{w.low:.4g} m/s² exceeds {high} {w.high:.4g} m/s²")
        return out
