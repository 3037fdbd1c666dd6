"""Winch haulage model (``model = "winch"``): forces, elongation, stroke and drive power.

Equations: Krauze et al. (2025), eq. (1)-(23), see :mod:`ropemodel.papers.krauze2025`.
Direction-dependent quantities carry the suffix ``_up`` (load hauled up) or
``_down`` (load lowered).

Effects and variants
--------------------
``forces``      ``krauze2025`` — eq. (1)-(14) and F_S, F_C of eq. (12)-(13), both directions.
``resistance``  ``case1`` (default) — μ_pl1 = μ_pl2 = μ_pl, eq. (15)-(16);
                ``case2`` — μ_pl1, μ_pl2 given separately, eq. (17)-(18).
``elongation``  ``krauze2025`` (default) — eq. (19)-(23); ``none`` builds no elongation equation.
``power``       ``none`` (default); ``drive`` — the drum's power P_drum = (F_C − F_S)·(±v_pj) and
                the drive's N_p = P_drum/η motoring, P_drum·η braking, per direction, signed:
                > 0 motoring, < 0 braking (not in the paper; force balance on the drum).
"""

from __future__ import annotations

import math

import numpy as np

from ropemodel.effects import domains as dom
from ropemodel.effects.base import Equation, Submodel, define_effect, register
from ropemodel.papers import krauze2025 as kr
from ropemodel.papers import route as rt
from ropemodel.quantity import Quantity, symbol_of

MODEL = "winch"
DIRECTIONS = {"up": kr.UP, "down": kr.DOWN}
SRC = "Krauze et al. 2025"

POSITIVE = dict(positive=True)      # solved for in log space where it is an unknown (its domain is > 0)
#: an output whose worst case is its largest value (:attr:`ropemodel.quantity.Quantity.worst`)
LARGEST = dict(worst=("largest",))

#: what a signed power's sign means (four-quadrant convention)
SIGNS = ("braking", "motoring")

#: where the usual ranges come from (warnings outside them; README, "Writing a scene")
JUDGEMENT = "engineering judgement, a wide margin around the paper's example"


def Q(name, unit, description, display=None, **kw) -> Quantity:
    """Shorthand for a winch quantity."""
    return Quantity(name, unit, description, display, **kw)


def usual(low, high, source) -> dict:
    """Keyword arguments of a usual range [low, high] (SI) and where it comes from."""
    return dict(warn_low=low, warn_high=high, usual_source=source)


# quantities several winch effects share, declared once (the registry refuses a second declaration)
V_PJ = Q("v_pj", "m/s", "haulage speed of the load", "m/s", guess=2.5,
         **usual(0.1, 8.0, f"rope-winch haulage speeds; {JUDGEMENT} (2.5 m/s)"), **dom.SPEED, **POSITIVE)
ETA = Q("eta", "1", "efficiency of the drive train", guess=0.85, default=1.0,
        default_note="no efficiency given: the power is the power at the drum rim",
        **usual(0.5, 1.0, "gear-motor drive trains (judgement)"), **dom.FRACTION)
STROKE = Q("stroke", "m", "installed stroke of the tensioner (return sheave): the rope take-up it allows", "mm",
           positive=True, unlimited=True, guess=1.0, default=math.inf,
           default_note="not given: unlimited (the take-up needed is reported)", **dom.ROUTE_LENGTH)
D_DRUM = Q("D", "m", "diameter of the driving drum (at the rope centre line)", "mm", guess=3.0,
           **usual(0.2, 8.0, "drums of 30 d for ropes of 8-60 mm, with margin (Krauze et al. 2025, introduction: "
                             "D >= 30 d)"), **dom.WHEEL, **POSITIVE)


def per_direction(name, unit, description, display=None, symbol="", **kw) -> tuple[Quantity, ...]:
    """The ``_up`` and ``_down`` versions of a direction-dependent quantity (``symbol``: the symbol both
    share, e.g. ``"m_safety"``, shown ``m_safety,up``; default: made from the name)."""
    return tuple(
        Q(f"{name}_{d}", unit, f"{description} ({'upward' if d == 'up' else 'downward'} travel)", display,
          symbol=symbol_of(f"{name}_{d}", symbol) if symbol else "", **kw)
        for d in DIRECTIONS
    )


