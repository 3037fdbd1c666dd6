"""Results of a solve: SI values with their quantities, shown in the user's units."""

from __future__ import annotations

import json
import math
import re

import pandas as pd

from ropemodel.units import label

_DIR = re.compile(r"^(?P<base>.+)_(?P<dir>up|down)$")


class Result:
    """Every known and solved quantity of one solve, in SI.

    ``values`` maps names to SI floats; :meth:`to_series` gives display units in the
    index (``F_C_up [kN]``), :meth:`to_json` SI numbers, :meth:`table` a readable
    text table with each quantity's equation.  ``frames`` holds extra tables a
    submodel publishes (e.g. the tension along a sheave's arc).
    """

    def __init__(self, scene, model, values: dict[str, float], given=(), find=()):
        self.scene, self.model = scene, model
        self.values = dict(values)
        self.given, self.find = list(given), list(find)
        self.frames: dict[str, pd.DataFrame] = {}
        for sm in model.submodels:
            self.frames.update(sm.frames(self.values, scene))

    def __getitem__(self, name: str) -> float:
        return self.values[name]

    @property
    def outputs(self) -> list[str]:
        """Solved quantities: the model's outputs not given, plus the parameters found."""
        return [o for o in self.model.outputs if o not in self.given] + self.find

    def to_dict(self) -> dict[str, float]:
        """Every solved quantity in SI (the JSON contract)."""
        return {k: self.values[k] for k in self.outputs}

    def to_json(self, **extra) -> str:
        """One JSON object, SI values; NaN/inf never written (they are refused earlier)."""
        out = {k: _json_num(v) for k, v in self.to_dict().items()}
        out.update(extra)
        return json.dumps(out, indent=2, allow_nan=False)

    def to_series(self, names=None, si: bool = False) -> pd.Series:
        """Values in display units (or SI), index labels carry the unit: ``F_C_up [kN]``."""
        names = list(names) if names is not None else list(self.values)
        data = {}
        for n in names:
            q = self.model.quantities[n]
            unit = q.unit if si else q.display_unit
            data[label(n, unit)] = self.values[n] if si else q.to_display(self.values[n])
        return pd.Series(data, name=self.scene.name, dtype=float)

    def table(self) -> str:
        """Text table in display units: inputs, then single quantities, then up/down pairs."""
        q = self.model.quantities
        lines = [f"{self.scene.name}  (model {self.model.name}; "
                 + ", ".join(f"{e}={v}" for e, v in self.model.built_effects.items()) + ")"]
        inputs = [n for n in self.model.parameters if n not in self.find] + self.given
        lines += ["", "inputs"] + [_row(n, q[n], self.values[n]) for n in inputs]
        single = [o for o in self.outputs if not _DIR.match(o)]
        paired = []
        for o in self.outputs:
            m = _DIR.match(o)
            if m and m["base"] not in paired:
                paired.append(m["base"])
        if single:
            lines += ["", "results"] + [_row(n, q[n], self.values[n], self._source(n)) for n in single]
        if paired:
            lines += ["", f"{'':<10}{'down':>14}{'up':>14}  {'unit':<8}source"]
            for base in paired:
                qq = q.get(f"{base}_up") or q[f"{base}_down"]
                cells = []
                for d in ("down", "up"):
                    n = f"{base}_{d}"
                    cells.append(f"{q[n].to_display(self.values[n]):>14.6g}" if n in self.values else f"{'':>14}")
                src = self._source(f"{base}_up" if f"{base}_up" in self.values else f"{base}_down")
                lines.append(f"{base:<10}{''.join(cells)}  {_unit(qq):<8}{src}".rstrip())
        for title, frame in self.frames.items():
            lines += ["", title, frame.to_string(index=False)]
        return "\n".join(lines)


    def _source(self, name: str) -> str:
        return self.model.equation_of(name).source if name in self.model.defined_by else ""


def _unit(q) -> str:
    return "-" if q.display_unit == "1" else q.display_unit


def _row(name, q, value, source="") -> str:
    return f"{name:<10}{q.to_display(value):>14.6g}  {_unit(q):<8}{source}".rstrip()


def _json_num(v):
    if isinstance(v, float) and not math.isfinite(v):
        raise ValueError(f"non-finite value {v} in a result")
    return v
