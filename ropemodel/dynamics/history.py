"""The result of a transient: history (units in the column names), summary and events."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd

from ropemodel.dynamics.system import OUT
from ropemodel.errors import SolveError


class Simulation:
    """A simulated start-up or braking of a winch scene.

    Attributes
    ----------
    history: DataFrame, one row per output time, SI units in the column names: time, drum and
        load speeds, slip speed (drum − rope on the drum) and accumulated slip, F_C and F_S at
        the drum's tangent points, the tension pulling the return sheave (both sides), the
        tensioner take-up z (rope length, the paper's stroke measure) and the carriage's travel
        z/2, the drum's work W, the change of kinetic + potential energy E, the dissipated
        energy D and the balance residual W − E − D, the least element tension, the modes.
    summary: dict of SI numbers and flags (see :meth:`to_dict`).
    events: located events (time, name, modes after it).
    """

    def __init__(self, scene, static, chain, sign, ratio):
        self.scene, self.static, self.chain, self.sign, self.ratio = scene, static, chain, sign, ratio
        self._t, self._x, self._o, self._modes = [], [], [], []

    def record(self, times, X, out, mode):
        self._t.append(np.asarray(times, float))
        self._x.append(np.asarray(X, float))
        self._o.append(np.asarray(out, float))
        self._modes += [tuple(mode)] * len(times)

    def finish(self, events, sys):
        t = np.concatenate(self._t)
        X = np.concatenate(self._x, axis=1)
        O = dict(zip(OUT, np.concatenate(self._o, axis=1)))
        n = self.chain.n
        z, s_d, W, D = X[2 * n], X[2 * n + 2], X[2 * n + 3], X[2 * n + 4]
        E = O["E"] - O["E"][0]
        self.history = pd.DataFrame({
            "t [s]": t, "v_drum [m/s]": O["v_drum"], "v_load [m/s]": O["v_load"],
            "slip_speed [m/s]": O["v_drum"] - O["v_rope_drum"], "slip [m]": s_d - X[0],
            "F_C [N]": O["F_C"], "F_S [N]": O["F_S"], "T_sheave [N]": O["T_sheave"],
            "take_up [m]": z, "carriage [m]": z / 2, "W_drum [J]": W, "E [J]": E, "D [J]": D,
            "energy_residual [J]": W - E - D, "T_min [N]": O["T_min"],
            "drum": [m[0] for m in self._modes], "tensioner": [m[1] for m in self._modes],
            "drive": [m[2] for m in self._modes],
        })
        numeric = self.history.select_dtypes("number").to_numpy()
        bad = ~np.isfinite(numeric).all(axis=1)
        if bad.any():
            raise SolveError(f"the transient has non-finite values from t = {t[bad.argmax()]:.6g} s on "
                             f"(an integrator failure); try a tighter [numerics] sim_rtol")
        self.events = events
        self.summary = self._summarise(events)

    def _summarise(self, events):
        h, vals = self.history, self.static.values
        d = "up" if self.sign > 0 else "down"
        F_C_static, F_S_static = vals[f"F_C_{d}"], vals[f"F_S_{d}"]
        slips, start = [], None
        first = h["drum"].iloc[0]
        if first in ("slip_fwd", "slip_back"):                 # slipping from the start
            start = (0.0, float(h["slip [m]"].iloc[0]), first)
        for ev in events:
            if ev.name in ("slip_fwd", "slip_back") and start is None:
                start = (ev.t, _slip_at(self.chain.n, ev.state), ev.name)
            elif ev.name == "stick" and ev.drum == "stick" and start is not None:
                slips.append(_slip_interval(start, ev.t, _slip_at(self.chain.n, ev.state)))
                start = None
        if start is not None:
            slips.append(_slip_interval(start, None, float(h["slip [m]"].iloc[-1])))
        stroke_events = [{"t": ev.t, "event": ev.name} for ev in events
                         if ev.name in ("stroke_end", "stroke_start", "release")]
        drive_events = [{"t": ev.t, "event": ev.name} for ev in events
                        if ev.name in ("torque_pos", "torque_neg", "on_profile")]
        first_drive = h["drive"].iloc[0]
        if first_drive != "profile":                          # at the torque limit from the start
            drive_events.insert(0, {"t": 0.0, "event": "torque_pos" if first_drive == "limited_pos" else "torque_neg"})
        W_max = max(float(np.max(np.abs(h["W_drum [J]"]))), float(np.max(np.abs(h["D [J]"]))), 1.0)
        tens = self.scene.effects["tensioner"]
        return {
            "direction": d,
            "dynamics": self.scene.effects["dynamics"],
            "F_C_max": float(h["F_C [N]"].max()),
            "F_C_end": float(h["F_C [N]"].iloc[-1]),
            "F_S_min": float(h["F_S [N]"].min()),
            "F_S_end": float(h["F_S [N]"].iloc[-1]),
            "v_load_end": float(h["v_load [m/s]"].iloc[-1]),
            "v_drum_end": float(h["v_drum [m/s]"].iloc[-1]),
            "F_C_static": F_C_static,
            "F_S_static": F_S_static,
            "dynamic_factor": float(h["F_C [N]"].max()) / F_C_static,
            "traction_ratio": self.ratio,
            "slip": bool(slips),
            "slip_distance": float(abs(h["slip [m]"].iloc[-1])),
            "slip_events": slips,
            "stroke_used": float(h["take_up [m]"].max()),
            "stroke": float(vals["stroke"]) if tens == "constant_force" else None,
            "stroke_exhausted": any(e["event"] == "stroke_end" for e in stroke_events)
                                or bool((h["tensioner"] == "at_end").any()),
            "stroke_events": stroke_events,
            "torque_limited": bool((h["drive"] != "profile").any()),
            "drive_events": drive_events,
            "slack": any(ev.name == "slack" for ev in events),
            "t_slack": next((ev.t for ev in events if ev.name == "slack"), None),
            "T_min": float(h["T_min [N]"].min()),
            "energy_residual": float(np.max(np.abs(h["energy_residual [J]"]))) / W_max,
            "moving_masses": {k: float(v) for k, v in self.chain.masses.items()}
                             | ({"carriage": float(vals["m_t"])} if tens == "constant_force"
                                and not self.chain.rigid else {}),
            "n_nodes": self.chain.n,
            # drum_contact = "capstan": the contact stiffnesses [N/m] (None: rigid side) and Li's F_p, F_T [N]
            "drum_contact": {k: (float(v) if math.isfinite(v) else None) for k, v in self.chain.contact.items()}
                            or None,
            "t_end": float(h["t [s]"].iloc[-1]),
        }

    def to_dict(self) -> dict:
        """The summary (SI): peak and end forces, dynamic factor, slip and stroke reports."""
        return dict(self.summary)

    def to_json(self) -> str:
        return json.dumps(_finite(self.summary), indent=2, allow_nan=False)

    def report(self) -> str:
        """A readable account of the transient in kN, mm, s."""
        s = self.summary
        lines = [f"{self.scene.name}: {s['dynamics']} ({s['direction']}), rope {self.scene.effects['rope_elasticity']}"
                 f", tensioner {self.scene.effects['tensioner']}, {s['n_nodes']} nodes",
                 f"  F_C max {s['F_C_max'] / 1e3:10.2f} kN   static {s['F_C_static'] / 1e3:8.2f} kN   "
                 f"dynamic factor {s['dynamic_factor']:.4f}",
                 f"  F_C end {s['F_C_end'] / 1e3:10.2f} kN   F_S end {s['F_S_end'] / 1e3:8.2f} kN   "
                 f"(static {s['F_S_static'] / 1e3:.2f} kN)",
                 f"  F_S min {s['F_S_min'] / 1e3:10.2f} kN   traction ratio {s['traction_ratio']:.4g} (at F_S static, v_pj)",
                 f"  at t = {s['t_end']:.3f} s: load {s['v_load_end']:.4g} m/s, drum {s['v_drum_end']:.4g} m/s"]
        if s["slip"]:
            for sl in s["slip_events"]:
                end = f"{sl['t_end']:.3f} s" if sl["t_end"] is not None else "the end (still slipping)"
                lines.append(f"  SLIP on the drum from t = {sl['t_start']:.3f} s to {end}: "
                             f"{sl['distance'] * 1e3:.1f} mm ({sl['kind']})")
        else:
            lines.append("  no slip on the drum")
        if s["drum_contact"]:
            K = s["drum_contact"]
            sides = ", ".join(f"{side} side {K[f'K_{side}'] / 1e6:.4g} MN/m" for side in ("C", "S")
                              if K[f"K_{side}"] is not None)
            lines.append(f"  drum contact (capstan, Li et al. eq. 12 at F_p {K['F_p'] / 1e3:.2f} kN, F_T "
                         f"{K['F_T'] / 1e3:.2f} kN): {sides or 'rigid on both sides'}")
        if s["stroke"] is not None:
            lines.append(f"  tensioner take-up max {s['stroke_used'] * 1e3:.1f} mm of {s['stroke'] * 1e3:.1f} mm")
        else:
            lines.append(f"  tensioner take-up {s['stroke_used'] * 1e3:.1f} mm (locked)")
        for ev in s["stroke_events"]:
            what = {"stroke_end": "RAN OUT OF STROKE (carriage on its end stop)",
                    "stroke_start": "carriage on its start stop", "release": "carriage free again"}[ev["event"]]
            lines.append(f"  t = {ev['t']:.3f} s: tensioner {what}")
        for ev in s["drive_events"]:
            what = {"torque_pos": "motor at its torque limit (driving): the drum falls behind the ramp",
                    "torque_neg": "motor at its torque limit (braking): the drum runs ahead of the ramp",
                    "on_profile": "drum back on the speed ramp"}[ev["event"]]
            lines.append(f"  t = {ev['t']:.3f} s: {what}")
        if s["slack"]:
            lines.append(f"  STOPPED at t = {s['t_slack']:.3f} s: the rope went slack (a tension reached 0); the "
                         f"linear rope model does not hold beyond, the results end there")
        lines.append(f"  energy balance residual {s['energy_residual']:.2e} of the drum's work")
        return "\n".join(lines)


def _slip_at(n, x):
    return float(x[2 * n + 2] - x[0])


def _slip_interval(start, t_end, slip_end):
    t0, s0, kind = start
    return {"t_start": float(t0), "t_end": None if t_end is None else float(t_end), "distance": abs(slip_end - s0),
            "kind": "drum ahead of the rope" if kind == "slip_fwd" else "rope overruns the drum"}


def _finite(obj):
    if isinstance(obj, float) and not math.isfinite(obj):
        raise ValueError(f"non-finite value {obj} in a simulation summary")
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_finite(v) for v in obj]
    return obj