define_effect(MODEL, "route", "straight", "the route: the paper's single incline, or a list of straight segments")
define_effect(MODEL, "forces", "krauze2025", "haulage forces of both directions, eq. (12)-(14)")
define_effect(MODEL, "resistance", "case1", "resistance coefficients of the winding rope, eq. (15)-(18)")
define_effect(MODEL, "elongation", "krauze2025", "rope elongation and tensioner stroke: eq. (19)-(23), or as built")
define_effect(MODEL, "power", "none", "drive power per direction")


F_NWL = Q("F_nwl", "N", "initial tension from the tensioner", "kN", guess=2e4,
          **usual(500.0, 5e5, f"{JUDGEMENT} (20 kN)"), **dom.FORCE)
G_LMC = Q("G_lmC", "N", "weight along the incline of load and winding rope", "kN", equation=f"{SRC}, eq. (14)")
_FORCES = ("F_S_up", "F_S_down", "F_C_up", "F_C_down")
_ROPE = {"S": "unwinding", "C": "winding"}
_TRAVEL = {"up": "upward travel", "down": "downward travel"}
ROPE_MU = usual(0.01, 0.5, f"{JUDGEMENT} (0.05): a rope on rollers to a rope dragging on the floor")


@register(MODEL, "forces", "krauze2025")
class HaulageForces(Submodel):
    """Forces in the winding (F_C) and unwinding (F_S) rope, Krauze et al. (2025) eq. (12)-(14).

    The weights and resistances of eq. (1)-(11) come from the ``route`` effect (the paper's single
    incline, or a route of segments).  With ``inertia = "rigid"`` a haulage speeding up at a_h adds
    the inertia of each side like a resistance (:mod:`ropemodel.papers.route`); without it (the
    default, the paper's) the forces are those of steady motion.
    """

    description = "static forces in the winding (F_C) and unwinding (F_S) rope, both directions"
    assumptions = ("The rope forces of eq. (12)-(13): half the tensioner's force F_nwl in each rope at the return "
                   "sheave, the weights along the incline, and resistances proportional to the normal forces.",)
    citations = ("krauze2025",)
    quantities = (
        F_NWL,
        G_LMC,
        *per_direction("F_S", "N", "force in the unwinding rope", "kN", equation=f"{SRC}, eq. (12)",
                       worst=("least", "largest")),
        *per_direction("F_C", "N", "force in the winding rope", "kN", equation=f"{SRC}, eq. (13)",
                       worst=("largest",)),
    )

    def equations(self, v):
        eqs = [Equation("G_lmC", v["G_lmC"] - (v["G_ml"] + v["G_l"]), "eq. (14)")]
        rigid = self.effects.get("inertia") == "rigid"
        for d, sign in DIRECTIONS.items():
            T_S, T_C = v["T_ls"], v["T_m"] + v["T_l"]
            if rigid:   # the inertia of a ramp acts like a resistance: with the sign of travel
                T_S, T_C = T_S + v["I_S"], T_C + v["I_C"]
            eqs.append(Equation(f"F_S_{d}", v[f"F_S_{d}"] - kr.unwinding_rope_force(v["F_nwl"], v["G_ls"], T_S, sign),
                                "eq. (12)" + (" + inertia" if rigid else "")))
            eqs.append(Equation(f"F_C_{d}",
                                v[f"F_C_{d}"] - kr.winding_rope_force(v["F_nwl"], v["G_lmC"], T_C, 0.0, sign),
                                "eq. (13)" + (" + inertia" if rigid else "")))
        return eqs

    invalid_needs = _FORCES

    def invalid_needs_for(self, outputs):
        """The forces of the directions of ``outputs`` when each belongs to one (``F_C_up``, ``dF_up``:
        a slack rope lowering does not spoil hauling up), else all four."""
        directions = {o.rsplit("_", 1)[-1] for o in outputs}
        if not directions <= set(_TRAVEL):
            return _FORCES
        return tuple(f for f in _FORCES if f.rsplit("_", 1)[-1] in directions)

    def invalid_mask(self, values):
        """A rope force <= 0: the rope would have to push, so it is slack (the model no longer holds)."""
        return slack_masks(values, _FORCES)

    def invalid(self, values):
        return slack_reasons(values, _FORCES)


