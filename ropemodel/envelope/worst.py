"""The worst case of every output over the load cases: evaluated at once, reduced to each output's worst.

:func:`envelope` evaluates a compiled :class:`~ropemodel.problem.Problem` at every
:class:`~ropemodel.envelope.cases.LoadCase` in one vectorised call and keeps, for each output, the extreme
its quantity declares as its worst (:attr:`ropemodel.quantity.Quantity.worst`: the least margin, the
largest rope force, the largest motoring and the largest braking power) with the case that governs it.
Nothing here dispatches on an output's name: the direction of an output is the suffix ``_up``/``_down``
of the paper's naming, everything else comes from the quantities.

An output with two senses (a signed power, F_S) has two extremes; its worst is the one of larger
magnitude (with its sign).  An output that is the same in every case is a plain result; one that varies
and declares no worst (an intermediate such as G_ml, the load's weight along its segment) has no single
value: :attr:`Envelope.no_worst` names them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ropemodel.envelope.cases import LoadCase, joint_ends
from ropemodel.errors import SolveError

#: relative difference below which an output counts as the same in two cases (rounding of equal sums)
SAME_RTOL = 1e-12


def direction_of(name: str) -> str | None:
    """``up``/``down`` of an output of one direction (``F_C_up``), else None."""
    tail = name.rsplit("_", 1)[-1]
    return tail if tail in ("up", "down") and "_" in name else None


def where_text(where: dict | str | None, direction: bool = False) -> str:
    """A :meth:`Extreme.where` dict as text: ``segment 2, x_m = 1300 m, start`` (``up, ...`` with
    ``direction``); ``the same in every case`` for None, ``anywhere`` when nothing in it matters."""
    if where is None:
        return "the same in every case"
    if isinstance(where, str):     # a model that says where in words (a Koepe hoist's end state)
        return where
    parts = [where.get("direction") if direction else None,
             f"segment {where['segment']}" if where.get("segment") is not None else None,
             f"x_m = {where['x_m']:g} m" if where.get("x_m") is not None else None, where.get("manoeuvre")]
    return ", ".join(p for p in parts if p) or "anywhere"


@dataclass(frozen=True)
class Extreme:
    """One extreme of an output over the cases: its ``sense`` (least, largest), ``value`` (SI), the
    ``case`` that governs it, and whether the place of the load and the manoeuvre matter for it at all."""

    name: str
    sense: str
    value: float
    case: LoadCase
    place_matters: bool
    manoeuvre_matters: bool

    def where(self, params: Mapping) -> dict:
        """``{"segment", "x_m", "direction", "manoeuvre"}``: None where it does not matter (or is pinned)."""
        c = self.case
        place = self.place_matters and c.joint is not None
        return {"segment": c.segment if place else None,
                "x_m": float(c.values(params)["x_m"]) if place else None,
                "direction": direction_of(self.name),
                "manoeuvre": c.manoeuvre if self.manoeuvre_matters else None}

    def text(self, params: Mapping) -> str:
        """``segment 2, x_m = 1300 m, start``; ``anywhere`` when neither the place nor the manoeuvre matters."""
        c = self.case
        parts = [c.place(params) if self.place_matters else "", c.manoeuvre if self.manoeuvre_matters else ""]
        return ", ".join(p for p in parts if p) or "anywhere"


@dataclass
class Envelope:
    """Every output at every case, and each output's worst.

    Attributes
    ----------
    cases: the load cases, in order; params: the SI values they were built from (scene and overrides).
    columns: output → its value at each case (SI arrays).
    extremes: output → its extremes (one per sense its quantity declares), for outputs that vary.
    constant: outputs that are the same in every case.
    no_worst: outputs that vary with the case and declare no worst.
    spanned: every case the worst is taken over, when ``cases`` are those of them that can govern
        (:func:`ropemodel.envelope.prune.prune`); None when every case was evaluated.
    """

    cases: list[LoadCase]
    params: dict
    columns: dict[str, np.ndarray]
    extremes: dict[str, tuple[Extreme, ...]] = field(default_factory=dict)
    constant: list[str] = field(default_factory=list)
    no_worst: list[str] = field(default_factory=list)
    spanned: list[LoadCase] | None = None

    def worst(self, name: str) -> Extreme:
        """The governing extreme of ``name``: its only one, or of two the one of larger magnitude."""
        return max(self.extremes[name], key=lambda e: (abs(e.value), e.sense == "largest"))

    def values(self) -> dict[str, float]:
        """Each output's value: the same in every case, or its worst (SI)."""
        out = {n: float(self.columns[n][0]) for n in self.constant}
        out.update({n: self.worst(n).value for n in self.extremes})
        return out

    def where(self) -> dict[str, str]:
        """Output → the place and manoeuvre that govern its worst, as text."""
        return {n: self.worst(n).text(self.params) for n in self.extremes}

    def at(self, i: int) -> dict[str, float]:
        """Every output at case ``i`` (SI)."""
        return {n: float(v[i]) for n, v in self.columns.items()}


