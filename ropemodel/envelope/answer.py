"""``run`` and ``solve`` at the worst case: each output at its worst over the load cases the scene leaves
open, and an inverse question answered where the given output is worst.

``solve`` at the worst case (a check given as 0 is met where it is worst: the answer is the largest load or
the longest route that passes everywhere): the question is solved at each load case; each case's answer is a
candidate, and the answer is the candidate at which the given output's worst over every case equals the
given value.  Its governing case is named.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ropemodel import budget
from ropemodel.envelope.cases import CASE_INPUTS, LoadCase, depends_on, load_cases, with_ramps
from ropemodel.envelope.prune import prune
from ropemodel.envelope.result import EnvelopeResult
from ropemodel.envelope.worst import case_columns, envelope
from ropemodel.errors import InputError, SolveError
from ropemodel.problem import Problem
from ropemodel.result import Result
from ropemodel.scene import SceneLike, as_scene

#: relative agreement of a candidate's worst with the given value (as Problem.solve checks a given value)
AGREE = 1e-6


def run(scene: SceneLike, values: Mapping | None = None) -> Result:
    """Forward solve: every output of the scene, each at its worst where the scene leaves the load's place or
    the manoeuvre open (``ropemodel run``).

    Parameters
    ----------
    scene : Scene or str or Path
        A loaded scene (:func:`ropemodel.load_scene`), a TOML scene file or the name of a built-in scene.
    values : dict, optional
        Parameters to override for this run: SI numbers, strings with units or pint Quantities
        (``{"x_m": "1300 m"}`` pins the load's place).

    Returns
    -------
    Result
        Every output in SI (``result["F_C_up"]`` in N); ``result.table()`` in the paper's units.  On a route
        without ``x_m`` (or with the ramps' inertia and no ``a_h``: a scene that gives ``t_ramp`` has them,
        :func:`~ropemodel.envelope.cases.with_ramps`) an
        :class:`~ropemodel.envelope.result.EnvelopeResult`: each output's worst over every place of the load
        and every manoeuvre, both directions, with ``result.where[name]`` saying where it governs.

    Raises
    ------
    InputError
        Bad input (exit status 2 from the command line).
    SolveError
        No valid result, e.g. a slack rope at some place (exit status 1).

    Examples
    --------
    >>> import ropemodel as rm
    >>> r = rm.run(rm.load_scene())          # Krauze et al. (2025), Fig. 9
    >>> round(r["F_C_up"] / 1e3, 2)          # kN, the paper prints 190.95
    190.95
    >>> r = rm.run(rm.load_scene("route_segments"))     # 22°, 9°, 3° segments; 5 s ramps
    >>> round(r["F_C_up"] / 1e3, 2), r.where["F_C_up"]
    (267.83, 'segment 1, x_m = 400 m, start')
    """
    loaded = as_scene(scene)
    sc = with_ramps(loaded.with_values(values) if values else loaded)
    cases = load_cases(sc)
    if len(cases) == 1:
        return Problem(sc).solve(cases[0].values(sc.parameters))
    # the places that can govern (on a long route a few of thousands; each case costs the whole route)
    env = envelope(Problem(sc), prune(cases, sc.parameters, sc.built))
    env.spanned = cases
    return EnvelopeResult(sc, sc.built, env)


def solve(scene: SceneLike, given: Mapping, find: Sequence[str] | str, bare: str = "si") -> Result:
    """Inverse solve: ``given`` outputs (name → value) in place of the ``find`` parameters, each given output
    met at its worst over the load cases the scene leaves open (``ropemodel solve``).

    Parameters
    ----------
    scene : Scene or str or Path
        A loaded scene (:func:`ropemodel.load_scene`), a TOML scene file or the name of a built-in scene.
    given : dict
        Output name → value: a string with a unit (``"1000 mm"``), a pint Quantity, or an SI number.
    find : str or sequence of str
        The parameters to solve for, one per given value.
    bare : {"si", "refuse"}
        Numbers without a unit are SI (Python) or refused for dimensional quantities (command line).

    Returns
    -------
    Result
        The found parameters and every output, in SI (a scene that gives ``t_ramp`` includes its starts and
        stops, :func:`~ropemodel.envelope.cases.with_ramps`); at the worst case an
        :class:`~ropemodel.envelope.result.EnvelopeResult` whose ``governing`` names the case that decides.

    Raises
    ------
    InputError
        Unknown names or an ill-posed question (the message names the variables involved); a given output
        that depends on the load's place and declares no worst, where the scene leaves the place open.
    SolveError
        No valid answer; the message says why in the quantities' terms.

    Examples
    --------
    >>> import ropemodel as rm
    >>> r = rm.solve(rm.load_scene(), given={"dF_up": "1000 mm"}, find=["G_m"])
    >>> round(r["G_m"] / 1e3, 3)             # kN: the heaviest load a 1000 mm stroke allows
    252.383
    """
    find = [find] if isinstance(find, str) else list(find)
    sc = with_ramps(as_scene(scene))
    problem = Problem(sc, given, find, bare=bare)
    cases = load_cases(sc, pinned=find)
    if len(cases) == 1:
        return problem.solve(cases[0].values(sc.parameters))
    if sc.route:
        # segment by segment: each case's root-find goes through the n segments; held as route numbers: each case is
        # a few numbers, but each case's answer may be checked at every case (_choose)
        n, numbers = len(sc.route), bool(sc.built.derived)
        budget.check("route solve", len(cases) * (len(cases) if numbers else n),
                     f"solving for {', '.join(find)} on a route of {n} segments at {len(cases)} load cases, "
                     + ("each answer checked at every case," if numbers else f"each through the {n} segments,"),
                     "pin the load's place (--at x_m=...), or join neighbouring segments of nearly the same "
                     "inclination")
    forward = Problem(sc)
    _needs_a_worst(forward, problem, cases)
    params = {**sc.parameters, **problem.inputs()}
    found = problem.evaluate(case_columns(cases, params))
    candidates = _candidates(found, find)
    k, governing = _choose(forward, problem, cases, params, candidates)
    values = {f: float(candidates[k][f]) for f in find}
    problem.solve({**values_of(cases[governing], params), **problem.given_values})    # validated there
    solved = sc.with_values(values, origin="solved for")
    result = EnvelopeResult(solved, solved.built, envelope(forward, cases, values), problem.given, find)
    result.values.update(problem.given_values)          # the given values as given (the worst agrees to 1e-6)
    result.governing = cases[governing]
    return result


def values_of(case: LoadCase, params: Mapping) -> dict:
    return {k: float(v) for k, v in case.values(params).items()}


def _needs_a_worst(forward: Problem, problem: Problem, cases: list[LoadCase]) -> None:
    """An :class:`InputError` for a given output that changes with the open case inputs and has no worst."""
    fun, q = forward.function, forward.model.quantities
    varied = [k for k in CASE_INPUTS if k in case_columns(cases, forward.scene.parameters)]
    depends = depends_on(fun, problem.given, varied, forward.model.derived)
    for g in problem.given:
        moves = list(depends[g])
        if moves and not q[g].worst:
            pins = " and ".join(f"--at {k}=..." for k in moves)
            raise InputError(f"--given {g}: {g} changes with {' and '.join(moves)} (left open: every place and "
                             f"manoeuvre) and has no worst case; give one point with {pins} "
                             f"(in Python, scene.with_values({{{', '.join(repr(k) + ': ...' for k in moves)}}}))")


def _candidates(found: dict, find: list[str]) -> list[dict]:
    n = len(next(iter(found.values())))
    out = []
    for i in range(n):
        cand = {f: float(found[f][i]) for f in find}
        if all(np.isfinite(v) for v in cand.values()):
            out.append(cand)
        else:
            out.append({})
    return out


#: the cases a "no solution" message lists (a long route has thousands)
SHOWN = 6


def _choose(forward: Problem, problem: Problem, cases, params, candidates) -> tuple[int, int]:
    """(candidate, governing case): the candidate at which every given output's worst over the cases is its
    given value, and the case where that worst is."""
    given, q = problem.given_values, forward.model.quantities
    failed: dict[int, str] = {}         # candidate -> why it is no answer (out of range; a slack rope at some case)
    for k, cand in enumerate(candidates):
        if not cand:
            continue
        outside = [f"{f} = {q[f].show(v)} is outside its valid range {q[f].range_text()}"
                   for f, v in cand.items() if not q[f].in_range(v)]
        if outside:
            failed[k] = "; ".join(outside)
            continue
        at = {**params, **cand}
        try:
            env = envelope(forward, cases, at)
        except (SolveError, InputError) as err:
            failed[k] = str(err)
            continue
        worst = {g: (env.worst(g) if g in env.extremes else None) for g in given}
        ok = all(abs((w.value if w else env.columns[g][0]) - given[g]) <= AGREE * max(1.0, abs(given[g]))
                 for g, w in worst.items())
        if ok:
            gov = [cases.index(w.case) for w in worst.values() if w is not None]
            return k, (gov[0] if gov else k)
    raise SolveError(_no_solution(forward, problem, cases, params, candidates, failed))


def _no_solution(forward: Problem, problem: Problem, cases, params, candidates, failed: dict[int, str]) -> str:
    """Why no candidate answers the question: each case's answer (the first few), and, where an answer does not
    hold (a found value outside its range, a rope slack at another case), the reason for one of them."""
    q = forward.model.quantities
    head = "; ".join(f"{g} = {q[g].show(v)}" for g, v in problem.given_values.items())
    found = [k for k, c in enumerate(candidates) if c]
    if not found:
        return f"no {', '.join(problem.find)} gives {head} at its worst over every place and manoeuvre (no case " \
               "has a solution)"

    def answer(k: int) -> str:
        return ", ".join(f"{f} = {q[f].show(v)}" for f, v in candidates[k].items())

    more = f", and {len(found) - SHOWN} more cases" if len(found) > SHOWN else ""
    shown = ", ".join(f"{cases[k].label(params)}: {answer(k)}" for k in found[:SHOWN]) + more
    why = "at none of them is it the worst)"
    if failed:
        k = next(iter(failed))
        why = (("none of them holds" if len(failed) == len(found) else
                f"{len(failed)} of them do not hold (at the others it is not the worst)")
               + f"), e.g. {answer(k)} ({cases[k].label(params)}'s answer): {failed[k]}")
    return f"no {', '.join(problem.find)} gives {head} at its worst over every place and manoeuvre (solved at " \
           f"each: {shown}; {why}"
