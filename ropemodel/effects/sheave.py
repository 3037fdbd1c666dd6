"""Rope on a friction sheave (``model = "sheave"``): tension along the arc of contact.

Hajduk (1992), :mod:`ropemodel.papers.hajduk1992`; docs/physics.md §3.  Outputs: ``S``
(tension where the rope leaves the sheave, after the wrap ``alpha``) and
``S_ratio`` = S/S_0; the distribution S(α) along the arc is the table
"tension along the arc" (``Result.frames``, and :func:`ropemodel.sheave.distribution`).

Effects and variants
--------------------
``lining``    ``voigt`` (default) — isotropic Voigt lining, ``Q`` [1/N] and ``lambda`` [s]
                (eq. (6), (19)); ``voigt_anisotropic`` — ``Q_R``, ``Q_T``, ``lambda_R``,
                ``lambda_T`` (eq. (5), (19) generalised); ``voigt_physical`` — from the
                lining's data ``h``, ``E``, ``G``, ``a``, ``R``, ``eta_R``, ``eta_T``
                (Q_R = h/(E R² a), Q_T = μ/(G R a), λ_R = η_R/E, λ_T = η_T/G);
                ``rigid`` — Euler–Eytelwein, S = S_0 e^{μα} (eq. (8)).
``friction``  ``constant`` (default) — μ constant; ``thirion`` — μ(p) = μ/(1 + p/p_c) with the
                contact pressure p = S/(R a) (Thirion 1946; ``mu`` is then the
                low-pressure limit): no closed form, needs ``[numerics] method = "ode"``.

Numerics
--------
``method``      ``"closed"`` (default): the exact implicit solution by Newton in ln s;
                ``"ode"``: integrate the ODE (the only way for ``friction = "thirion"``).
``integrator``  ``"dopri5"`` (default: adaptive Dormand–Prince 5(4)), ``"rk4"``, ``"rk"``,
                ``"collocation"`` (step doubling), ``"cvodes"``, ``"idas"``
                (:mod:`ropemodel.numerics.hajduk_integrators`); each error-controlled.
``rtol``        relative error of S the ODE must meet (default 1e-7); a point that cannot is a
                :class:`~ropemodel.errors.SolveError`.

Output ``S_error`` is the estimate of the relative error of S: with ``method = "ode"`` the
integrator's (≤ rtol by construction), with ``"closed"`` the next Newton step of eq. (19) plus
rounding.  Documented range, tested on 10⁴ random points each against independent exact
solutions (``tests/test_lining_accuracy_properties.py``): μ ∈ [0.05, 0.6], Q·S_0 ∈ [0, 10³],
λω ∈ [10⁻⁵, 10²] rad, α ∈ [0, 10π], isotropic and anisotropic.
``state``       ``"log"`` (default: ln S in a stretched angle) or ``"invariant"``.
``points``      number of angles in the distribution table (default 37).

Limits: ``omega = 0`` (slow sheave) and ``lambda = 0`` (elastic lining) are the
limit k = λω → 0, handled exactly (see :mod:`ropemodel.papers.hajduk1992`).
"""

from __future__ import annotations

import math
import warnings
from typing import ClassVar

import casadi as ca
import numpy as np

from ropemodel.effects import domains as dom
from ropemodel.effects.base import (Equation, Submodel, choice, define_effect, define_numerics,
                                    positive_number, register, whole_number)
from ropemodel.errors import InputError, SolveError
from ropemodel.numerics.hajduk_integrators import (DEFAULT, DESCRIPTIONS, INTEGRATORS, log_ratio_function,
                                                   segment_function)
from ropemodel.papers import friction as fr
from ropemodel.papers import hajduk1992 as hj
from ropemodel.quantity import Quantity, positive

MODEL = "sheave"
SRC = "Hajduk 1992"


S_0 = Quantity("S_0", "N", "tension of the rope entering the arc (slack side)", "kN", guess=1e4, positive=True,
               **dom.FORCE_POSITIVE)
