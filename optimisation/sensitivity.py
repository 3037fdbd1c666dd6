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

#: the KKT matrix's parts in x of each problem ((H, J_x) of its NLP, and of the NLP with the scene's values folded
#: in), and its weighted parameter derivatives by the constraints they take, built once (kept while it lives)
_KKT: weakref.WeakKeyDictionary[SizingProblem, dict] = weakref.WeakKeyDictionary()


def _kkt_x(problem: SizingProblem, folded: bool) -> ca.Function:
    """(x, p, λ) → H = ∇²_xx (f + λᵀg), J_x = ∂g/∂x; ``folded``: of the NLP with the scene's values folded in
    (:attr:`SizingProblem.at_scene`: the same matrices at p = p0, built without every segment's parameters)."""
    kept = _KKT.setdefault(problem, {})
    if folded not in kept:
        nlp = problem.at_scene if folded else problem.nlp()
        lam = ca.MX.sym("lam", problem.g.numel())
        grad_L = ca.gradient(nlp["f"] + ca.dot(lam, nlp["g"]), problem.xs)
        kept[folded] = ca.Function("kkt", [problem.xs, problem.p, lam],
                                   [ca.jacobian(grad_L, problem.xs), ca.jacobian(nlp["g"], problem.xs)],
                                   ["x", "p", "lam"], ["H", "Jx"])
    return kept[folded]


def _kkt_p(problem: SizingProblem, taken: tuple[int, ...], kept: tuple[int, ...] | None = None) -> ca.Function:
    """(x, p, λ_S, w_x, w_S) → w_x ∂(∇_x L)/∂p + w_S ∂g_S/∂p, of the active constraints S = ``taken`` (an inactive
    one has neither a multiplier nor a weight; a static NLP's from a model of their checks alone,
    :meth:`SizingProblem.nlp_of`): the few rows of ∂x*/∂p wanted, one adjoint sweep per row (a route has thousands
    of parameters: a Jacobian in them costs a forward sweep per colour).  ``kept`` (indices into
    ``problem.params``, a static NLP's): the derivatives in those parameters alone, the others folded in at
    ``p0`` (:meth:`SizingProblem.nlp_of`); its ``p`` is then theirs."""
    built = _KKT.setdefault(problem, {})
    if (taken, kept) not in built:
        n, p = problem.xs.numel(), problem.p
        if kept is not None:
            p = ca.MX.sym("p", len(kept))
            f, g = problem.nlp_of(taken, kept, p)
        elif getattr(problem, "STATIC", False):
            f, g = problem.nlp_of(taken)
        else:
            f, g = problem.f, problem.g[list(taken)] if taken else ca.MX(0, 1)
        lam, w_x, w_g = ca.MX.sym("lam", len(taken)), ca.MX.sym("w_x", n, n), ca.MX.sym("w_g", n, len(taken))
        lagrangian = f + ca.dot(lam, g)
        # row i: ∂/∂p of w_x,i ∇_x L (a forward derivative of L in x along w_x,i) + w_g,i g, by one adjoint sweep
        rows = [ca.gradient(ca.jtimes(lagrangian, problem.xs, w_x[i, :].T) + ca.dot(w_g[i, :].T, g), p).T
                for i in range(n)]
        built[(taken, kept)] = ca.Function("kkt_p", [problem.xs, p, lam, w_x, w_g], [ca.vertcat(*rows)],
                                           ["x", "p", "lam", "w_x", "w_g"], ["dW"])
    return built[(taken, kept)]


def sensitivities(problem: SizingProblem, sol: Solution, p=None, params=None) -> dict[str, dict[str, float]]:
    """∂{d, F_nwl, stroke}*/∂p_j in SI units for every scene parameter p_j, or for those named in ``params``
    (at the scene's parameters of a static NLP: the others are folded in, and no derivative in them is made).

    Returns ``{param: {"d": ∂d*/∂p, "F_nwl": ∂F_nwl*/∂p, "stroke": ∂stroke*/∂p}}``, or ``{}`` where the
    optimum is not regular (the KKT matrix is singular, e.g. a load G_m near 0 on which nothing
    depends): the derivatives do not exist there, and no number is made up for them.
    """
    p = problem.p0 if p is None else np.asarray(p, dtype=float)
    folded = getattr(problem, "STATIC", False) and np.array_equal(p, problem.p0)
    idx = [problem.constraints.index(c) for c in sol.active]
    lam = np.zeros_like(sol.lam_g)       # an inactive constraint's multiplier is 0 (IPOPT leaves ~1e-10 there)
    lam[idx] = sol.lam_g[idx]
    out = _kkt_x(problem, folded)(x=sol.xs, p=p, lam=lam)
    H, Jx = (np.asarray(out[k]) for k in ("H", "Jx"))
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
    taken = tuple(sorted(set(idx)))
    kept = None
    if params is not None and folded and problem.nlp_model.is_a("SXFunction"):
        wanted = set(params)
        kept = tuple(j for j, name in enumerate(problem.params) if name in wanted)
    dW = np.asarray(_kkt_p(problem, taken, kept)(x=sol.xs, p=p if kept is None else p[list(kept)],
                                                 lam=lam[list(taken)], w_x=Z[:, :n], w_g=w_g[:, list(taken)])["dW"])
    dx = -dW * problem.x_scale[:, None]
    if not np.all(np.isfinite(dx)):
        return {}
    names = problem.params if kept is None else [problem.params[j] for j in kept]
    out = {name: {v: float(dx[i, j]) for i, v in enumerate(problem.variables)} for j, name in enumerate(names)}
    return out if params is None else {k: v for k, v in out.items() if k in set(params)}
