"""Error-controlled integrators of the lining ODE, wrapped as differentiable CasADi Functions.

Every integrator integrates the stretched ODE of :mod:`ropemodel.numerics.hajduk_ode` over
σ ∈ [0, 1] and returns, besides ln s, an *estimate of its error* ``err`` (absolute error of
ln s, i.e. the relative error of S).  The target ``rtol`` is met by error control, not by a
step count calibrated on test cases: a point whose estimate cannot be brought to ``rtol``
gives NaN (callers turn it into :class:`~ropemodel.errors.SolveError`), never a number.
``INTEGRATORS`` maps the ``[numerics] integrator`` name to ``(state, rtol) → Function
(x0, p) → (xf, err)``:

* ``dopri5`` (default) — adaptive Dormand–Prince 5(4) with error per unit step
  (:mod:`ropemodel.numerics.adaptive`), local tolerance ``DOPRI_SHARE·rtol``.  The lining
  ODE's flow does not expand (∂f/∂ln s < 0: the friction term falls and the lining term
  rises with s), so the global error is at most the sum of the local errors, which is the
  estimate.  ``DOPRI_SHARE`` = 1/4 leaves room for the local estimates' own error (measured
  over 4·10⁴ random points of the documented range: true error ≤ 1.6× the estimate).
* ``rk4`` — classical RK4 on a fixed grid of N steps, ``rk`` — CasADi's RK4 plugin,
  ``collocation`` — Radau IIA (order 5, 3 points) on N elements: *step doubling*, err =
  |x_{2N} − x_N|, the error of the coarser run (Richardson's estimate of it would divide by
  2^p − 1; undivided it over-estimates the error of x_{2N}, which is returned: Richardson's
  divided estimate was measured up to 5× below the true error in the boundary layer); if
  err > rtol, N doubles again (up to ``LEVELS`` times).  A level is accepted only after two
  agreements in a row (|x_N − x_{N/2}| and |x_{2N} − x_N| ≤ rtol): fixed grids can agree by
  accident before they resolve a second, wider creep layer (51 and 102 Radau elements agreed
  to 2e-8 while both were 2.8e-6 off).
* ``cvodes`` (BDF), ``idas`` (as a DAE) — SUNDIALS at tolerance t = rtol·``SUNDIALS_SAFETY``
  and at t/10: err = |x(t) − x(t/10)| (the error of the looser run, an over-estimate of the
  tighter one's, which is returned); if err > rtol, both tolerances tighten tenfold.
  (SUNDIALS' own tolerance is not a bound on the global error: the safety factor and the
  comparison of two runs are what make the result meet rtol.)

The refinements are short-circuiting conditionals (CasADi ``if_else``): a point that passes
at the first level costs only that level.  Derivatives come from CasADi (differentiated
steps, step sizes and conditionals; forward/adjoint sensitivities for SUNDIALS), so the core
can solve inverse questions through the integrator by Newton.

Documented range (each tested on 10⁴ random points against the exact solution,
``tests/test_lining_accuracy_properties.py``): μ ∈ [0.05, 0.6], q = Q·S_0 ∈ [0, 10³],
k = λω ∈ [10⁻⁵, 10²] rad (and 0), α ∈ [0, 10π], λ_R, λ_T and Q_R, Q_T independent.
"""

from __future__ import annotations

import math
from functools import lru_cache

import casadi as ca

from ropemodel.numerics import hajduk_ode as ode
from ropemodel.numerics.adaptive import dopri_function

DEFAULT = "dopri5"
#: each integrator in words, for reports
DESCRIPTIONS = {"dopri5": "adaptive Dormand–Prince 5(4)", "rk4": "classical RK4 with step doubling",
                "rk": "CasADi's RK4 with step doubling", "collocation": "Radau IIA collocation with step doubling",
                "cvodes": "SUNDIALS CVODES (BDF) at two tolerances", "idas": "SUNDIALS IDAS at two tolerances"}
#: integrators built only of CasADi expressions and loops: C code generation works for these
CODEGEN = ("dopri5", "rk4")
DOPRI_SHARE = 0.25
DOPRI_STEPS_C = 18.0  # loop length ceil(C·rtol^(-1/5)): 2.6x the most steps measured at rtol 1e-7
RK_C = 4.0
COLLOCATION_C = 2.0
LEVELS = 5
SUNDIALS_SAFETY = 1 / 100
SEGMENT_INPUTS = ("y_a", "alpha_a", "alpha_b", "mu", "q_R", "k_R", "q_T", "k_T", "beta")
RATIO_INPUTS = ("mu", "alpha", "q_R", "k_R", "q_T", "k_T", "beta")


