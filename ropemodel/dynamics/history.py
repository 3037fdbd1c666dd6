"""The result of a transient: history (units in the column names), summary and events."""

from __future__ import annotations

import json

import numpy as np

from ropemodel.views.records import SimulationViews, finite_summary


class Simulation(SimulationViews):
    """A simulated start-up or braking (the result of a machine that declares no result of its own).

    Attributes
    ----------
    history: DataFrame, one row per output time, SI units in the column names: the columns every
        variant publishes (drum and load speeds, slip speed and accumulated slip, F_C and F_S at the
        drum's tangent points, the tension pulling the return sheave, the tensioner's take-up z — rope
        length, the paper's stroke measure — and the carriage's travel z/2, the least element tension,
        ...), the drum's work W, the change of kinetic + potential energy E, the dissipated energy D and
        the balance residual W − E − D, and one column per variant with modes (``drum``, ``tensioner``,
        ``drive``).
    summary: dict of SI numbers and flags (see :meth:`to_dict`).
    events: located events (time, name, modes after it, state and history columns there).

    In Jupyter it shows its summary with units; ``to_series()``, ``to_frame()`` (the history) and
    ``plot()`` (the rope forces against time).
    """

    def finish(self, events):
        self.history = self._history("W_drum [J]")
        self.events = events
        self.summary = self._summarise()

    def _summarise(self) -> dict:
        h, nums, parts = self.history, self.setup.numbers, self.system.parts
        F_C_static, F_S_static = (float(nums[f"{f}_{self.setup.travel}"]) for f in ("F_C", "F_S"))
        W_max = max(float(np.max(np.abs(h["W_drum [J]"]))), float(np.max(np.abs(h["D [J]"]))), 1.0)
        masses = {}
        for p in parts:
            masses.update({k: float(v) for k, v in p.moving_masses().items()})
        out = {}
        for p in parts:                                  # what the transient is (travel, profile) first
            if p.order < 10:
                out.update(p.summary(self))
        out.update({
            "F_C_max": float(h["F_C [N]"].max()), "F_C_end": float(h["F_C [N]"].iloc[-1]),
            "F_S_min": float(h["F_S [N]"].min()), "F_S_end": float(h["F_S [N]"].iloc[-1]),
            "v_load_end": float(h["v_load [m/s]"].iloc[-1]), "v_drum_end": float(h["v_drum [m/s]"].iloc[-1]),
            "F_C_static": F_C_static, "F_S_static": F_S_static,
            "dynamic_factor": float(h["F_C [N]"].max()) / F_C_static,
        })
        for p in parts:
            if p.order >= 10:
                out.update(p.summary(self))
        out.update({"energy_residual": float(np.max(np.abs(h["energy_residual [J]"]))) / W_max,
                    "moving_masses": masses, "t_end": float(h["t [s]"].iloc[-1])})
        return out

    def to_dict(self) -> dict:
        """The summary (SI): peak and end forces, dynamic factor, the load's position, slip, stroke and
        drive reports, the moving masses."""
        return dict(self.summary)

    def to_json(self) -> str:
        return json.dumps(finite_summary(self.summary), indent=2, allow_nan=False)

    def report(self) -> str:
        """A readable account of the transient in kN, mm, s."""
        s = self.summary
        chosen = ", ".join(f"{p.effect} {p.variant}" for p in self.system.parts)
        lines = [f"{self.scene.name}: {chosen} ({s['n_nodes']} nodes)",
                 f"  F_C max {s['F_C_max'] / 1e3:10.2f} kN   static {s['F_C_static'] / 1e3:8.2f} kN   "
                 f"dynamic factor {s['dynamic_factor']:.4f}",
                 f"  F_C end {s['F_C_end'] / 1e3:10.2f} kN   F_S end {s['F_S_end'] / 1e3:8.2f} kN   "
                 f"(static {s['F_S_static'] / 1e3:.2f} kN)",
                 f"  F_S min {s['F_S_min'] / 1e3:10.2f} kN",
                 f"  at t = {s['t_end']:.3f} s: load {s['v_load_end']:.4g} m/s, drum {s['v_drum_end']:.4g} m/s"]
        for p in self.system.parts:
            lines += p.report(s)
        masses = ", ".join(f"{k} {v:.6g} kg" for k, v in s["moving_masses"].items())
        lines += [f"  moving masses: {masses}",
                  f"  energy balance residual {s['energy_residual']:.2e} of the drum's work"]
        return "\n".join(lines + [line for p in self.system.parts for line in p.ending(s)])
