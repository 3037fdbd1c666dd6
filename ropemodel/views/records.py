"""What a trip, a transient and a sweep file show: a summary table with units, pandas forms, a picture.

A summary is SI, as ``--json`` prints it; the tables show forces in kN, power in kW and energy in
kWh (:data:`DISPLAY`), every other unit as it is.
"""

from __future__ import annotations

import json
import math
from typing import Any, ClassVar

import numpy as np

from ropemodel.errors import SolveError
from ropemodel.units import factor, label
from ropemodel.views import html
from ropemodel.views.plotting import axes, finish

#: SI unit → the unit a summary table shows
DISPLAY = {"N": "kN", "W": "kW", "J": "kWh"}
#: units of a transient's summary keys that are not the extreme, end or static value of a history column
#: (those take the column's unit: F_C_max is the largest of ``F_C [N]``)
SIMULATION_UNITS = {"x_m": "m", "stroke_used": "m", "stroke": "m", "slip_distance": "m", "t_end": "s",
                    "t_slack": "s", "dynamic_factor": "1", "traction_ratio": "1", "energy_residual": "1",
                    "n_nodes": "1",
                    # a Koepe transient's (ropemodel.machines.koepe.simulation)
                    **dict.fromkeys(("t_T_L_max", "t_T_L_min", "t_T_E_max", "t_T_E_min", "t_T_min", "t_worst",
                                     "t_rest", "t_stopped"), "s"),
                    **dict.fromkeys(("y_start", "travel_nominal", "reel", "overwind", "run"), "m"),
                    "segments": "1", "sim_rtol": "1"}
_SUFFIXES = ("_max", "_min", "_end", "_static", "_start")


def shown(value: float, unit: str) -> tuple[float, str]:
    """An SI ``value`` of ``unit`` in the unit a table shows (:data:`DISPLAY`)."""
    display = DISPLAY.get(unit, unit)
    return value * factor(unit, display), display


def summary_rows(summary: dict, units: dict[str, str]) -> tuple[list[tuple], list[tuple]]:
    """(numbers, the rest): numbers as (name, value, unit) in display units, the rest (flags, words,
    lists, nested tables) as (name, text)."""
    numbers, rest = [], []
    for k, v in summary.items():
        if isinstance(v, (int, float)) and not isinstance(v, bool) and k in units:
            value, unit = shown(float(v), units[k])
            numbers.append((k, value, html.unit_text(unit)))
        elif isinstance(v, (dict, list)):
            rest.append((k, json.dumps(v) if v else "none"))
        else:
            rest.append((k, html.number(v) if v is not None else "none"))
    return numbers, rest


def _series(summary: dict, units: dict[str, str], name: str, si: bool):
    import pandas as pd

    data = {}
    for k, v in summary.items():
        if isinstance(v, (int, float)) and not isinstance(v, bool) and k in units and v is not None:
            value, unit = (float(v), units[k]) if si else shown(float(v), units[k])
            data[label(k, unit)] = value
    return pd.Series(data, name=name, dtype=float)


class TripViews:
    """``_repr_html_``, :meth:`to_series`, :meth:`to_frame` and :meth:`plot` of a :class:`~ropemodel.trips.Trip`."""

    #: summary key → SI unit (the class's own table)
    units: ClassVar[dict[str, str]] = {}
    summary: dict
    direction: str
    scene: Any

    def to_series(self, si: bool = False):
        """The summary as a Series, labels with units: ``F_C_max [kN]``, ``E_trip [kWh]`` (SI with ``si``)."""
        return _series(self.summary, self.units, f"{self.scene.name}: trip {self.direction}", si)

    def to_frame(self):
        """The trip sampled in time (``history``: ``t [s]``, ``x_m [m]``, ``F_C [N]``, ``P [W]``, ...)."""
        trip: Any = self       # a Trip: its history is a property of its own
        return trip.history

    def _repr_html_(self) -> str:
        numbers, rest = summary_rows({**self.summary, "direction": self.direction}, self.units)
        parts = [html.table(("name", "value", "unit"), numbers, "summary")]
        return html.page(f"{self.scene.name}: trip {self.direction}", *parts,
                         notes=[", ".join(f"{k} {v}" for k, v in rest)])

    def plot(self, ax: Any = None) -> Any:
        """The drive's power along the trip, N_p [kW] (motoring > 0, braking < 0), and the drum's, P_drum;
        returns the axes."""
        ax = axes(ax)
        h = self.to_frame()
        P = h["N_p [W]"] / 1e3
        ax.plot(h["t [s]"], P, label="N_p, drive power")
        ax.plot(h["t [s]"], h["P_drum [W]"] / 1e3, "--", lw=0.8, label="P_drum, at the drum")
        ax.fill_between(h["t [s]"], P, 0.0, where=P >= 0, alpha=0.15, label="motoring")
        ax.fill_between(h["t [s]"], P, 0.0, where=P < 0, alpha=0.15, color="C3", label="braking")
        ax.axhline(0.0, color="0.4", lw=0.8)
        return finish(ax, f"{self.scene.name}: trip {self.direction}", "t [s]", "P [kW]")