MU = Quantity("mu", "1", "friction coefficient of the rope on the lining (low-pressure limit with "
              "friction = thirion)", warn_high=1.0, guess=0.2, positive=True, **dom.FRICTION)
ALPHA = Quantity("alpha", "rad", "wrap angle (arc of contact)", "deg", warn_high=10 * math.pi, guess=math.pi,
                 positive=True, **dom.WRAP)
OMEGA = Quantity("omega", "rad/s", "angular speed of the sheave (0: the slow-sheave limit)", guess=1.0,
                 **dom.domain(0.0, 1e3, "0 to 1000 rad/s (about 10 000 rpm): beyond any sheave's speed"))
# guesses: starting points of Newton when an inverse question makes these unknowns of an implicit block
S_OUT = Quantity("S", "N", "tension of the rope leaving the arc", "kN", equation=f"{SRC}, eq. (19)",
                 low=0.0, low_open=True, positive=True, guess=2e4)
S_RATIO = positive("S_ratio", "1", "tension ratio S/S_0 over the arc", equation="S/S_0", guess=2.0)
S_ERROR = Quantity("S_error", "1", "estimated relative error of S (method ode: the integrator's estimate, at most "
                   "rtol; closed: the next Newton step plus rounding)",
                   equation=f"{SRC}, eq. (19) (closed) or eq. (5)-(6) integrated (ode)", low=0.0, guess=1e-9)
C_MU = Quantity("c_mu", "1/N", "pressure sensitivity of friction, mu(S) = mu/(1 + c_mu S) (0: constant)",
                equation="1/(p_c R a)", guess=3e-5,
                **dom.domain(0.0, 1e3, "0 (constant friction) to 1000 1/N: friction halved by 1 mN of tension"))
R_SHEAVE = Quantity("R", "m", "sheave radius to the rope centre", "mm", guess=1.0, positive=True, **dom.WHEEL)
#: a width or thickness of a lining
LINING_SIZE = dom.domain(1e-6, 10.0, "1 um to 10 m: beyond any lining")
A_WIDTH = Quantity("a", "m", "width of the lining in contact with the rope", "mm", guess=0.03, positive=True,
                   **LINING_SIZE)


#: a viscosity of a lining
VISCOSITY = dom.domain(0.0, 1e15, "0 to 10^15 Pa s: a modulus of up to 1 TPa times a retardation time of 1000 s")


def _compliance(name, what):
    return Quantity(name, "1/N", f"{what} compliance of the lining", guess=1e-5, **dom.COMPLIANCE)


def _retardation(name, what):
    return Quantity(name, "s", f"{what} retardation time of the lining (eta/modulus)", guess=0.01,
                    **dom.RETARDATION)


define_effect(MODEL, "lining", "voigt", "the sheave's lining: Voigt bodies (visco-elastic) or rigid")
define_effect(MODEL, "friction", "constant", "rope-lining friction law")
define_numerics(MODEL, "method", "closed", "closed: exact implicit solution; ode: integrate the ODE",
                choice("closed", "ode"))
define_numerics(MODEL, "integrator", DEFAULT, "ODE integrator (each error-controlled)", choice(*INTEGRATORS))
define_numerics(MODEL, "rtol", 1e-7, "relative error of S the ODE must meet", positive_number(1e-12, 1e-2))
define_numerics(MODEL, "state", "log", "ODE state: log (ln S, stretched angle) or invariant",
                choice("log", "invariant"))
define_numerics(MODEL, "points", 37, "angles in the distribution table", whole_number(2, 10000))