def slack_masks(values: dict, names, where: str = "") -> dict:
    """Reason → mask of the points where a rope tension among ``names`` (``F_S_up``, ``F_C_least_down``: the
    side is the letter after ``F_``, the direction the suffix) is <= 0: the rope would have to push, so it is
    slack (the model no longer holds) ``where`` (e.g. " inside the route")."""
    out = {}
    for name in (n for n in names if n in values):
        mask = np.asarray(values[name]) <= 0.0
        if np.any(mask):
            out[f"{name} <= 0: the {_ROPE[name[2]]} rope is slack{where} ({_TRAVEL[name.rsplit('_', 1)[1]]})"] = mask
    return out


def slack_reasons(values: dict, names, where: str = "") -> list[str]:
    """:func:`slack_masks` at one point: the least of ``names`` if <= 0, in words, with the least F_nwl that keeps
    every rope taut (each tension carries F_nwl/2)."""
    forces: dict[str, float] = {n: float(values[n]) for n in names if n in values}
    if not forces or min(forces.values()) > 0.0:
        return []
    worst = min(forces, key=lambda n: forces[n])
    need, now = values.get("F_nwl", 0.0) - 2.0 * forces[worst], values.get("F_nwl", 0.0)
    return [f"{worst} = {forces[worst] / 1e3:.6g} kN: the {_ROPE[worst[2]]} rope would have to push{where} "
            f"({_TRAVEL[worst.rsplit('_', 1)[1]]}); a rope cannot, it is slack and the model no longer holds. "
            f"Every rope stays taut with F_nwl > {need / 1e3:.6g} kN (now {now / 1e3:.6g} kN)"]


define_effect(MODEL, "inertia", "none", "inertia of a haulage speeding up or slowing down (rigid rope)")


@register(MODEL, "inertia", "none")
class SteadyMotion(Submodel):
    """Steady motion: no inertia force (the paper's forces)."""

    description = "steady motion: no inertia force"
    assumptions = ("Steady motion: the forces are those at constant speed; starting and stopping add inertia "
                   "(inertia = \"rigid\", or the transient).",)

    def rope_force_per_metre(self, v):
        """The inertia force per metre of rope [N/m] (0: steady motion), for a side's tension profile."""
        return 0.0

    def acceleration(self, v):
        """The haulage's acceleration the forces include [m/s²]: none."""
        return 0.0


#: the deceleration of an emergency stop: no default number (no source fits every safety brake), so without it
#: no emergency stop is checked, and the output says so
A_E = Q("a_e", "m/s^2", "deceleration of an emergency stop (the safety brake's, > 0); 0: none checked", "m/s^2",
        guess=1.0, default=0.0,
        **dom.domain(0.0, 100.0, "0 (none checked) to 10 g: beyond any safety brake (emergency brakes of mine "
                                 "hoists about 5 m/s^2)"),
        default_note="not given: no emergency stop is checked (no general source gives a deceleration that fits "
                     "every safety brake: give the brake's rated deceleration)")


@register(MODEL, "inertia", "rigid")
class RigidInertia(Submodel):
    """A haulage speeding up at ``a_h`` in its direction of travel (negative: slowing down), the rope
    inextensible: the winding side gains (G_m + q_l L_u)/g·a_h, the unwinding side loses q_l L_u/g·a_h
    (:mod:`ropemodel.papers.route`).  The trip (:mod:`ropemodel.trips`) and sizing through the ramps use it."""

    description = "rigid-body inertia of the load and both rope sides at acceleration a_h"
    citations = ("krauze2025",)
    quantities = (
        Q("a_h", "m/s^2", "acceleration of the haulage in its direction of travel (< 0: slowing down)", "m/s^2",
          guess=0.5, default=0.0,
          default_note="not given: every manoeuvre of the scene, each result at its worst (steady motion; a start "
                       "and a stop at the ramp's acceleration with t_ramp; an emergency stop at -a_e with a_e); "
                       "steady motion at a single point (a trip sets it along its ramps)",
          **dom.domain(-100.0, 100.0, "10 g either way: beyond any haulage's start or stop (emergency brakes "
                                      "of mine hoists about 5 m/s^2)")),
        A_E,
        Q("I_C", "N", "inertia force of the winding side (load and winding rope), (G_m + q_l L_u)/g a_h", "kN",
          equation="rigid-body inertia (not in the paper)"),
        Q("I_S", "N", "inertia force of the unwinding rope, q_l L_u/g a_h", "kN",
          equation="rigid-body inertia (not in the paper)"),
    )

    def rope_force_per_metre(self, v):
        """The rope's inertia per metre, I_S/L_u = q_l a_h/g [N/m] (the same on both sides)."""
        return v["I_S"] / v["L_u"]

    def acceleration(self, v):
        """The haulage's acceleration the forces include [m/s²]: a_h."""
        return v["a_h"]

    def equations(self, v):
        v["a_e"]  # noqa: B018 - a parameter of the scene: the emergency stop of the worst case (ropemodel.envelope)
        return [
            Equation("I_C", v["I_C"] - rt.winding_side_mass(v["G_m"], v["q_l"], v["L_u"]) * v["a_h"],
                     "rigid-body inertia (not in the paper)"),
            Equation("I_S", v["I_S"] - rt.unwinding_side_mass(v["q_l"], v["L_u"]) * v["a_h"],
                     "rigid-body inertia (not in the paper)"),
        ]


