"""Constraint generation: the NLP of a long route makes each check only where it can be least, and every design
it finds is checked at every candidate case.

A route of n segments has O(n) places that can govern (:func:`ropemodel.envelope.prune.prune`: the candidates),
and each case is a copy of the model, whose size grows with n: an NLP of every check at every candidate grows as
O(n²) (10 000 points, every rope weight: 948 cases, 9487 constraints, 3.6 GB before IPOPT starts).  Only a few
cases are active at the optimum, so the NLP starts from the case in which each check is least at the starting
design (:func:`first_cases`), and after each solve the design is checked at every candidate in one vectorised
call (:func:`uncovered`); a check less at a candidate left out than the NLP held it (below zero, by more than
:data:`TOL`) adds that case, and the NLP is solved again.  This is the exchange (cutting-plane) method of
semi-infinite programming (Blankenship & Falk 1976, J. Optim. Theory Appl. 19(2), 261-281; Hettich & Kortanek
1993, SIAM Review 35(3), 380-429): the NLP of a subset of the constraints is a relaxation, so its optimum, once it
holds every constraint, is the optimum of the whole (here a finite set: it ends after at most as many rounds as
candidates, and :data:`ROUNDS` bounds it before the NLP of every candidate is solved instead).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import casadi as ca
import numpy as np

from ropemodel.envelope.cases import distinct, joint_ends

if TYPE_CHECKING:
    from ropemodel.envelope import LoadCase
    from optimisation.problem import SizingProblem

#: a candidate case is added where a check there is below zero and below what the NLP held by more than this
#: (scaled as the NLP's constraints: N over the force scale, m, ratios): the rounding of the margins, far below
#: IPOPT's tolerance, so a design that passes is the whole NLP's optimum to the last digits IPOPT gives
TOL = 1e-12
#: rounds of adding cases before the NLP takes every candidate (each round adds at least one case)
ROUNDS = 12


def _screen(problem: SizingProblem) -> tuple[ca.Function, np.ndarray]:
    """The checks' constraints (scaled, in the order of ``problem.checks``) as a Function of the scaled design and
    the case inputs, the scene's parameters folded in, and the case inputs of every candidate (one column each)."""
    kept = problem.__dict__.get("_screen")
    if kept is None:
        model = problem.folded_model()
        x, c = ca.SX.sym("x", len(problem.variables)), ca.SX.sym("c", len(problem.case_inputs))
        x_si = x * ca.DM(problem.x_scale)
        out = model.call({"x": x_si, "c": c})
        args = problem.known_values([float(v) for v in problem.p0], x_si)
        g = [problem.sizing.nlp_form(k, out, args) / problem.check_scale[k] for k in problem.checks]
        params = problem.scene.parameters
        ends = joint_ends(params) if problem.scene.route else None
        rows = [problem.case_values(case, params, ends) for case in problem.candidates]
        columns = np.array([[float(r.get(k, 0.0)) for r in rows] for k in problem.case_inputs],
                           dtype=float).reshape(len(problem.case_inputs), len(rows))
        kept = problem.__dict__["_screen"] = (ca.Function("screen", [x, c], [ca.vertcat(*g)]), columns)
    return kept


def values(problem: SizingProblem, xs) -> np.ndarray:
    """Every check's constraint (scaled) at scaled ``xs`` in every candidate case: an array checks x candidates."""
    fun, columns = _screen(problem)
    n = columns.shape[1]
    x = np.repeat(np.asarray(xs, dtype=float).reshape(-1, 1), n, axis=1)
    return np.asarray(fun.map(n)(x, columns)).reshape(len(problem.checks), n)


def first_cases(problem: SizingProblem) -> list[LoadCase]:
    """The candidate in which each check is least at the starting design (:meth:`SizingProblem.x0`), each once."""
    table = values(problem, problem.x0())
    picked = set()
    for k, check in enumerate(problem.checks):
        idx = distinct(problem.candidates, problem.depends[check])
        picked.add(idx[int(np.argmin(table[k, idx]))])
    return [problem.candidates[i] for i in sorted(picked)]


def uncovered(problem: SizingProblem, designs) -> list[int]:
    """Candidates (indices into ``problem.candidates``) to add: for each scaled design of ``designs`` and each check,
    the candidate left out of the NLP where the check is least, if it is there below zero and below the least the
    NLP held by more than :data:`TOL`."""
    more: set[int] = set()
    for xs in designs:
        table = values(problem, xs)
        for k, check in enumerate(problem.checks):
            inputs = problem.depends[check]
            held_keys = {case.key(inputs) for case in problem.cases}
            idx = distinct(problem.candidates, inputs)
            row = table[k, idx]
            held = [v for i, v in zip(idx, row) if problem.candidates[i].key(inputs) in held_keys]
            j = int(np.argmin(row))
            if problem.candidates[idx[j]].key(inputs) not in held_keys and row[j] < min([0.0, *held]) - TOL:
                more.add(idx[j])
    return sorted(more)
