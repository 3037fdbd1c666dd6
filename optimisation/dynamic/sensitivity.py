"""Sensitivities of the dynamic optimum, ∂x*/∂p, from its active checks.

At the usual dynamic optimum, a vertex (as many active checks and bounds as design variables — e.g.
the rope safety at the peak of the upward start, no slip at another instant of it, and the static
stroke), the active set fixes the design: g_A(x*(p), p) = 0, so

    ∂x*/∂p = −J_A⁻¹ ∂g_A/∂p,

with J_A = ∂g_A/∂x (and unit rows for active bounds).  Both Jacobians are exact CasADi derivatives
through the integrator (forward sensitivities).  An active check at an instant t* stays active at
the moving instant t*(p): its value there is a local minimum in t, so ∂g/∂t = 0 and moving the
instant changes g only to second order (an envelope argument); the NLP's grid point is the
refinement's exact t* (:mod:`optimisation.dynamic.refine`).  Elsewhere (fewer active constraints
than variables) the KKT system needs the Lagrangian's second derivatives through the integrator:
:func:`optimisation.sensitivity.sensitivities` computes it exactly (slower).

Parameters that fix the transient's structure (the route's geometry, where the load is, the
transient's duration t_end) are not symbols of the transient and get no sensitivity.  Nor do the
parameters that move where a manoeuvre's phases meet (:func:`timing_params`, read from each smooth mode's
phase bounds: the ramp's ``t_ramp``, an S-curve's ``jerk_max`` and ``v_pj``, whatever a machine's profile
makes its phases' ends of): a peak force sits at such a joint (the linear ramp's acceleration steps at its end),
where g has a kink in t and the envelope argument above fails.  Measured on the tests' scene (4 s linear ramp):
∂F_nwl*/∂t_ramp from the active set was −9157 N/s against −8569 N/s from central differences of re-solves
(7 %), ∂stroke*/∂t_ramp 0.0648 m/s against 0.0747 m/s (15 %); so none is given rather than a wrong one.  A
re-solve (``sweep --sizing --dynamic --vary t_ramp=...``) answers it.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from optimisation.ipopt import Solution


def symbolic_params(problem) -> list[str]:
    """The parameters every manoeuvre's transient has as symbols (those with a sensitivity)."""
    shared = set.intersection(*[set(path.names) for path in problem.all_paths])
    return [k for k in problem.params if k in shared]


def timing_params(problem) -> set[str]:
    """The parameters that move where the phases of any manoeuvre meet: those the smooth modes' phase bounds
    (t0, t1 of each phase, the profile's) depend on."""
    out: set[str] = set()
    for path in problem.all_paths:
        bounds = path.sm.bounds
        cols = set(bounds.sparsity_jac(0, 0).get_col()) | set(bounds.sparsity_jac(0, 1).get_col())
        out |= {path.names[i] for i in cols}
    return out


def sensitivities(problem, sol: Solution, p=None) -> dict[str, dict[str, float]]:
    """∂x*/∂p_j (x the machine's design variables) in SI units for every parameter of :func:`symbolic_params`
    but those that move where a manoeuvre's phases meet (:func:`timing_params`)."""
    p = problem.p0 if p is None else np.asarray(p, float)
    timing = timing_params(problem)
    names = [k for k in symbolic_params(problem) if k not in timing]
    idx = [problem.constraints.index(c) for c in sol.active]
    fixed = [i for i, _ in sol.active_bounds]
    if len(idx) + len(fixed) != len(problem.variables):
        from optimisation.sensitivity import sensitivities as kkt

        full = kkt(problem, sol, p)      # {} where the optimum is not regular: no number made up
        return {k: full[k] for k in names if k in full}
    cols = [problem.params.index(k) for k in names]
    g = problem.g_function(problem.xs, problem.p)
    active = ca.vertcat(*[g[i] for i in idx])
    jac = ca.Function("jac_active", [problem.xs, problem.p],
                      [ca.jacobian(active, problem.xs), ca.jacobian(active, problem.p)])
    Jx, Jp = (np.asarray(a) for a in jac(sol.xs, p))
    E = np.eye(len(problem.variables))[fixed, :]
    A = np.vstack([Jx, E]) if fixed else Jx
    rhs = -np.vstack([Jp[:, cols], np.zeros((len(fixed), len(cols)))])
    dx = np.linalg.solve(A, rhs) * problem.x_scale[:, None]
    return {name: {v: float(dx[i, j]) for i, v in enumerate(problem.variables)} for j, name in enumerate(names)}
