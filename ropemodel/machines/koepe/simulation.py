"""The result of a Koepe transient: history (units in the column names), summary (SI) and events."""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from ropemodel.errors import SolveError
from ropemodel.views.plotting import axes, finish
from ropemodel.views.records import SimulationViews, finite_summary

#: the instant's columns named in the summary at the worst instant
INSTANT = {"T_L [N]": "T_L", "T_E [N]": "T_E", "v_rope [m/s]": "v_rope", "a_rope [m/s^2]": "a_rope",
           "y_L [m]": "y_L", "slip_margin [N]": "slip_margin"}
#: the events where the ropes start to slip on the wheel
SLIP_EVENTS = ("slip_L", "slip_E")


class KoepeSimulation(SimulationViews):
    """A simulated braking or start of a Koepe hoist with elastic head ropes.

    Attributes
    ----------
    history: DataFrame, one row per output time, SI units in the column names: the tangent tensions at the wheel
        ``T_L [N]`` (loaded side) and ``T_E [N]``, the least tension anywhere in the head ropes ``T_min [N]``, the
        margin against slip ``slip_margin [N]`` (>= 0 while the ropes stick: the smaller of the slip conditions
        toward either side), the speeds and accelerations of the ropes on the wheel and of the wheel, the wheel's
        force ``F_wheel [N]`` (+ toward the loaded conveyance rising: a brake while hoisting is negative), the
        slip, the conveyances' depths, the energy balance, and one column per variant with modes.
    summary: dict of SI numbers and flags (see :meth:`to_dict`).
    events: located events (time, name, modes after it, state and history columns there).
    """

    def finish(self, events):
        self.history = self._history("W_wheel [J]")
        self.events = events
        run_out = next((e for e in events if e.name == "run_out"), None)
        if run_out is not None:
            prof = self.setup.part("dynamics")
            slipped = next((f"; the ropes started to slip on the wheel at t = {e.t:.4g} s" for e in events
                            if e.name in SLIP_EVENTS), "")
            raise SolveError(f"at t = {run_out.t:.4g} s the ropes ran more than the {prof.reel:.4g} m over the wheel "
                             f"the mesh allows (the nominal manoeuvre runs {prof.travel_nominal:.4g} m){slipped}: "
                             f"the results beyond are not computed; give a t_end before {run_out.t:.4g} s")
        self.summary = self._summarise()

    def _summarise(self) -> dict:
        h, parts = self.history, self.system.parts
        out: dict[str, Any] = {}
        for p in parts:                                  # what the transient is first
            if p.order < 10:
                out.update(p.summary(self))
        out.update(self._tensions(h))
        out.update(self._motion(h))
        for p in parts:
            if p.order >= 10:
                out.update(p.summary(self))
        onset = next((e for e in self.events if e.name in SLIP_EVENTS), None)
        if onset is not None:                            # the worst instant is where the ropes start to slip
            out.update({"t_worst": float(onset.t),
                        "worst": {name: float(onset.values[col]) for col, name in INSTANT.items()}})
        masses: dict[str, float] = {}
        for p in parts:
            masses.update({k: float(v) for k, v in p.moving_masses().items()})
        scale = max(float(np.max(np.abs(h["W_wheel [J]"]))), float(np.max(np.abs(h["D [J]"]))), 1.0)
        out.update({"energy_residual": float(np.max(np.abs(h["energy_residual [J]"]))) / scale,
                    "moving_masses": masses, "t_end": float(h["t [s]"].iloc[-1]),
                    "sim_rtol": float(self.scene.numerics["sim_rtol"])})
        return out

    @staticmethod
    def _tensions(h) -> dict:
        """Peak and least tensions and the worst instant for slip (the least slip margin), with their times."""
        t = h["t [s]"].to_numpy()
        out: dict[str, Any] = {"T_L_start": float(h["T_L [N]"].iloc[0]), "T_E_start": float(h["T_E [N]"].iloc[0])}
        for side in ("T_L", "T_E"):
            col = h[f"{side} [N]"].to_numpy()
            out.update({f"{side}_max": float(col.max()), f"t_{side}_max": float(t[col.argmax()]),
                        f"{side}_min": float(col.min()), f"t_{side}_min": float(t[col.argmin()])})
        margin = h["slip_margin [N]"].to_numpy()
        i = int(margin.argmin())          # without slip the least margin; with slip its onset (_summarise)
        out.update({"slip_margin_start": float(margin[0]), "slip_margin_min": float(margin[i]),
                    "t_worst": float(t[i]),
                    "worst": {name: float(h[col].iloc[i]) for col, name in INSTANT.items()}})
        return out

    @staticmethod
    def _motion(h) -> dict:
        """When and where the wheel came to rest, the largest wheel force and rope acceleration."""
        v = h["v_wheel [m/s]"].to_numpy()
        rest = np.flatnonzero(np.abs(v) <= 1e-9 * max(float(np.abs(v).max()), 1e-300))
        t = h["t [s]"].to_numpy()
        return {"v_wheel_end": float(v[-1]), "t_rest": float(t[rest[0]]) if rest.size and v[0] != 0 else None,
                "run": float(h["x [m]"].iloc[-1]), "F_wheel_max": float(np.max(np.abs(h["F_wheel [N]"]))),
                "a_rope_max": float(np.max(np.abs(h["a_rope [m/s^2]"])))}

    def to_dict(self) -> dict:
        """The summary (SI): tensions at the wheel (start, peak, least, with their times), the least tension in
        the head ropes, the least slip margin and the instant it occurs (``t_worst``, ``worst``), slip episodes,
        the stop (``t_rest``, ``run``), the energy balance, the moving masses."""
        return dict(self.summary)

    def to_json(self) -> str:
        return json.dumps(finite_summary(self.summary), indent=2, allow_nan=False)

    def report(self) -> str:
        """A readable account of the transient in kN, m, s."""
        s = self.summary
        chosen = ", ".join(f"{p.effect} {p.variant}" for p in self.system.parts)
        w = s["worst"]
        lines = [f"{self.scene.name}: {chosen} ({s['n_nodes']} nodes, sim_rtol {s['sim_rtol']:g})"]
        for p in self.system.parts:
            if p.order < 10:
                lines += p.report(s)
        lines += [_side_line(s, "T_L", "T_L (loaded side)"), _side_line(s, "T_E", "T_E (other side) "),
                  f"  least tension in the head ropes {s['T_min'] / 1e3:.2f} kN at t = {s['t_T_min']:.3f} s",
                  f"  slip margin: start {s['slip_margin_start'] / 1e3:.2f} kN, least "
                  f"{s['slip_margin_min'] / 1e3:.2f} kN at t = {s['t_worst']:.3f} s (the worst instant: T_L "
                  f"{w['T_L'] / 1e3:.2f} kN, T_E {w['T_E'] / 1e3:.2f} kN, ropes at {w['v_rope']:.3f} m/s, "
                  f"{w['a_rope']:.3f} m/s², loaded conveyance at y = {w['y_L']:.1f} m)"]
        rest = (f"at rest at t = {s['t_rest']:.3f} s" if s["t_rest"] is not None
                else f"at {s['v_wheel_end']:.4g} m/s at t = {s['t_end']:.3f} s")
        lines.append(f"  wheel {rest}; ropes ran {s['run']:.3f} m; largest wheel force "
                     f"{s['F_wheel_max'] / 1e3:.2f} kN, largest rope acceleration {s['a_rope_max']:.3f} m/s²")
        for p in self.system.parts:
            if p.order >= 10:
                lines += p.report(s)
        lines.append(f"  energy balance residual {s['energy_residual']:.2e} of the wheel's work")
        if s["slack"]:
            lines.append(f"  STOPPED at t = {s['t_stopped']:.3f} s: a head rope went slack (a tension reached 0); the "
                         f"linear rope model does not hold beyond, the results end there")
        return "\n".join(lines)

    def plot(self, ax: Any = None) -> Any:
        """T_L and T_E at the wheel against time [kN]; returns the axes."""
        ax = axes(ax)
        h = self.to_frame()
        for i, side in enumerate(("T_L", "T_E")):
            ax.plot(h["t [s]"], h[f"{side} [N]"] / 1e3, color=f"C{i}", label=side)
        return finish(ax, f"{self.scene.name}: {self.summary.get('dynamics', 'transient')}", "t [s]", "tension [kN]")


def _side_line(s: dict, side: str, label: str) -> str:
    return (f"  {label} at the wheel: start {s[f'{side}_start'] / 1e3:9.2f} kN, "
            f"max {s[f'{side}_max'] / 1e3:9.2f} kN at t = {s[f't_{side}_max']:.3f} s, "
            f"min {s[f'{side}_min'] / 1e3:9.2f} kN at t = {s[f't_{side}_min']:.3f} s")
