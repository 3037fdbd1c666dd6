"""CasADi integrators for the lining ODE, wrapped as differentiable Functions.

Every integrator integrates the stretched ODE of :mod:`ropemodel.numerics.hajduk_ode`
over σ ∈ [0, 1].  ``INTEGRATORS`` maps the ``[numerics] integrator`` name to a
function ``rtol → CasADi options``:

* ``rk4`` (default) — classical RK4 on a fixed grid of N = ceil(RK_C · rtol^(−1/4))
  steps, built here as one SX expression (CasADi ``mapaccum`` of the step,
  expanded), so a point costs only arithmetic and a batch is one SX ``map``.
  The same scheme as CasADi's ``rk`` plugin; that plugin cannot be expanded to
  SX and measured 3-5x slower per point (``studies/lining_accuracy.py``).  In
  the stretched variable the ODE is not stiff (see :mod:`ropemodel.numerics.hajduk_ode`),
  so an explicit fixed-step method is the right tool; it cannot fail.
* ``rk`` — CasADi's RK4 plugin, same N;
* ``cvodes`` — SUNDIALS CVODES, variable-order BDF, adaptive steps,
  ``reltol = abstol = rtol·SUNDIALS_SAFETY`` (the state is ln s, so abstol is a
  relative error of S);
* ``idas`` — SUNDIALS IDAS (the ODE as a semi-explicit DAE), same tolerances;
* ``collocation`` — Radau IIA collocation of order 5 (3 points) on a fixed grid
  of N = ceil(COLLOCATION_C · rtol^(−1/5)) elements.

The constants were calibrated on the extreme grid of the accuracy requirement
(μ ∈ {0.05, 0.3, 0.6}, α ∈ {1e-3, π/4, π, 10π}, q ∈ {0, 1e-3, 1, 30, 1e3},
k ∈ {1e-5, …, 1e2}) so that the measured maximum relative error of S is about
rtol (see ``studies/lining_accuracy.py`` for the measurement).  Derivatives come
from CasADi (forward/adjoint sensitivities for SUNDIALS, differentiated steps
for the fixed-grid methods), so the core can solve inverse questions through
the integrator by Newton.
"""

from __future__ import annotations

import math
from functools import lru_cache

import casadi as ca

from ropemodel.numerics import hajduk_ode as ode

RK_C = 8.75
COLLOCATION_C = 4.65
SUNDIALS_SAFETY = 1 / 200
SEGMENT_INPUTS = ("y_a", "alpha_a", "alpha_b", "mu", "q_R", "k_R", "q_T", "k_T", "beta")
RATIO_INPUTS = ("mu", "alpha", "q_R", "k_R", "q_T", "k_T", "beta")


def _sundials(rtol):
    tol = rtol * SUNDIALS_SAFETY
    return {"reltol": tol, "abstol": tol, "max_num_steps": 100000}


def _collocation(rtol):
    return {"number_of_finite_elements": int(math.ceil(COLLOCATION_C * rtol ** (-1 / 5))),
            "interpolation_order": 3, "collocation_scheme": "radau"}


def _rk(rtol):
    return {"number_of_finite_elements": _rk_steps(rtol)}


def _rk_steps(rtol) -> int:
    return int(math.ceil(RK_C * rtol ** (-1 / 4)))


def _casadi(plugin, options):
    def build(state, rtol):
        x, sigma, p, dx = ode.rhs(state)
        dae = {"x": x, "t": sigma, "p": p, "ode": dx}
        opts = {**options(rtol), "expand": True}
        return ca.integrator(f"lining_{plugin}_{state}", plugin, dae, 0.0, 1.0, opts)

    return build


