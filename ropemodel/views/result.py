"""What a :class:`ropemodel.result.Result` shows: an HTML table, a DataFrame and a picture per model.

The pictures (:meth:`ResultViews.plot`):

* winch: the forces in both ropes, both directions, as the load moves along the route (x_m from
  the drive to the return sheave); on the paper's straight route they do not depend on where the
  load is (docs/physics.md §1), on a route of segments they change where the load crosses a joint
  (§4);
* sheave: the tension along the arc S(α)/S_0 against Euler–Eytelwein's e^{μα} (Hajduk 1992, §3);
* capstan: the load curve, the equivalent stiffness K against the load F_T (Li et al., eq. (26), §5);
* koepe: the static tension ratio T_1/T_2 as the conveyances move through the wind, loaded and empty, against
  the traction limit (docs/physics.md §7).
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from ropemodel.errors import InputError
from ropemodel.views import html
from ropemodel.views.plotting import axes, finish

_DIR = re.compile(r"^(?P<base>.+)_(?P<dir>up|down)$")
#: points of a curve drawn along one input
POINTS = 401


class ResultViews:
    """``_repr_html_``, :meth:`to_frame` and :meth:`plot` of a :class:`~ropemodel.result.Result`."""

    values: dict[str, float]
    model: Any
    scene: Any
    given: list[str]
    find: list[str]
    frames: dict
    where: dict[str, str]

    def _rows(self) -> list[tuple[str, str, str]]:
        """(name, role, source or note) in the order of :meth:`Result.table`."""
        r: Any = self     # a Result: _mark, _source and outputs are its own
        rows = [(n, "given" if n in self.given else "input", r._mark(n))
                for n in [n for n in self.model.parameters if n not in self.find] + self.given]
        rows += [(n, "found", "solved for") for n in self.find]
        rows += [(n, "result", r._source(n) + (f"; worst case: {self.where[n]}" if n in self.where else ""))
                 for n in r.outputs if n not in self.find]
        return rows

    def to_frame(self, si: bool = False):
        """Every input and result as a DataFrame indexed by name: ``value`` (display units, or SI with
        ``si=True``), ``unit``, ``role`` (input, given, found, result) and ``source`` (the equation,
        or why an input has its value)."""
        import pandas as pd

        q = self.model.quantities
        data = []
        for name, role, source in self._rows():
            x, value = q[name], self.values[name]
            data.append((name, value if si else x.to_display(value), html.unit_text(x.unit if si else x.display_unit),
                         role, source))
        return pd.DataFrame(data, columns=["name", "value", "unit", "role", "source"]).set_index("name")

    def _repr_html_(self) -> str:
        q = self.model.quantities
        rows = self._rows()
        show = lambda n: q[n].to_display(self.values[n])                                  # noqa: E731
        unit = lambda n: html.unit_text(q[n].display_unit)                                # noqa: E731
        parts = [html.table(("name", "value", "unit", "note"),
                            [(n, show(n), unit(n), s) for n, r, s in rows if r in ("input", "given")], "inputs")]
        if self.find:
            parts.append(html.table(("name", "value", "unit", "note"),
                                    [(n, show(n), unit(n), s) for n, r, s in rows if r == "found"], "found"))
        single = [(n, show(n), unit(n), s) for n, r, s in rows if r == "result" and not _DIR.match(n)]
        if single:
            parts.append(html.table(("name", "value", "unit", "source"), single, "results"))
        pairs = _pairs([n for n, r, _ in rows if r == "result"])
        if pairs:
            cell = lambda n: show(n) if n in self.values else None                        # noqa: E731
            source = {n: s for n, _, s in rows}
            parts.append(html.table(("name", "down", "up", "unit", "source"),
                                    [(b, cell(f"{b}_down"), cell(f"{b}_up"), unit(u), source[u]) for b, u in pairs],
                                    "by direction of travel", numeric=(1, 2)))
        for title, frame in self.frames.items():
            parts.append(html.table(list(frame.columns), frame.itertuples(index=False), title,
                                    numeric=range(frame.shape[1])))
        effects = ", ".join(f"{e}={v}" for e, v in self.model.built_effects.items())
        defaults = [f"default: {k}, {why}" for k, why in self.scene.defaults.items() if k in self.values]
        return html.page(f"{self.scene.name} (model {self.model.name}; {effects})", *parts,
                         notes=[*defaults, "references: " + "; ".join(self.model.citations)])

    def plot(self, ax: Any = None) -> Any:
        """The picture of this result (see the module docstring); returns the matplotlib axes.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw (default: a new figure).
        """
        picture = PICTURES.get(self.model.name)
        if picture is None:
            raise InputError(f"no picture for a {self.model.name} result; its numbers are in to_frame()")
        return picture(self, axes(ax))


def _pairs(names: list[str]) -> list[tuple[str, str]]:
    """(base, a name of the pair) for every output with an up/down twin, in order."""
    out: dict[str, str] = {}
    for n in names:
        m = _DIR.match(n)
        if m:
            out.setdefault(m["base"], n)
    return list(out.items())


def along(result: ResultViews, columns: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The result's model evaluated at many values of some inputs, the others at the result's values (an input
    a worst case leaves open, the acceleration a_h, at the scene's own value: steady motion)."""
    from ropemodel.core.compile import forward_of
    from ropemodel.core.evaluate import evaluate_columns

    fun = forward_of(result.model)
    constants = {k: result.values.get(k, result.scene.parameters.get(k)) for k in fun.name_in() if k not in columns}
    return evaluate_columns(fun, columns, constants)


