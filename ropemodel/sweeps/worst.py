"""A sweep at the worst case: each point's outputs at their worst over the load cases, and where.

Where a scene leaves the load's place (``x_m``) or the manoeuvre (``a_h``) open and the sweep does not vary
it, each point's outputs are their worst over every load case (:mod:`ropemodel.envelope`), reduced inside
the swept Function: the cases' places and accelerations follow the point's own parameters (a swept segment
length moves its joints).  For each output that depends on an open input, the columns ``<output>@x_m [m]``
and ``<output>@a_h [m/s^2]`` give the place and the acceleration of the case that governs it at that point
(the segment follows from x_m and the route; the manoeuvre from the sign of a_h: 0 steady, > 0 a start,
< 0 a stop).  Each case is checked against the physics (a slack rope) at every point.
"""

from __future__ import annotations

from collections import ChainMap
from dataclasses import dataclass, field

from ropemodel.envelope import CASE_INPUTS, LoadCase, free, load_cases
from ropemodel.envelope.cases import depends_on, distinct, joint_ends
from ropemodel.envelope.cases import reads as case_reads
from ropemodel.envelope.worst import pick, symbolic_worst
from ropemodel.errors import InputError
from ropemodel.sweeps.chunk import RouteStep

#: the unit of each case input's column (SI and display alike)
UNITS = {"x_m": "m", "a_h": "m/s^2"}


#: what a long route's numbers are computed from besides its segments (and the ramps, :func:`case_reads`)
ROUTE_READS = ("mu_pl", "x_m", "a_h", "L_ul")


@dataclass
class Worst:
    """The load cases of a sweep and, per output, the open case inputs it depends on."""

    cases: list[LoadCase]
    depends: dict[str, tuple[str, ...]]
    #: a long route's numbers at each case (:meth:`ropemodel.problem.Problem.case_numbers`), and the places' x_m
    numbers: dict = field(default_factory=dict)
    ends: list | None = None
    #: the sweep varies what a long route's numbers are computed from: each point and case has its own
    #: (:mod:`ropemodel.sweeps.per_case`), not ``numbers``
    follows: bool = False

    def where_columns(self, outputs) -> list[tuple[str, str]]:
        """(column name, case input): ``F_C_up@x_m`` for each output that depends on an open input."""
        return [(f"{o}@{k}", k) for o in outputs for k in self.depends.get(o, ())]


def plan(scene, problem, varied, find, outputs) -> tuple[Worst | None, list[str] | None]:
    """The sweep's load cases (None at a single point) and its outputs (by default every output that has a
    value at the worst case; one named that varies with an open input and has no worst is refused)."""
    pinned = set(varied) | set(find)
    cases = load_cases(scene, pinned=pinned)
    if len(cases) == 1:
        return None, outputs
    open_ = [k for k in free(scene) if k not in pinned]
    if problem.given:
        raise InputError(f"an inverse sweep is solved at one place and manoeuvre: give {' and '.join(open_)} "
                         f"(--set, or vary it)")
    depends = depends_on(problem.function, problem.unknowns, open_, problem.model.derived)
    q = problem.model.quantities
    no_worst = [o for o in problem.unknowns if depends[o] and not q[o].worst]
    ends = joint_ends(scene.parameters) if problem.model.derived else None
    follows = bool(problem.model.derived) and bool(set(varied) & {*problem.model.edges, *ROUTE_READS,
                                                                   *case_reads(scene)})
    worst = Worst(cases, depends, {} if follows else problem.case_numbers(cases, ends), ends, follows)
    if outputs is None:
        return worst, [o for o in problem.unknowns if o not in no_worst]
    bad = [o for o in ([outputs] if isinstance(outputs, str) else outputs) if o in no_worst]
    if bad:
        raise InputError(f"{', '.join(bad)} change with {' and '.join(open_)} and have no worst case: give one "
                         f"point (--set {open_[0]}=..., or vary it)")
    return worst, outputs


def route_step(problem, varied, base: dict, worst: Worst | None) -> RouteStep | None:
    """A long route's numbers computed at each point, where the sweep varies what they are computed from at one
    load case (the route's segments, mu_pl, the load's place or acceleration, L_ul); None otherwise (they are
    then the base's constants, or each case's: :func:`columns`)."""
    model = problem.model
    if not model.derived or worst is not None or not set(varied) & {*model.edge_set, *ROUTE_READS}:
        return None
    values = {**problem.scene.parameters, **{k: v for k, v in base.items() if k not in model.derived}}
    return RouteStep(model, values, [k for k in problem.knowns if k in model.derived])


def route_edges(problem, varied) -> dict:
    """The quantities of the segments of a long route among ``varied`` (swept by name)."""
    model = problem.model
    return {k: model.quantities[k] for k in varied if k in model.edge_set}


def columns(worst: Worst, fun, args: dict, base: dict, outputs, quantities) -> tuple[list[str], list, list]:
    """(names, expressions, cases): each output at its worst over the cases and its where columns, then
    (case name, every output at that case) for the physics checks of each case.  ``args``: the swept
    Function's inputs (symbols, or expressions of them), ``base`` the numbers of the others."""
    values = ChainMap(args, base)
    at: dict[int, dict] = {}

    def result(i: int) -> dict:
        if i not in at:
            case = {**worst.cases[i].values(values, worst.ends), **worst.numbers.get(worst.cases[i], {})}
            at[i] = fun.call({**args, **{k: v for k, v in case.items() if k in args}})
        return at[i]

    names, exprs = [], []
    for o in outputs:
        deps = worst.depends.get(o, ())
        idx = distinct(worst.cases, deps)
        if not deps:
            names.append(o)
            exprs.append(result(idx[0])[o])
            continue
        value, k = symbolic_worst([result(i)[o] for i in idx], quantities[o].worst)
        names.append(o)
        exprs.append(value)
        for inp in deps:
            names.append(f"{o}@{inp}")
            exprs.append(pick(k, [worst.cases[i].values(values, worst.ends)[inp] for i in idx]))
    return names, exprs, [(worst.cases[i].name(), result(i)) for i in range(len(worst.cases))]


def watches(per_case, physics, problem, outputs, single: bool, names: list, outs: list) -> list:
    """What the physics checks of each case read (:class:`~ropemodel.sweeps.chunk.ChunkJob`'s ``watch``): per
    case (its name, ``""`` at a single point), each quantity the ``physics`` submodels need → the input or
    output holding it; a needed output that is not swept as it is (or is swept at its worst) is added to
    ``names`` and ``outs`` as ``watch_NAME_k``."""
    needed = list(dict.fromkeys(n for sm in physics for n in sm.invalid_needs_for(outputs)))
    out = []
    for k, (case, res) in enumerate(per_case):
        looks = {}
        for name in needed:
            if name in problem.knowns or (name in outputs and single):
                looks[name] = name
            elif name in problem.unknowns:
                looks[name] = f"watch_{name}_{k}"
                names.append(looks[name])
                outs.append(res[name])
        out.append((case, looks))
    return out


__all__ = ["CASE_INPUTS", "UNITS", "Worst", "columns", "plan", "watches"]
