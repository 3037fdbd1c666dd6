"""Many neighbouring NLPs solved at once on a known active set, each accepted only as a KKT point.

An NLP ``min f(x, p)  s.t.  g(x, p) >= 0,  lbx <= x <= ubx`` (CasADi's signs: L = f + λᵀg + νᵀx, so
λ_i <= 0 on an active g_i >= 0, ν_j <= 0 at a lower bound and >= 0 at an upper one) has, near a regular
optimum, a locally constant active set: constraints A and bounds B (Fiacco 1976, the basis of
:mod:`optimisation.sensitivity`).  Given A and B the optimum of every nearby p solves

* at a vertex (|A| + |B| = n, the usual sizing design): ``g_A(x, p) = 0``, ``x_B = b_B`` — n equations,
  no second derivatives;
* otherwise the KKT equations ``∇f + J_Aᵀλ_A + E_Bᵀν = 0``, ``g_A = 0``, ``x_B = b_B`` in (x, λ_A, ν).

:meth:`BatchNLP.solve` runs Newton on them for a whole batch of parameter vectors at once: one mapped
CasADi call per iteration (the derivatives are exact, the expressions expanded to SX where they can be)
and batched numpy linear algebra.  A point is *accepted* only when it is a KKT point of its own NLP:

1. Newton converged: ``|g_A| <= RES_TOL`` (bounds are met exactly);
2. every other constraint holds, ``g_i >= -G_TOL``, and x lies within its bounds;
3. the multipliers have the right signs (at a vertex they are recovered from ∇f + Aᵀμ = 0 and the
   residual of that system is checked: ``<= STAT_TOL·max(1, |∇f|)``);
4. away from a vertex the Hessian of the Lagrangian is positive definite on the null space of the active
   normals (a strict local minimum, not a saddle).

A point that fails is left for the caller (IPOPT).  Nothing here decides *which* active set: the caller
takes it from a solved neighbour (:func:`identify`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import casadi as ca
import numpy as np

#: Newton stops when a step is below this, relative to max(1, |x|)
STEP_TOL = 1e-13
MAX_ITER = 20
#: acceptance: residual of the active constraints (scaled), inactive constraints >= -G_TOL, multiplier
#: signs within LAM_TOL, stationarity residual relative to max(1, |∇f|)
RES_TOL = 1e-11
G_TOL = 1e-10
LAM_TOL = 1e-9
STAT_TOL = 1e-8
#: identification of an active set from a converged solve (the thresholds of :mod:`optimisation.ipopt`)
ACTIVE_G = 1e-7
ACTIVE_LAM = 1e-9
LOOSE_G = 1e-3


@dataclass
class Mode:
    """An active set (constraint indices, bounds as (index, "lower"|"upper")) with a solved point of it:
    x and its multipliers (λ of every constraint, zero off A; ν of every bound, zero off B)."""

    constraints: tuple[int, ...]
    bounds: tuple[tuple[int, str], ...]
    x: np.ndarray
    lam_g: np.ndarray
    lam_x: np.ndarray

    @property
    def size(self) -> int:
        return len(self.constraints) + len(self.bounds)


@dataclass
class Batch:
    """Result of :meth:`BatchNLP.solve` at N points: x (N, n), lam_g (N, ng), lam_x (N, n), ok (N,)."""

    x: np.ndarray
    lam_g: np.ndarray
    lam_x: np.ndarray
    ok: np.ndarray


def _function(inputs, outputs, name):
    """A Function of (x, p_varied, p_const[, lam]) with its outputs stacked in one dense column (column-major
    blocks, in order); SX if it expands."""
    names = ["x", "p_varied", "p_const", "lam"][:len(inputs)]
    fun = ca.Function(name, inputs, [ca.densify(ca.vertcat(*[ca.vec(o) for o in outputs]))], names, ["stacked"])
    try:
        return fun.expand()
    except RuntimeError:   # a rootfinder inside (e.g. the Voigt lining): evaluate the MX graph
        return fun


class BatchNLP:
    """The derivatives an active-set Newton needs, mapped over batches of points.

    x, p: CasADi MX symbols (vectors); f, g: expressions in them; lbx, ubx: bounds of x (arrays);
    varied: indices of the entries of p that differ between points (the others are passed once).
    """

    def __init__(self, x, p, f, g, lbx, ubx, varied, p_const):
        self.n, self.ng = x.numel(), g.numel()
        self.lbx, self.ubx = np.asarray(lbx, dtype=float), np.asarray(ubx, dtype=float)
        self.varied = np.asarray(varied, dtype=int)
        const = np.setdiff1d(np.arange(p.numel()), self.varied)
        pv, pc = ca.MX.sym("pv", len(self.varied)), ca.MX.sym("pc", len(const))
        parts = [None] * p.numel()
        for i, k in enumerate(self.varied):
            parts[k] = pv[i]
        for i, k in enumerate(const):
            parts[k] = pc[i]
        fg = ca.Function("fg", [x, p], [f, g])
        f, g = fg(x, ca.vertcat(*parts))
        self._x, self._pv, self._pc, self._f, self._g = x, pv, pc, f, g
        self._first = _function([x, pv, pc], [g, ca.jacobian(g, x), ca.gradient(f, x)], "kkt_first")
        self.p_const = ca.DM(np.asarray(p_const, dtype=float)[const])
        self._maps: dict = {}

    @cached_property
    def _second(self):
        """∇²_xx(f + λᵀg), built when a mode away from a vertex first needs it."""
        lam = ca.MX.sym("lam", self.ng)
        hess = ca.hessian(self._f + ca.dot(lam, self._g), self._x)[0]
        return _function([self._x, self._pv, self._pc, lam], [hess], "kkt_second")

    def _mapped(self, which: str, n: int):
        fm = self._maps.get((which, n))
        if fm is None:
            fun = self._first if which == "first" else self._second
            fm = self._maps[(which, n)] = fun.map(f"{fun.name()}_{n}", "serial", n, [2], [])
        return fm

    def first(self, X, PV):
        """g (N, ng), J (N, ng, n), ∇f (N, n) at the rows of X (N, n) and varied parameters PV (N, nv)."""
        N, n, ng = X.shape[0], self.n, self.ng
        out = self._mapped("first", N)(X.T, PV.T, self.p_const).full()
        g = out[:ng].T
        J = out[ng:ng + ng * n].reshape(n, ng, N).transpose(2, 1, 0)
        return g, J, out[ng + ng * n:].T

    def hessian(self, X, PV, LAM):
        """∇²_xx(f + λᵀg) (N, n, n)."""
        N, n = X.shape[0], self.n
        out = self._mapped("second", N)(X.T, PV.T, self.p_const, LAM.T).full()
        return out.reshape(n, n, N).transpose(2, 1, 0)

    # ---------------------------------------------------------------- Newton
    def solve(self, mode: Mode, PV, X0=None) -> Batch:
        """Newton on ``mode``'s active set at every row of PV (from ``X0``, default the mode's x), then the
        acceptance tests of the module docstring."""
        N = PV.shape[0]
        X = np.tile(mode.x, (N, 1)) if X0 is None else np.array(X0, dtype=float)
        B, bval = self._bounds(mode)
        X[:, B] = bval
        if mode.size == self.n:
            X = self._newton_vertex(mode, X, PV)
            return self._accept_vertex(mode, X, PV)
        X, lam_a, nu = self._newton_kkt(mode, X, PV)
        return self._accept_kkt(mode, X, PV, lam_a, nu)

    def _bounds(self, mode):
        B = np.array([i for i, _ in mode.bounds], dtype=int)
        bval = np.array([self.lbx[i] if side == "lower" else self.ubx[i] for i, side in mode.bounds])
        return B, bval

    def _newton_vertex(self, mode, X, PV):
        A, (B, _) = list(mode.constraints), self._bounds(mode)
        E = np.eye(self.n)[B]
        live = np.arange(X.shape[0])
        for _ in range(MAX_ITER):
            if live.size == 0:
                break
            g, J, _ = self.first(X[live], PV[live])
            M = np.concatenate([J[:, A, :], np.broadcast_to(E, (live.size, *E.shape))], axis=1)
            r = np.concatenate([g[:, A], np.zeros((live.size, len(B)))], axis=1)
            step = _solve(M, -r)
            X[live] += step
            done = np.abs(step).max(axis=1) <= STEP_TOL * np.maximum(1.0, np.abs(X[live]).max(axis=1))
            live = live[~done & np.isfinite(step).all(axis=1)]
        return X

    def _newton_kkt(self, mode, X, PV):
        A, (B, _) = list(mode.constraints), self._bounds(mode)
        n, na, nb, N = self.n, len(A), len(B), X.shape[0]
        E = np.eye(n)[B]
        lam_a = np.tile(mode.lam_g[A], (N, 1))
        nu = np.tile(mode.lam_x[B], (N, 1))
        live = np.arange(N)
        for _ in range(MAX_ITER):
            if live.size == 0:
                break
            L = live.size
            g, J, gf = self.first(X[live], PV[live])
            lam = np.zeros((L, self.ng))
            lam[:, A] = lam_a[live]
            H = self.hessian(X[live], PV[live], lam)
            K = np.zeros((L, n + na + nb, n + na + nb))
            K[:, :n, :n] = H
            K[:, :n, n:n + na] = J[:, A, :].transpose(0, 2, 1)
            K[:, n:n + na, :n] = J[:, A, :]
            K[:, :n, n + na:] = E.T
            K[:, n + na:, :n] = E
            stat = gf + np.einsum("bij,bi->bj", J[:, A, :], lam_a[live]) + nu[live] @ E
            r = np.concatenate([stat, g[:, A], np.zeros((L, nb))], axis=1)
            step = _solve(K, -r)
            X[live] += step[:, :n]
            lam_a[live] += step[:, n:n + na]
            nu[live] += step[:, n + na:]
            done = np.abs(step[:, :n]).max(axis=1) <= STEP_TOL * np.maximum(1.0, np.abs(X[live]).max(axis=1))
            live = live[~done & np.isfinite(step).all(axis=1)]
        return X, lam_a, nu

    # ------------------------------------------------------------ acceptance
    def _common(self, mode, X, g, lam_a, nu, stat):
        """Tests 1-3 of the module docstring (rows of X)."""
        A, (B, _) = list(mode.constraints), self._bounds(mode)
        inactive = np.setdiff1d(np.arange(self.ng), A)
        ok = np.isfinite(X).all(axis=1) & np.isfinite(g).all(axis=1) & np.isfinite(lam_a).all(axis=1)
        ok &= np.abs(g[:, A]).max(axis=1, initial=0.0) <= RES_TOL
        ok &= g[:, inactive].min(axis=1, initial=np.inf) >= -G_TOL
        slack = 1e-12 * np.maximum(1.0, np.abs(X))
        ok &= ((X >= self.lbx - slack) & (X <= self.ubx + slack)).all(axis=1)
        ok &= lam_a.max(axis=1, initial=-np.inf) <= LAM_TOL
        sign = np.array([1.0 if side == "lower" else -1.0 for _, side in mode.bounds])
        ok &= (nu * sign).max(axis=1, initial=-np.inf) <= LAM_TOL
        ok &= stat
        lam_g = np.zeros((X.shape[0], self.ng))
        lam_g[:, A] = lam_a
        lam_x = np.zeros_like(X)
        lam_x[:, B] = nu
        return Batch(X, lam_g, lam_x, ok)

    def _accept_vertex(self, mode, X, PV):
        A, (B, _) = list(mode.constraints), self._bounds(mode)
        E = np.eye(self.n)[B]
        g, J, gf = self.first(X, PV)
        M = np.concatenate([J[:, A, :], np.broadcast_to(E, (X.shape[0], *E.shape))], axis=1)
        MT = M.transpose(0, 2, 1)
        mu = _solve(MT, -gf)
        resid = np.abs(np.einsum("bij,bj->bi", MT, mu) + gf).max(axis=1)
        stat = resid <= STAT_TOL * np.maximum(1.0, np.abs(gf).max(axis=1))
        return self._common(mode, X, g, mu[:, :len(A)], mu[:, len(A):], stat)

    def _accept_kkt(self, mode, X, PV, lam_a, nu):
        A, (B, _) = list(mode.constraints), self._bounds(mode)
        E = np.eye(self.n)[B]
        g, J, gf = self.first(X, PV)
        res = gf + np.einsum("bij,bi->bj", J[:, A, :], lam_a) + nu @ E
        stat = np.abs(res).max(axis=1) <= STAT_TOL * np.maximum(1.0, np.abs(gf).max(axis=1))
        lam = np.zeros((X.shape[0], self.ng))
        lam[:, A] = lam_a
        stat &= _reduced_pd(self.hessian(X, PV, np.nan_to_num(lam)),
                            np.concatenate([J[:, A, :], np.broadcast_to(E, (X.shape[0], *E.shape))], axis=1))
        return self._common(mode, X, g, lam_a, nu, stat)


def _solve(M, r):
    """Batched ``M x = r``; rows with a singular or non-finite M get NaN (an ill-conditioned one gives a
    useless step, which the acceptance tests reject)."""
    good = np.isfinite(M).all(axis=(1, 2)) & np.isfinite(r).all(axis=1)
    out = np.full(r.shape, np.nan)
    idx = np.flatnonzero(good)
    try:
        out[idx] = np.linalg.solve(M[idx], r[idx][..., None])[..., 0]
    except np.linalg.LinAlgError:   # some exactly singular: one at a time
        for i in idx:
            try:
                out[i] = np.linalg.solve(M[i], r[i])
            except np.linalg.LinAlgError:
                pass
    return out


def _reduced_pd(H, A):
    """True where H (N, n, n) is positive definite on the null space of the rows of A (N, m, n)."""
    N, m, n = A.shape
    ok = np.isfinite(H).all(axis=(1, 2)) & np.isfinite(A).all(axis=(1, 2))
    out = np.zeros(N, dtype=bool)
    for b in np.flatnonzero(ok):
        _, s, vt = np.linalg.svd(A[b]) if m else (None, np.zeros(0), np.eye(n))
        Z = vt[int(np.sum(s > 1e-12 * max(1.0, s.max(initial=0.0)))):].T
        out[b] = Z.shape[1] == 0 or np.linalg.eigvalsh(Z.T @ H[b] @ Z).min() > 1e-12
    return out


def identify(g, lam_g, x, lam_x, lbx, ubx, loose: bool = False):
    """The active set of a converged solve (x, its multipliers): constraints at zero with a binding multiplier,
    bounds with one (:func:`regular_subset` then keeps a regular set of at most n).

    ``loose``: also constraints with a binding multiplier whose margin is below :data:`LOOSE_G` — an
    interior-point method leaves a constraint with a small multiplier λ at a margin of about μ/λ (μ its
    final barrier parameter), above :data:`ACTIVE_G`.  Either is only a guess: Newton and the acceptance
    tests decide.
    """
    bounds = []
    for i in range(len(x)):
        near = ACTIVE_G * max(1.0, abs(x[i]))
        if lbx[i] == ubx[i] or (abs(x[i] - lbx[i]) < near and lam_x[i] < -ACTIVE_LAM):
            bounds.append((i, "lower"))
        elif np.isfinite(ubx[i]) and abs(x[i] - ubx[i]) < near and lam_x[i] > ACTIVE_LAM:
            bounds.append((i, "upper"))
    limit = LOOSE_G if loose else ACTIVE_G
    active = [i for i in range(len(g)) if g[i] < limit and abs(lam_g[i]) > ACTIVE_LAM]
    return tuple(active), tuple(bounds)


def regular_subset(constraints, bounds, J, lam_g, n: int):
    """At most n active members with independent normals: every bound, then constraints by decreasing |λ|
    (J: the constraint Jacobian at the point).  A degenerate vertex (more members than n) becomes a regular
    one; the members left out are then checked as inactive constraints."""
    rows = [np.eye(n)[i] for i, _ in bounds]
    keep = []
    for i in sorted(constraints, key=lambda k: -abs(lam_g[k])):
        trial = np.array(rows + [J[i]])
        if len(rows) < n and np.linalg.matrix_rank(trial, tol=1e-10 * max(1.0, np.abs(trial).max())) == len(trial):
            rows.append(J[i])
            keep.append(i)
    return tuple(sorted(keep)), tuple(bounds)