class _Lining(Submodel):
    """Common part of the lining variants: S from (q_R, k_R, q_T, k_T) by the closed form or the ODE.

    Subclasses give ``args`` (the quantities the lining data come from) and
    ``data(S_0, omega, *args)`` → (Q_R, k_R, Q_T, k_T) as expressions (SX, MX or float).
    """

    citations: ClassVar[tuple[str, ...]] = ("hajduk1992",)
    args: tuple[str, ...] = ()

    def data(self, S_0, omega, *args):
        raise NotImplementedError

    def _closed(self, v):
        """(ln s, its error estimate, the residual of eq. (19) at S) of the exact solution, as SX."""
        Q_R, k_R, Q_T, k_T = self.data(v["S_0"], v["omega"], *[v[a] for a in self.args])
        g = (v["mu"], v["alpha"], Q_R * v["S_0"], k_R, Q_T * v["S_0"], k_T)
        governing = hj.tension_residual(v["S"], v["S_0"], v["mu"], v["alpha"], Q_R, k_R, Q_T, k_T)
        return hj.log_tension_ratio(*g), hj.log_tension_ratio_error(*g), governing

    def _integrator(self):
        o = self.options
        return log_ratio_function(o.get("integrator", DEFAULT), o.get("state", "log"), float(o.get("rtol", 1e-7)))

    def _call(self):
        """MX Function (S_0, mu, alpha, omega, c_mu, *args) → (S, S_error) through the integrator."""
        names = ("S_0", "mu", "alpha", "omega", "c_mu", *self.args)
        syms = [ca.MX.sym(n) for n in names]
        env = dict(zip(names, syms))
        Q_R, k_R, Q_T, k_T = self.data(env["S_0"], env["omega"], *[env[a] for a in self.args])
        S0 = env["S_0"]
        out = self._integrator()(mu=env["mu"], alpha=env["alpha"], q_R=Q_R * S0, k_R=k_R, q_T=Q_T * S0, k_T=k_T,
                                 beta=env["c_mu"] * S0)
        return ca.Function(f"S_{self.variant}_ode", syms, [S0 * ca.exp(out["y"]), out["err"]], list(names),
                           ["S", "S_error"]), names

    def equations(self, v):
        eqs = [Equation("S_ratio", v["S_ratio"] * v["S_0"] - v["S"], "the tension ratio over the arc")]
        if self.options.get("method", "closed") == "ode":
            fun, names = self._call()
            name = self.options.get("integrator", DEFAULT)
            rtol = float(self.options.get("rtol", 1e-7))
            method = (f"{DESCRIPTIONS[name]} ([numerics] integrator = {name!r}) of eq. (5)-(6) from S(0) = S_0, "
                      f"error-controlled to rtol = {rtol:g}")
            for k, (out, src) in enumerate((("S", f"{SRC}, eq. (5)-(6) integrated"),
                                            ("S_error", "the integrator's estimate of the relative error of S"))):
                # one Function per output, inlined where called: the core merges the two calls (CSE)
                part = ca.Function(f"{fun.name()}_{out}", fun.mx_in(), [fun.call(fun.mx_in())[k]], fun.name_in(),
                                   [out], {"always_inline": True})
                eqs.append(Equation.from_call(out, part, names, src, method, rtol))
        else:
            y, err, governing = self._closed(v)
            eqs.append(Equation("S", v["S"] - v["S_0"] * ca.exp(y), f"{SRC}, eq. (19)", governing=governing,
                                method=hj.NEWTON_METHOD))
            eqs.append(Equation("S_error", v["S_error"] - err, f"{SRC}, eq. (19)",
                                method="the size of the next Newton step of eq. (19) in ln s, plus 8 ulp of rounding "
                                "times (1 + μα)"))
        return eqs

    def numeric_data(self, values):
        """(q_R, k_R, q_T, k_T) as floats for the SI ``values`` of a solved point."""
        Q_R, k_R, Q_T, k_T = self.data(values["S_0"], values["omega"], *[values[a] for a in self.args])
        return Q_R * values["S_0"], k_R, Q_T * values["S_0"], k_T

    def lining_values(self, values):
        """The SI values that :meth:`numeric_data` needs, from the parameters alone (hook for derived data)."""
        return values

    def validate(self, values):
        """With method = "ode": integrate once at the given parameters; :class:`SolveError` if the
        integrator cannot meet its tolerance there (the compiled model would give NaN)."""
        if self.options.get("method", "closed") != "ode":
            return
        try:
            v = self.lining_values(dict(values))
            q_R, k_R, q_T, k_T = self.numeric_data(v)
            beta = v["S_0"] / (v["p_c"] * v["R"] * v["a"]) if "p_c" in v else 0.0
            args = (v["mu"], v["alpha"], q_R, k_R, q_T, k_T, beta)
        except (KeyError, ZeroDivisionError):
            return  # an inverse question: checked again once the unknowns are found
        if not all(math.isfinite(float(a)) for a in args):
            return
        o = self.options
        try:
            err = float(self._integrator()(*args)[1])
        except RuntimeError as exc:
            raise SolveError(f"the lining ODE ({o.get('integrator', DEFAULT)}) failed at this point: "
                             f"{str(exc).splitlines()[-1]}") from None
        if not math.isfinite(err):
            raise SolveError(f"the lining ODE ({o.get('integrator', DEFAULT)}) cannot meet rtol = "
                             f"{float(o.get('rtol', 1e-7)):g} at this point; loosen [numerics] rtol or use "
                             "method = 'closed'")

    def frames(self, values, scene, where=None):
        return {"tension along the arc": distribution_frame(values, scene)}