def _route(result: ResultViews, ax):
    """F_C and F_S of both directions against the load's place x_m on the route."""
    v, q = result.values, result.model.quantities
    ends = np.cumsum([v[f"L_{i}"] for i in range(1, 10_000) if f"L_{i}" in v])
    x = np.linspace(0.0, v["L_u"], POINTS)
    if "x_m" in result.model.parameters:
        eps = 1e-9 * v["L_u"]
        x = np.unique(np.clip(np.concatenate([x, ends - eps, ends + eps]), 0.0, v["L_u"]))
        out = along(result, {"x_m": x})
    else:
        out = {k: np.full(len(x), v[k]) for k in v}
    for name, style in (("F_C_up", "-"), ("F_S_up", "-"), ("F_C_down", "--"), ("F_S_down", "--")):
        if name in out:
            rope, direction = name.rsplit("_", 1)
            ax.plot(x, q[name].to_display(np.asarray(out[name])), style, label=f"{rope}, {direction}")
    for e in ends[:-1]:
        ax.axvline(e, color="0.6", lw=0.8)
    unit = html.unit_text(q["F_C_up"].display_unit)
    steady = ", steady motion" if "a_h" in result.model.parameters and "a_h" not in v else ""
    return finish(ax, f"{result.scene.name}: rope forces as the load moves{steady}",
                  "x_m, the load's distance from the drive [m]", f"force [{unit}]")


def _arc(result: ResultViews, ax):
    """S/S_0 along the arc of contact, and e^{μα} for a rigid lining."""
    frame = result.frames["tension along the arc"]
    a = frame["alpha [deg]"]
    ax.plot(a, frame["S/S_0 [-]"], label="S/S_0 (Hajduk 1992)")
    ax.plot(a, frame["e^(mu alpha) [-]"], "--", label="e^(μα) (rigid lining)")
    return finish(ax, f"{result.scene.name}: tension along the arc", "α, angle from where the rope enters [deg]",
                  "S/S_0 [-]")


def _load_curve(result: ResultViews, ax):
    """K against F_T from no load to twice the preload (or the result's load, if larger)."""
    v, q = result.values, result.model.quantities
    F = np.linspace(0.0, max(v["F_T"], 2.0 * v["F_p"]), POINTS)
    out = along(result, {"T": 2.0 * v["R"] * F} if "T" in result.model.parameters else {"F_T": F})
    K = np.asarray(out["K"])
    ok = np.isfinite(K) & (np.asarray(out["alpha_2"]) > 0)   # beyond: the slack side would unwrap
    unit = q["K"].display_unit
    ax.plot(F[ok], q["K"].to_display(K[ok]), label="K, equivalent stiffness")
    ax.plot([v["F_T"]], [q["K"].to_display(v["K"])], "o", label=f"this result, regime {v['regime']:.0f}")
    return finish(ax, f"{result.scene.name}: load curve", "F_T, load [N]", f"K [{unit}]")


def _wind(result: ResultViews, ax):
    """T_1/T_2 at rest against the depth of conveyance L (the payload's), loaded and empty, and the traction
    limit of the worst static state (:func:`ropemodel.papers.koepe.side_tensions`)."""
    from ropemodel.papers.koepe import side_tensions

    v = result.values
    y = np.linspace(0.0, v["H"], POINTS)
    tail = (v.get("n_tail", 0.0), v.get("q_tail", 0.0), v.get("h_loop", 0.0))    # none without tail ropes
    for payload, label in ((v["m_payload"], "loaded"), (0.0, "empty")):
        T_L, T_E = side_tensions(y, v["m_conveyance"], payload, v["H"], v["H_head"], v["n_head"], v["q_head"], *tail)
        ax.plot(y, np.maximum(T_L, T_E) / np.minimum(T_L, T_E), label=f"T_1/T_2, {label}")
    ax.axhline(v["traction_limit"], color="0.3", ls="--", label="traction limit (worst static state)")
    return finish(ax, f"{result.scene.name}: tension ratio through the wind", "depth of conveyance L below its "
                  "upper position [m]", "T_1/T_2 [-]")


#: model → its picture
PICTURES = {"winch": _route, "sheave": _arc, "capstan": _load_curve, "koepe": _wind}
