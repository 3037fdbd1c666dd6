"""A question put to a scene: which quantities are given, which are found.

:class:`Problem` compiles the scene's equations once for a choice of unknowns
(by default the model's outputs; ``given`` outputs replace the parameters named
in ``find``) and evaluates it for one point or for many (CasADi ``map``).
Solving is kept apart from the equations (:mod:`ropemodel.papers`) and from the
wiring of effects (:mod:`ropemodel.effects`).
"""

from __future__ import annotations

from functools import lru_cache

import casadi as ca
import numpy as np

from ropemodel.core import analyse, compile_solver
from ropemodel.core.evaluate import evaluate_columns
from ropemodel.errors import InputError, SolveError
from ropemodel.result import Result
from ropemodel.scene import Scene
from ropemodel.units import to_si


class Problem:
    """The scene's equations compiled for ``find`` unknowns given ``given`` values.

    Parameters
    ----------
    scene: the validated scene (its parameter values are the defaults of every evaluation).
    given: names of outputs whose values are given (values may be passed here as a dict).
    find: parameters to solve for, one per given output.

    Attributes
    ----------
    function: ``ca.Function`` with one named input per known and one named output per unknown.
    """

    def __init__(self, scene: Scene, given=(), find=()):
        self.scene = scene
        model = self.model = scene.built
        given_values = dict(given) if isinstance(given, dict) else {}
        given = list(given)
        find = list(find)
        model.check_names(given, "given quantity")
        model.check_names(find, "unknown to find")
        for n in given:
            if n not in model.outputs:
                raise InputError(f"--given {n}: {n} is a parameter of this scene; set it with --set {n}=...")
        for n in find:
            if n not in model.parameters:
                raise InputError(f"--find {n}: {n} is computed by this scene anyway; --find takes a parameter")
        self.given, self.find = given, find
        self.unknowns = [o for o in model.outputs if o not in given] + find
        self.knowns = [p for p in model.parameters if p not in find] + given
        self.structure = analyse(model, self.unknowns, self.knowns)
        guesses = {n: scene.parameters[n] for n in find}
        self.function = _compiled(scene, self.structure, tuple(sorted(guesses.items())))
        self.given_values = {n: to_si(n, v, model.quantities[n].unit) for n, v in given_values.items()}

    def inputs(self, values: dict | None = None) -> dict[str, float]:
        """SI values of every known: the scene's parameters, then ``given`` values, then ``values``."""
        out = {k: self.scene.parameters[k] for k in self.knowns if k in self.scene.parameters}
        out.update(self.given_values)
        for k, v in (values or {}).items():
            if k not in self.knowns:
                raise InputError(f"{k} is not an input of this problem; inputs: {', '.join(self.knowns)}")
            out[k] = to_si(k, v, self.model.quantities[k].unit) if not isinstance(v, np.ndarray) else v
        missing = [k for k in self.knowns if k not in out]
        if missing:
            raise InputError(f"no value given for {', '.join(missing)}")
        return out

    def solve(self, values: dict | None = None) -> Result:
        """Solve for one point; ``values`` override scene parameters or given outputs."""
        x = self.inputs(values)
        self.model.validate({k: v for k, v in x.items() if k in self.model.parameters})
        out = self.function(**x)
        sol = {k: float(v) for k, v in out.items()}
        bad = [k for k, v in sol.items() if not np.isfinite(v)]
        if bad:
            raise SolveError(f"no finite solution for {', '.join(sorted(bad))} "
                             f"(an implicit block did not converge or a division by zero)")
        self._check_found(sol)
        values_all = {**x, **sol}
        self._check_round_trip(values_all)
        if self.find:  # found parameters meet the cross-parameter rules too (e.g. a found L_u >= L_ul)
            self.model.validate({k: values_all[k] for k in self.model.parameters})
        return Result(self.scene, self.model, values_all, self.given, self.find)

    def evaluate(self, columns: dict[str, np.ndarray], parallel: int = 1) -> dict[str, np.ndarray]:
        """Vectorised solve: arrays of SI inputs (missing ones from the scene) → arrays of unknowns.

        Evaluated in chunks of 65536 points by :func:`ropemodel.core.evaluate.evaluate_columns`
        (``Function.map``, or the same Function compiled to C; ``parallel`` threads), so memory
        stays bounded and the Function is compiled once per process.  No range check is made
        here; callers validate their inputs (see :mod:`ropemodel.sweep`).
        """
        n = max((np.size(v) for v in columns.values()), default=1)
        base = self.inputs({k: v for k, v in columns.items() if not isinstance(v, np.ndarray)})
        arrays = {k: np.broadcast_to(np.asarray(columns[k], dtype=float), (n,)) for k in self.knowns
                  if isinstance(columns.get(k), np.ndarray)}
        constants = {k: base[k] for k in self.knowns if k not in arrays}
        out = evaluate_columns(self.function, arrays, constants, threads=parallel)
        return {u: out[u] for u in self.unknowns}

    def _check_round_trip(self, values_all):
        """The forward model at the solution must reproduce every given output: an implicit
        block whose Newton stopped without converging (e.g. a no-slip pretension that does
        not exist) is a :class:`SolveError`, never a silently wrong answer."""
        if not self.given:
            return
        ref = _Structural(self.scene)
        fwd = _compiled_cached(ref, _forward_structure(ref), ())
        out = fwd(**{k: values_all[k] for k in self.model.parameters})
        for n in self.given:
            got, want = float(out[n]), values_all[n]
            if not abs(got - want) <= 1e-6 * max(1.0, abs(want)):
                q = self.model.quantities[n]
                u = q.unit_text
                raise SolveError(
                    f"no solution with {n} = {q.to_display(want):.6g}{u}: the solver stopped "
                    f"where {n} = {q.to_display(got):.6g}{u} (no such {', '.join(self.find)} "
                    f"or the Newton iteration did not converge)")

    def _check_found(self, sol):
        for n in self.find:
            q = self.model.quantities[n]
            if not q.in_range(sol[n]):
                raise SolveError(
                    f"no valid {n}: the solution {n} = {q.to_display(sol[n]):.6g}{q.unit_text} "
                    f"is outside its valid range {q.range_text()}"
                )


def _compiled(scene: Scene, structure, guesses) -> ca.Function:
    return _compiled_cached(_Structural(scene), structure, guesses)


class _Structural:
    """A scene keyed by its structure (model, effects, numerics), not its values: one compile serves all values."""

    def __init__(self, scene):
        self.scene = scene
        self.key = (scene.model, tuple(sorted(scene.effects.items())), repr(sorted(scene.numerics.items())))

    def __hash__(self):
        return hash(self.key)

    def __eq__(self, other):
        return isinstance(other, _Structural) and other.key == self.key


@lru_cache(maxsize=64)
def _compiled_cached(ref: _Structural, structure, guesses) -> ca.Function:
    return compile_solver(ref.scene.built, structure, dict(guesses))


@lru_cache(maxsize=64)
def _forward_structure(ref: _Structural):
    """The structure of the forward problem (every output from the parameters)."""
    model = ref.scene.built
    return analyse(model, model.outputs, model.parameters)


def run(scene: Scene, values: dict | None = None) -> Result:
    """Forward solve: every output of the scene from its parameters."""
    return Problem(scene).solve(values)


def solve(scene: Scene, given: dict, find) -> Result:
    """Inverse solve: ``given`` outputs (name → value, SI or unit string) in place of the ``find`` parameters."""
    if isinstance(find, str):
        find = [find]
    return Problem(scene, given, find).solve()
