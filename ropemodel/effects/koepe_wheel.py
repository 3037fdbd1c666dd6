"""Traction of the Koepe wheel (effect ``lining``): static slip, the anti-slip factor, the slip accelerations.

At rest, in each static end state (:data:`ropemodel.effects.koepe_states.STATIC`) the high and low side's
tensions T_1, T_2 give the anti-slip factor σ = (ρ − 1) T_2/(T_1 − T_2) (Chinese practice,
:func:`ropemodel.papers.koepe.anti_slip_factor`) with the lining's traction limit ρ (T_1/T_2 at the onset of
slip).  The worst static state is the one of least σ (with a rigid lining, of largest T_1/T_2); ``T_1``,
``T_2``, ``ratio_static``, ``traction_limit`` and ``sigma_static`` are that state's.  ``traction_limit_run`` is
the limit while the ropes run steadily at v_max, at the same T_2.  A hoist with σ < 1 slips at rest: no
result (exit 1), the state and numbers named (:func:`ropemodel.papers.koepe.slip_at_rest`).

The four slip accelerations (``a_slip_hoist_accel`` …, :mod:`ropemodel.papers.koepe_slip`; "hoist" moves the
loaded conveyance up) are the least over every manoeuvre's end states
(:data:`~ropemodel.effects.koepe_states.DYNAMIC`), each at the speed between rest and v_max (a start, a stop)
where the lining holds least.  A point outside the physics gives no result (exit 1): slip at rest, a shaft
resistance that would slacken the ropes of conveyance L's side lowering, ropes lifting off the lining.

``rigid``  ρ = e^{μα} (Euler–Eytelwein); the ropes on the wheel and their centrifugal force included
           (:func:`ropemodel.papers.koepe_slip.slip_acceleration`).  The limit falls with the speed (the
           centrifugal term −(e^{μα} − 1) q v² of its numerator), so the least is at v_max.  The slip condition
           holds while the ropes press on the lining: no result where q v_max² reaches the low side's tension.
``voigt``  Hajduk (1992), eq. (19) on the wheel, S_0 = T_2/n_head (:mod:`ropemodel.papers.koepe_lining`).
           The crept compliance C(α) = Q_R (1 − e^{−α/k_R}) + Q_T (1 − e^{−α/k_T}), k = λ v/R, is largest at
           rest (k = 0), and a larger C holds less (eq. (19)'s residual rises with C, so its root T_U falls),
           so the static traction and the least slip acceleration are at v → 0, the lining fully crept; λ enters
           ``traction_limit_run`` only.  The slip acceleration is Newton's method on
           :func:`~ropemodel.papers.koepe_lining.voigt_slip_residual` from its monotone start, unrolled
           (:data:`NEWTON_STEPS`); a step still above 1e-12 after them gives no number (NaN, an error).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from ropemodel._math import exp, fabs, fmax, fmin, if_else
from ropemodel.effects import domains as dom
from ropemodel.effects import koepe_states as st
from ropemodel.effects.base import Equation, Submodel, register
from ropemodel.effects.koepe import (ALPHA, D_WHEEL, F_R, M_SHEAVE, MODEL, MU, V_MAX, Q, static_states,
                                     tail_terms, usual)
from ropemodel.papers import hajduk1992 as hj
from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_lining as kl
from ropemodel.papers import koepe_slip as ks
from ropemodel.quantity import Quantity

SRC = "docs/physics.md §7"
#: Newton steps of the Voigt slip limit, unrolled: from its monotone start it needs at most 10 on 2e5 random
#: cases (tests/test_koepe_lining.py); the rest is margin, and the last step is checked
NEWTON_STEPS = 20
MANOEUVRES = {"hoist_accel": "hoisting, speeding up", "hoist_decel": "hoisting, slowing down",
              "lower_accel": "lowering, speeding up", "lower_decel": "lowering, slowing down"}
#: what the physics checks of a sweep's points are computed from (those the scene has)
NEEDS = ("H", "H_head", "m_conveyance", "m_payload", "n_head", "q_head", "n_tail", "q_tail", "h_loop", "F_r",
         "m_sheave_a", "m_sheave_b", "mu", "alpha", "D", "v_max")
STATIC_OUT = ("T_1", "T_2", "ratio_static", "traction_limit", "traction_limit_run", "sigma_static")

OUTPUTS = (
    Q("T_1", "N", "the high side's static tension in the worst static state (least anti-slip factor)", "kN",
      equation=f"{SRC}: max(T_L, T_E)", guess=8e5),
    Q("T_2", "N", "the low side's static tension in the worst static state", "kN", equation=f"{SRC}: min(T_L, T_E)",
      guess=6e5),
    Q("ratio_static", "1", "static tension ratio T_1/T_2 of the worst static state", equation=f"{SRC}: T_1/T_2"),
    Q("traction_limit", "1", "the lining's traction limit at rest: T_1/T_2 at the onset of slip", symbol="ρ",
      equation="rigid: e^{μα} (Euler–Eytelwein); voigt: Hajduk 1992 eq. (19) at rest, S_0 = T_2/n_head"),
    Q("traction_limit_run", "1", "the traction limit while the ropes run steadily at v_max, at T_2", symbol="ρ_run",
      equation="rigid: e^{μα} − (e^{μα} − 1) q v²/T_2 (centrifugal force); voigt: Hajduk 1992 eq. (19), k = λ v/R"),
    Q("sigma_static", "1", "static anti-slip factor (ρ − 1) T_2/(T_1 − T_2), the least over the static states",
      equation="Chinese friction-hoist practice (antislip_cn)"),
    *(Q(f"a_slip_{m}", "m/s^2", f"largest acceleration magnitude before the head ropes slip, {text}: the least "
        f"over the end states", "m/s^2", equation=f"{SRC}: koepe_slip.a_slip_{m}") for m, text in MANOEUVRES.items()),
)


class WheelLining(Submodel):
    """The outputs of every lining; a variant gives its traction limits and its slip acceleration."""

    #: how a variant's slip acceleration is computed, and the tolerance it meets
    slip_method: ClassVar[str] = ""
    slip_tolerance: ClassVar[float | None] = None
    citations: ClassVar[tuple[str, ...]] = ("delavergne2003", "antislip_cn")
    quantities: ClassVar[tuple[Quantity, ...]] = (MU, ALPHA, D_WHEEL, V_MAX, F_R, *M_SHEAVE, *OUTPUTS)

    def limit(self, v, T_2, speed=0.0):
        """Traction limit ρ = T_1/T_2 for the low side's tension T_2 [N], the ropes running steadily at
        ``speed`` [m/s] (0: at rest) [-]."""
        raise NotImplementedError

    def limit_equation(self, v, name: str, speed) -> Equation:
        """The equation of ``traction_limit`` (speed 0) or ``traction_limit_run`` (speed v_max), at T_2."""
        raise NotImplementedError

    def slip(self, v, F_U, F_D, M_U, M_D):
        """The least slip acceleration of side U at a speed between rest and v_max [m/s²]."""
        raise NotImplementedError

    def static_rows(self, v) -> list:
        """(sides, T_1, T_2, ρ, σ) of each static state."""
        rows = []
        for s in static_states(self, v):
            T_1, T_2 = kp.high_low(s.T_L, s.T_E)
            rho = self.limit(v, T_2)
            rows.append((s, T_1, T_2, rho, kp.anti_slip_factor(T_1, T_2, rho)))
        return rows

    def slip_rows(self, v) -> list:
        """(sides, {manoeuvre: slip acceleration}) of each state of the manoeuvres."""
        tail, rows = tail_terms(self, v), []
        for state in st.DYNAMIC:
            s = st.sides(v, tail, state)
            M_L, M_E = st.masses(v, s)
            sides = ks.manoeuvre_sides(s.T_L, s.T_E, M_L, M_E, v["F_r"])
            rows.append((s, {m: self.slip(v, *sides[m]) for m in MANOEUVRES}))
        return rows

    def equations(self, v):
        static = self.static_rows(v)
        sigma = [r[4] for r in static]
        T_1, T_2 = st.pick(sigma, [r[1] for r in static], [r[2] for r in static])
        worst = "in the static end state of least σ (loaded at the bottom, at the top, empty)"
        eqs = [Equation("T_1", v["T_1"] - T_1, f"{SRC}: the high side", method=f"max(T_L, T_E) {worst}"),
               Equation("T_2", v["T_2"] - T_2, f"{SRC}: the low side", method=f"min(T_L, T_E) {worst}"),
               Equation("ratio_static", v["ratio_static"] - v["T_1"] / v["T_2"], f"{SRC}: T_1/T_2"),
               self.limit_equation(v, "traction_limit", 0.0),
               self.limit_equation(v, "traction_limit_run", v["v_max"]),
               Equation("sigma_static", v["sigma_static"] - st.smallest(sigma),
                        "anti-slip factor of Chinese practice (antislip_cn)",
                        governing=v["sigma_static"] - kp.anti_slip_factor(v["T_1"], v["T_2"], v["traction_limit"]),
                        method=f"the least over the static end states; T_1, T_2 and ρ {worst}")]
        dynamic = self.slip_rows(v)
        for m, text in MANOEUVRES.items():
            eqs.append(Equation(f"a_slip_{m}", v[f"a_slip_{m}"] - st.smallest([r[1][m] for r in dynamic]),
                                f"{SRC}: koepe_slip.a_slip_{m} ({text})", method=self.slip_method,
                                tolerance=self.slip_tolerance))
        return eqs

    def where(self, values):
        static = self.static_rows(values)
        worst = static[st.argleast([r[4] for r in static])][0]
        out = dict.fromkeys(STATIC_OUT, st.describe(worst, high=True))
        dynamic = self.slip_rows(values)
        differ = values["m_sheave_a"] != values["m_sheave_b"]
        for m, text in MANOEUVRES.items():
            i = st.argleast([r[1][m] for r in dynamic])
            out[f"a_slip_{m}"] = f"{text}: {st.describe(dynamic[i][0], compartment=differ)}"
        return out

    def frames(self, values, scene):
        import pandas as pd        # only where a table is made: the command line starts without it

        static = pd.DataFrame([{"state": r[0].state.name, "T_L [kN]": r[0].T_L / 1e3, "T_E [kN]": r[0].T_E / 1e3,
                                "T_1/T_2 [-]": r[1] / r[2], "traction limit [-]": r[3], "sigma [-]": r[4]}
                               for r in self.static_rows(values)])
        rows = []
        for s, limits in self.slip_rows(values):
            rows.append({"state": s.state.name, "conveyance L in": s.state.compartment,
                         **{f"a_slip_{m} [m/s^2]": a for m, a in limits.items()}})
        return {"static states at the wheel": static, "slip accelerations in each end state": pd.DataFrame(rows)}

    def troubles(self, v) -> dict:
        """Each way a point leaves the physics → (where: a bool, or a boolean array over a sweep's points; the
        force [N] that crosses; the force it reaches)."""
        lowest = st.smallest([s.T_L for s in (st.sides(v, tail_terms(self, v), x) for x in st.DYNAMIC[::2])])
        return {"the head ropes slip on the wheel at rest (sigma_static < 1)": (v["sigma_static"] < 1.0, 0.0, 0.0),
                "lowering, the ropes of conveyance L's side would go slack: the shaft resistance F_r reaches their "
                "tension": (v["F_r"] >= lowest, v["F_r"], lowest)}

    def invalid(self, values):
        out = []
        for reason, (bad, force, reached) in self.troubles(values).items():
            if not bad:
                continue
            if reason.startswith("the head ropes slip"):
                cases = kp.static_cases(values["m_conveyance"], values["m_payload"], values["H"], values["H_head"],
                                        values["n_head"], values["q_head"], *tail_terms(self, values))
                out.append(f"no result: {kp.slip_at_rest(cases, lambda T_2: self.limit(values, T_2)).message}")
            else:
                out.append(f"no result: {reason} ({force / 1e3:.4g} kN against {reached / 1e3:.4g} kN)")
        return out

    def invalid_mask(self, values):
        return {reason: bad for reason, (bad, _, _) in self.troubles(values).items() if np.any(bad)}

    def invalid_needs_for(self, outputs):
        """sigma_static and what the tensions and the lining's limits are computed from (those of the scene)."""
        return ("sigma_static", *NEEDS)


