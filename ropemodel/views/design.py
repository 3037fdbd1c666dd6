"""What a sizing answer (:class:`optimisation.design.Design`) shows: the design and every check.

Values are SI inside the design; the table shows each in its quantity's display unit (the scene's
own: d and stroke in mm, F_nwl in kN, N_p in kW, margins as the model defines them).
"""

from __future__ import annotations

from typing import Any

from ropemodel.views import html

#: the variables of the design, in order
VARIABLES = ("d", "F_nwl", "stroke")


class DesignViews:
    """``_repr_html_`` and :meth:`to_frame` of a :class:`~optimisation.design.Design`."""

    scene: Any
    feasible: bool
    design: dict[str, float] | None
    continuous: dict[str, float] | None
    margins: dict[str, float]
    margins_continuous: dict[str, float]
    power: dict[str, float]
    least_drum: float | None
    active: list[str]
    active_continuous: list[str]
    message: str

    def _values(self) -> list[tuple[str, float | None, float | None]]:
        """(name, at the catalogue design, at the continuous optimum), SI."""
        design, cont = self.design or {}, self.continuous or {}
        names = list(cont) or [k for k in VARIABLES if k in design]    # the design variables (a winch's by default)
        rows = [(k, design.get(k), cont.get(k)) for k in names]
        rows += [(k, v, None) for k, v in design.items() if k not in names]     # what follows from them
        rows += [(k, v, None) for k, v in self.power.items()]
        if self.least_drum is not None:
            rows.append(("D", self.least_drum, None))
        rows += [(k, v, self.margins_continuous.get(k)) for k, v in self.margins.items()]
        rows += [(k, None, v) for k, v in self.margins_continuous.items() if k not in self.margins]
        return rows

    def to_frame(self, si: bool = False):
        """The design as a DataFrame indexed by name: ``design`` (the catalogue design), ``continuous``
        (the continuous optimum), ``unit`` (display units, or SI with ``si=True``) and ``active`` (the
        check limits the catalogue design).  Rows: d, F_nwl, stroke, the drive power, the least drum
        D (when the scene gives none) and every margin (>= 0 passes).  Empty when no design exists."""
        import pandas as pd

        q = self.scene.built.quantities
        data = []
        for name, at, cont in self._values():
            x = q[name]
            conv = (lambda v: v) if si else x.to_display
            data.append((name, None if at is None else conv(at), None if cont is None else conv(cont),
                         html.unit_text(x.unit if si else x.display_unit),
                         name in {a.split(" @ ")[0] for a in self.active}))
        return pd.DataFrame(data, columns=["name", "design", "continuous", "unit", "active"]).set_index("name")

    def _repr_html_(self) -> str:
        title = f"{self.scene.name}: " + ("design" if self.feasible else "no design")
        if not self.feasible:
            return html.page(title, notes=self.message.splitlines())
        frame = self.to_frame()
        rows = []
        for name, r in frame.iterrows():
            passes = "" if name not in self.margins else "pass" if r["design"] >= 0 else ("FAIL", "fail")
            rows.append((name, r["design"], r["continuous"], r["unit"], passes, "active" if r["active"] else ""))
        table = html.table(("name", "design", "continuous", "unit", "check", "limits the design"), rows,
                           numeric=(1, 2))
        return html.page(title, table, notes=[self.message, "active at the continuous optimum: "
                                              + ", ".join(self.active_continuous)])
