"""Capstan cable drive (``model = "capstan"``): stiffness, slip regime and rotation under load.

Equations: Li, Liang, Dong, Qiu, eq. (6), (12)-(26), see :mod:`ropemodel.papers.li_capstan`;
the rotation δ(F_T) = ∫dF/K is :mod:`ropemodel.numerics.capstan_rotation` (not in the paper).

Effects and variants
--------------------
``stiffness``  ``li`` (default) — eq. (26) in the tight + slack reading, *as published*:
               the slack side's stiffness jumps up where its slip zone reaches its wrap
               (θ_s2 = α2; F_p = 60 N: 90 369 → 98 777 N/m at F_T ≈ 14.62 N);
               ``continuous`` — the slack side's saturated stiffness continued from eq. (18)
               (μEA/(R(e^{μα2} − 1)) in place of eq. 21), continuous at both slip switches;
               ``smooth`` — the published law with logistic switches, ``[numerics] sharpness``.
``load``       ``force`` (default) — F_T given, torque T = 2R F_T published;
               ``torque`` — T given, F_T = T/(2R).  Either question also works through
               ``solve``: ``--given T=... --find F_T``.

Outputs: T or F_T, delta [m] (cable displacement at the capstan rim, self-consistent),
delta_alpha = δ/R [rad], alpha_1, alpha_2 [rad], theta_s1, theta_s2 [rad] (slip angles, eq. 6
and 16, limited by the wrap as eq. 13 and 19 state), K_ti, K_sl, K [N/m] at the wraps after
rotation, regime [-]:

====== ==========================================================================
regime meaning
====== ==========================================================================
1      both slip zones inside their wraps, F_T < F_p (eq. 26 row 1)
2      slack side saturated (θ_s2 ≥ α2), tight not, F_T < F_p (row 2)
3      both sides saturated, F_T < F_p (row 3)
4      F_T ≥ F_p, slack side unloaded, tight side saturated (row 4)
5      completed case: tight saturated, slack not, F_T < F_p (only if α1 < α2)
6      completed case: F_T ≥ F_p with the tight side not yet saturated (large wraps)
====== ==========================================================================

``[numerics]``: ``rtol`` (relative error of the rotation δ to meet, default 1e-7), ``steps`` (the
rotation's first trial step is 1/steps of the load range in ln(1 + F/F_p), default 16; the steps then
adapt), ``sharpness`` (smooth law, default 30).  Output ``delta_error`` is the estimated relative
error of δ (summed local error estimates of the adaptive, event-located Dormand–Prince 5(4),
:func:`ropemodel.numerics.capstan_rotation.rotation_function`, rounded up to one significant digit;
at most rtol); a point that cannot meet rtol is a :class:`~ropemodel.errors.SolveError`.  Documented
range, tested on 10⁴ random points per law against an independent integration (true error ≤
delta_error ≤ rtol): μ ≤ 1, α0 ≤ 40 rad, 0 ≤ F_T ≤ 2F_p, EA 10³–10⁷ N, R 0.01–1 m, L 0–10 m,
F_p 1–10⁴ N, except loads that unwrap the slack side.
"""

from __future__ import annotations

import math

import casadi as ca

from ropemodel.numerics.capstan_laws import LAWS, regime_number
from ropemodel.numerics.capstan_rotation import ARGS, RTOL, STEPS, check_wrap, rotation_function
from ropemodel.effects import domains as dom
from ropemodel.effects.base import Equation, Submodel, define_effect, define_numerics, positive_number, register
from ropemodel.errors import InputError, SolveError
from ropemodel.papers import li_capstan as li
from ropemodel.quantity import Quantity

MODEL = "capstan"
SRC = "Li et al."


define_effect(MODEL, "stiffness", "li", "equivalent stiffness and rotation under load, eq. (6)-(26)")
define_effect(MODEL, "load", "force", "the load as tension change F_T or as torque T = 2 R F_T")


def _steps(key, value):
    if isinstance(value, bool) or not isinstance(value, int) or not 4 <= value <= 4096:
        raise InputError(f"numerics {key} = {value!r} must be a whole number in [4, 4096]")
    return value


define_numerics(MODEL, "steps", STEPS, "the rotation's first trial step is 1/steps of the load range in "
                "ln(1 + F/F_p) (adaptive steps follow; switches are located)", _steps)
define_numerics(MODEL, "rtol", RTOL, "relative error of the rotation delta to meet", positive_number(1e-12, 1e-2))
define_numerics(MODEL, "sharpness", 30.0, "sharpness s of the smooth law's logistic switches (width ~ F_p/s)",
                positive_number(0.0, 1e6))

