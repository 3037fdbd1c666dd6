"""Hybrid integration: CasADi BDF integrators between events, events located by root finding.

Time is scaled per call, t = t0 + h·τ with τ ∈ [0, 1] and (t0, h) parameters, so one
compiled integrator serves every interval of a mode.  Each call integrates a chunk of
``CHUNK`` output steps (``[numerics] sim_dt``); the integrator's dense output gives the state
on a detection grid of ``SUB`` points per output step (interpolated: the BDF's internal
steps do not depend on it).

Events not stepped over.  On every detection interval [t_j, t_j+1] (length δ = sim_dt/SUB)
each switching function g is checked with its value *and its rate* ġ = ∇g·ẋ + ∂g/∂t at both
ends (compiled from the mode's ODE):

* a sign change (g_j ≥ 0 > g_j+1) is located by Brent's method on g of the state integrated
  from t_j (each evaluation one integrator call, to ``xtol`` in time);
* an *excursion* below zero that begins and ends inside the interval (both ends positive,
  e.g. a slip episode shorter than the output step) is caught by the cubic Hermite
  interpolant of (g, ġ) at the ends dipping below zero: its minimum is located by bounded
  minimisation of g of the re-integrated state, and if that is negative, the first crossing
  by Brent's method on [t_j, t_min].

The rate argument: the Hermite cubic H differs from g by at most δ⁴ max|g⁗|/384 on the
interval, so every excursion deeper than that is found, whatever its length; one shallower
than the interpolation error can still be missed.  For a switching function oscillating at
ω with amplitude A, |g⁗| = Aω⁴: with the default sim_dt = 0.02 s (δ = 0.01 s) and the load
mode of the Fig. 9 haulage (ω ≈ 2 rad/s) the bound is 4e-10·A; at sim_dt = 0.7 s, 6e-4·A.
(The tests' slip excursions, driven by a cosine ramp, ω = π/t_ramp = 0.63 rad/s, bound 6e-6·A
at sim_dt = 0.7 s, are 1e-3·A and 1e-5·A deep: both found.)  The location itself is to the
integrator's tolerance.

Thresholds.  A function that starts a mode above ``ARM_TOL`` is *armed* and fires below 0.
One that starts within ±ARM_TOL (e.g. the slip speed at the onset of slip) is *banded*: it
fires below −ARM_TOL, so that rounding at its start cannot fire it at once, and the event is
then moved back to where it crossed 0 after its highest point, so that an excursion too
short to be seen above ARM_TOL at a detection point (a slip of 21 ms and 0.9 nm in the tests)
still ends where g = 0.  Once above ARM_TOL at a detection point it is armed.  One that
starts below −ARM_TOL (an inconsistent start) fires only after it has been armed.

CasADi 3.8's own event support (``zero`` outputs with a ``transition`` function, marked
experimental) was tried first.  It fails with CV_ILL_INPUT ("tout too far back in direction
of integration") when a crossing lies before the integrator's last internal step, e.g.
ẏ = t, zero = 2e-4 − y on the output grid 0.04, 0.08, ... s (crossing at 0.02 s), the pattern
of the slip speed at the onset of slip (starts at 0 with zero slope); so it is not used.

Phase boundaries of the drive profile (the ramp's kink) and t_end are known time
events: chunks end exactly on them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ropemodel.dynamics.system import OUT, LoopSystem, mode_functions
from ropemodel.errors import SolveError

CHUNK = 25
#: detection points per output step (the dense output between them is checked by the Hermite test)
SUB = 2
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
        grid = np.linspace(0, 1, CHUNK * SUB + 1)[1:]
        self.chunk = ca.integrator("chunk", integrator, dae, 0.0, list(grid), opts)
        self.one = ca.integrator("one", integrator, dae, 0.0, 1.0, opts)
        self.grid = grid
        # switching functions and their rates along the mode's flow, on the detection grid
        g = self.fun.g(sys.x, sys.t)
        gdot = ca.jtimes(g, sys.x, self.fun.ode) + ca.jacobian(g, sys.t)
        self.ggdot = ca.Function("ggdot", [sys.x, sys.t], [g, gdot], ["x", "t"], ["g", "gdot"])
        self.gmap = self.ggdot.map(CHUNK * SUB)
        self.omap = self.fun.out.map(CHUNK)


def hermite_min(g0, g1, d0, d1):
    """Least value and its place u ∈ [0, 1] of the cubic Hermite interpolant with values g0, g1 and
    slopes d0, d1 (per unit u) at the ends, for arrays of functions."""
    # H(u) = g0 + d0 u + (3(g1 − g0) − 2d0 − d1) u² + (2(g0 − g1) + d0 + d1) u³
    b, c3 = 3 * (g1 - g0) - 2 * d0 - d1, 2 * (g0 - g1) + d0 + d1
    A, B, C = 3 * c3, 2 * b, d0                         # H'(u) = A u² + B u + C
    best_v, best_u = np.minimum(g0, g1), np.where(g0 <= g1, 0.0, 1.0)
    disc = B * B - 4 * A * C
    with np.errstate(divide="ignore", invalid="ignore"):
        sq = np.sqrt(np.maximum(disc, 0.0))
        lin = np.where(B != 0, -C / np.where(B != 0, B, 1.0), -1.0)
        for r in ((-B - sq) / (2 * A), (-B + sq) / (2 * A)):
            u = np.where(np.abs(A) > 1e-14 * (np.abs(B) + np.abs(C) + 1e-300), r, lin)
            ok = (disc >= 0) & (u > 0) & (u < 1) & np.isfinite(u)
            v = g0 + d0 * u + b * u * u + c3 * u ** 3
            better = ok & (v < best_v)
            best_v, best_u = np.where(better, v, best_v), np.where(better, u, best_u)
    return best_v, best_u


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
        armed = banded = None
        while t < t_end * (1 - 1e-14):
            while t >= self.phases[k].t1 * (1 - 1e-14) and k + 1 < len(self.phases):
                k += 1
                mode = choose(x, t, k, mode)
                armed = None
            m = self.mode(k, mode)
            if armed is None:
                g_start = np.array(m.fun.g(x, t)).ravel()
                armed, banded = g_start > ARM_TOL, g_start >= -ARM_TOL
            h = min(CHUNK * self.dt, self.phases[k].t1 - t)
            try:
                X = np.array(m.chunk(x0=x, p=[t, h])["xf"])
            except RuntimeError as exc:
                raise SolveError(f"the integrator failed after t = {t:.6g} s (mode {mode}): {exc}") from None
            times = t + h * m.grid
            hit, armed_at, G = self._detect(m, x, t, X, times, armed, banded)
            if hit is None:
                self._record(m, times[SUB - 1::SUB], X[:, SUB - 1::SUB], on_record, mode)
                x, t = X[:, -1], times[-1]
                armed = armed_at
                continue
            j = hit[0]
            x_a, t_a = (x, t) if j == 0 else (X[:, j - 1], times[j - 1])
            best = self._locate(m, hit, x_a, t_a, times[j] - t_a, armed_at, t_end)
            if best is None:                       # false alarm: accept the interval and go on
                armed = armed_at | (G[:, j] > ARM_TOL)
                if times[SUB - 1:j + 1:SUB].size:
                    self._record(m, times[SUB - 1:j + 1:SUB], X[:, SUB - 1:j + 1:SUB], on_record, mode)
                x, t = X[:, j], times[j]
                continue
            if times[SUB - 1:j:SUB].size:
                self._record(m, times[SUB - 1:j:SUB], X[:, SUB - 1:j:SUB], on_record, mode)
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

    @staticmethod
    def _detect(m: _Mode, x, t, X, times, armed, banded):
        """The first detection interval j where a switching function crosses or dips below its threshold.

        Returns (hit, armed, G): hit = (j, crossed functions, dipped functions, Hermite minimum places u)
        or None; ``armed`` at the start of interval j (or after the chunk when there is no hit); G the
        switching functions on the detection grid.  Armed functions fire below 0, banded ones (within
        ±ARM_TOL at the mode's start, not yet armed) below −ARM_TOL, the others not at all.
        """
        n_det = CHUNK * SUB
        if not m.fun.g_names:
            return None, armed, np.zeros((0, n_det))
        G, Gd = (np.array(a).reshape(-1, n_det) for a in m.gmap(X, times[None, :]))
        g0, d0 = (np.array(a) for a in m.ggdot(x, t))
        Gp, Dp = np.hstack([g0, G[:, :-1]]), np.hstack([d0, Gd[:, :-1]])     # values at the interval starts
        delta = np.diff(np.concatenate([[t], times]))
        # armed at the start of each interval: before the chunk, or above ARM_TOL at an earlier point
        above = np.logical_or.accumulate(G > ARM_TOL, axis=1)
        armed_at = armed[:, None] | np.hstack([np.zeros((len(armed), 1), bool), above[:, :-1]])
        active = armed_at | banded[:, None]
        band = np.where(armed_at, 0.0, ARM_TOL)
        crossed = active & (G + band < 0)
        low, u = hermite_min(Gp + band, G + band, Dp * delta, Gd * delta)
        dipped = active & ~crossed & (Gp + band >= 0) & (G + band >= 0) & (low < 0)
        flagged = (crossed | dipped).any(axis=0)
        if not flagged.any():
            return None, armed_at[:, -1] | (G[:, -1] > ARM_TOL), G
        j = int(np.argmax(flagged))
        return (j, np.flatnonzero(crossed[:, j]), np.flatnonzero(dipped[:, j]), u[:, j]), armed_at[:, j], G

    def _locate(self, m: _Mode, hit, x_a, t_a, h_j, armed, t_end):
        """Time (from t_a) and index of the first crossing in the flagged interval, or None (false alarm).

        Each function evaluation integrates from (x_a, t_a).  A dip: its lowest point by bounded
        minimisation, then the crossing before it by Brent.  A banded function (not armed) is found
        where it passes −ARM_TOL; if it rose above 0 before, the crossing of 0 after its highest point
        is taken, so that a short excursion (a slip shorter than the detection step) ends at g = 0.
        """
        _, crossed, dipped, u = hit
        xtol = 1e-12 * max(1.0, t_end)
        best = None
        for i in list(crossed) + list(dipped):
            def g_i(s, i=i):
                xs = x_a if s <= 0 else self._step(m, x_a, t_a, s)
                return float(np.array(m.fun.g(xs, t_a + s))[i, 0])

            band = 0.0 if armed[i] else ARM_TOL

            def f(s, i=i):
                return g_i(s) + band

            hi = h_j
            if i in dipped:                        # an excursion inside the interval: find its lowest point
                res = minimize_scalar(f, bounds=(0.0, h_j), method="bounded", options={"xatol": 1e-10 * max(1.0, t_end)})
                s_min = min(float(res.x), u[i] * h_j, key=f)
                if f(s_min) >= 0:
                    continue                       # the interpolant's dip was not real
                hi = s_min
            s_star = 0.0 if f(0.0) <= 0 else brentq(f, 0.0, hi, xtol=xtol, rtol=1e-14)
            if band > 0 and s_star > 0:            # back to g = 0 after the excursion, if there was one
                res = minimize_scalar(lambda s: -g_i(s), bounds=(0.0, s_star), method="bounded",
                                      options={"xatol": 1e-10 * max(1.0, t_end)})
                s_top = float(res.x)
                if g_i(s_top) > 0:
                    s_star = brentq(g_i, s_top, s_star, xtol=xtol, rtol=1e-14)
            if best is None or s_star < best[0]:
                best = (s_star, i)
        return best

    def _record(self, m: _Mode, times, X, on_record, mode):
        n = X.shape[1]
        if n == CHUNK:
            out = np.array(m.omap(X, times[None, :]))
        else:
            out = np.column_stack([np.array(m.fun.out(X[:, j], times[j])).ravel() for j in range(n)])
        on_record(times, X, out, mode)


__all__ = ["HybridIntegrator", "Event", "OUT"]
