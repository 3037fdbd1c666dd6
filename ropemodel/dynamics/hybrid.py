"""Hybrid integration: CasADi BDF integrators between events, events located by root finding.

Time is scaled per call, t = t0 + h·τ with τ ∈ [0, 1] and (t0, h) parameters, so one compiled
integrator serves every interval of a mode.  Each call integrates a chunk of ``CHUNK`` output steps
(``[numerics] sim_dt``); the integrator's dense output gives the state on a detection grid of ``SUB``
points per output step (interpolated: the BDF's internal steps do not depend on it).

Events not stepped over (:mod:`.detect`): on every detection interval each switching function is
checked with its value and its rate ġ = ∇g·ẋ + ∂g/∂t at both ends (compiled from the mode's ODE).  A
sign change is located by Brent's method on g of the state integrated from the interval's start (each
evaluation one integrator call, to ``xtol`` in time); an excursion inside the interval (both ends
positive, e.g. a slip episode shorter than the output step) is caught by the cubic Hermite
interpolant dipping below zero: its minimum is located by bounded minimisation of g of the
re-integrated state, and if that is negative, the first crossing by Brent's method before it.
For a switching function oscillating at ω with amplitude A, |g⁗| = Aω⁴: with the default
sim_dt = 0.02 s (δ = 0.01 s) and the load mode of the Fig. 9 haulage (ω ≈ 2 rad/s) the bound
δ⁴|g⁗|/384 is 4e-10·A; at sim_dt = 0.7 s, 6e-4·A.

CasADi 3.8's own event support (``zero`` outputs with a ``transition`` function, marked experimental)
was tried first.  It fails with CV_ILL_INPUT ("tout too far back in direction of integration") when a
crossing lies before the integrator's last internal step, e.g. ẏ = t, zero = 2e-4 − y on the output
grid 0.04, 0.08, ... s (crossing at 0.02 s), the pattern of the slip speed at the onset of slip
(starts at 0 with zero slope); so it is not used.

Phase boundaries of the drive profile (the ramp's pieces) and t_end are known time events: chunks end
exactly on them, and the modes are made consistent there (the drive's acceleration jumps).
"""

from __future__ import annotations

import casadi as ca
import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ropemodel.dynamics.detect import ARM_TOL, Crossing, Detection, SwitchState, first_flagged, hermite_min
from ropemodel.dynamics.system import Event, Settled, TransientSystem
from ropemodel.errors import SolveError

CHUNK = 25
#: detection points per output step (the dense output between them is checked by the Hermite test)
SUB = 2
MAX_EVENTS = 2000
#: the linear solver of the BDF's Newton iteration (cvodes and idas; the winch's and the Koepe hoist's transients):
#: sparse LU, not CasADi's default "qr".  Only the rounding of each Newton step changes
#: (tests/test_dynamics_linear_solver.py: the peaks to rounding, the history within its own integration error);
#: the cost of "qr" grows as about n^2.7 with the states.  Measured on winch_start (CPU-s, medians of three):
#: 0.23 -> 0.21, 0.40 -> 0.31, 1.11 -> 0.54, 8.0 -> 1.7 at 8 (its own), 16, 32, 64 elements; the three-segment
#: route's upward start at 32 elements a span 5.4 -> 2.3
LINEAR_SOLVER = "csparse"


class _Compiled:
    """Integrators and event-test functions of one mode in one phase."""

    def __init__(self, system: TransientSystem, k: int, mode, opts: dict, integrator: str):
        self.fun = system.functions(k, mode)
        x, t = system.x, system.t
        tau, p = ca.SX.sym("tau"), ca.SX.sym("p", 2)
        ode = ca.substitute(self.fun.ode, t, p[0] + p[1] * tau) * p[1]
        dae = {"x": x, "p": p, "t": tau, "ode": ode}
        self.grid = np.linspace(0, 1, CHUNK * SUB + 1)[1:]
        self.chunk = ca.integrator("chunk", integrator, dae, 0.0, list(self.grid), opts)
        self.one = ca.integrator("one", integrator, dae, 0.0, 1.0, opts)
        g = self.fun.g(x, t)
        gdot = ca.jtimes(g, x, self.fun.ode) + ca.jacobian(g, t)
        self.ggdot = ca.Function("ggdot", [x, t], [g, gdot], ["x", "t"], ["g", "gdot"])
        self.gmap = self.ggdot.map(CHUNK * SUB)
        self.omap = self.fun.out.map(CHUNK)

    def g(self, x, t) -> np.ndarray:
        return np.array(self.fun.g(x, t)).ravel()