def dopri_steps(rtol: float) -> int:
    """Loop length of the adaptive integrator at ``rtol`` (its maximum number of attempted steps)."""
    return max(64, int(math.ceil(DOPRI_STEPS_C * rtol ** (-1 / 5))))


def _rhs_function(state):
    x, sigma, p, dx = ode.rhs(state)
    return ca.Function(f"lining_rhs_{state}", [x, sigma, p], [dx], ["x", "sigma", "p"], ["dx"])


def _dopri(state, rtol):
    F = dopri_function(_rhs_function(state), dopri_steps(rtol))
    x0, p = ca.MX.sym("x0"), ca.MX.sym("p", len(ode.PARAMS))
    out = F(x0=x0, p=p, tol=DOPRI_SHARE * rtol)
    err = ca.if_else(out["done"], out["err"], ca.inf)
    return ca.Function(f"lining_dopri5_{state}", [x0, p], [out["xf"], err], ["x0", "p"], ["xf", "err"])


def _rk4_grid(state, n):
    """Classical RK4 with n equal steps over σ ∈ [0, 1]: a CasADi loop (mapaccum) of an SX step."""
    f = _rhs_function(state)
    h = 1.0 / n
    X, P = ca.SX.sym("X", 2), ca.SX.sym("P", len(ode.PARAMS))
    x, s = X[0], X[1]
    k1 = f(x, s, P)
    k2 = f(x + h / 2 * k1, s + h / 2, P)
    k3 = f(x + h / 2 * k2, s + h / 2, P)
    k4 = f(x + h * k3, s + h, P)
    step = ca.Function("rk4_step", [X, P], [ca.vertcat(x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), s + h)])
    loop = step.mapaccum("rk4_steps", n, [0], [0])
    x0, p = ca.MX.sym("x0"), ca.MX.sym("p", len(ode.PARAMS))
    return ca.Function(f"rk4_{n}", [x0, p], [loop(ca.vertcat(x0, 0.0), p)[0, -1]], ["x0", "p"], ["xf"])


def _casadi_plugin(plugin, state, options):
    x, sigma, p, dx = ode.rhs(state)
    F = ca.integrator(f"lining_{plugin}_{state}", plugin, {"x": x, "t": sigma, "p": p, "ode": dx}, 0.0, 1.0,
                      {**options, "expand": True})
    x0, pp = ca.MX.sym("x0"), ca.MX.sym("p", len(ode.PARAMS))
    return ca.Function(f"{plugin}_run", [x0, pp], [F(x0=x0, p=pp)["xf"]], ["x0", "p"], ["xf"])


def _refined(name, runs, rtol, confirm=False):
    """(x0, p) → (xf, err) from a sequence of runs of rising accuracy (``runs[l]``: Function (x0, p) → xf):
    err_l = |x_{l+1} − x_l| (the error of the coarser run, an over-estimate of the finer one's); the first
    level with err_l ≤ rtol gives x_{l+1}; none: err = inf.

    ``confirm``: a level is accepted only when the level before it also met rtol (err_{l−1}, err_l ≤ rtol).
    Fixed-grid runs can agree by accident before they resolve a feature (a second, wider creep layer:
    51 and 102 Radau elements agreed to 2e-8 while both were 2.8e-6 off); two agreements in a row
    rule that out at the cost of one more run."""
    x0, p = ca.MX.sym("x0"), ca.MX.sym("p", len(ode.PARAMS))

    def level(lv, prev, prev_ok):  # [x, err] of the first level from lv on that meets rtol (one switch per level)
        x_next = runs[lv + 1](x0, p)
        err = ca.fabs(x_next - prev)
        ok = ca.logic_and(err <= rtol, prev_ok) if confirm else err <= rtol
        if lv + 2 == len(runs):
            return ca.vertcat(x_next, ca.if_else(ok, err, ca.inf))
        return ca.if_else(ok, ca.vertcat(x_next, err), level(lv + 1, x_next, err <= rtol), True)

    out = level(0, runs[0](x0, p), ca.DM(0) if confirm else ca.DM(1))
    return ca.Function(name, [x0, p], [out[0], out[1]], ["x0", "p"], ["xf", "err"])