@register(MODEL, "lining", "rigid")
class RigidLining(_Lining):
    """Rigid lining: Euler–Eytelwein, S = S_0 e^{μα}; Hajduk (1992) eq. (8), the Q = 0 case."""

    description = "rigid lining (Euler-Eytelwein)"
    citations = ("euler_eytelwein", "hajduk1992")
    quantities = (S_0, MU, ALPHA, S_OUT, S_RATIO, S_ERROR)

    def data(self, S_0, omega, *args):
        return 0.0, 1.0, 0.0, 1.0

    def _call(self):
        fun, names = super()._call()
        # a rigid lining has no omega: bind it to 1 (unused: q = 0)
        syms = [ca.MX.sym(n) for n in ("S_0", "mu", "alpha", "c_mu")]
        out = fun(syms[0], syms[1], syms[2], 1.0, syms[3])
        return ca.Function("S_rigid_ode", syms, list(out), ["S_0", "mu", "alpha", "c_mu"], ["S", "S_error"]), \
            ("S_0", "mu", "alpha", "c_mu")

    def equations(self, v):
        if self.options.get("method", "closed") == "ode":
            return super().equations(v)
        return [Equation("S_ratio", v["S_ratio"] * v["S_0"] - v["S"], "the tension ratio over the arc"),
                Equation("S", v["S"] - v["S_0"] * fr.euler_eytelwein_ratio(v["mu"], v["alpha"]),
                         "Euler-Eytelwein, Hajduk 1992 eq. (8)"),
                Equation("S_error", v["S_error"] - hj.ROUNDING * (1.0 + v["mu"] * v["alpha"]),
                         "Euler-Eytelwein: the closed form's rounding, 8 ulp times (1 + μα)")]

    def numeric_data(self, values):
        return 0.0, 1.0, 0.0, 1.0

    def lining_values(self, values):
        return {**values, "omega": 1.0}


@register(MODEL, "lining", "voigt")
class VoigtLining(_Lining):
    """Isotropic Voigt lining (λ_R = λ_T = λ, Q = Q_R + Q_T): Hajduk (1992) eq. (6), (19)."""

    description = "isotropic Voigt lining: compliance Q, retardation time lambda"
    quantities = (S_0, MU, ALPHA, OMEGA, _compliance("Q", "total (radial + tangential)"),
                  _retardation("lambda", "the"), S_OUT, S_RATIO, S_ERROR)
    args = ("Q", "lambda")

    def data(self, S_0, omega, Q, lam):
        return Q, lam * omega, 0.0, 1.0