@register(MODEL, "resistance", "case1")
class ResistanceCase1(Submodel):
    """Case 1 of Krauze et al. (2025), eq. (15): μ_pl1 = μ_pl2 = μ_pl; eq. (16) follows."""

    description = "one resistance coefficient mu_pl for all rope sections"
    assumptions = ("One resistance coefficient μ_pl for every section of the rope, eq. (15).",)
    citations = ("krauze2025",)
    #: the winding rope's resistance changes at point A (the straight route is two pieces there)
    split_at_A = False

    def equations(self, v):
        if self.effects.get("route") == "segments":   # each segment carries its own coefficient
            return []
        return [
            Equation("mu_pl1", v["mu_pl1"] - v["mu_pl"], "eq. (15)"),
            Equation("mu_pl2", v["mu_pl2"] - v["mu_pl"], "eq. (15)"),
        ]


@register(MODEL, "resistance", "case2")
class ResistanceCase2(Submodel):
    """Case 2 of Krauze et al. (2025), eq. (17)-(18): μ_pl1 ≠ μ_pl2 given; L_ul matters.

    Erratum: the second line of eq. (18) has a misplaced parenthesis; the model
    uses eq. (13) with eq. (17), which equals the first line of eq. (18).
    """

    description = "separate coefficients mu_pl1, mu_pl2 for the winding rope either side of point A"
    citations = ("krauze2025",)
    split_at_A = True


#: the rope's stiffness and the elongations every elongation variant defines (declared once, shared)
Q_LW = Q("q_lw", "m/N", "unit elongation of the installed rope", "mm/kN", guess=5.8e-6,
         **usual(3e-7, 1.2e-3, "q_lw = L_u/(E C d^2) for routes of 100-3000 m and EN 12385-4 ropes of 8-60 mm "
                               "(E C of 40-70 GPa); the paper's rope: 5.8 mm/kN"), **POSITIVE,
         **dom.domain(1e-12, 10.0, "q_lw = L_u/EA from 1 m of the stiffest rope (EA about 5e10 N) to 100 km "
                                   "of an 8-mm synthetic rope (EA about 1e4 N)"))
EA = Q("EA", "N", "axial stiffness of the rope, L_u/q_lw", "MN",
       equation="Hooke's law over the route (not in the paper)")
_AS_BUILT = "as built: the side's tension profile integrated (docs/physics.md §8)"
DF_NWL = Q("dF_nwl", "m", "elongation under the initial tension", "mm",
           equation=f"{SRC}, eq. (22)")
DF_SIDES = (*per_direction("dF_C", "m", "elongation of the winding rope", "mm",
                           equation=f"{SRC}, eq. (19); {_AS_BUILT}", **LARGEST),
            *per_direction("dF_S", "m", "elongation of the unwinding rope", "mm",
                           equation=f"{SRC}, eq. (20); {_AS_BUILT}", **LARGEST),
            *per_direction("dF_CS", "m", "elongation of both ropes", "mm", equation=f"{SRC}, eq. (21)",
                           **LARGEST))
DF = per_direction("dF", "m", "minimum stroke of the return sheave", "mm",
                   equation=f"{SRC}, eq. (23); as built: with reeving, constructional stretch, temperature",
                   **LARGEST)