def _doubling(make, c, exponent):
    def build(state, rtol):
        n0 = int(math.ceil(c * rtol ** (-1 / exponent)))
        runs = [make(state, n0 * 2**lv) for lv in range(LEVELS + 1)]
        return _refined(f"lining_doubling_{state}", runs, rtol, confirm=True)

    return build


def _sundials(plugin):
    def build(state, rtol):
        # SUNDIALS prints its own errors on the C-level stderr ("At t = 0, too much accuracy requested"):
        # silenced here, a failure is reported by the caller in the user's terms
        runs = [_casadi_plugin(plugin, state, {"reltol": t, "abstol": t, "max_num_steps": 100000,
                                               "disable_internal_warnings": True})
                for t in (rtol * SUNDIALS_SAFETY * 10.0**-lv for lv in range(4))]
        return _refined(f"lining_{plugin}_{state}", runs, rtol)

    return build


def _rk_plugin(state, n):
    return _casadi_plugin("rk", state, {"number_of_finite_elements": n})


def _collocation(state, n):
    return _casadi_plugin("collocation", state, {"number_of_finite_elements": n, "interpolation_order": 3,
                                                  "collocation_scheme": "radau"})


#: ``[numerics] integrator`` name → (state, rtol) → Function (x0, p) → (xf, err) over σ ∈ [0, 1]
INTEGRATORS = {
    "dopri5": _dopri,
    "rk4": _doubling(_rk4_grid, RK_C, 4),
    "rk": _doubling(_rk_plugin, RK_C, 4),
    "collocation": _doubling(_collocation, COLLOCATION_C, 5),
    "cvodes": _sundials("cvodes"),
    "idas": _sundials("idas"),
}


@lru_cache(maxsize=32)
def stretched_integrator(plugin: str, state: str, rtol: float) -> ca.Function:
    """The integrator of the stretched ODE over σ ∈ [0, 1] (inputs x0, p; outputs xf, err)."""
    return INTEGRATORS[plugin](state, rtol)


def _checked(y, err):
    """(y, err) where err is finite, else (NaN, NaN): a result that missed its tolerance is no number."""
    ok = err < ca.inf
    return ca.if_else(ok, y, math.nan), ca.if_else(ok, err, math.nan)


@lru_cache(maxsize=32)
def segment_function(plugin: str = DEFAULT, state: str = "log", rtol: float = 1e-7) -> ca.Function:
    """(y_b, err): y_b = ln s(α_b) from y_a = ln s(α_a) by one stretched integration [α_a, α_b], and the
    estimate of its error (named inputs :data:`SEGMENT_INPUTS`; α in rad, q = Q S_0, k = λω, β = c_mu S_0).
    Both outputs are NaN where the tolerance could not be met."""
    syms = {n: ca.MX.sym(n) for n in SEGMENT_INPUTS}
    F = stretched_integrator(plugin, state, rtol)
    pv = ca.vertcat(*[syms[n] for n in ode.PARAMS])
    g = (syms["q_R"], syms["k_R"], syms["q_T"], syms["k_T"])
    x0 = ode.state_of(state, syms["y_a"], syms["alpha_a"], *g, syms["alpha_b"])
    out = F(x0=x0, p=pv)
    y_b = ode.log_ratio_of(state, out["xf"], syms["alpha_b"], *g, syms["alpha_b"])
    y_b, err = _checked(y_b, out["err"])
    return ca.Function(f"lining_segment_{plugin}_{state}", [syms[n] for n in SEGMENT_INPUTS], [y_b, err],
                       list(SEGMENT_INPUTS), ["y_b", "err"])


@lru_cache(maxsize=32)
def log_ratio_function(plugin: str = DEFAULT, state: str = "log", rtol: float = 1e-7) -> ca.Function:
    """(y, err): ln(S/S_0) at angle α by integration from α = 0 and the estimate of its error
    (named inputs :data:`RATIO_INPUTS`; NaN where the tolerance could not be met)."""
    syms = {n: ca.MX.sym(n) for n in RATIO_INPUTS}
    seg = segment_function(plugin, state, rtol)
    out = seg(y_a=0.0, alpha_a=0.0, alpha_b=syms["alpha"],
              **{n: syms[n] for n in ("mu", "q_R", "k_R", "q_T", "k_T", "beta")})
    return ca.Function(f"lining_log_ratio_{plugin}_{state}", [syms[n] for n in RATIO_INPUTS],
                       [out["y_b"], out["err"]], list(RATIO_INPUTS), ["y", "err"])