PARAMS = (
    Quantity("mu", "1", "friction coefficient between cable and wheel", guess=0.25, warn_high=1.0, positive=True,
             **dom.FRICTION),
    Quantity("EA", "N", "axial stiffness of the cable", "kN", guess=5e4, positive=True,
             **dom.domain(1e-3, 1e11, "1 mN (a thread) to 10^11 N, twice the stiffest rope (500 mm of steel: "
                                      "about 5e10 N)")),
    Quantity("R", "m", "wheel radius", "mm", guess=0.075, positive=True, **dom.WHEEL),
    Quantity("L", "m", "free length of the cable between the wheels", "mm", guess=0.36, **dom.ROUTE_POSITION),
    Quantity("alpha_0", "rad", "initial wrap angle on each side", "deg", guess=1.117, positive=True, **dom.WRAP),
    Quantity("F_p", "N", "preload", "N", guess=60.0, positive=True, **dom.FORCE_POSITIVE),
)
F_T_PARAM = Quantity("F_T", "N", "load: tension change in the free span, T/(2R)", "N", guess=10.0, **dom.FORCE,
                     equation=f"{SRC}, section 3: F_T = T/(2R)")
T_PARAM = Quantity("T", "N*m", "load torque on the capstan", "N*m", guess=1.0, **dom.TORQUE,
                   equation=f"{SRC}, section 3: T = 2 R F_T")


def Q(name, unit, description, display, equation, symbol=""):
    return Quantity(name, unit, description, display, equation=f"{SRC}, {equation}", symbol=symbol)


OUTPUTS = (
    Q("delta", "m", "cable displacement at the capstan rim, integral of dF/K", "mm", "eq. (11) integrated"),
    Q("delta_alpha", "rad", "rotation of the capstan, delta/R", "deg", "eq. (13), (19)", "Δα"),
    Q("alpha_1", "rad", "tight-side wrap after rotation", "deg", "eq. (13)"),
    Q("alpha_2", "rad", "slack-side wrap after rotation", "deg", "eq. (19)"),
    Q("theta_s1", "rad", "tight-side slip angle, at most alpha_1", "deg", "eq. (6), (13)"),
    Q("theta_s2", "rad", "slack-side slip angle, at most alpha_2", "deg", "eq. (16), (19)"),
    Q("K_ti", "N/m", "stiffness of the tight side", "N/mm", "eq. (24), (26)"),
    Q("K_sl", "N/m", "stiffness of the slack side", "N/mm", "eq. (25), (26)"),
    Q("K", "N/m", "equivalent stiffness of the drive", "N/mm", "eq. (23), (26)"),
    Q("regime", "1", "slip regime (1-6, see ropemodel.effects.capstan)", None, "eq. (26)"),
    Quantity("delta_error", "1", "estimated relative error of delta (summed local estimates of the adaptive "
             "Dormand-Prince 5(4), rounded up to one digit; at most [numerics] rtol)",
             equation="ropemodel.numerics.capstan_rotation: 2 x (sum of local estimates)/delta"),
)


class _Stiffness(Submodel):
    """Common wiring of the stiffness variants; subclasses name the law."""

    citations = ("li_capstan",)
    quantities = PARAMS + (F_T_PARAM,) + OUTPUTS

    def _settings(self):
        o = self.options
        return o.get("steps", STEPS), float(o.get("sharpness", 30.0)), float(o.get("rtol", RTOL))

    def _rotation(self):
        return rotation_function(self.variant, *self._settings())

    def _rotation_equations(self):
        """delta and delta_error as two call equations of one rotation Function (inlined: the core merges them)."""
        fun = self._rotation()
        rtol = self._settings()[2]
        src = ("eq. (11) integrated over the load from 0 to F_T, the wraps following the rotation (not in the paper)",
               "the rotation's error estimate: twice the summed local estimates, relative to δ, rounded up to one "
               "digit (not in the paper)")
        method = (f"adaptive, event-located Dormand–Prince 5(4) in u = ln(1 + F/F_p), the switches of eq. (26) "
                  f"located, error-controlled to rtol = {rtol:g}")
        eqs = []
        for k, (out, text) in enumerate(zip(("delta", "delta_error"), src)):
            part = ca.Function(f"capstan_{out}", fun.mx_in(), [fun.call(fun.mx_in())[k]], fun.name_in(), [out],
                               {"always_inline": True})
            eqs.append(Equation.from_call(out, part, ARGS, text, method, rtol))
        return eqs

    def equations(self, v):
        law = LAWS[self.variant]
        mu, EA, R, L, a0, F_p, F = (v[n] for n in ("mu", "EA", "R", "L", "alpha_0", "F_p", "F_T"))
        a1, a2 = v["alpha_1"], v["alpha_2"]
        w1, w2 = li.wrap_angles(a0, v["delta"], R)
        k_ti, k_sl = law.parts(F, F_p, mu, EA, R, L, a1, a2, self.options.get("sharpness", 30.0))
        return self._rotation_equations() + [
            Equation("delta_alpha", v["delta_alpha"] - v["delta"] / R, "eq. (13), (19): the rotation"),
            Equation("alpha_1", a1 - w1, "eq. (13)"),
            Equation("alpha_2", a2 - w2, "eq. (19)"),
            Equation("theta_s1", v["theta_s1"] - li.tight_slip_angle_limited(F, F_p, mu, a1), "eq. (6), (13)"),
            Equation("theta_s2", v["theta_s2"] - li.slack_slip_angle_limited(F, F_p, mu, a2), "eq. (16), (19)"),
            Equation("K_ti", v["K_ti"] - k_ti, "eq. (24), (26)"),
            Equation("K_sl", v["K_sl"] - k_sl, "eq. (25), (26)"),
            Equation("K", v["K"] - (v["K_ti"] + v["K_sl"]), "eq. (23)"),
            Equation("regime", v["regime"] - regime_number(F, F_p, mu, a1, a2), "eq. (26), tight + slack reading"),
        ]

    def validate(self, values):
        values = dict(values)
        if "F_T" not in values and "T" in values and values.get("R", 0) > 0:
            values["F_T"] = values["T"] / (2.0 * values["R"])  # torque-loaded scene
        need = ("F_T", "mu", "EA", "R", "L", "alpha_0", "F_p")
        if not all(n in values for n in need):
            return
        F, mu, EA, R, L, a0, F_p = (values[n] for n in need)
        if not all(math.isfinite(x) for x in (F, mu, EA, R, L, a0, F_p)) or min(mu, EA, R, a0, F_p) <= 0 \
                or L < 0 or F < 0:
            return  # the quantities' ranges report these
        if L == 0 and F == 0:
            raise InputError("L = 0 with F_T = 0: the drive has no compliant length and K = 2EA/L is infinite; "
                             "give a free length L > 0 or a load F_T > 0")
        delta, err = (float(v) for v in self._rotation()(F, mu, EA, R, L, a0, F_p))
        steps, sharpness, rtol = self._settings()
        if not math.isfinite(delta) or a0 - delta / R <= 0:
            # unwrapped (the integrand is not physical past α2 = 0): names the largest valid load
            check_wrap(F, delta if math.isfinite(delta) else math.inf, mu, EA, R, L, a0, F_p, self.variant,
                       steps, sharpness, rtol)
        if not math.isfinite(err):
            raise SolveError(f"the capstan rotation cannot meet rtol = {rtol:g} at F_T = {F:.6g} N (adaptive steps "
                             f"up to the limit); loosen [numerics] rtol")