@register(MODEL, "elongation", "krauze2025")
class Elongation(Submodel):
    """Rope elongation and the minimum tensioner stroke, Krauze et al. (2025) eq. (19)-(23)."""

    description = ("eq. (19)-(23): each whole rope side under its force at the drive, the return sheave taking up "
                   "the loop's whole elongation")
    assumptions = (
        "Each rope side stretches under its largest force over its whole length, eq. (19)-(20): the elastic "
        "elongation is bounded from above.",
        "No constructional (permanent) stretch of a new rope: it comes on top of the elastic elongation and usually "
        "dominates the first months.",
        "The tensioner takes up the loop's whole elongation: its reeving (number of falls) is not modelled "
        "(elongation = \"asbuilt\" models the profile, the falls, constructional stretch and temperature).",
    )
    citations = ("krauze2025",)
    quantities = (Q_LW, EA, DF_NWL, *DF_SIDES, *DF)

    def equations(self, v):
        eqs = [Equation("dF_nwl", v["dF_nwl"] - kr.elongation(v["q_lw"], v["F_nwl"]), "eq. (22)"),
               Equation("EA", v["EA"] - v["L_u"] / v["q_lw"], "Hooke's law over the route: EA = L_u/q_lw "
                                                              "(not in the paper)")]
        for d in DIRECTIONS:
            eqs += [
                Equation(f"dF_C_{d}", v[f"dF_C_{d}"] - kr.elongation(v["q_lw"], v[f"F_C_{d}"]), "eq. (19)"),
                Equation(f"dF_S_{d}", v[f"dF_S_{d}"] - kr.elongation(v["q_lw"], v[f"F_S_{d}"]), "eq. (20)"),
                Equation(f"dF_CS_{d}", v[f"dF_CS_{d}"] - (v[f"dF_C_{d}"] + v[f"dF_S_{d}"]), "eq. (21)"),
                Equation(f"dF_{d}", v[f"dF_{d}"] - (v[f"dF_CS_{d}"] + v["dF_nwl"]), "eq. (23)"),
            ]
        return eqs


@register(MODEL, "elongation", "none")
class NoElongation(Submodel):
    """Elongation off: no elongation or stroke equation is built."""

    description = "no elongation equations"
    missing = ("No elongation: the tensioner's stroke is not computed (elongation = \"krauze2025\").",)


@register(MODEL, "power", "none")
class NoPower(Submodel):
    """Drive power off: no power equation is built."""

    description = "no drive power"


@register(MODEL, "power", "drive")
class DrivePower(Submodel):
    """Drive power per direction, signed (four-quadrant; not in Krauze et al. 2025).

    The drum's power P_drum = (F_C − F_S)·u with u = s·v_pj the load's signed speed (s = +1 upward,
    −1 downward; :func:`ropemodel.papers.krauze2025.drum_power`), and the drive's
    N_p = P_drum/η while it motors (P_drum > 0), P_drum·η while it brakes (P_drum < 0;
    :func:`~ropemodel.papers.krauze2025.drive_power`).  η is the efficiency of the drive train from
    motor to drum rim.  Lowering the paper's load (Fig. 9) the drive brakes: N_p_down = −243.584 kW.
    """

    description = "drive power per direction, > 0 motoring, < 0 braking, from the force balance on the drum"
    assumptions = ("The drive train's efficiency η divides the power while motoring and multiplies it while "
                   "braking; the drum's own inertia and losses are not included.",)
    citations = ("krauze2025",)
    quantities = (
        V_PJ,
        ETA,
        *per_direction("P_drum", "W", "power at the drum, (F_C − F_S) times the load's signed speed: > 0 motoring, "
                       "< 0 braking", "kW", equation="force balance on the drum (not in the paper)",
                       signs=SIGNS, worst=("largest", "least")),
        *per_direction("N_p", "W", "drive power, P_drum/η motoring (> 0), P_drum·η braking (< 0)", "kW",
                       equation="force balance on the drum and the drive train's efficiency (not in the paper)",
                       signs=SIGNS, worst=("largest", "least")),
    )

    def equations(self, v):
        eqs = []
        for d, sign in DIRECTIONS.items():
            eqs += [Equation(f"P_drum_{d}", v[f"P_drum_{d}"] - kr.drum_power(v[f"F_C_{d}"], v[f"F_S_{d}"],
                                                                           sign * v["v_pj"]),
                             "force balance on the drum (not in the paper)"),
                    Equation(f"N_p_{d}", v[f"N_p_{d}"] - kr.drive_power(v[f"P_drum_{d}"], v["eta"]),
                             "the drive train's efficiency, four-quadrant (not in the paper)")]
        return eqs
