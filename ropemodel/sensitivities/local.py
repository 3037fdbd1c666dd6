"""Local sensitivities: elasticities ∂ln y/∂ln p of every output to every input, by AD.

The elasticity ``e = (p / y) ∂y/∂p`` is the percentage change of an output per
percent change of an input, so quantities of any unit compare on one scale
(a tornado chart).  The derivative comes from the CasADi Jacobian of the
problem's compiled Function — exact, through explicit blocks and through
Newton blocks alike (implicit function theorem) — never from differences.

On a route without ``x_m`` (or with the ramps' inertia and no ``a_h``) each output is its worst over the
load cases (:mod:`ropemodel.envelope`), and its elasticities are those of that worst: the derivatives at the
case that governs it (where the worst is unique, the derivative of the worst is the governing case's), the
case's place and acceleration moving with the parameters they come from (the segments' lengths, v_pj,
t_ramp, a_e).  Each row names that case (``where``).

Zeros: where ``y = 0`` (or ``y`` is zero up to rounding, i.e. ``|y|`` below
``1e-12`` times the sum of the terms ``|∂y/∂p_j · p_j|`` that make it up) or
``p = 0``, the elasticity is undefined.  It is then reported as missing with
``defined = False`` and a ``note`` saying why, and the plain derivative
``dy_dp`` (display units of y per display unit of p) is always given — no NaN
appears without a reason next to it.  A term ``|∂y/∂p · p|`` below ``1e-12``
times that sum is rounding of an exact cancellation and reported as 0.
"""

from __future__ import annotations

import math
from collections import ChainMap
from collections.abc import Mapping, Sequence
from typing import Any

import casadi as ca
import numpy as np
import pandas as pd

from ropemodel.envelope import envelope, free, load_cases, with_ramps
from ropemodel.errors import InputError, SolveError
from ropemodel.problem import Problem
from ropemodel.scene import SceneLike, as_scene
from ropemodel.units import label


ZERO_RTOL = 1e-12


def jacobian(problem: Problem, values: Mapping | None = None, parameters=None, outputs=None, case=None):
    """(y, J, x): outputs, ∂outputs/∂parameters (SI) and the parameter values at one point; ``case`` (a
    :class:`~ropemodel.envelope.LoadCase`) sets the load's place and acceleration from the parameters."""
    fun = problem.function
    x = problem.inputs(values)
    parameters = list(problem.user_knowns) if parameters is None else list(parameters)
    outputs = list(problem.unknowns) if outputs is None else list(outputs)
    for p in parameters:
        if p not in problem.user_knowns and p not in problem.model.edge_set:
            raise InputError(f"parameter {p!r} is not an input of this problem; inputs: "
                             f"{', '.join(problem.user_knowns)}")
    for o in outputs:
        if o not in problem.unknowns:
            raise InputError(f"output {o!r} is not a result of this problem; results: {', '.join(problem.unknowns)}")
    P = ca.MX.sym("p", len(parameters))
    args = {k: ca.MX(x[k]) for k in problem.knowns}
    args.update({k: P[i] for i, k in enumerate(parameters) if k not in problem.model.edge_set})
    edges = {k: P[i] for i, k in enumerate(parameters) if k in problem.model.edge_set}     # a long route's segments
    ruled = problem.scene.ruled()      # a factor a rule gives follows its length, plus its own change
    for k, v in problem.scene.rule_values(args, [p for p in parameters if p not in ruled]).items():
        args[k] = v + (args[k] - x[k])
    numbers = dict(x)
    if case is not None:
        given: ChainMap[str, Any] = ChainMap(edges, args, problem.scene.parameters)
        args.update({k: ca.MX(v) if isinstance(v, float) else v for k, v in case.values(given).items()})
        numbers.update(case.values(ChainMap(x, problem.scene.parameters)))
    if problem.model.derived:       # a long route's numbers at the point, through the segments' values varied
        at = problem.model.derive_through({**problem.scene.parameters, **numbers}, edges)
        args.update({k: v for k, v in at.items() if k in args})
    res = fun.call(args)
    Y = ca.vertcat(*[res[o] for o in outputs])
    f = ca.Function("elasticity_jacobian", [P], [Y, ca.jacobian(Y, P)])
    p0 = np.array([x[k] if k in x else problem.scene.parameters[k] for k in parameters], dtype=float)
    y, J = (np.asarray(a, dtype=float) for a in f(p0))
    y = y.ravel()
    J = J.reshape(len(outputs), len(parameters))
    bad = [outputs[i] for i in range(len(outputs)) if not (np.isfinite(y[i]) and np.isfinite(J[i]).all())]
    if bad:
        raise SolveError(f"no finite value or derivative for {', '.join(bad)} at this point")
    return y, J, dict(zip(parameters, p0)), outputs