class HybridIntegrator:
    """Integrates a :class:`~ropemodel.dynamics.system.TransientSystem` through its modes over the drive
    profile's phases."""

    def __init__(self, system: TransientSystem, rtol: float, dt: float, integrator: str, atol: float = 1e-9,
                 linear_solver: str | None = None):
        self.system, self.phases, self.dt, self.integrator = system, system.phases, dt, integrator
        # SUNDIALS's own messages stay off the C-level stderr: a failure is reported in the user's terms
        self.opts = {"reltol": rtol, "abstol": atol, "max_num_steps": 200000, "disable_internal_warnings": True,
                     "linear_solver": linear_solver or LINEAR_SOLVER}
        self._compiled: dict = {}

    def mode(self, k: int, mode) -> _Compiled:
        """The compiled mode of phase ``k`` (built on first use only)."""
        key = (k, mode)
        if key not in self._compiled:
            self._compiled[key] = _Compiled(self.system, k, mode, self.opts, self.integrator)
        return self._compiled[key]

    def _step(self, m: _Compiled, x, t0, h):
        try:
            return np.array(m.one(x0=x, p=[t0, h])["xf"]).ravel()
        except RuntimeError as exc:
            raise SolveError(f"the integrator failed at t = {t0:.6g} s: {exc}") from None

    def run(self, x0, mode, on_record) -> list[Event]:
        """Integrate from t = 0 in ``mode``; ``on_record(times, X, out, mode)`` receives every accepted chunk."""
        events: list[Event] = []
        t_end, k, t = self.phases[-1].t1, 0, 0.0
        now = self.system.settle(np.asarray(x0, float), t, k, mode)
        self._record(self.mode(k, now.mode), np.array([t]), now.x[:, None], on_record, now.mode)
        while True:
            events += now.events
            if now.terminal or t >= t_end * (1 - 1e-14):
                return events
            if len(events) > MAX_EVENTS:
                raise SolveError(f"more than {MAX_EVENTS} events by t = {t:.6g} s: a slip or end-stop mode "
                                 f"chatters; refine the model or check the traction")
            while t >= self.phases[k].t1 * (1 - 1e-14) and k + 1 < len(self.phases):
                k += 1
                now = self.system.settle(now.x, t, k, now.mode)
                events += now.events
                now = Settled(now.x, now.mode, (), now.terminal)
            if now.terminal:
                return events
            now, t = self._advance(now, t, k, on_record)

    def _advance(self, now: Settled, t: float, k: int, on_record):
        """Integrate the mode from ``t`` up to its next event or the end of the phase; the state after it."""
        x, mode = now.x, now.mode
        m = self.mode(k, mode)
        state = SwitchState.at_start(m.g(x, t))
        while True:
            h = min(CHUNK * self.dt, self.phases[k].t1 - t)
            try:
                X = np.array(m.chunk(x0=x, p=[t, h])["xf"])
            except RuntimeError as exc:
                raise SolveError(f"the integrator failed after t = {t:.6g} s (mode {mode}): {exc}") from None
            times = t + h * m.grid
            hit, G, after = self._detect(m, state, x, t, X, times)
            if hit is None:
                self._record(m, times[SUB - 1::SUB], X[:, SUB - 1::SUB], on_record, mode)
                x, t, state = X[:, -1], times[-1], after
                if t >= self.phases[k].t1 * (1 - 1e-14):
                    return Settled(x, mode), t
                continue
            j = hit.j
            x_a, t_a = (x, t) if j == 0 else (X[:, j - 1], times[j - 1])
            best = self._locate(m, hit, x_a, t_a, times[j] - t_a)
            keep = slice(SUB - 1, j + 1 if best is None else j, SUB)
            if times[keep].size:
                self._record(m, times[keep], X[:, keep], on_record, mode)
            if best is None:                       # false alarm: accept the interval and go on
                x, t, state = X[:, j], times[j], hit.state.arm(G[:, j] > ARM_TOL)
                continue
            x = self._step(m, x_a, t_a, best.s) if best.s > 0 else x_a
            t = t_a + best.s
            self._record(m, np.array([t]), x[:, None], on_record, mode)
            return self.system.transition(k, mode, best.switch, x, t), t

    def _detect(self, m: _Compiled, state: SwitchState, x, t, X, times):
        """(first flagged :class:`~ropemodel.dynamics.detect.Detection` or None, switching functions on the
        grid, switch state after the chunk)."""
        n_det = CHUNK * SUB
        if not m.fun.switches:
            return None, np.zeros((0, n_det)), state
        G, Gd = (np.array(a).reshape(-1, n_det) for a in m.gmap(X, times[None, :]))
        g0, d0 = (np.array(a) for a in m.ggdot(x, t))
        delta = np.diff(np.concatenate([[t], times]))
        hit, after = first_flagged(state, g0, d0, G, Gd, delta)
        return hit, G, after

    def _locate(self, m: _Compiled, hit: Detection, x_a, t_a, h_j) -> Crossing | None:
        """The first crossing in the flagged interval (time from t_a, function), or None (a false alarm).

        Each function evaluation integrates from (x_a, t_a).  A dip: its lowest point by bounded
        minimisation, then the crossing before it by Brent.  A banded function (not armed) is found where
        it passes −ARM_TOL; if it rose above 0 before, the crossing of 0 after its highest point is taken,
        so that a short excursion (a slip shorter than the detection step) ends at g = 0.
        """
        t_end = self.phases[-1].t1
        xtol, xatol = 1e-12 * max(1.0, t_end), 1e-10 * max(1.0, t_end)
        best = None
        for i in list(hit.crossed) + list(hit.dipped):
            def g_i(s, i=i):
                return float(m.g(x_a if s <= 0 else self._step(m, x_a, t_a, s), t_a + s)[i])

            band = 0.0 if hit.state.armed[i] else ARM_TOL

            def f(s, band=band):
                return g_i(s) + band

            hi = h_j
            if i in hit.dipped:                    # an excursion inside the interval: find its lowest point
                res = minimize_scalar(f, bounds=(0.0, h_j), method="bounded", options={"xatol": xatol})
                s_min = min(float(res.x), hit.u[i] * h_j, key=f)
                if f(s_min) >= 0:
                    continue                       # the interpolant's dip was not real
                hi = s_min
            s_star = 0.0 if f(0.0) <= 0 else brentq(f, 0.0, hi, xtol=xtol, rtol=1e-14)
            if band > 0 and s_star > 0:            # back to g = 0 after the excursion, if there was one
                res = minimize_scalar(lambda s: -g_i(s), bounds=(0.0, s_star), method="bounded",
                                      options={"xatol": xatol})
                if g_i(float(res.x)) > 0:
                    s_star = brentq(g_i, float(res.x), s_star, xtol=xtol, rtol=1e-14)
            if best is None or s_star < best.s:
                best = Crossing(s_star, int(i))
        return best

    def _record(self, m: _Compiled, times, X, on_record, mode):
        n = X.shape[1]
        if n == CHUNK:
            out = np.array(m.omap(X, times[None, :]))
        else:
            out = np.column_stack([np.array(m.fun.out(X[:, j], times[j])).ravel() for j in range(n)])
        on_record(times, X, out, mode)


__all__ = ["HybridIntegrator", "Event", "hermite_min"]