class SimulationViews:
    """``_repr_html_``, :meth:`to_series`, :meth:`to_frame` and :meth:`plot` of a
    :class:`~ropemodel.dynamics.Simulation`."""

    summary: dict
    scene: Any
    system: Any
    history: Any

    def __init__(self, scene, system) -> None:
        self.scene, self.system = scene, system
        self._t: list = []
        self._o: list = []
        self._modes: list = []

    @property
    def setup(self):
        return self.system.setup

    def record(self, times, X, out, mode):
        """Keep what the integrator hands over for one stretch in one mode: output ``times`` [s], the
        states ``X`` (not kept) and the outputs ``out`` (one row per output name)."""
        self._t.append(np.asarray(times, float))
        self._o.append(np.asarray(out, float))
        self._modes += [mode] * len(times)

    def _history(self, work: str):
        """The recorded stretches as one DataFrame: ``t [s]``, every output, the energy E from its start,
        the drive's work renamed ``work`` and the balance residual W − E − D; one column per variant with
        modes.  Raises SolveError at the first non-finite row (an integrator failure)."""
        import pandas as pd

        t = np.concatenate(self._t)
        names = self.system.functions(0, self._modes[0]).out_names
        out = dict(zip(names, np.concatenate(self._o, axis=1)))
        W = out.pop("W_drum [J]")
        out["E [J]"] = out["E [J]"] - out["E [J]"][0]
        columns = {"t [s]": t, **out, work: W, "energy_residual [J]": W - out["E [J]"] - out["D [J]"]}
        for p in self.system.parts:
            if p.column:
                columns[p.column] = [m[p.effect] for m in self._modes]
        history = pd.DataFrame(columns)
        bad = ~np.isfinite(history.select_dtypes("number").to_numpy()).all(axis=1)
        if bad.any():
            raise SolveError(f"the transient has non-finite values from t = {t[bad.argmax()]:.6g} s on "
                             f"(an integrator failure); try a tighter [numerics] sim_rtol")
        return history

    @property
    def summary_units(self) -> dict[str, str]:
        """Unit of every number of the summary (SI): :data:`SIMULATION_UNITS`, or that of the history
        column it is the extreme, end or static value of."""
        columns = {c.split(" [")[0]: c.split(" [")[1][:-1] for c in self.to_frame().columns if " [" in c}
        out = {}
        for k in self.summary:
            base = next((k[: -len(s)] for s in _SUFFIXES if k.endswith(s)), k)
            unit = SIMULATION_UNITS.get(k) or columns.get(k) or columns.get(base)
            if unit is not None:
                out[k] = unit
        return out

    def to_series(self, si: bool = False):
        """The summary's numbers as a Series, labels with units: ``F_C_max [kN]`` (SI with ``si``)."""
        return _series(self.summary, self.summary_units, self.scene.name, si)

    def to_frame(self):
        """The history: one row per output time, SI units in the column names (``t [s]``, ``F_C [N]``, ...)."""
        return self.history

    def _repr_html_(self) -> str:
        summary = {k: v for k, v in self.summary.items() if k != "moving_masses"}
        numbers, rest = summary_rows(summary, self.summary_units)
        masses = [(k, v, "kg") for k, v in self.summary.get("moving_masses", {}).items()]
        parts = [html.table(("name", "value", "unit"), numbers, "summary"),
                 html.table(("name", "value"), rest, "what happened", numeric=()),
                 html.table(("mass", "value", "unit"), masses, "moving masses")]
        return html.page(f"{self.scene.name}: {self.summary.get('dynamics', 'transient')}", *parts)

    def plot(self, ax: Any = None) -> Any:
        """F_C and F_S against time [kN], with the static forces they settle on; returns the axes."""
        ax = axes(ax)
        h, s = self.to_frame(), self.summary
        for i, rope in enumerate(("F_C", "F_S")):
            ax.plot(h["t [s]"], h[f"{rope} [N]"] / 1e3, color=f"C{i}", label=rope)
            if math.isfinite(s.get(f"{rope}_static", math.nan)):
                ax.axhline(s[f"{rope}_static"] / 1e3, color=f"C{i}", ls="--", lw=0.8, label=f"{rope}, static")
        return finish(ax, f"{self.scene.name}: {s.get('dynamics', 'transient')}", "t [s]", "force [kN]")


class SweepFileViews:
    """``_repr_html_`` and :meth:`to_frame` of a :class:`~ropemodel.sweeps.runner.SweepFile`."""

    path: Any
    rows: int
    columns: list[str]
    status: str

    def to_frame(self):
        """The file read back (CSV or Parquet), columns labelled with their units."""
        import pandas as pd

        return pd.read_parquet(self.path) if str(self.path).endswith(".parquet") else pd.read_csv(self.path)

    def _repr_html_(self) -> str:
        cols = html.table(("column",), [(c,) for c in self.columns], "columns", numeric=())
        return html.page(f"sweep {self.status}: {self.path} ({self.rows} points x {len(self.columns)} columns)",
                         cols, notes=["to_frame() reads it"])


def finite_summary(obj):
    """``obj`` (a summary: dicts, lists, numbers) as it is; :class:`ValueError` naming a non-finite number."""
    if isinstance(obj, float) and not math.isfinite(obj):
        raise ValueError(f"non-finite value {obj} in a simulation summary")
    if isinstance(obj, dict):
        return {k: finite_summary(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [finite_summary(v) for v in obj]
    return obj