@register(MODEL, "lining", "rigid")
class RigidWheel(WheelLining):
    """Euler–Eytelwein on the wheel: ρ = e^{μα}; the ropes on the wheel and their centrifugal force at v_max."""

    description = "rigid lining: Euler–Eytelwein, with the ropes on the wheel (mass, centrifugal force)"
    citations = (*WheelLining.citations, "euler_eytelwein")
    slip_method = ("the least over the end states (both ends, loaded and empty, conveyance L in either "
                   "compartment) of koepe_slip.slip_acceleration at v_max, each a closed form")

    def limit(self, v, T_2, speed=0.0):
        E, c = exp(v["mu"] * v["alpha"]), ks.centrifugal_tension(v["n_head"] * v["q_head"], speed)
        return (E * (T_2 - c) + c) / T_2

    def limit_equation(self, v, name, speed):
        if name == "traction_limit":
            return Equation(name, v[name] - exp(v["mu"] * v["alpha"]), "Euler–Eytelwein, Hajduk 1992 eq. (8)")
        return Equation(name, v[name] - self.limit(v, v["T_2"], speed),
                        f"{SRC}: the slip condition at a = 0, T_1 − q v² = e^(μα) (T_2 − q v²)")

    def slip(self, v, F_U, F_D, M_U, M_D):
        return ks.slip_acceleration(F_U, F_D, M_U, M_D, v["mu"], v["alpha"], v["n_head"] * v["q_head"],
                                    v["D"] / 2.0, v["v_max"])

    def troubles(self, v):
        """Also: the ropes lift off the lining where their centrifugal force q v_max² reaches the low side's
        tension, at rest or at a manoeuvre's slip limit (the slip condition holds while they press on it)."""
        c = ks.centrifugal_tension(v["n_head"] * v["q_head"], v["v_max"])
        lows = [fmin(s.T_L, s.T_E) for s in static_states(self, v)]
        for s, limits in self.slip_rows(v):
            sides = ks.manoeuvre_sides(s.T_L, s.T_E, *st.masses(v, s), v["F_r"])
            lows += [sides[m][1] - sides[m][3] * a for m, a in limits.items()]
        return {**super().troubles(v), "the head ropes lift off the lining: their centrifugal force q v_max² "
                                       "reaches the low side's tension, at rest or at a slip limit (a slower hoist, "
                                       "or more tension)": (st.smallest(lows) <= c, c, st.smallest(lows))}


