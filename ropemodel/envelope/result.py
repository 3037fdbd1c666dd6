"""The answer of ``ropemodel run`` where the load's place or the manoeuvre is left open: each output at its
worst, and where that is (:class:`EnvelopeResult`)."""

from __future__ import annotations

import math
from typing import Any

from ropemodel.envelope.cases import OPEN, LoadCase, describe, free
from ropemodel.envelope.cases import reads as cases_reads
from ropemodel.envelope.worst import Envelope
from ropemodel.result import Result, row, unit_cell, value_cell


class EnvelopeResult(Result):
    """A :class:`~ropemodel.result.Result` whose values are each output's worst over the load cases.

    ``values`` holds the parameters, the outputs that are the same in every case, and the worst of each
    output that declares one (:attr:`ropemodel.quantity.Quantity.worst`); :attr:`envelope` holds every case
    and extreme, :attr:`where` the governing place of each worst as text.  Outputs that vary with the case
    and have no worst (:attr:`no_worst`) have no value here: pin the place (``x_m``) or the manoeuvre
    (``a_h``) to see them.
    """

    #: an inverse question's case where the given outputs are worst (what decides the answer), else None
    governing: LoadCase | None = None

    def __init__(self, scene, model, env: Envelope, given=(), find=()):
        self.envelope = env
        self.free = free(scene)
        self.where = env.where()
        checks_where = {**{n: "the same in every case" for n in env.constant}, **self.where}
        params = {k: env.params[k] for k in (*model.parameters, *model.edges) if k in env.params and k not in self.free}
        self.scene, self.model = scene, model
        self.values = {**params, **env.values()}
        self.given, self.find = list(given), list(find)
        self.frames = {}
        for sm in model.submodels:
            self.frames.update(sm.frames(self.values, scene, where=checks_where))

    @property
    def outputs(self) -> list[str]:
        return [o for o in self.model.outputs if o in self.values and o not in self.given] + self.find

    @property
    def no_worst(self) -> list[str]:
        """Outputs that vary with the place or the manoeuvre and declare no worst (no value here)."""
        return list(self.envelope.no_worst)

    def cases_text(self) -> str:
        """``4 places of the load x 3 manoeuvres (steady, start, stop)``; on a long route, with the places that
        can govern evaluated (:mod:`ropemodel.envelope.prune`): ``… (evaluated at the 36 places that can govern)``."""
        env = self.envelope
        text = describe(env.spanned or env.cases, env.params)
        if env.spanned and len(env.spanned) != len(env.cases):
            places = len({c.joint for c in env.cases})
            text += f" (evaluated at the {places} places that can govern)"
        return text

    def worst_case(self) -> dict:
        """The JSON of the worst cases: what was spanned, and for each output its sense, value and place."""
        env, params = self.envelope, self.envelope.params
        outputs: dict[str, Any] = {}
        for name in env.extremes:
            top = env.worst(name)
            entry: dict[str, Any] = {"sense": top.sense, "value": _finite(top.value), "where": top.where(params)}
            for other in env.extremes[name]:
                if other is not top:
                    entry[other.sense] = {"value": _finite(other.value), "where": other.where(params)}
            outputs[name] = entry
        out = {"cases": len(env.spanned or env.cases), "evaluated": len(env.cases), "spans": self.cases_text(),
               "free": list(self.free), "outputs": outputs,
               "no_worst": self.no_worst}
        if self.governing is not None:
            c = self.governing
            out["governing_case"] = {"segment": c.segment, "x_m": c.values(env.params).get("x_m"),
                                     "manoeuvre": c.manoeuvre}
        return out

    def critical(self) -> tuple[LoadCase, str]:
        """The one case a sheet of equations is written at, and why: an inverse question's governing case, else
        where the winding rope pulls hardest hauling up (F_C_up: the rope's safety, the stroke and the drive's
        largest power govern there on a route), else where the first output with a worst governs, else (no output
        depends on the case) the first case."""
        if self.governing is not None:
            return self.governing, f"where {', '.join(self.given)} governs"
        if not self.envelope.extremes:
            return self.envelope.cases[0], "every output is the same in every case"
        name = "F_C_up" if "F_C_up" in self.envelope.extremes else next(iter(self.envelope.extremes))
        return self.envelope.worst(name).case, f"where {name} is worst"

    def point(self) -> tuple[Result, str]:
        """The plain :class:`~ropemodel.result.Result` at :meth:`critical`'s case, where every equation holds
        with its own inputs (each worst of this result may come from another case), and that case in words."""
        from ropemodel.problem import Problem

        case, why = self.critical()
        params = {**self.envelope.params, **{f: self.values[f] for f in self.find}}
        values = {k: v for k, v in params.items() if k in self.scene.parameters}
        result = Problem(self.scene).solve({**values, **case.values(params)})
        return result, f"{case.label(params)} ({why})"

    def to_json(self, **extra) -> str:
        return super().to_json(worst_case=self.worst_case(), **extra)

    def reads(self) -> set[str]:
        """The equations' inputs and what the worst case spans (:func:`ropemodel.envelope.cases.reads`: the open
        case inputs and what their manoeuvres' accelerations come from)."""
        return super().reads() | cases_reads(self.scene)

    def table(self) -> str:
        """Inputs, the outputs the same everywhere, then each output's worst and where, the design checks
        with where each governs, the defaults used and the references."""
        q, env = self.model.quantities, self.envelope
        lines = [f"{self.scene.name}  (model {self.model.name}; "
                 + ", ".join(f"{e}={v}" for e, v in self.model.built_effects.items()) + ")"]
        lines += ["", "inputs"] + [row(n, q[n], self.values[n], self._mark(n)) for n in self.shown_inputs()]
        lines += [f"{n:<14}{OPEN[n]:>14}  {unit_cell(q[n]):<8}the worst case below" for n in self.free]
        if self.find:
            why = ("solved for" if self.governing is None else
                   f"solved for: {', '.join(self.given)} worst at {self.governing.label(env.params)}")
            lines += ["", "found (solved for)"] + [row(n, q[n], self.values[n], why) for n in self.find]
        same = [o for o in self.outputs if o in env.constant and o not in self.find]
        if same:
            lines += ["", "results (the same in every case)"] + [row(n, q[n], self.values[n], self._source(n))
                                                                 for n in same]
        w = max((len(n) for n in env.extremes), default=0) + 2
        lines += ["", f"worst case over {self.cases_text()}, both directions: each result at its own worst",
                  f"{'':<{w}}{'worst':>8}{'value':>14}  {'unit':<8}where"]
        for name, extremes in env.extremes.items():
            for e in sorted(extremes, key=lambda e: e is not env.worst(name)):
                lines.append(f"{name:<{w}}{e.sense:>8}{value_cell(q[name], e.value):>14}  {unit_cell(q[name]):<8}"
                             f"{e.text(env.params)}")
        if env.no_worst:
            pins = " or ".join(f"--at {n}=..." for n in self.free)
            lines += ["", f"depend on the case and have no worst (give one point with {pins}): "
                      + ", ".join(env.no_worst)]
        for title, frame in self.frames.items():
            lines += ["", title, frame.to_string(index=False)]
        if self.defaults_used():
            lines += ["", "defaults used"] + [f"  {k}: {why}" for k, why in self.defaults_used().items()]
        lines += ["", "references"] + [f"  {c}" for c in self.citations]
        return "\n".join(lines)


def _finite(v: float):
    return v if math.isfinite(v) else None


__all__ = ["EnvelopeResult"]