def elasticities(scene: SceneLike, values: Mapping | None = None, outputs: Sequence[str] | None = None,
                 parameters: Sequence[str] | None = None, given: Mapping | Sequence[str] = (),
                 find: Sequence[str] = ()) -> pd.DataFrame:
    """Local sensitivities: elasticities ∂ln y/∂ln p of a scene's outputs, exact (CasADi's Jacobian).

    Parameters
    ----------
    scene : Scene or str or Path
        The scene (:func:`ropemodel.load_scene`).
        A TOML scene file or a built-in scene's name is loaded first (:func:`ropemodel.load_scene`).
    values : dict, optional
        Inputs that override the scene's, ``{name: value}`` (SI floats, strings with units or
        pint Quantities).
    outputs : list of str, optional
        Outputs y (default: every unknown of the problem).
    parameters : list of str, optional
        Inputs p (default: every input with a finite value; an unlimited one, such as a stroke not
        given, has no elasticity).
    given, find : dict and list of str, optional
        An inverse problem, as in :func:`ropemodel.solve`: ``find`` parameters become unknowns and
        the ``given`` outputs inputs.

    Returns
    -------
    pandas.DataFrame
        One row per (output, parameter): ``output``, ``parameter``, ``y`` [y_unit], ``y_unit``,
        ``p`` [p_unit], ``p_unit`` (display units: kN, deg, mm, ...), ``dy_dp`` [y_unit/p_unit],
        ``elasticity`` [-] (% change of y per % change of p; missing where y = 0 or p = 0),
        ``defined`` (bool), ``note`` (why undefined) and ``where`` (the load case of the output's worst;
        empty at a single point).

    Raises
    ------
    InputError
        Unknown or misplaced names, bad values.
    SolveError
        The point has no solution, or an output or derivative is not finite there.

    Examples
    --------
    The winding rope's force (Krauze et al. 2025, eq. (12)) rises 0.79 % per % of the load:

    >>> import ropemodel as rm
    >>> e = rm.elasticities(rm.load_scene(), outputs=["F_C_up"], parameters=["G_m", "alpha_u", "mu_pm"])
    >>> e[["parameter", "y", "y_unit", "elasticity"]].round(4)
      parameter         y y_unit  elasticity
    0       G_m  190.9485     kN      0.7917
    1   alpha_u  190.9485     kN      0.7746
    2     mu_pm  190.9485     kN      0.1175
    """
    scene = as_scene(scene)
    values = dict(values or {})
    pinned = {k: values.pop(k) for k in list(values) if k in scene.built.parameters}
    scene = with_ramps(scene.with_values(pinned) if pinned else scene)
    problem = Problem(scene, given, find)
    open_ = [k for k in free(scene) if k not in find]
    if parameters is None:
        x = problem.inputs(values)
        parameters = [k for k in problem.user_knowns if math.isfinite(x[k]) and k not in open_]
    rows = []
    for case, outs, where in _governing(scene, problem, outputs, find):
        y, J, p, names = jacobian(problem, values, parameters, outs, case)
        rows += _rows(problem, y, J, p, names, where)
    return pd.DataFrame(rows)


def _governing(scene, problem: Problem, outputs, find):
    """[(case, outputs, where)]: the outputs grouped by the load case that governs their worst (one group, no
    case, at a single point)."""
    cases = load_cases(scene, pinned=find)
    if len(cases) == 1:
        return [(cases[0], outputs, {})]
    if problem.given:
        raise InputError(f"an inverse question's elasticities are taken at one point: give the load's place and "
                         f"the manoeuvre ({', '.join(free(scene))}) in values")
    env = envelope(Problem(scene), cases)
    if outputs is None:
        outputs = [o for o in problem.unknowns if o not in env.no_worst]
    bad = [o for o in outputs if o in env.no_worst]
    if bad:
        raise InputError(f"{', '.join(bad)} change with the load's place or the manoeuvre and have no worst case: "
                         f"give one point, values={{{', '.join(repr(k) + ': ...' for k in free(scene))}}} "
                         f"(--at on the command line)")
    groups: dict[int, list[str]] = {}
    for o in outputs:
        i = cases.index(env.worst(o).case) if o in env.extremes else 0
        groups.setdefault(i, []).append(o)
    where = env.where()
    return [(cases[i], outs, {o: where.get(o, "the same in every case") for o in outs}) for i, outs in groups.items()]


