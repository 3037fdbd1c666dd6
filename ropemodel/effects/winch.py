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
``power``       ``none`` (default); ``drive`` — N_p = (F_C − F_S)·v_pj/η per direction (not in
                the paper; force balance on the drum).
"""

from __future__ import annotations

import math

import numpy as np

from ropemodel.effects.base import Equation, Submodel, define_effect, register
from ropemodel.papers import krauze2025 as kr
from ropemodel.quantity import Quantity

MODEL = "winch"
DIRECTIONS = {"up": kr.UP, "down": kr.DOWN}
SRC = "Krauze et al. 2025"

_pos = dict(low=0.0, low_open=True, positive=True)
_nonneg = dict(low=0.0)
_coef = dict(low=0.0, high=1.0)

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
         **usual(0.1, 8.0, f"rope-winch haulage speeds; {JUDGEMENT} (2.5 m/s)"), **_pos)
ETA = Q("eta", "1", "efficiency of the drive train", low=0.0, high=1.0, low_open=True, guess=0.85, default=1.0,
        default_note="no efficiency given: the power is the power at the drum rim",
        **usual(0.5, 1.0, "gear-motor drive trains (judgement)"))
STROKE = Q("stroke", "m", "installed stroke of the tensioner (return sheave): the rope take-up it allows", "mm",
           low=0.0, low_open=True, positive=True, unlimited=True, guess=1.0, default=math.inf,
           default_note="not given: unlimited (the take-up needed is reported)")
D_DRUM = Q("D", "m", "diameter of the driving drum (at the rope centre line)", "mm", guess=3.0,
           **usual(0.2, 8.0, "drums of 30 d for ropes of 8-60 mm, with margin (Krauze et al. 2025, introduction: "
                             "D >= 30 d)"), **_pos)


def per_direction(name, unit, description, display=None, **kw) -> tuple[Quantity, ...]:
    """The ``_up`` and ``_down`` versions of a direction-dependent quantity."""
    return tuple(
        Q(f"{name}_{d}", unit, f"{description} ({'upward' if d == 'up' else 'downward'} travel)", display, **kw)
        for d in DIRECTIONS
    )


define_effect(MODEL, "forces", "krauze2025", "haulage forces of both directions, eq. (1)-(14)")
define_effect(MODEL, "resistance", "case1", "resistance coefficients of the winding rope, eq. (15)-(18)")
define_effect(MODEL, "elongation", "krauze2025", "rope elongation and tensioner stroke, eq. (19)-(23)")
define_effect(MODEL, "power", "none", "drive power per direction")


_FORCES = ("F_S_up", "F_S_down", "F_C_up", "F_C_down")
_ROPE = {"S": "unwinding", "C": "winding"}
_TRAVEL = {"up": "upward travel", "down": "downward travel"}
_ROPE_MU = usual(0.01, 0.5, f"{JUDGEMENT} (0.05): a rope on rollers to a rope dragging on the floor")


@register(MODEL, "forces", "krauze2025")
class HaulageForces(Submodel):
    """Forces of an endless-rope winch haulage on an incline, Krauze et al. (2025) eq. (1)-(14)."""

    description = "static forces in the winding (F_C) and unwinding (F_S) rope, both directions"
    citations = ("krauze2025",)
    quantities = (
        Q("G_m", "N", "weight of the transported load", "kN", guess=4e5,
          **usual(1e3, 5e6, f"{JUDGEMENT} (467 kN): from one light car to a heavy train"), **_pos),
        Q("L_u", "m", "length of the inclined route", "m", guess=1000.0,
          **usual(20.0, 5000.0, f"{JUDGEMENT} (1150 m): rope-winch routes are tens of metres to a few km"),
          **_pos),
        Q("L_ul", "m", "distance of point A from the guiding sheave K_K", "m", guess=500.0, **_nonneg),
        Q("alpha_u", "rad", "inclination of the route", "deg", low=-math.pi / 2, high=math.pi / 2,
          low_open=True, high_open=True, guess=0.3,
          **usual(-math.pi / 4, math.pi / 4, f"{SRC}, introduction: rope winches serve workings inclined up to 45 deg")),
        Q("mu_pm", "1", "coefficient of resistance of the load", guess=0.05,
          **usual(0.005, 0.2, f"{JUDGEMENT} (0.05): mine cars roll at about 0.01, a sliding load up to 0.2"),
          **_coef),
        Q("mu_pl", "1", "coefficient of resistance of the unwinding rope", guess=0.05, **_ROPE_MU, **_coef),
        Q("mu_pl1", "1", "coefficient of resistance of the winding rope from K_ZN to point A", guess=0.05,
          **_ROPE_MU, **_coef),
        Q("mu_pl2", "1", "coefficient of resistance of the winding rope from point A to the drive", guess=0.05,
          **_ROPE_MU, **_coef),
        Q("q_l", "N/m", "weight of the rope per metre", "kN/m", guess=80.0,
          **usual(1.0, 200.0, "EN 12385-4 ropes of 8 to 60 mm, q_l = g W d^2 (the paper's 42 mm rope: 0.08 kN/m)"),
          **_pos),
        Q("F_nwl", "N", "initial tension from the tensioner", "kN", guess=2e4,
          **usual(500.0, 5e5, f"{JUDGEMENT} (20 kN)"), **_nonneg),
        Q("G_ml", "N", "load weight along the incline", "kN", equation=f"{SRC}, eq. (1)"),
        Q("G_l1", "N", "weight along the incline of the winding rope from K_ZN to A", "kN", equation=f"{SRC}, eq. (3)"),
        Q("G_l2", "N", "weight along the incline of the winding rope from A to the drive", "kN",
          equation=f"{SRC}, eq. (4)"),
        Q("G_l", "N", "weight along the incline of the winding rope", "kN", equation=f"{SRC}, eq. (2)"),
        Q("G_mo", "N", "load weight normal to the incline", "kN", equation=f"{SRC}, eq. (5)"),
        Q("G_ls", "N", "weight along the incline of the unwinding rope", "kN", equation=f"{SRC}, eq. (6)"),
        Q("T_m", "N", "travel resistance of the load", "kN", equation=f"{SRC}, eq. (7)"),
        Q("T_l1", "N", "resistance of the winding rope from K_ZN to A", "kN", equation=f"{SRC}, eq. (8)"),
        Q("T_l2", "N", "resistance of the winding rope from A to the drive", "kN", equation=f"{SRC}, eq. (9)"),
        Q("T_l", "N", "resistance of the winding rope", "kN", equation=f"{SRC}, eq. (10)"),
        Q("T_ls", "N", "resistance of the unwinding rope", "kN", equation=f"{SRC}, eq. (11)"),
        Q("G_lmC", "N", "weight along the incline of load and winding rope", "kN", equation=f"{SRC}, eq. (14)"),
        *per_direction("F_S", "N", "force in the unwinding rope", "kN", equation=f"{SRC}, eq. (12)"),
        *per_direction("F_C", "N", "force in the winding rope", "kN", equation=f"{SRC}, eq. (13)"),
    )

    def equations(self, v):
        a = v["alpha_u"]
        eqs = [
            Equation("G_ml", v["G_ml"] - kr.load_weight_along_incline(v["G_m"], a), "eq. (1)"),
            Equation("G_l1", v["G_l1"] - kr.rope_weight_along_incline(v["q_l"], v["L_u"] - v["L_ul"], a), "eq. (3)"),
            Equation("G_l2", v["G_l2"] - kr.rope_weight_along_incline(v["q_l"], v["L_ul"], a), "eq. (4)"),
            Equation("G_l", v["G_l"] - (v["G_l1"] + v["G_l2"]), "eq. (2)"),
            Equation("G_mo", v["G_mo"] - kr.load_weight_normal(v["G_m"], a), "eq. (5)"),
            Equation("G_ls", v["G_ls"] - kr.rope_weight_along_incline(v["q_l"], v["L_u"], a), "eq. (6)"),
            Equation("T_m", v["T_m"] - kr.load_resistance(v["mu_pm"], v["G_m"], a), "eq. (7)"),
            Equation("T_l1", v["T_l1"] - kr.rope_resistance(v["mu_pl1"], v["q_l"], v["L_u"] - v["L_ul"], a),
                     "eq. (8)"),
            Equation("T_l2", v["T_l2"] - kr.rope_resistance(v["mu_pl2"], v["q_l"], v["L_ul"], a), "eq. (9)"),
            Equation("T_l", v["T_l"] - (v["T_l1"] + v["T_l2"]), "eq. (10)"),
            Equation("T_ls", v["T_ls"] - kr.rope_resistance(v["mu_pl"], v["q_l"], v["L_u"], a), "eq. (11)"),
            Equation("G_lmC", v["G_lmC"] - (v["G_ml"] + v["G_l"]), "eq. (14)"),
        ]
        for d, sign in DIRECTIONS.items():
            eqs.append(Equation(f"F_S_{d}", v[f"F_S_{d}"] - kr.unwinding_rope_force(v["F_nwl"], v["G_ls"],
                                                                                      v["T_ls"], sign), "eq. (12)"))
            eqs.append(Equation(f"F_C_{d}", v[f"F_C_{d}"] - kr.winding_rope_force(
                v["F_nwl"], v["G_lmC"], v["T_m"], v["T_l"], sign), "eq. (13)"))
        return eqs

    def invalid_mask(self, values):
        """A rope force <= 0: the rope would have to push, so it is slack (the model no longer holds)."""
        out = {}
        for name in _FORCES:
            if name in values:
                mask = np.asarray(values[name]) <= 0.0
                if np.any(mask):
                    out[f"{name} <= 0: the {_ROPE[name[2]]} rope is slack ({_TRAVEL[name[4:]]})"] = mask
        return out

    def invalid(self, values):
        forces = {n: values[n] for n in _FORCES if n in values}
        if not forces or min(forces.values()) > 0.0:
            return []
        worst = min(forces, key=forces.get)
        need = values.get("F_nwl", 0.0) - 2.0 * forces[worst]
        return [f"{worst} = {forces[worst] / 1e3:.6g} kN: the {_ROPE[worst[2]]} rope would have to push "
                f"({_TRAVEL[worst[4:]]}); a rope cannot, it is slack and the model no longer holds. "
                f"Every rope stays taut with F_nwl > {need / 1e3:.6g} kN (now {values.get('F_nwl', 0.0) / 1e3:.6g} kN)"]

    def rules(self, values):
        if "L_ul" in values and "L_u" in values and values["L_ul"] > values["L_u"]:
            return [f"L_ul = {values['L_ul']:g} m is beyond L_u = {values['L_u']:g} m: point A must lie on the "
                    f"route, 0 <= L_ul <= L_u"]
        return []


@register(MODEL, "resistance", "case1")
class ResistanceCase1(Submodel):
    """Case 1 of Krauze et al. (2025), eq. (15): μ_pl1 = μ_pl2 = μ_pl; eq. (16) follows."""

    description = "one resistance coefficient mu_pl for all rope sections"
    citations = ("krauze2025",)

    def equations(self, v):
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


@register(MODEL, "elongation", "krauze2025")
class Elongation(Submodel):
    """Rope elongation and the minimum tensioner stroke, Krauze et al. (2025) eq. (19)-(23)."""

    description = "elongation of both ropes and the minimum stroke of the return sheave"
    citations = ("krauze2025",)
    quantities = (
        Q("q_lw", "m/N", "unit elongation of the installed rope", "mm/kN", guess=5.8e-6,
          **usual(3e-7, 1.2e-3, "q_lw = L_u/(E C d^2) for routes of 100-3000 m and EN 12385-4 ropes of 8-60 mm "
                                "(E C of 40-70 GPa); the paper's rope: 5.8 mm/kN"), **_pos),
        Q("dF_nwl", "m", "elongation under the initial tension", "mm", equation=f"{SRC}, eq. (22)"),
        *per_direction("dF_C", "m", "elongation of the winding rope", "mm", equation=f"{SRC}, eq. (19)"),
        *per_direction("dF_S", "m", "elongation of the unwinding rope", "mm", equation=f"{SRC}, eq. (20)"),
        *per_direction("dF_CS", "m", "elongation of both ropes", "mm", equation=f"{SRC}, eq. (21)"),
        *per_direction("dF", "m", "minimum stroke of the return sheave", "mm", equation=f"{SRC}, eq. (23)"),
    )

    def equations(self, v):
        eqs = [Equation("dF_nwl", v["dF_nwl"] - kr.elongation(v["q_lw"], v["F_nwl"]), "eq. (22)")]
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


@register(MODEL, "power", "none")
class NoPower(Submodel):
    """Drive power off: no power equation is built."""

    description = "no drive power"


@register(MODEL, "power", "drive")
class DrivePower(Submodel):
    """Drive power N_p = (F_C − F_S)·v_pj/η per direction (not in Krauze et al. 2025).

    The drum's torque balances the difference of the winding and unwinding rope
    forces; η is the efficiency of the drive train from motor to drum rim.
    """

    description = "drive power per direction from the force balance on the drum"
    citations = ("krauze2025",)
    quantities = (
        V_PJ,
        ETA,
        *per_direction("N_p", "W", "drive power", "kW", equation="force balance on the drum"),
    )

    def equations(self, v):
        return [
            Equation(f"N_p_{d}", v[f"N_p_{d}"] - kr.drive_power(v[f"F_C_{d}"], v[f"F_S_{d}"], v["v_pj"], v["eta"]),
                     "N_p = (F_C - F_S) v_pj / eta")
            for d in DIRECTIONS
        ]
