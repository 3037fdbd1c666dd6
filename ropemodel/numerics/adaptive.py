"""An error-controlled explicit Runge–Kutta integrator as one differentiable CasADi Function.

Dormand–Prince 5(4) (Dormand & Prince 1980; Hairer, Nørsett & Wanner, *Solving Ordinary
Differential Equations I*, 2nd ed., §II.5, Table 5.2) for a scalar ODE dx/dt = f(x, t, p)
over t ∈ [0, 1], with adaptive steps:

* each step computes the 5th-order solution (propagated: local extrapolation) and the
  embedded 4th-order one; their difference ``le`` estimates the local error of the
  4th-order solution, an upper estimate of the propagated one's;
* control by *error per unit step*: a step of length h is accepted when
  ``le <= tol·h + floor`` (``floor`` = a few ulps of x: rounding), so the accepted
  local errors add up to at most ``tol`` over t ∈ [0, 1] (plus rounding);
* the next step is h·min(5, max(0.2, 0.9 (tol·h/le)^{1/4})) (the standard controller
  for an error ∝ h⁵ per step, i.e. ∝ h⁴ per unit step), clipped to the end t = 1.

**Global error.** For an ODE whose flow does not expand distances (∂f/∂x ≤ 0, true of
the lining ODE: see :mod:`ropemodel.numerics.hajduk_ode`), the global error at t = 1 is
at most the sum of the local errors, so the returned estimate ``err`` = Σ le over the
accepted steps bounds it (to the accuracy of the local estimates).  Where ∂f/∂x > 0
the sum would have to be amplified by e^{∫∂f/∂x}: callers with such ODEs must not use
``err`` as a bound.

**Fixed maximum.** The loop is ``max_steps`` iterations of a CasADi ``mapaccum``
(a loop in generated C, not an unrolled expression); once t = 1 is reached each
further iteration is a conditional no-op (``Function.if_else``: in generated C a
branch that skips the step).  A run that has not reached t = 1 after ``max_steps``
iterations returns ``done = 0``: callers turn that into an error, never a number.

The result is differentiable in x0 and p (CasADi differentiates the steps, the step
sizes and the conditionals; accept/reject decisions are piecewise constant).
"""

from __future__ import annotations

from functools import lru_cache

import casadi as ca

#: Dormand–Prince 5(4): nodes c, matrix a, 5th-order weights b, b − b̂ (error weights)
C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0)
A = (
    (),
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
    (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84),
)
B = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0)
E = tuple(b - bh for b, bh in zip(B, (5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200,
                                          187 / 2100, 1 / 40)))
#: continuous extension of order 4 (Hairer, Nørsett & Wanner, §II.6, the coefficients of DOPRI5's
#: ``contd5``): y(θ) = y0 + θ(r1 + (1 − θ)(r2 + θ(r3 + (1 − θ) r4))) with r4 = h·Σ DENSE_i k_i
DENSE = (-12715105075 / 11282082432, 0.0, 87487479700 / 32700410799, -10690763975 / 1880347072,
         701980252875 / 199316789632, -1453857185 / 822651844, 69997945 / 29380423)
#: first trial step (a fraction of [0, 1]); the controller adapts it from the first step on
H0 = 0.02
#: largest growth of the step from one step to the next
GROW = 1.5
#: rounding allowance per step, in units of (1 + |x|)
ULPS = 8 * 2.0**-52
STATE = ("t", "x", "h", "err", "steps")


def stages(f, t, x, h, p, k1=None):
    """The seven stage derivatives k_i = f(t + c_i h, x + h Σ a_ij k_j, p) of one Dormand–Prince step
    (``k1`` = f(t, x, p) if already known)."""
    k = [] if k1 is None else [k1]
    for i in range(len(k), 7):
        xi = x + h * sum((a * kj for a, kj in zip(A[i], k) if a != 0.0), ca.SX(0))
        k.append(f(t + C[i] * h, xi, p))
    return k


def combine(weights, k, h):
    """h Σ w_i k_i (skipping zero weights)."""
    return h * sum((w * kj for w, kj in zip(weights, k) if w != 0.0), ca.SX(0))


def dense(theta, h, x0, x1, k):
    """The continuous extension (:data:`DENSE`) at θ ∈ [0, 1] of a step x0 → x1 and its θ-derivative."""
    r1 = x1 - x0
    r2 = h * k[0] - r1
    r3 = r1 - h * k[6] - r2
    r4 = combine(DENSE, k, h)
    inner = r3 + (1 - theta) * r4                       # r3 + (1 − θ) r4
    mid = r2 + theta * inner                            # r2 + θ(...)
    outer = r1 + (1 - theta) * mid
    d_mid = inner - theta * r4
    d_outer = -mid + (1 - theta) * d_mid
    return x0 + theta * outer, outer + theta * d_outer