def _rows(problem: Problem, y, J, p, outputs, where) -> list[dict]:
    q = problem.model.quantities
    names = list(p)
    pv = np.array([p[k] for k in names])
    rows = []
    for i, o in enumerate(outputs):
        contributions = np.abs(J[i] * pv).sum()
        y_zero = y[i] == 0.0 or abs(y[i]) <= ZERO_RTOL * contributions
        fy = float(q[o].to_display(1.0))
        for j, k in enumerate(names):
            fp = float(q[k].to_display(1.0))
            if y_zero:
                e, note = math.nan, "undefined: y = 0"
            elif pv[j] == 0.0:
                e, note = math.nan, "undefined: p = 0"
            else:
                e, note = float(J[i, j] * pv[j] / y[i]), ""
                if abs(J[i, j] * pv[j]) <= ZERO_RTOL * contributions:
                    e = 0.0  # terms that cancel exactly (e.g. equal resistances of both ropes): rounding of 0
            rows.append({"output": o, "parameter": k, "y": y[i] * fy, "y_unit": q[o].display_unit,
                         "p": pv[j] * fp, "p_unit": q[k].display_unit, "dy_dp": float(J[i, j] * fy / fp),
                         "elasticity": e, "defined": not note, "note": note, "where": where.get(o, "")})
    return rows


def matrix(frame: pd.DataFrame) -> pd.DataFrame:
    """Outputs × parameters table of elasticities (labels with units)."""
    lab_o = {o: label(o, u) for o, u in zip(frame["output"], frame["y_unit"])}
    m = frame.pivot(index="output", columns="parameter", values="elasticity")
    m = m.loc[list(dict.fromkeys(frame["output"])), list(dict.fromkeys(frame["parameter"]))]
    m.index = [lab_o[o] for o in m.index]
    return m


def table(frame: pd.DataFrame, width: int = 10) -> str:
    """Text table: rows outputs, columns parameters; undefined cells say why."""
    params = list(dict.fromkeys(frame["parameter"]))
    width = max(width, 1 + max(len(p) for p in params))  # ".3g" takes up to 9 characters
    outs = list(dict.fromkeys(frame["output"]))
    cell = {(r.output, r.parameter): r for r in frame.itertuples()}
    head = f"{'d ln y / d ln p':<22}" + "".join(f"{p:>{width}}" for p in params)
    lines = [head]
    for o in outs:
        r0 = cell[(o, params[0])]
        text = f"{label(o, str(r0.y_unit)):<22}"
        for p in params:
            r = cell[(o, p)]
            why = "y=0" if "y = 0" in str(r.note) else "p=0"
            text += f"{r.elasticity:>{width}.3g}" if r.defined else f"{why:>{width}}"
        lines.append(text)
    where = dict(zip(frame["output"], frame["where"])) if "where" in frame else {}
    if any(where.values()):
        lines += ["", "each output at its worst, the elasticities there:"]
        lines += [f"  {o}: {where[o]}" for o in outs if where.get(o)]
    notes = frame.loc[~frame["defined"], ["output", "parameter", "dy_dp", "y_unit", "p_unit", "note"]]
    if len(notes):
        lines += ["", "undefined elasticities (y = 0 or p = 0): derivative dy/dp instead"]
        for r in notes.itertuples():
            if r.dy_dp != 0.0:
                lines.append(f"  d{r.output}/d{r.parameter} = {r.dy_dp:.6g} {r.y_unit}/{r.p_unit}   ({r.note})")
        zero = int((notes["dy_dp"] == 0.0).sum())
        if zero:
            lines.append(f"  ({zero} more with dy/dp = 0)")
    return "\n".join(lines)