@register(MODEL, "stiffness", "li")
class PublishedStiffness(_Stiffness):
    """Eq. (26) of Li et al. in the tight + slack reading, as published.

    K = K_ti + K_sl; the tight part switches from eq. (24) with (12) to (24) with (15)
    where θ_s1 = α1 (continuous); the slack part from eq. (25) with (18) to (25) with
    (21) where θ_s2 = α2 — *with the published upward jump* (eq. 21 is e^{μα2} times
    eq. 18 there) — and is 0 for F_T ≥ F_p.  The rotation integrates dF/K with this K.
    """

    description = LAWS["li"].doc
    assumptions = ("Eq. (26) as published, the slack side's stiffness jumping up where its slip zone fills its "
                   "wrap.",)


@register(MODEL, "stiffness", "continuous")
class ContinuousStiffness(_Stiffness):
    """Eq. (26) with the slack side's saturated stiffness continued from eq. (18): μEA/(R(e^{μα2} − 1)).

    Not in the paper (derivation: :func:`ropemodel.papers.li_capstan.slack_saturated_stiffness_continuous`);
    continuous at both slip switches.  The drop of K_sl to 0 at F_T = F_p (the slack side
    goes slack) is physical and kept.
    """

    description = LAWS["continuous"].doc


@register(MODEL, "stiffness", "smooth")
class SmoothStiffness(_Stiffness):
    """The published law with logistic switches σ(s·z) (``[numerics] sharpness`` s): smooth in every input.

    z are dimensionless switching functions (:func:`ropemodel.numerics.capstan_laws.switching_functions`):
    μ(θ_s1 − α1), (F_T − F_p(1 − e^{−μα2}))/F_p and (F_T − F_p)/F_p, so each transition is
    about F_p/s wide in load.  At F_T = 0 the slack weight is σ(−s(1 − e^{−μα0})), so K(0)
    misses 2EA/L by that fraction of the jump (1e-4 at s = 30 in the experiment).  ``regime`` is reported by the
    crisp conditions.  For gradient-based optimisation; accuracy cost in
    ``studies/capstan_smooth_cost.py``.
    """

    description = LAWS["smooth"].doc


@register(MODEL, "load", "force")
class ForceLoad(Submodel):
    """The load given as the tension change F_T; publishes the torque T = 2 R F_T (Li et al., section 3)."""

    description = "load F_T given; torque T = 2 R F_T computed"
    citations = ("li_capstan",)
    quantities = (F_T_PARAM, T_PARAM, PARAMS[2])

    def equations(self, v):
        return [Equation("T", v["T"] - 2.0 * v["R"] * v["F_T"], "section 3")]


@register(MODEL, "load", "torque")
class TorqueLoad(Submodel):
    """The load given as the torque T; F_T = T/(2R) (Li et al., section 3)."""

    description = "torque T given; load F_T = T/(2R) computed"
    citations = ("li_capstan",)
    quantities = (F_T_PARAM, T_PARAM, PARAMS[2])

    def equations(self, v):
        return [Equation("F_T", v["T"] - 2.0 * v["R"] * v["F_T"], "section 3")]