VOIGT = (
    Q("Q_R", "1/N", "radial compliance of the wheel's lining per head rope (Hajduk 1992: h/(E R² a))", "1/N",
      **dom.COMPLIANCE, guess=2e-9, **usual(1e-11, 3e-7, "h/(E R² a) of linings 10-50 mm thick of E = 10-500 MPa "
                                                          "on wheels of R = 1-5 m under ropes 20-60 mm wide "
                                                          "(judgement)")),
    Q("lambda_R", "s", "retardation time of the lining's radial Voigt bodies (η/E)", "s", **dom.RETARDATION,
      guess=0.5, **usual(1e-3, 10.0, "polymer linings: milliseconds to seconds (judgement)")),
    Q("Q_T", "1/N", "tangential compliance of the lining per head rope (Hajduk 1992: μ/(G R a))", "1/N",
      **dom.COMPLIANCE, guess=1e-9, default=0.0, default_note="not given: no tangential compliance"),
    Q("lambda_T", "s", "retardation time of the lining's tangential Voigt bodies (η/G)", "s", **dom.RETARDATION,
      guess=0.2, default=0.0, default_note="not given: 0 (a tangential compliance creeps at once)"),
)


@register(MODEL, "lining", "voigt")
class VoigtWheel(WheelLining):
    """Hajduk's Voigt lining on the wheel, per rope, S_0 = T_2/n_head (:mod:`ropemodel.papers.koepe_lining`)."""

    description = "Voigt lining (Hajduk 1992): the lining's creep along the arc costs traction"
    citations = (*WheelLining.citations, "hajduk1992")
    quantities = (*WheelLining.quantities, *VOIGT)
    slip_method = (f"the least over the end states (both ends, loaded and empty, conveyance L in either "
                   f"compartment) of Newton's method on eq. (19) at rest (koepe_lining.voigt_slip_residual) "
                   f"from its monotone start, {NEWTON_STEPS} steps, the last below 1e-12 in ln(T_D/F_D)")
    slip_tolerance = kl.STEP_TOL

    def _terms(self, v, T_2, speed):
        """(μ, α, q_R, k_R, q_T, k_T) of eq. (19) for the slack side T_2/n_head at ``speed``."""
        R, per_rope = v["D"] / 2.0, T_2 / v["n_head"]
        return (v["mu"], v["alpha"], v["Q_R"] * per_rope, kl.creep_parameter(v["lambda_R"], speed, R),
                v["Q_T"] * per_rope, kl.creep_parameter(v["lambda_T"], speed, R))

    def limit(self, v, T_2, speed=0.0):
        return kl.voigt_traction_ratio(T_2, v["n_head"], v["mu"], v["alpha"], v["D"] / 2.0, speed, v["Q_R"],
                                       v["lambda_R"], v["Q_T"], v["lambda_T"])

    def limit_equation(self, v, name, speed):
        where = "at rest (fully crept)" if name == "traction_limit" else "at v_max, k = λ v_max/R"
        return Equation(name, v[name] - self.limit(v, v["T_2"], speed),
                        f"Hajduk 1992, eq. (19) {where}, S_0 = T_2/n_head",
                        governing=hj.tension_ratio_residual(v[name], *self._terms(v, v["T_2"], speed)),
                        method=hj.NEWTON_METHOD)

    def slip(self, v, F_U, F_D, M_U, M_D):
        C = kl.lining_compliance(v["alpha"], v["D"] / 2.0, 0.0, v["Q_R"], v["lambda_R"], v["Q_T"], v["lambda_T"])
        args = (F_U, F_D, M_U, M_D, v["n_head"], v["mu"], v["alpha"], C)
        y = kl.voigt_slip_guess(*args)
        for _ in range(NEWTON_STEPS):
            y = y + kl.voigt_newton_step(y, *args)
        converged = fabs(kl.voigt_newton_step(y, *args)) <= kl.STEP_TOL * fmax(1.0, fabs(y))
        return if_else(converged, kl.acceleration_from_log(y, F_D, M_D), math.nan + 0.0 * y)
