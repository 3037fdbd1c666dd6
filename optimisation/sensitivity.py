"""Parametric sensitivities of the optimum, ∂x*/∂p, from the KKT system.

At a regular optimum (LICQ, strict complementarity, second-order sufficiency) the
active set is locally constant and the KKT conditions

    ∇_x f + J_A(x, p)ᵀ λ_A + E_Bᵀ ν = 0,   g_A(x, p) = 0,   E_B x = const

define x*(p), λ*(p) implicitly (Fiacco 1976).  Differentiating once:

    [ H     J_Aᵀ  E_Bᵀ ] [ ∂x/∂p ]     [ ∂(∇_x L)/∂p ]
    [ J_A   0     0    ] [ ∂λ/∂p ] = − [ ∂g_A/∂p     ]
    [ E_B   0     0    ] [ ∂ν/∂p ]     [ 0           ]

with H = ∇²_xx L and L = f + λᵀg (CasADi's sign convention).  Every matrix is an
exact CasADi derivative of the scene's equations (through the Voigt lining's
rootfinder where it is used).  At a vertex design (as many active constraints
as variables) the first block row drops out: ∂x/∂p = −J_A⁻¹ ∂g_A/∂p.
"""

from __future__ import annotations

import weakref

import casadi as ca
import numpy as np

from optimisation.ipopt import Solution
from optimisation.problem import SizingProblem

#: the KKT matrices' Functions of each problem, built once (kept while the problem lives)
_KKT: weakref.WeakKeyDictionary[SizingProblem, tuple[ca.Function, ca.Function]] = weakref.WeakKeyDictionary()


def _functions(problem: SizingProblem) -> tuple[ca.Function, ca.Function]:
    """The KKT matrix's parts in x (H, J_x), and the weighted parameter derivative w_x ∂(∇_x L)/∂p + w_g ∂g/∂p:
    the few rows of ∂x*/∂p wanted, by as many adjoint sweeps (a route has thousands of parameters: their full
    Jacobians cost a forward sweep each)."""
    kkt = _KKT.get(problem)
    if kkt is None:
        n, m = problem.xs.numel(), problem.g.numel()
        lam, w_x, w_g = ca.MX.sym("lam", m), ca.MX.sym("w_x", n, n), ca.MX.sym("w_g", n, m)
        grad_L = ca.gradient(problem.f + ca.dot(lam, problem.g), problem.xs)
        weighted = ca.mtimes(w_x, grad_L) + ca.mtimes(w_g, problem.g)
        kkt = _KKT[problem] = (
            ca.Function("kkt", [problem.xs, problem.p, lam], [ca.jacobian(grad_L, problem.xs),
                                                               ca.jacobian(problem.g, problem.xs)],
                        ["x", "p", "lam"], ["H", "Jx"]),
            ca.Function("kkt_p", [problem.xs, problem.p, lam, w_x, w_g], [ca.jacobian(weighted, problem.p)],
                        ["x", "p", "lam", "w_x", "w_g"], ["dW"]))
    return kkt


def sensitivities(problem: SizingProblem, sol: Solution, p=None) -> dict[str, dict[str, float]]:
    """∂{d, F_nwl, stroke}*/∂p_j in SI units for every scene parameter p_j.

    Returns ``{param: {"d": ∂d*/∂p, "F_nwl": ∂F_nwl*/∂p, "stroke": ∂stroke*/∂p}}``, or ``{}`` where the
    optimum is not regular (the KKT matrix is singular, e.g. a load G_m near 0 on which nothing
    depends): the derivatives do not exist there, and no number is made up for them.
    """
    p = problem.p0 if p is None else np.asarray(p, dtype=float)
    kkt, kkt_p = _functions(problem)
    out = kkt(x=sol.xs, p=p, lam=sol.lam_g)
    H, Jx = (np.asarray(out[k]) for k in ("H", "Jx"))
    idx = [problem.constraints.index(c) for c in sol.active]
    fixed = [i for i, _ in sol.active_bounds]
    n, na, nb = 3, len(idx), len(fixed)
    E = np.eye(3)[fixed, :] if fixed else np.zeros((0, 3))
    K = np.zeros((n + na + nb, n + na + nb))
    K[:n, :n] = H
    K[:n, n:n + na] = Jx[idx, :].T
    K[:n, n + na:] = E.T
    K[n:n + na, :n] = Jx[idx, :]
    K[n + na:, :n] = E
    # ∂x/∂p = −Z [∂(∇_x L)/∂p; ∂g_A/∂p; 0], Z the first n rows of K⁻¹ (solved from Kᵀ)
    try:
        Z = np.linalg.solve(K.T, np.eye(n + na + nb)[:, :n]).T
    except np.linalg.LinAlgError:
        return {}
    w_g = np.zeros((n, Jx.shape[0]))
    np.add.at(w_g.T, idx, Z[:, n:n + na].T)
    dW = np.asarray(kkt_p(x=sol.xs, p=p, lam=sol.lam_g, w_x=Z[:, :n], w_g=w_g)["dW"])
    dx = -dW * problem.x_scale[:, None]
    if not np.all(np.isfinite(dx)):
        return {}
    return {name: {v: float(dx[i, j]) for i, v in enumerate(problem.variables)}
            for j, name in enumerate(problem.params)}
