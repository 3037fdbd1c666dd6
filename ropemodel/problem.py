"""A question put to a scene: which quantities are given, which are found.

:class:`Problem` compiles the scene's equations once for a choice of unknowns
(by default the model's outputs; ``given`` outputs replace the parameters named
in ``find``) and evaluates it for one point (:meth:`Problem.solve`) or for many
(:meth:`Problem.evaluate`).  Solving is kept apart from the equations
(:mod:`ropemodel.papers`) and from the wiring of effects (:mod:`ropemodel.effects`).

A solution is returned only when it is a valid one: finite, inside the valid
ranges and rules, reproducing every given value, and inside the physics (a rope
that would have to push is slack, not a negative force).  Otherwise
:class:`~ropemodel.errors.SolveError` says why in the user's terms, e.g. the
range a given output can reach at all.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ropemodel.core.compile import forward_of, solver_of, structure_of
from ropemodel.core.evaluate import evaluate_columns
from ropemodel.errors import InputError, Problems, SolveError
from ropemodel.result import Result
from ropemodel.scene import SceneLike, as_scene


class Problem:
    """The scene's equations compiled for ``find`` unknowns given ``given`` values.

    Parameters
    ----------
    scene : Scene or str or Path
        The validated scene; its parameter values are the defaults of every evaluation.  A TOML scene
        file or a built-in scene's name is loaded first (:func:`ropemodel.load_scene`).
    given : dict or sequence of str
        Outputs whose values are given.  As a dict, name → value: a string with a unit
        (``"1000 mm"``), a pint Quantity, or a number (SI with ``bare="si"``, the default of the
        Python API; refused for a dimensional quantity with ``bare="refuse"``, the command line's).
    find : sequence of str
        Parameters to solve for, one per given output.
    bare : {"si", "refuse"}
        How a number without a unit is read (see above).

    Attributes
    ----------
    function : casadi.Function
        One named input per known and one named output per unknown (SI).
    knowns, unknowns : list of str
        The inputs and outputs of ``function``.

    Raises
    ------
    InputError
        Unknown names, a ``find`` that is not a parameter, a ``given`` that is not an output, an
        ill-posed choice (:class:`~ropemodel.errors.IllPosedError` names the variables), listed at once.
    """

    def __init__(self, scene: SceneLike, given=(), find=(), bare: str = "si"):
        self.scene = scene = as_scene(scene)
        model = self.model = scene.built
        given_values = dict(given) if isinstance(given, dict) else {}
        given, find = list(given), list(find)
        found = Problems()
        for n in given:
            problem = model.name_problem(n, "given quantity")
            if problem is None and n not in model.outputs:
                problem = f"--given {n}: {n} is a parameter of this scene; set it with --set {n}=..."
            if problem:
                found.add(problem)
        for n in find:
            problem = model.name_problem(n, "unknown to find")
            if problem is None and n in model.edge_set:
                problem = (f"--find {n}: a route of {len(scene.route)} segments is held as route numbers per load "
                           f"case, so a segment's own value cannot be solved for; sweep it (or --set it) and read the "
                           f"output, or join segments to at most 100")
            elif problem is None and n not in model.parameters:
                problem = f"--find {n}: {n} is computed by this scene anyway; --find takes a parameter"
            if problem:
                found.add(problem)
        for names, what in ((given, "--given"), (find, "--find")):
            for n in {n for n in names if names.count(n) > 1}:
                found.add(f"{what} {n} is named twice")
        self.given_values = {}
        for n, v in given_values.items():
            if n in model.outputs:
                with found.collect():
                    self.given_values[n] = model.quantities[n].to_si(v, bare)
        for n in find:
            held = scene.ruled_by(n)
            if held:
                found.add(f"--find {n}: {n} sets {', '.join(held)} through the scene's rule set "
                          f"({'; '.join(scene.basis(p) for p in held)}); an inverse solve holds every other "
                          f"parameter, so {', '.join(held)} would stay at its value for this scene's {n}: override "
                          f"it in [rules] with its reason to solve with it fixed, or sweep {n} instead")
        found.raise_if_any()
        self.given, self.find = given, find
        self.unknowns = [o for o in model.outputs if o not in given] + find
        self.knowns = [p for p in model.arguments if p not in find] + given
        self.structure = structure_of(model, self.unknowns, self.knowns)
        guesses = {n: scene.parameters[n] for n in find if n in scene.parameters}
        self.function = solver_of(model, self.structure, guesses)

    def inputs(self, values: Mapping | None = None) -> dict[str, float]:
        """SI values of every known: the scene's parameters, then ``given`` values, then ``values``."""
        # floats; an array given in ``values`` passes through as it is
        out: dict[str, Any] = {k: self.scene.parameters[k] for k in self.knowns if k in self.scene.parameters}
        out.update(self.given_values)
        knowns, model, edges = set(self.knowns), self.model, {}
        for k, v in (values or {}).items():
            if k in model.edge_set:         # a segment of a route held as route numbers
                edges[k] = v if isinstance(v, np.ndarray) else model.quantities[k].to_si(v, "si")
                continue
            if k in model.derived:          # computed again from the segments below
                continue
            if k not in knowns:
                raise InputError(f"{k} is not an input of this problem; inputs: {', '.join(self.user_knowns)}")
            out[k] = v if isinstance(v, np.ndarray) else model.quantities[k].to_si(v, "si")
        if model.derived:
            out.update({k: v for k, v in self.derived({**out, **edges}).items() if k in knowns})
        missing = [k for k in self.knowns if k not in out]
        if missing:
            raise InputError(f"no value given for {', '.join(missing)}")
        out.update(self.scene.rule_values(out, values or {}))   # a rule's length changed: its factor follows
        return out

    @property
    def user_knowns(self) -> list[str]:
        """The knowns a user gives (not a long route's numbers, which follow from its segments)."""
        return [k for k in self.knowns if k not in self.model.derived]

    def derived(self, values: Mapping) -> dict:
        """A long route's numbers (:meth:`ropemodel.core.model.Model.derive`) at the scene's values with ``values``
        on top (SI; segments by name among them; numpy arrays over points allowed, a segment's too)."""
        merged = {**self.scene.parameters, **values}
        segments = [k for k in values if k in self.model.edge_set and np.ndim(values[k])]
        if not segments:
            return self.model.derive(merged)
        n = max(np.size(values[k]) for k in values if np.ndim(values[k]))
        rows = [self.model.derive({k: np.broadcast_to(v, (n,))[i] if np.ndim(v) else v for k, v in merged.items()})
                for i in range(n)]                     # a segment that varies: the route's numbers point by point
        return {k: np.array([r[k] for r in rows]) for k in rows[0]}

    def case_numbers(self, cases, ends=None, values: Mapping | None = None) -> dict:
        """A long route's numbers (:meth:`derived`) at each of ``cases`` (:class:`~ropemodel.envelope.LoadCase`,
        at the scene's values with SI ``values`` on top (segments by name among them), the case's place and
        acceleration; ``ends`` the places' x_m there, :func:`ropemodel.envelope.cases.joint_ends`), all at once:
        case -> {name: float}; {} for a model without."""
        if not self.model.derived or not cases:
            return {}
        values = dict(values or {})
        params = {**self.scene.parameters, **values}
        rows = [c.values(params, ends) for c in cases]
        columns = {k: np.array([float(r.get(k, params.get(k, 0.0))) for r in rows]) for k in ("x_m", "a_h")
                   if k in params}
        numbers = self.derived({**values, **columns})
        return {c: {k: float(np.broadcast_to(v, (len(cases),))[i]) for k, v in numbers.items()}
                for i, c in enumerate(cases)}

    def solve(self, values: Mapping | None = None) -> Result:
        """Solve for one point; ``values`` override scene parameters or given outputs (SI or with units).

        Returns
        -------
        Result
            Every known and solved quantity (SI).

        Raises
        ------
        InputError
            An input outside its valid range or rules.
        SolveError
            No valid solution: the message says why (e.g. the range a given output can reach).
        """
        x = self.inputs(values)
        self.model.validate({k: v for k, v in x.items() if k in self.model.parameters})
        sol = {k: float(v) for k, v in self.function(**x).items()}
        bad = [k for k, v in sol.items() if not (math.isfinite(v) or self._unlimited(k, v, x))]
        if bad and self.find:
            raise SolveError(self._explain(x, f"no finite solution for {', '.join(sorted(bad))}"))
        if bad:
            raise SolveError(f"no finite value for {', '.join(sorted(bad))} at these inputs (a division by zero "
                             f"or an overflow in the equations)")
        values_all = {**x, **sol}
        if self.find:
            self._check_found(x, values_all)
        for sm in self.model.submodels:
            for why in sm.invalid(values_all):
                raise SolveError(why)
        edges = {k: self.scene.parameters[k] for k in self.model.edges if k in self.scene.parameters}
        edges.update({k: self.model.quantities[k].to_si(v, "si") for k, v in (values or {}).items()
                      if k in self.model.edge_set})
        shown = {**edges, **{k: v for k, v in values_all.items() if k not in self.model.derived}}
        return Result(self.scene, self.model, shown, self.given, self.find)

    def evaluate(self, columns: dict[str, np.ndarray], parallel: int = 1, outputs=None) -> dict[str, np.ndarray]:
        """Vectorised solve: arrays of SI inputs (missing ones from the scene) → arrays of unknowns (every one,
        or only ``outputs``).

        Evaluated in chunks by :func:`ropemodel.core.evaluate.evaluate_columns` (``Function.map``, or
        the same Function compiled to C; ``parallel`` threads), so memory stays bounded and the
        Function is compiled once per process.  No range check is made here; callers validate their
        inputs (see :mod:`ropemodel.sweeps`).
        """
        n = max((np.size(v) for v in columns.values()), default=1)
        base = self.inputs({k: v for k, v in columns.items() if not isinstance(v, np.ndarray)})
        arrays = {k: np.broadcast_to(np.asarray(columns[k], dtype=float), (n,)) for k in self.knowns
                  if isinstance(columns.get(k), np.ndarray)}
        varied = {k: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for k, v in columns.items()
                  if isinstance(v, np.ndarray)}       # a case input need not be the Function's (x_m without checks)
        if self.model.derived and varied:       # a long route: its numbers at every point
            numbers = self.derived({**base, **varied, **arrays})
            arrays.update({k: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for k, v in numbers.items()
                           if np.ndim(v) and k in set(self.knowns)})
            base.update({k: v for k, v in numbers.items() if not np.ndim(v)})
        arrays.update({k: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for k, v in
                       self.scene.rule_values({**base, **arrays}, arrays).items()})
        constants = {k: base[k] for k in self.knowns if k not in arrays}
        out = evaluate_columns(self.function, arrays, constants, threads=parallel, outputs=outputs)
        return {u: out[u] for u in (self.unknowns if outputs is None else outputs)}

    def _unlimited(self, name: str, value: float, x: dict) -> bool:
        """An infinite output is allowed where it follows from an unlimited input (e.g. no stroke given)."""
        if value != math.inf:
            return False
        q = self.model.quantities
        fun = self.function
        j = fun.index_out(name)
        return any(q[k].unlimited and x[k] == math.inf and fun.sparsity_jac(fun.index_in(k), j).nnz() > 0
                   for k in self.knowns if k in q)

    def _check_found(self, x: dict, values_all: dict) -> None:
        """Found parameters in range and rules; the forward model reproduces each given value."""
        for n in self.find:
            q = self.model.quantities[n]
            if not q.in_range(values_all[n]):
                raise SolveError(self._explain(x, f"the solution {n} = {q.show(values_all[n])} is outside its valid "
                                                  f"range {q.range_text()}"))
        out = forward_of(self.model)(**{k: values_all[k] for k in self.model.arguments})
        for n in self.given:
            got, want = float(out[n]), values_all[n]
            if not abs(got - want) <= 1e-6 * max(1.0, abs(want)):
                raise SolveError(self._explain(x, f"the solver stopped where {n} = "
                                                  f"{self.model.quantities[n].show(got)}"))
        broken = self.model.problems({k: values_all[k] for k in self.model.parameters})
        if broken:
            raise SolveError(f"no valid solution: the solution breaks a rule: {'; '.join(broken)}")

    def _explain(self, x: dict, what: str) -> str:
        """Why an inverse question has no answer, in the user's terms (see :func:`reach`)."""
        q = self.model.quantities
        head = "; ".join(f"{g} = {q[g].show(x[g])}" for g in self.given)
        if len(self.find) != 1 or len(self.given) != 1:
            return f"no {', '.join(self.find)} gives {head} ({what})"
        f, g = self.find[0], self.given[0]
        lo, hi, swept = reach(self.model, {k: v for k, v in x.items() if k in self.model.arguments}, f, g)
        if lo is None:
            return f"no {f} gives {head}: {g} has no finite value over the valid range of {f} ({what})"
        over = (f"for {f} in {q[f].range_text()}" if swept is None else
                f"for {f} from {q[f].show(swept[0])} to {q[f].show(swept[1])} (its valid range here)")
        span = (f"{over}, {g} stays within [{q[g].show(lo[0])}, {q[g].show(hi[0])}] "
                f"({_at(q, f, g, lo)}; {_at(q, f, g, hi)})")
        if lo[0] <= x[g] <= hi[0]:
            return (f"no {f} found for {head} ({what}); {span}: the value is within reach, so try another "
                    f"starting value of {f} (--set {f}=...)")
        return f"{g} = {q[g].show(x[g])} is out of reach: {span}"


def _at(q, f: str, g: str, extreme) -> str:
    value, where, limit = extreme
    return f"{q[g].show(value)} " + (f"as {f} -> {limit}" if limit else f"at {f} = {q[f].show(where)}")


def reach(model, params: dict, find: str, given: str, n: int = 401):
    """Least and largest value of output ``given`` as parameter ``find`` sweeps its valid range.

    The other parameters are held at ``params`` (SI).  Returns two triples (value, where, limit) for
    the least and the largest value: ``where`` the value of ``find`` there, ``limit`` a text such as
    ``"0"`` or ``"inf"`` when the extreme is approached at an open or infinite end of the range (else
    None); then the (least, largest) value of ``find`` swept when the scene's rules narrowed its range
    (else None).  (None, None, None) when ``given`` is nowhere finite.  A positive quantity without an upper
    bound is swept on a log scale over twelve decades either side of its guess.
    """
    q = model.quantities[find]
    g = abs(q.guess) or 1.0
    if q.low >= 0 and not math.isfinite(q.high):
        grid = np.concatenate([[q.low] if not q.low_open else [], g * np.logspace(-12, 12, n)])
        ends: tuple[str | None, str | None] = (_fmt_limit(q.low) if q.low_open else None, "inf")
    else:
        lo = q.low if math.isfinite(q.low) else -1e12 * g
        hi = q.high if math.isfinite(q.high) else 1e12 * g
        eps = 1e-9 * (hi - lo)
        grid = np.linspace(lo + (eps if q.low_open else 0.0), hi - (eps if q.high_open else 0.0), n)
        ends = (_fmt_limit(q.low) if q.low_open or not math.isfinite(q.low) else None,
                _fmt_limit(q.high) if q.high_open or not math.isfinite(q.high) else None)
    valid = np.array([not model.problems({**params, find: float(v)}) for v in grid])
    if not valid.any():
        return None, None, None
    kept = grid[valid]
    swept = None
    if not valid.all():   # the edges of the rules' interval, to rounding (bisection between grid points)
        i, j = int(np.argmax(valid)), len(grid) - 1 - int(np.argmax(valid[::-1]))
        ok = lambda v: not model.problems({**params, find: float(v)})  # noqa: E731
        swept = (_edge(ok, grid[i], grid[i - 1]) if i > 0 else float(grid[i]),
                 _edge(ok, grid[j], grid[j + 1]) if j < len(grid) - 1 else float(grid[j]))
    if swept is not None:   # a rule (e.g. L_ul <= L_u) bounds the range: sweep that interval evenly
        kept = np.linspace(swept[0], swept[1], n)
        ends = (None, None)
    grid = kept
    fun = forward_of(model)
    args = [grid if k == find else np.full_like(grid, params[k]) for k in fun.name_in()]
    with np.errstate(all="ignore"):
        y = np.asarray(fun.map(len(grid))(*[a.reshape(1, -1) for a in args])[fun.index_out(given)]).ravel()
    ok = np.isfinite(y)
    if not ok.any():
        return None, None, None

    def extreme(i):
        limit = ends[0] if i == 0 else ends[1] if i == len(grid) - 1 else None
        return float(y[i]), float(grid[i]), limit

    return (extreme(int(np.argmin(np.where(ok, y, np.inf)))), extreme(int(np.argmax(np.where(ok, y, -np.inf)))),
            swept)


def _edge(ok, inside: float, outside: float) -> float:
    """The last value on the way from ``inside`` to ``outside`` where ``ok`` holds (bisection)."""
    for _ in range(80):
        mid = 0.5 * (inside + outside)
        if ok(mid):
            inside = mid
        else:
            outside = mid
    return float(inside)


def _fmt_limit(x: float) -> str:
    return "inf" if x == math.inf else "-inf" if x == -math.inf else f"{x:g}"


def run(scene: SceneLike, values: Mapping | None = None) -> Result:
    """Forward solve at one point: every output of the scene from its parameters, the load's place and the
    acceleration as the scene gives them (``x_m`` not given: on the last segment; ``a_h``: steady motion).
    ``values`` override parameters (SI numbers, strings with units, pint Quantities).  ``ropemodel run`` and
    :func:`ropemodel.run` take each output at its worst instead (:func:`ropemodel.envelope.run`, with the
    parameters, returns and errors documented there).

    Examples
    --------
    >>> from ropemodel.scene import load
    >>> round(run(load())["F_C_up"] / 1e3, 2)          # kN, Krauze et al. (2025) Fig. 9 prints 190.95
    190.95
    """
    return Problem(scene).solve(values)


def solve(scene: SceneLike, given: Mapping, find: Sequence[str] | str, bare: str = "si") -> Result:
    """Inverse solve at one point: ``given`` outputs (name → value) in place of the ``find`` parameters, the load's
    place and the acceleration as the scene gives them.  ``ropemodel solve`` and :func:`ropemodel.solve` meet
    the given outputs at their worst (:func:`ropemodel.envelope.solve`, where the arguments are documented).

    Examples
    --------
    >>> from ropemodel.scene import load
    >>> round(solve(load(), given={"dF_up": "1000 mm"}, find=["G_m"])["G_m"] / 1e3, 3)   # kN
    252.383
    """
    if isinstance(find, str):
        find = [find]
    return Problem(scene, given, find, bare=bare).solve()


__all__ = ["Problem", "reach", "run", "solve"]
