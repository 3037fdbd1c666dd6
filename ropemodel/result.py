"""Results of a solve: SI values with their quantities, shown in the user's units."""

from __future__ import annotations

import json
import math
import re
from typing import Any

from ropemodel.rules.describe import summary as rules_summary
from ropemodel.units import label
from ropemodel.views.result import ResultViews

_DIR = re.compile(r"^(?P<base>.+)_(?P<dir>up|down)$")
#: keys of the JSON object that are not quantities (no quantity has one of these names)
META = ("given", "found", "where", "defaults", "unused", "unlimited", "warnings", "citations", "rules")


class Result(ResultViews):
    """Every known and solved quantity of one solve, in SI.

    ``values`` maps names to SI floats; :meth:`to_series` gives display units in the
    index (``F_C_up [kN]``), :meth:`to_json` SI numbers, :meth:`table` a readable
    text table with each quantity's equation.  ``frames`` holds extra tables a
    submodel publishes (e.g. the tension along a sheave's arc); ``where`` says where each output taken at
    its worst occurs (a Koepe hoist's end state and manoeuvre).  An output that is
    infinite because an input is unlimited (no stroke given) reads ``unlimited`` in
    the table and ``null`` in JSON, and is listed under ``"unlimited"``.  In Jupyter it shows as
    HTML tables with units; :meth:`to_frame` gives a DataFrame and :meth:`plot` its picture
    (:mod:`ropemodel.views.result`).
    """

    def __init__(self, scene, model, values: dict[str, float], given=(), find=()):
        self.scene, self.model = scene, model
        self.values = dict(values)
        self.given, self.find = list(given), list(find)
        self.frames: dict = {}
        #: output → where its worst case is, for outputs taken at their worst
        self.where: dict[str, str] = {}
        for sm in model.submodels:
            self.frames.update(sm.frames(self.values, scene))
            self.where.update(sm.where(self.values))

    def __getitem__(self, name: str) -> float:
        return self.values[name]

    @property
    def outputs(self) -> list[str]:
        """Solved quantities: the model's outputs not given, plus the parameters found."""
        return [o for o in self.model.outputs if o not in self.given] + self.find

    @property
    def citations(self) -> list[str]:
        """Full references of the papers behind these results."""
        return self.model.citations

    def to_dict(self) -> dict[str, float]:
        """Every solved quantity in SI (the JSON contract's numbers)."""
        return {k: self.values[k] for k in self.outputs}

    def to_json(self, **extra) -> str:
        """One JSON object: every solved quantity (SI), then ``given`` (inverse questions), ``found``,
        ``where`` (output → where its worst case is), ``defaults`` (parameter → why its default), ``unused``,
        ``unlimited``, ``warnings``, ``citations`` and, for a model with design checks, ``rules`` (what each
        factor rests on; see :func:`ropemodel.rules.describe.summary`)."""
        out: dict[str, Any] = {k: (v if math.isfinite(v) else None) for k, v in self.to_dict().items()}
        if self.given:
            out["given"] = {k: self.values[k] for k in self.given}
            out["found"] = list(self.find)
        where = {k: w for k, w in self.where.items() if k in self.outputs}
        if where:
            out["where"] = where
        out["defaults"] = self.defaults_used()
        out["unused"] = dict(self.scene.unused)
        out["unlimited"] = [k for k in self.outputs if self.values[k] == math.inf]
        out["warnings"] = list(self.scene.warnings)
        out["citations"] = self.citations
        rules = rules_summary(self.scene)
        if rules:
            out["rules"] = rules    # every factor of the checks: its rule (set, clause, status) or user-given
        out.update(extra)
        return json.dumps(out, indent=2, allow_nan=False)

    def to_series(self, names=None, si: bool = False):
        """Values in display units (or SI), index labels carry the unit: ``F_C_up [kN]``."""
        import pandas as pd

        names = list(names) if names is not None else list(self.values)
        data = {}
        for n in names:
            q = self.model.quantities[n]
            unit = q.unit if si else q.display_unit
            data[label(n, unit)] = self.values[n] if si else q.to_display(self.values[n])
        return pd.Series(data, name=self.scene.name, dtype=float)

    def table(self) -> str:
        """Text table in display units: inputs, found parameters, single quantities, up/down pairs,
        extra tables, the defaults used and the references."""
        q = self.model.quantities
        lines = [f"{self.scene.name}  (model {self.model.name}; "
                 + ", ".join(f"{e}={v}" for e, v in self.model.built_effects.items()) + ")"]
        inputs = self.shown_inputs()
        single = [o for o in self.outputs if not _DIR.match(o) and o not in self.find]
        w = max(len(n) for n in inputs + self.find + single + [" " * 13]) + 1    # names longer than 13: wider
        lines += ["", "inputs"] + [row(n, q[n], self.values[n], self._mark(n), w) for n in inputs]
        if self.find:
            lines += ["", "found (solved for)"] + [row(n, q[n], self.values[n], "solved for", w) for n in self.find]
        if single:
            lines += ["", "results"] + [row(n, q[n], self.values[n], self._source(n), w) for n in single]
        lines += self._pairs()
        for title, frame in self.frames.items():
            lines += ["", title, frame.to_string(index=False)]
        where = [k for k in self.outputs if k in self.where]
        if where:
            lines += ["", "where each worst case is"] + [f"  {k}: {self.where[k]}" for k in where]
        if self.defaults_used():
            lines += ["", "defaults used"] + [f"  {k}: {why}" for k, why in self.defaults_used().items()]
        lines += ["", "references"] + [f"  {c}" for c in self.citations]
        return "\n".join(lines)

    def defaults_used(self) -> dict[str, str]:
        """Each default the answer rests on, with why: a parameter the outputs are computed from
        (:meth:`reads`), not one only a transient reads (``v_eps``, ``rope_damping``, ``m_t`` of the ramps a
        ``t_ramp`` brings into a static command)."""
        reads = self.reads()
        return {k: why for k, why in self.scene.defaults.items() if k in reads}

    def reads(self) -> set[str]:
        """The parameters the outputs are computed from (through the equations)."""
        return self.model.inputs_of()

    def shown_inputs(self) -> list[str]:
        """The inputs the text table lists: every parameter but a default none of the outputs is computed from (a
        transient's own, ``v_eps``, ``rope_damping``, ``m_t``, ``mesh_tol``, ``n_slip_dynamic``, which a
        ``t_ramp`` brings into a static command with its ramps), then the given outputs.  A value the user gave
        and the outputs do not read stays, and the command warns of it (:mod:`ropemodel.unread`)."""
        reads, defaults = self.reads(), self.scene.defaults
        return [n for n in self.model.parameters if n in self.values and n not in self.find
                and (n in reads or n not in defaults)] + self.given

    def _pairs(self) -> list[str]:
        q = self.model.quantities
        paired = []
        for o in self.outputs:
            m = _DIR.match(o)
            if m and m["base"] not in paired:
                paired.append(m["base"])
        if not paired:
            return []
        lines = ["", f"{'':<14}{'down':>14}{'up':>14}  {'unit':<8}source"]
        for base in paired:
            qq = q.get(f"{base}_up") or q[f"{base}_down"]
            cells = []
            for d in ("down", "up"):
                n = f"{base}_{d}"
                cells.append(f"{value_cell(q[n], self.values[n]):>14}" if n in self.values else f"{'':>14}")
            src = self._source(f"{base}_up" if f"{base}_up" in self.values else f"{base}_down")
            lines.append(f"{base:<14}{''.join(cells)}  {unit_cell(qq):<8}{src}".rstrip())
            if qq.signs:   # a signed quantity: what each sign means, under its number
                signs = [q[f"{base}_{d}"].sign_text(self.values.get(f"{base}_{d}", 0.0)) for d in ("down", "up")]
                lines.append(f"{'':<14}{''.join(f'{t:>14}' for t in signs)}".rstrip())
        return lines

    def _mark(self, name: str) -> str:
        if name in self.given:
            return "given"
        if self.scene.origin.get(name) in ("rules", "rules override"):
            return self.scene.basis(name)       # the rule (set, clause, formula, status) or the override's reason
        return "default" if name in self.scene.defaults else ""

    def _source(self, name: str) -> str:
        return self.model.equation_of(name).source if name in self.model.defined_by else ""


def unit_cell(q) -> str:
    """The display unit of ``q`` as a table shows it (``-`` for a pure number)."""
    return "-" if q.display_unit == "1" else q.display_unit


def value_cell(q, value) -> str:
    """``value`` (SI) in the display unit as a table shows it (``unlimited`` for an unlimited infinity)."""
    return q.unlimited_text if value == math.inf else f"{q.to_display(value):.6g}"


def row(name, q, value, source="", width=14) -> str:
    """One line of a result table: name (in ``width`` columns), value, unit, source."""
    return f"{name:<{width}}{value_cell(q, value):>14}  {unit_cell(q):<8}{source}".rstrip()


__all__ = ["META", "Result", "row", "unit_cell", "value_cell"]
