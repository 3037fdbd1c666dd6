"""Dynamic factors of a design, and the static design with a flat dynamic factor (the NLP's start).

The usual practice sizes on static forces with a flat dynamic factor k: the rope safety against
k·F_C (n_rope → k·n_rope) and the traction against k·F_C (n_slip → k·n_slip), e.g. k = 1.1 (German
mining rules).  :func:`factored_design` is that sizing.  The transient shows its own factors
(:func:`transient_factors`): the peak winding force over the static one, k_C = max_t F_C(t)/F_C, and
the peak force ratio over the static one, k_R = max_t (F_C/F_S)(t)/(F_C/F_S) (what the traction must
hold).  :func:`factored_start` sizes with the factors the transient shows at the design it sizes (a
fixed point, three rounds) and the stroke the take-up reaches: a start of the dynamic NLP near its
optimum, cheaply (static solves and plain integrations, no sensitivities).
"""

from __future__ import annotations

import numpy as np

from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem

#: step [s] of the dense grid the factors are read on
DT_DENSE = 0.01
ROUNDS = 3


def transient_factors(problem, xs, p=None, dt: float = DT_DENSE) -> list[dict]:
    """Per case (every manoeuvre, every place of the load) at scaled design ``xs``: the peaks of its transient
    in the smooth mode (SI) and its factors against the static forces its direction of travel is sized for,
    the largest over the route (the NLP's integrator on a ``dt`` grid): k_C = max_t F_C(t) / max_x F_C and
    k_R = max_t (F_C/F_S)(t) / max_x (F_C/F_S), x the load's places (on a straight route the static forces do
    not depend on it)."""
    p = problem.p0 if p is None else np.asarray(p, float)
    statics = [problem.static_at(xs, p, path.manoeuvre.x_m) for path in problem.all_paths]
    C = {w: max(s[f"F_C_{w}"] for s in statics) for w in ("up", "down")}
    R = {w: max(s[f"F_C_{w}"] / s[f"F_S_{w}"] for s in statics) for w in ("up", "down")}
    out = []
    for path in problem.all_paths:
        pp = problem.pp0(path, xs, p)
        _, o, _ = path.samples(pp, path.uniform_grid(pp, dt))
        F_C, F_S = o["F_C"].ravel(), o["F_S"].ravel()
        w = path.manoeuvre.travel
        out.append({"manoeuvre": path.manoeuvre.tag, "F_C_max": float(F_C.max()), "F_S_min": float(F_S.min()),
                    "take_up_max": float(o["take_up"].max()), "k_C": float(F_C.max() / C[w]),
                    "k_R": float(np.max(F_C / F_S) / R[w])})
    return out


def factored_design(static: SizingProblem, k_rope: float, k_slip: float, x0=None, p=None):
    """The static optimum with the rope safety and the traction checked against k·F_C (scaled solution)."""
    p = static.p0 if p is None else np.asarray(p, float)
    names = static.params
    q = p.copy()
    q[names.index("n_rope")] *= k_rope
    if "n_slip" in names:
        q[names.index("n_slip")] *= k_slip
    return solve_continuous(static, p=q, x0=x0)


def factored_start(problem, static_xs, p=None) -> np.ndarray:
    """A start for the dynamic NLP: the static design sized with the factors its own transient shows (the
    rope safety with k_C, the traction with max(n_slip, n_slip_dynamic k_R) — the transient asks
    n_slip_dynamic, the static check n_slip) and the stroke the take-up reaches, :data:`ROUNDS` rounds from
    the static optimum."""
    p = problem.p0 if p is None else np.asarray(p, float)
    n_slip = p[problem.params.index("n_slip")] if "n_slip" in problem.params else 1.0
    n_slip /= p[problem.params.index("n_slip_dynamic")] if "n_slip_dynamic" in problem.params else 1.0
    x = np.asarray(static_xs, float).copy()
    static = SizingProblem(problem.scene)
    for _ in range(ROUNDS):
        f = transient_factors(problem, x, p)
        k_C = max(1.0, max(m["k_C"] for m in f))
        k_R = max(1.0, max(m["k_R"] for m in f) / n_slip)
        sol = factored_design(static, k_C, k_R, x0=x, p=p)
        if not sol.feasible:
            break
        x = sol.xs.copy()
    take_up = max(m["take_up_max"] for m in transient_factors(problem, x, p))
    x[2] = max(x[2], take_up / problem.x_scale[2]) * 1.01
    return x


def flat_factor(problem, static_xs, p=None) -> float:
    """The factor the transient shows at the static design: the largest F_C,max/F_C,static of its four
    manoeuvres (≥ 1), what ``ropemodel simulate`` reports as the dynamic factor."""
    return max(1.0, max(m["k_C"] for m in transient_factors(problem, static_xs, p)))


def fallback_starts(problem, static_xs, p=None) -> list[np.ndarray]:
    """Further starts of the dynamic NLP: the static design sized with the flat factor its transient shows
    (rope safety and traction both), when that static problem has a design."""
    k = flat_factor(problem, static_xs, p)
    sol = factored_design(SizingProblem(problem.scene), k, k, x0=static_xs, p=p)
    return [sol.xs] if sol.feasible else []
