"""Hybrid integration: CasADi BDF integrators between events, events located by root finding.

Time is scaled per call, t = t0 + h·τ with τ ∈ [0, 1] and (t0, h) parameters, so one
compiled integrator serves every interval of a mode.  Each call integrates a chunk of
``CHUNK`` output steps; the switching functions of the current mode are evaluated at
the chunk's outputs.  Where one changes sign between two outputs, the crossing is
located by Brent's method on the switching function of the state integrated from the
last output (each evaluation one integrator call, to ``xtol`` in time), the state at
the crossing is taken, the transition applied and the integration restarted from it.
A crossing that comes and goes within one output step (``[numerics] sim_dt``) is not
seen; the default 0.02 s is below a tenth of the fastest load mode of haulage ropes.

Phase boundaries of the drive profile (the ramp's kink) and t_end are known time
events: chunks end exactly on them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np
from scipy.optimize import brentq

from ropemodel.dynamics.system import OUT, LoopSystem, mode_functions
from ropemodel.errors import SolveError

CHUNK = 25
ARM_TOL = 1e-9
MAX_EVENTS = 2000


@dataclass
class Event:
    """A located event: time, switching function, the mode (drum, tensioner, drive) after it, state."""

    t: float
    name: str
    mode: tuple
    state: np.ndarray = field(repr=False)

    @property
    def drum(self) -> str:
        return self.mode[0]

    @property
    def tensioner(self) -> str:
        return self.mode[1]


class _Mode:
    """Compiled integrators of one mode (drum, tensioner, drive) in one phase."""

    def __init__(self, sys, phase, mode, opts, f_scale, v_scale, integrator):
        self.fun = mode_functions(sys, phase, *mode, f_scale, v_scale)
        tau, p = ca.SX.sym("tau"), ca.SX.sym("p", 2)
        ode = ca.substitute(self.fun.ode, sys.t, p[0] + p[1] * tau) * p[1]
        dae = {"x": sys.x, "p": p, "t": tau, "ode": ode}
        grid = np.linspace(0, 1, CHUNK + 1)[1:]
        self.chunk = ca.integrator("chunk", integrator, dae, 0.0, list(grid), opts)
        self.one = ca.integrator("one", integrator, dae, 0.0, 1.0, opts)
        self.grid = grid
        self.gmap = self.fun.g.map(CHUNK)
        self.omap = self.fun.out.map(CHUNK)


class HybridIntegrator:
    """Integrates a :class:`LoopSystem` through its modes over the drive profile's phases."""

    def __init__(self, sys: LoopSystem, phases, rtol: float, dt: float, integrator: str,
                 f_scale: float, v_scale: float, atol_u: float = 1e-9):
        self.sys, self.phases, self.dt = sys, phases, dt
        self.integrator = integrator
        self.f_scale, self.v_scale = f_scale, v_scale
        self.opts = {"reltol": rtol, "abstol": atol_u, "max_num_steps": 200000}
        self._modes: dict = {}

    def mode(self, k, mode) -> _Mode:
        """The compiled mode ``(drum, tensioner, drive)`` of phase ``k`` (built on first use only)."""
        key = (k, tuple(mode))
        if key not in self._modes:
            self._modes[key] = _Mode(self.sys, self.phases[k], tuple(mode), self.opts, self.f_scale,
                                     self.v_scale, self.integrator)
        return self._modes[key]

    def _step(self, m: _Mode, x, t0, h):
        try:
            return np.array(m.one(x0=x, p=[t0, h])["xf"]).ravel()
        except RuntimeError as exc:
            raise SolveError(f"the integrator failed at t = {t0:.6g} s: {exc}") from None

    def run(self, x0, mode, choose, transition, on_record):
        """Integrate from t = 0 in ``mode`` = (drum, tensioner, drive).  ``choose(x, t, k, mode)`` → a
        consistent mode at the start and at phase boundaries; ``transition(name, x, t, k, mode)`` →
        (x, mode) after an event, or None to end the simulation there (a terminal event);
        ``on_record(times, X, out, mode)`` receives every accepted chunk."""
        x = np.asarray(x0, float)
        events: list[Event] = []
        t_end = self.phases[-1].t1
        k = 0
        t = 0.0
        mode = choose(x, t, k, tuple(mode))
        self._record(self.mode(k, mode), np.array([t]), x[:, None], on_record, mode)
        armed = None
        while t < t_end * (1 - 1e-14):
            while t >= self.phases[k].t1 * (1 - 1e-14) and k + 1 < len(self.phases):
                k += 1
                mode = choose(x, t, k, mode)
                armed = None
            m = self.mode(k, mode)
            if armed is None:
                armed = np.array(m.fun.g(x, t)).ravel() > ARM_TOL
            h = min(CHUNK * self.dt, self.phases[k].t1 - t)
            try:
                X = np.array(m.chunk(x0=x, p=[t, h])["xf"])
            except RuntimeError as exc:
                raise SolveError(f"the integrator failed after t = {t:.6g} s (mode {mode}): {exc}") from None
            times = t + h * m.grid
            G = np.array(m.gmap(X, times[None, :])).reshape(-1, CHUNK) if m.fun.g_names else np.zeros((0, CHUNK))
            hit = None
            for j in range(CHUNK):
                fired = armed & (G[:, j] < 0) if G.size else np.zeros(0, bool)
                if fired.any():
                    hit = (j, np.flatnonzero(fired))
                    break
                if G.size:
                    armed = armed | (G[:, j] > ARM_TOL)
            if hit is None:
                self._record(m, times, X, on_record, mode)
                x, t = X[:, -1], times[-1]
                continue
            j, which = hit
            x_a = x if j == 0 else X[:, j - 1]
            t_a = t if j == 0 else times[j - 1]
            h_j = times[j] - t_a
            if j > 0:
                self._record(m, times[:j], X[:, :j], on_record, mode)
            best = None
            for i in which:
                def g_i(s, i=i):
                    if s <= 0:
                        return float(np.array(m.fun.g(x_a, t_a))[i, 0])
                    return float(np.array(m.fun.g(self._step(m, x_a, t_a, s), t_a + s))[i, 0])

                lo = g_i(0.0)
                s_star = 0.0 if lo <= 0 else brentq(g_i, 0.0, h_j, xtol=1e-12 * max(1.0, t_end), rtol=1e-14)
                if best is None or s_star < best[0]:
                    best = (s_star, i)
            s_star, i = best
            x = self._step(m, x_a, t_a, s_star) if s_star > 0 else x_a
            t = t_a + s_star
            name = m.fun.g_names[i]
            self._record(m, np.array([t]), x[:, None], on_record, mode)
            after = transition(name, x, t, k, mode)
            if after is None:                      # a terminal event: the model's validity ends here
                events.append(Event(float(t), name, mode, x.copy()))
                break
            x, mode = after
            events.append(Event(float(t), name, mode, x.copy()))
            if len(events) > MAX_EVENTS:
                raise SolveError(f"more than {MAX_EVENTS} events by t = {t:.6g} s: the slip or stroke state "
                                 f"chatters; refine the model or check the traction")
            armed = None
        return events

    def _record(self, m: _Mode, times, X, on_record, mode):
        n = X.shape[1]
        if n == CHUNK:
            out = np.array(m.omap(X, times[None, :]))
        else:
            out = np.column_stack([np.array(m.fun.out(X[:, j], times[j])).ravel() for j in range(n)])
        on_record(times, X, out, mode)


__all__ = ["HybridIntegrator", "Event", "OUT"]