@register(MODEL, "lining", "voigt_anisotropic")
class AnisotropicVoigtLining(_Lining):
    """Voigt lining with separate radial and tangential bodies: Hajduk (1992) eq. (5), (19) generalised."""

    description = "anisotropic Voigt lining: Q_R, Q_T, lambda_R, lambda_T"
    quantities: ClassVar[tuple[Quantity, ...]] = (
        S_0, MU, ALPHA, OMEGA, _compliance("Q_R", "radial"), _compliance("Q_T", "tangential"),
        _retardation("lambda_R", "radial"), _retardation("lambda_T", "tangential"), S_OUT, S_RATIO, S_ERROR)
    args = ("Q_R", "Q_T", "lambda_R", "lambda_T")

    def data(self, S_0, omega, Q_R, Q_T, lam_R, lam_T):
        return Q_R, lam_R * omega, Q_T, lam_T * omega


@register(MODEL, "lining", "voigt_physical")
class PhysicalVoigtLining(AnisotropicVoigtLining):
    """Voigt lining from its physical data: Hajduk (1992) eq. (1), (3): Q_R = h/(E R² a),
    Q_T = μ/(G R a), λ_R = η_R/E, λ_T = η_T/G; then as ``voigt_anisotropic``."""

    description = "Voigt lining from thickness, moduli, viscosities and the contact geometry"
    quantities = (
        *AnisotropicVoigtLining.quantities[:4], R_SHEAVE, A_WIDTH,
        Quantity("h", "m", "thickness of the lining", "mm", guess=0.02, positive=True, **LINING_SIZE),
        Quantity("E", "Pa", "Young's modulus of the lining", "MPa", guess=5e7, positive=True, **dom.MODULUS),
        Quantity("G", "Pa", "shear modulus of the lining", "MPa", guess=2e7, positive=True, **dom.MODULUS),
        Quantity("eta_R", "Pa*s", "viscosity of the lining in compression", "MPa*s", guess=1e5, **VISCOSITY),
        Quantity("eta_T", "Pa*s", "viscosity of the lining in shear", "MPa*s", guess=1e5, **VISCOSITY),
        *AnisotropicVoigtLining.quantities[4:8],   # computed here (eq. (1), (6)): the same quantities
        S_OUT, S_RATIO, S_ERROR,
    )

    def equations(self, v):
        return super().equations(v) + [
            Equation("Q_R", v["Q_R"] - hj.radial_compliance(v["h"], v["E"], v["R"], v["a"]), f"{SRC}, eq. (6)"),
            Equation("Q_T", v["Q_T"] - hj.tangential_compliance(v["mu"], v["G"], v["R"], v["a"]), f"{SRC}, eq. (6)"),
            Equation("lambda_R", v["lambda_R"] - hj.retardation_time(v["eta_R"], v["E"]), f"{SRC}, eq. (1)"),
            Equation("lambda_T", v["lambda_T"] - hj.retardation_time(v["eta_T"], v["G"]), f"{SRC}, eq. (1)"),
        ]

    def lining_values(self, values):
        v = values
        return {**v, "Q_R": hj.radial_compliance(v["h"], v["E"], v["R"], v["a"]),
                "Q_T": hj.tangential_compliance(v["mu"], v["G"], v["R"], v["a"]),
                "lambda_R": hj.retardation_time(v["eta_R"], v["E"]),
                "lambda_T": hj.retardation_time(v["eta_T"], v["G"])}


@register(MODEL, "friction", "constant")
class ConstantFriction(Submodel):
    """Constant friction coefficient μ (c_mu = 0)."""

    description = "constant friction coefficient"
    assumptions = ("A constant friction coefficient μ, independent of the contact pressure.",)
    quantities = (C_MU,)

    def equations(self, v):
        return [Equation("c_mu", v["c_mu"], "constant friction (no pressure dependence)")]


