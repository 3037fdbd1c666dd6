"""Which cases the NLP integrates: the load positions that govern each check, screened cheaply.

Every case (:func:`~optimisation.dynamic.manoeuvres.cases`: four manoeuvres, the load at three places per
segment, 36 cases on a three-segment route) inside IPOPT would multiply the cost of each iteration as
many times.  The cases are screened instead with the NLP's own integrator at numbers (the smooth mode,
no sensitivities, on a grid of :data:`~optimisation.dynamic.start.DT_DENSE`), which costs about one
iteration's integration for all of them:

* :func:`governing`: at a design, for each manoeuvre and each check, the case where that check's margin
  is least, when that margin is below :data:`SCREEN_TOL` (a check far from its limit there cannot govern
  the optimum nearby) — the NLP's cases;
* :func:`uncovered`: at the NLP's optimum, the cases left out where some check comes within the back-off
  — added to the NLP, which is solved again (:func:`~optimisation.dynamic.refine.solve_refined`), until
  every case left out keeps every check with the back-off to spare.

The screening only chooses what the NLP integrates: every design is then simulated in every case by the
hybrid simulator (:mod:`optimisation.dynamic.verify`).
"""

from __future__ import annotations

import numpy as np

from optimisation.dynamic.start import DT_DENSE

#: a check whose least scaled margin at the screening design is below this may govern the optimum: its worst
#: case joins the NLP (scaled as the NLP scales it: 0.5 is 5 % of the load's weight for a force, 0.5 m of
#: take-up).  A check it leaves out is still screened at the optimum (:func:`uncovered`).  Measured on the
#: three-segment route of issue 21, screened at :func:`~optimisation.dynamic.start.factored_start`: with
#: every check's worst case in the NLP (no threshold) 21 of the 36 cases were integrated and the sizing took
#: 380 CPU-s; with it 3, the screening at the optimum added 2, and it took 241 CPU-s, to the same design
SCREEN_TOL = 0.5


def check_scale(problem, check) -> float:
    """The scale of a check's margin in the NLP (F_ref for a force, 1 m for a length)."""
    return problem.F_ref if check.unit == "N" else 1.0


def least_margins(problem, path, xs, p, a: dict) -> dict[str, float]:
    """Every check's least scaled margin (before the back-off) through ``path`` at scaled design ``xs``,
    parameters ``p`` (``a``: the values the checks read, :meth:`DynamicSizingProblem.values` as floats)."""
    pp = problem.pp0(path, xs, p)
    _, o, _ = path.samples(pp, path.uniform_grid(pp, DT_DENSE))
    return {c.name: float(np.min(np.asarray(c.nlp(o, a), float))) / check_scale(problem, c) for c in path.checks}


def all_margins(problem, xs, p=None, which=None) -> dict[int, dict[str, float]]:
    """:func:`least_margins` of every case (index into ``problem.cases``; ``which``: only these)."""
    p = problem.p0 if p is None else np.asarray(p, float)
    a = {k: float(v) for k, v in problem.values(np.asarray(xs, float) * problem.x_scale, p).items()}
    indices = range(len(problem.cases)) if which is None else which
    return {i: least_margins(problem, problem.all_paths[i], xs, p, a) for i in indices}


def governing(problem, xs, p=None, tol: float = SCREEN_TOL) -> list[int]:
    """The cases (indices, in order) where some check of some manoeuvre has its least margin at ``xs``, that
    margin below ``tol`` (scaled); at least the case of the least margin of all."""
    margins = all_margins(problem, xs, p)
    out: set[int] = set()
    for label in dict.fromkeys(m.label for m in problem.cases):
        mine = [i for i, m in enumerate(problem.cases) if m.label == label]
        for check in dict.fromkeys(c for i in mine for c in margins[i]):
            worst = min((i for i in mine if check in margins[i]), key=lambda i: margins[i][check])
            if margins[worst][check] < tol:
                out.add(worst)
    return sorted(out) or [min(margins, key=lambda i: min(margins[i].values()))]


def uncovered(problem, xs, p=None, below: float = 0.0) -> list[int]:
    """The cases outside the NLP where some check's least margin at ``xs`` is below ``below`` (scaled)."""
    outside = [i for i in range(len(problem.cases)) if i not in problem.selected]
    margins = all_margins(problem, xs, p, outside)
    return [i for i in outside if min(margins[i].values()) < below]