def until_done(body: ca.Function, inner: int, outer: int, name: str) -> ca.Function:
    """``body`` (z, p) → z' repeated ``inner·outer`` times, skipping the rest once z[0] ≥ p[-1] (done).

    Two nested loops (``mapaccum``) of conditionals (``Function.if_else``): once done, each further
    outer iteration skips a whole block of ``inner`` steps, so a long maximum costs little.
    """
    z, p = ca.MX.sym("z", body.size1_in(0)), ca.MX.sym("p", body.size1_in(1))
    idle = ca.Function(f"{name}_idle", [z, p], [z])
    step = ca.Function(f"{name}_body", [z, p], [ca.Function.if_else(f"{name}_one", body, idle)(z[0] < p[-1], z, p)])
    block = step.mapaccum(f"{name}_block", inner, [0], [0])
    blk = ca.Function(f"{name}_blk", [z, p], [block(z, p)[:, -1]])
    run = ca.Function.if_else(f"{name}_outer", blk, idle)
    outer_body = ca.Function(f"{name}_outer_body", [z, p], [run(z[0] < p[-1], z, p)])
    loop = outer_body.mapaccum(f"{name}_loop", outer, [0], [0])
    return ca.Function(name, [z, p], [loop(z, p)[:, -1]], ["z0", "p"], ["zf"])


def _dopri_step(f: ca.Function, n_p: int) -> ca.Function:
    """One controlled step: (z, p, tol) → z' with z = (t, x, h, err, steps) (SX)."""
    z = ca.SX.sym("z", len(STATE))
    p = ca.SX.sym("p", n_p)
    tol = ca.SX.sym("tol")
    t, x, h, err, steps = (z[i] for i in range(len(STATE)))
    rest = 1.0 - t
    last = h >= rest
    he = ca.if_else(last, rest, h)
    k: list[ca.SX] = []
    for i in range(7):
        xi = x + he * sum((a * kj for a, kj in zip(A[i], k) if a != 0.0), ca.SX(0))
        k.append(f(xi, t + C[i] * he, p))
    x5 = x + he * sum((b * kj for b, kj in zip(B, k) if b != 0.0), ca.SX(0))
    le = ca.fabs(he * sum((e * kj for e, kj in zip(E, k)), ca.SX(0)))
    allowed = tol * he + ULPS * (1.0 + ca.fabs(x))
    ok = le <= allowed
    ratio = ca.fmax(le / allowed, 1e-12)
    h_new = he * ca.fmin(GROW, ca.fmax(0.2, 0.9 * ratio ** -0.25))
    t_new = ca.if_else(ok, ca.if_else(last, 1.0, t + he), t)
    z_new = ca.vertcat(t_new, ca.if_else(ok, x5, x), ca.if_else(ca.logic_and(ok, last), h, h_new),
                       ca.if_else(ok, err + le, err), steps + 1.0)
    return ca.Function("dopri_step", [z, p, tol], [z_new], ["z", "p", "tol"], ["z_next"])


@lru_cache(maxsize=16)
def dopri_function(f: ca.Function, max_steps: int) -> ca.Function:
    """(x0, p, tol) → (xf, err, done, steps): DP5(4) with error per unit step over t ∈ [0, 1].

    f: SX Function (x, t, p) → dx/dt, scalar x and t; max_steps: iterations of the loop.
    ``err`` is Σ of the accepted local error estimates (a bound of the global error of x
    for a non-expanding flow); ``done`` 1 if t = 1 was reached; ``steps`` attempted steps.
    """
    n_p = f.size1_in(2)
    step = _dopri_step(f, n_p)
    z, p, tol = ca.MX.sym("z", len(STATE)), ca.MX.sym("p", n_p), ca.MX.sym("tol")
    idle = ca.Function("idle", [z, p, tol], [z], ["z", "p", "tol"], ["z_next"])
    branch = ca.Function.if_else("dopri_branch", step, idle)
    body = ca.Function("dopri_body", [z, p, tol], [branch(z[0] < 1.0, z, p, tol)], ["z", "p", "tol"],
                       ["z_next"])
    loop = body.mapaccum("dopri_loop", max_steps, [0], [0])
    x0 = ca.MX.sym("x0")
    zf = loop(ca.vertcat(0.0, x0, H0, 0.0, 0.0), p, tol)[:, -1]
    return ca.Function("dopri", [x0, p, tol], [zf[1], zf[3], zf[0] >= 1.0, zf[4]],
                       ["x0", "p", "tol"], ["xf", "err", "done", "steps"])