@register(MODEL, "friction", "thirion")
class ThirionFriction(Submodel):
    """Pressure-dependent friction, Thirion's law 1/μ = 1/μ_0 + p/(μ_0 p_c), i.e. μ = μ_0/(1 + p/p_c).

    Thirion (1946) measured that the friction coefficient of rubber falls with the
    contact pressure as 1/μ = a + b p; Hajduk (1992) notes (footnote, refs [1]-[4])
    that the friction of elastic linings depends on pressure.  The contact
    pressure of a rope on a lining of width a at radius R is p = S/(R a) (the
    radial load per unit arc length S/R spread over the width; Hajduk eq. (3)).
    So μ(S) = μ/(1 + c_mu S) with c_mu = 1/(p_c R a) [1/N]; ``mu`` is the
    low-pressure limit μ_0.  p_c → ∞ is constant friction.  The tangential
    compliance Q_T (∝ μ) is kept at its given value.

    No closed form: needs ``[numerics] method = "ode"``.
    """

    description = "friction falling with contact pressure (Thirion's law)"
    citations = ("thirion1946",)
    quantities = (C_MU, R_SHEAVE, A_WIDTH,
                  Quantity("p_c", "Pa", "pressure at which friction halves (Thirion's law)", "MPa", guess=1e6,
                           positive=True, **dom.MODULUS))

    def equations(self, v):
        # multiplied out: linear in c_mu and in p_c, R, a, so either direction is explicit
        return [Equation("c_mu", v["c_mu"] * v["p_c"] * v["R"] * v["a"] - 1.0,
                         "Thirion 1946, with the contact pressure p = S/(R a)")]

    def validate(self, values):
        if self.options.get("method", "closed") != "ode":
            raise InputError("friction = 'thirion' (pressure-dependent) has no closed form: "
                             "set [numerics] method = \"ode\"")


def _lining_of(scene) -> _Lining:
    return next(sm for sm in scene.built.submodels if isinstance(sm, _Lining))


def distribution_frame(values: dict, scene, points: int | None = None):
    """S along the arc at ``points`` equally spaced angles 0 … alpha for the SI ``values`` of a
    solved sheave point (columns with units); by the scene's method."""
    sm = _lining_of(scene)
    n = int(points or scene.numerics.get("points", 37))
    alpha = np.linspace(0.0, values["alpha"], max(n, 2))
    q_R, k_R, q_T, k_T = sm.numeric_data(values)
    o = scene.numerics
    if o.get("method", "closed") == "ode":
        seg = segment_function(o.get("integrator", DEFAULT), o.get("state", "log"), float(o.get("rtol", 1e-7)))
        ys = [0.0]
        for a0, a1 in zip(alpha[:-1], alpha[1:]):
            ys.append(float(seg(y_a=ys[-1], alpha_a=a0, alpha_b=a1, mu=values["mu"], q_R=q_R, k_R=k_R, q_T=q_T,
                                k_T=k_T, beta=values.get("c_mu", 0.0) * values["S_0"])["y_b"]))
        y = np.array(ys)
        if not np.all(np.isfinite(y)):
            raise SolveError("the lining ODE could not meet its tolerance along the arc; loosen [numerics] rtol")
    else:
        y = np.asarray(hj.log_tension_ratio(values["mu"], alpha, q_R, k_R, q_T, k_T), float)
    s = np.exp(y)
    import pandas as pd

    frame = {"alpha [deg]": np.degrees(alpha), "S [kN]": values["S_0"] * s / 1e3, "S/S_0 [-]": s}
    with np.errstate(over="ignore"):
        euler = np.exp(values["mu"] * alpha)   # the rigid-lining reference (Euler-Eytelwein)
    if np.all(np.isfinite(euler)):
        frame["e^(mu alpha) [-]"] = euler
    else:   # no inf in a result: the reference column is left out, and said so
        warnings.warn(f"the reference column e^(mu alpha) is left out: at mu alpha = "
                      f"{values['mu'] * values['alpha']:.4g} it exceeds the largest number a float holds", UserWarning,
                      stacklevel=2)
    return pd.DataFrame(frame)