def symbolic_worst(exprs: list, senses: tuple[str, ...]):
    """(worst, index) of CasADi expressions, one per case: the least or the largest (of two senses the one of
    larger magnitude, as :meth:`Envelope.worst`), and the index of the (first) case it is at."""
    best = {}
    for sense in senses:
        value, index = exprs[0], ca.MX(0.0)
        for k, e in enumerate(exprs[1:], start=1):
            better = e < value if sense == "least" else e > value
            index, value = ca.if_else(better, k, index), ca.if_else(better, e, value)
        best[sense] = (value, index)
    if len(best) == 1:
        return next(iter(best.values()))
    (lo, i_lo), (hi, i_hi) = best["least"], best["largest"]
    pick = ca.fabs(hi) >= ca.fabs(lo)
    return ca.if_else(pick, hi, lo), ca.if_else(pick, i_hi, i_lo)


def pick(index, exprs: list):
    """``exprs[index]`` for a symbolic index (:func:`symbolic_worst`)."""
    out = exprs[0]
    for k, e in enumerate(exprs[1:], start=1):
        out = ca.if_else(index == k, e, out)
    return out


def case_columns(cases: list[LoadCase], params: Mapping) -> dict[str, np.ndarray]:
    """The inputs the cases set, as arrays over the cases (SI)."""
    ends = joint_ends(params)
    rows = [c.values(params, ends) for c in cases]
    names = list(dict.fromkeys(k for r in rows for k in r))
    return {k: np.array([float(r[k]) for r in rows]) for k in names}


def envelope(problem, cases: list[LoadCase], params: Mapping | None = None) -> Envelope:
    """Evaluate ``problem`` (a forward :class:`~ropemodel.problem.Problem`) at every case at once and reduce
    each output to its worst.

    ``params``: SI values overriding the scene's (the cases' places and accelerations follow them).
    Raises :class:`~ropemodel.errors.SolveError` where a case lies outside the physics (a rope that would
    have to push), naming the case.
    """
    params = dict(params or {})
    knowns = set(problem.knowns)
    inputs = problem.inputs({k: v for k, v in params.items() if k in knowns})
    values = {**problem.scene.parameters, **inputs, **params}
    columns = problem.evaluate({**inputs, **case_columns(cases, values)})
    env = Envelope(cases, values, columns)
    _check_physics(problem, env, inputs)
    quantities = problem.model.quantities
    places = [c.joint for c in cases]
    moves = [c.manoeuvre for c in cases]
    for name, col in columns.items():
        if _same(col):
            env.constant.append(name)
            continue
        senses = quantities[name].worst
        if not senses:
            env.no_worst.append(name)
            continue
        place, move = _matters(col, places, moves), _matters(col, moves, places)
        arg = {"least": np.argmin, "largest": np.argmax}
        env.extremes[name] = tuple(Extreme(name, s, float(col[i]), cases[i], place, move)
                                   for s in senses for i in [int(arg[s](col))])
    return env


def _same(col: np.ndarray) -> bool:
    finite = np.isfinite(col)
    if not finite.all():
        return bool(np.all(col == col[0]))
    return bool(np.all(np.abs(col - col[0]) <= SAME_RTOL * np.max(np.abs(col))))


def _matters(col: np.ndarray, key: list, other: list) -> bool:
    """Whether ``col`` changes with ``key`` while ``other`` is held (e.g. with the place, manoeuvre held)."""
    groups: dict = {}
    for i, o in enumerate(other):
        groups.setdefault(o, []).append(i)
    return any(not _same(col[idx]) for idx in groups.values() if len({key[i] for i in idx}) > 1)


def _check_physics(problem, env: Envelope, inputs: dict) -> None:
    """:class:`SolveError` at the first case with no value (an implicit block that did not converge) or outside the
    physics (a slack rope), with the submodel's reason: a worst case never skips a case."""
    for name, col in env.columns.items():
        bad = np.flatnonzero(np.isnan(col))
        if bad.size:
            raise SolveError(f"with the load at {env.cases[int(bad[0])].label(env.params)}: no finite value for "
                             f"{name} (an implicit equation did not converge, or a division by zero)")
    values = {**env.columns, **{k: np.full(len(env.cases), v) for k, v in inputs.items()}}
    for sm in problem.model.submodels:
        for mask in sm.invalid_mask(values).values():
            bad = np.flatnonzero(np.asarray(mask) & np.ones(len(env.cases), dtype=bool))
            if bad.size:
                i = int(bad[0])
                why = sm.invalid({**inputs, **env.at(i)}) or ["outside the model"]
                raise SolveError(f"with the load at {env.cases[i].label(env.params)}: {why[0]}")