def _rk4_sx(state, rtol):
    """RK4 over σ ∈ [0, 1] as one expanded SX Function (x0, p) → xf."""
    x, sigma, p, dx = ode.rhs(state)
    f = ca.Function("f", [x, sigma, p], [dx])
    n = _rk_steps(rtol)
    h = 1.0 / n
    X, S, P = ca.SX.sym("X"), ca.SX.sym("S"), ca.SX.sym("P", p.numel())
    k1 = f(X, S, P)
    k2 = f(X + h / 2 * k1, S + h / 2, P)
    k3 = f(X + h / 2 * k2, S + h / 2, P)
    k4 = f(X + h * k3, S + h, P)
    step = ca.Function("rk4_step", [ca.vertcat(X, S), P], [ca.vertcat(X + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), S + h)])
    steps = step.mapaccum("rk4_steps", n, [0], [0])
    x0, pp = ca.SX.sym("x0"), ca.SX.sym("p", p.numel())
    xf = steps(ca.vertcat(x0, 0.0), pp)[0, -1]
    return ca.Function(f"lining_rk4_{state}", [x0, pp], [xf], ["x0", "p"], ["xf"]).expand()


#: ``[numerics] integrator`` name → (state, rtol) → Function (x0, p) → xf over σ ∈ [0, 1]
INTEGRATORS = {
    "rk4": _rk4_sx,
    "rk": _casadi("rk", _rk),
    "cvodes": _casadi("cvodes", _sundials),
    "idas": _casadi("idas", _sundials),
    "collocation": _casadi("collocation", _collocation),
}


@lru_cache(maxsize=32)
def stretched_integrator(plugin: str, state: str, rtol: float) -> ca.Function:
    """The integrator of the stretched ODE over σ ∈ [0, 1] (inputs x0, p; output xf)."""
    return INTEGRATORS[plugin](state, rtol)


@lru_cache(maxsize=32)
def segment_function(plugin: str = "rk4", state: str = "log", rtol: float = 1e-7) -> ca.Function:
    """y_b = ln s(α_b) from y_a = ln s(α_a): one stretched integration [α_a, α_b] (named inputs
    :data:`SEGMENT_INPUTS`; α in rad, q = Q S_0, k = λω, β = c_mu S_0)."""
    syms = {n: ca.MX.sym(n) for n in SEGMENT_INPUTS}
    F = stretched_integrator(plugin, state, rtol)
    pv = ca.vertcat(*[syms[n] for n in ode.PARAMS])
    g = (syms["q_R"], syms["k_R"], syms["q_T"], syms["k_T"])
    x0 = ode.state_of(state, syms["y_a"], syms["alpha_a"], *g, syms["alpha_b"])
    xf = F(x0=x0, p=pv)["xf"]
    y_b = ode.log_ratio_of(state, xf, syms["alpha_b"], *g, syms["alpha_b"])
    f = ca.Function(f"lining_segment_{plugin}_{state}", [syms[n] for n in SEGMENT_INPUTS], [y_b],
                    list(SEGMENT_INPUTS), ["y_b"])
    return f.expand() if plugin == "rk4" else f


@lru_cache(maxsize=32)
def log_ratio_function(plugin: str = "rk4", state: str = "log", rtol: float = 1e-7) -> ca.Function:
    """ln(S/S_0) at angle α by integration from α = 0 (named inputs :data:`RATIO_INPUTS`, output ``y``)."""
    syms = {n: ca.MX.sym(n) for n in RATIO_INPUTS}
    seg = segment_function(plugin, state, rtol)
    y = seg(y_a=0.0, alpha_a=0.0, alpha_b=syms["alpha"],
            **{n: syms[n] for n in ("mu", "q_R", "k_R", "q_T", "k_T", "beta")})["y_b"]
    f = ca.Function(f"lining_log_ratio_{plugin}_{state}", [syms[n] for n in RATIO_INPUTS], [y],
                    list(RATIO_INPUTS), ["y"])
    return f.expand() if plugin == "rk4" else f


@lru_cache(maxsize=64)
def mapped_log_ratio_function(plugin: str, state: str, rtol: float, n: int, parallel: int = 1) -> ca.Function:
    """:func:`log_ratio_function` mapped over n points (serial, or ``thread`` with ``parallel`` > 1)."""
    f = log_ratio_function(plugin, state, rtol)
    return f.map(n, "thread", parallel) if parallel > 1 else f.map(n)
