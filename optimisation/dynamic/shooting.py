"""One manoeuvre's transient inside the NLP: single shooting with CasADi's cvodes and its sensitivities.

The smooth mode (:func:`ropemodel.dynamics.smooth_mode`: rope sticking, carriage free, the drive on
its ramp) is integrated phase by phase of the drive profile — restarted at every phase's end, as the
hybrid simulator does, so no step of the drive's acceleration is stepped over — in scaled time
t = t0 + (t1 − t0)·τ, τ ∈ [0, 1], so that a phase's end may be a decision variable (``t_ramp`` for the
shortest ramp).  The integrator returns the state on the grid of τ; the checks
(:data:`~ropemodel.machines.winch.manoeuvres.CHECKS`) are evaluated there.  Exact derivatives: CasADi
differentiates through the integrator by forward sensitivities (the Jacobian) and
forward-over-adjoint ones (the Hessian of the Lagrangian), under cvodes' own error control.

Why single shooting, measured (the test scene of ``tests/_dynamic_scene.py``: Fig. 9 route and load, 4 rope
elements per span, 22 states per manoeuvre, 12 s manoeuvres; the design fixed at d 48 mm, F_nwl 59.8 kN):

* **single shooting** (this module): 3 decision variables and 7 819 path constraints over the four
  manoeuvres.  All four integrated with the Jacobian of every constraint (forward sensitivities): 0.18 s,
  i.e. one IPOPT iteration; the whole continuous solve with grid refinement took 9-14 s, and the
  integration agrees with the hybrid simulator's to 0.2 N (:mod:`optimisation.dynamic.verify`).
* **direct collocation** (Radau, 3 points per interval, one manoeuvre only, design fixed — just solving
  the transient): 10 582 variables and equations at 0.1 s intervals, 1.1 s; 21 142 at 0.05 s, 2.6 s; its
  peak F_C off the integrator's by 8e-5 relative (25 N: five times the NLP's back-off of 4.7 N, so the
  transcription error would decide the design, with no error control); at 0.02 s (52 822 variables)
  IPOPT's restoration failed from a constant initial guess.  Four manoeuvres with free design variables
  would be four times larger again.  Multiple shooting would add the node states (22 per node) for
  no gain: the smooth mode is stable (damped) over a manoeuvre, which is where multiple shooting earns
  its keep.

So the transient's accuracy is the integrator's error control, not a discretisation the NLP picks,
and the design is checked between grid points by adding each check's exact local minima to the grid
(:mod:`optimisation.dynamic.refine`) and, independently, by the hybrid simulator
(:mod:`optimisation.dynamic.verify`).
"""

from __future__ import annotations

import math
from typing import Any

import casadi as ca
import numpy as np
from scipy.optimize import minimize_scalar

from optimisation.dynamic.manoeuvres import Manoeuvre, declared
from ropemodel.dynamics import smooth_mode

#: cvodes tolerances of the NLP's integration: relative, and absolute in the states' units (m, m/s, J)
RTOL = 1e-10
ATOL = 1e-11
#: ``second_order_correction`` off: the Newton iteration of the forward-sensitivity system (the Jacobian IPOPT and
#: the warm re-solves ask) solves with its block-diagonal part only, leaving out the second derivatives' product
#: (CasADi's ``fwd_jtimes``, a forward derivative of the Jacobian-times-vector per direction and step).  The Newton
#: iteration converges to the same corrector either way and cvodes' error test is the same, so only the work
#: changes: measured on the shipped sizing scene (8 elements a span, four cases), one Jacobian of the dynamic NLP
#: 0.49 -> 0.25 CPU-s, equal to 2e-8 in scaled units (the back-off is 1e-4)
#: ``linear_solver`` "csparse": the Newton iteration's linear systems (the state's and its sensitivities') solved by
#: sparse LU, not CasADi's default "qr".  The corrector and the error test are the same, so are the steps: measured
#: on the three-segment route's upward start (d 50 mm, F_nwl 100.9 kN; 64 elements a span, 390 states, 1554
#: nonzeros in the Jacobian) the same 1123 + 2114 steps, right-hand sides and Newton iterations either way, the
#: integration 1.76 -> 0.13 CPU-s; with "qr" its cost grew as n^2.7 with the elements a span (0.20, 1.3, 8.1 CPU-s
#: at 32, 64, 128), with "csparse" as n
OPTS: dict[str, Any] = {"reltol": RTOL, "abstol": ATOL, "max_num_steps": 100000, "show_eval_warnings": False,
        "disable_internal_warnings": True, "second_order_correction": False, "linear_solver": "csparse"}
#: integrators at numbers kept per path (:meth:`Path._integrator`)
KEPT = 16
#: samplings at numbers kept per path (:meth:`Path.samples`): one sizing reads the same design through the same
#: case on the same dense grid several times in a row — the screening of the cases left out at an optimum, the
#: mesh control's every case there, the next problem's screening from it, the refinement's minima.  Measured on
#: the shipped sizing scene: 264 samplings, 72 of them repeats (1.9 of 9.4 CPU-s).  One is kept: the repeats
#: follow each other, and at 32 elements a span one sampling holds ~2 MB of states
KEPT_SAMPLES = 1


class Path:
    """The smooth mode of one manoeuvre and its checks, integrated on a grid of each phase's τ.

    ``names``: the smooth mode's symbolic parameters (the sized design and the scene's other
    parameters); ``pp`` below is a vector of them (numbers or MX).  A *grid* is a list, one entry per
    phase, of increasing τ in [0, 1] that starts at 0 and ends at 1.
    """

    def __init__(self, manoeuvre: Manoeuvre, scene, names):
        self.manoeuvre, self.names = manoeuvre, tuple(names)
        self.sm = smooth_mode(scene, self.names, whole=False)       # integrated phase by phase: the pieces
        outs = self.sm.pieces[0].out.name_out()
        self.n_elements = self.sm.pieces[0].out.size1_out("T")
        # an inextensible rope has no element and no take-up (its carriage does not move): no tension or take-up
        # check to make through a manoeuvre (the static stroke check, eq. (23), stays)
        self.checks = [c for c in declared(scene).CHECKS
                       if c.needs in outs and (c.needs not in ("T", "take_up") or self.n_elements)]
        self._dae = []
        tau, x, ends = ca.SX.sym("tau"), ca.SX.sym("x", self.sm.layout.nx), ca.SX.sym("ends", 2)
        self.moving, q, pp = self._moving()
        for piece in self.sm.pieces:
            h = ends[1] - ends[0]
            ode = h * piece.f(x, ends[0] + h * tau, pp)
            self._dae.append({"x": x, "t": tau, "p": ca.vertcat(q, ends), "ode": ode})
        self._x0 = ca.Function("x0", [q], [self.sm.x0(pp)])
        self._bounds = ca.Function("bounds", [q], list(self.sm.bounds(pp)))
        self._steps: dict = {}
        self._numeric: dict = {}
        self._sampled: dict = {}
        self._maps: dict = {}

    def _moving(self):
        """(indices into ``names`` of the parameters the transient moves with, their symbols q, ``pp`` in terms of
        q): those the right-hand sides, the start state or the phases' ends depend on.  Only q enters the
        integrators, so a parameter only a check reads (the stroke, against the take-up) takes no direction of
        their forward sensitivities: CasADi drops a direction whose seeds are structurally zero, and each one
        integrates the state's sensitivities again (measured on the shipped sizing scene: three directions -> two,
        one Jacobian of the dynamic NLP 0.32 -> 0.25 CPU-s on the same loaded machine)."""
        pp, x, t = ca.SX.sym("pp", len(self.names)), ca.SX.sym("x", self.sm.layout.nx), ca.SX.sym("t")
        exprs = [piece.f(x, t, pp) for piece in self.sm.pieces] + [self.sm.x0(pp), *self.sm.bounds(pp)]
        depends = ca.which_depends(ca.vertcat(*exprs), pp, 1, False)
        moving = [i for i, d in enumerate(depends) if d]
        q = ca.SX.sym("q", len(moving))
        full = ca.SX.zeros(len(self.names))        # the others: any value (nothing here depends on them)
        for j, i in enumerate(moving):
            full[i] = q[j]
        return moving, q, full

    # ------------------------------------------------------------------ grids
    def phase_bounds(self, pp) -> np.ndarray:
        """Numeric (t0, t1) of every phase at the numbers ``pp``."""
        t0, t1 = self.sm.bounds(pp)
        return np.column_stack([np.asarray(t0).ravel(), np.asarray(t1).ravel()])

    def uniform_grid(self, pp, dt: float) -> list[np.ndarray]:
        """At most ``dt`` [s] between grid points in every phase."""
        out = []
        for t0, t1 in self.phase_bounds(pp):
            n = max(2, math.ceil((t1 - t0) / dt))
            out.append(np.linspace(0.0, 1.0, n + 1))
        return out

    def times(self, pp, grid) -> list[np.ndarray]:
        """The grid's times [s] per phase at the numbers ``pp``."""
        return [t0 + (t1 - t0) * np.asarray(g) for (t0, t1), g in zip(self.phase_bounds(pp), grid)]

    # ------------------------------------------------------------------ the transient on a grid
    def samples(self, pp, grid, name: str = "I"):
        """The smooth mode at every grid point: (times, outputs, states) with ``outputs`` a dict name →
        row(s) of samples (F_C, F_S, take_up, T, slip_fwd, slip_back) and ``states`` one column per
        sample; MX when ``pp`` is, numpy arrays for numbers.

        Each phase contributes its own τ = 0 (the state where the previous phase ended, with this
        phase's drive acceleration) and τ = 1: both one-sided values at a step of acceleration.  At numbers the
        last :data:`KEPT_SAMPLES` results are kept (read-only arrays) and returned again for the same numbers
        and grid."""
        if isinstance(pp, ca.MX):
            return self._samples(pp, grid, name, True)
        key = (np.asarray(pp, float).tobytes(), tuple(np.asarray(g, float).tobytes() for g in grid))
        if key not in self._sampled:
            times, outputs, states = self._samples(pp, grid, name, False)
            for a in (times, states, *outputs.values()):
                a.flags.writeable = False
            self._sampled[key] = (times, outputs, states)
            while len(self._sampled) > KEPT_SAMPLES:
                self._sampled.pop(next(iter(self._sampled)))
        times, outputs, states = self._sampled[key]
        return times, dict(outputs), states

    def _samples(self, pp, grid, name: str, symbolic: bool):
        if not symbolic:
            return self._numeric_samples(np.asarray(pp, float).ravel(), grid, name)
        q = pp[self.moving]
        t0s, t1s = self._bounds(q)
        x = self._x0(q)
        times: list = []
        cols: dict[str, list] = {}
        states: list = []
        for k, (piece, tau) in enumerate(zip(self.sm.pieces, grid)):
            tau = np.asarray(tau, float)
            t0, t1 = t0s[k], t1s[k]
            integ = self._integrator(k, tau, name, symbolic)
            X = integ(x0=x, p=ca.vertcat(q, t0, t1))["xf"]
            X = ca.horzcat(x, X)
            t = t0 + (t1 - t0) * ca.DM(tau).T
            out = piece.out.map(len(tau))(X, t, pp)
            for key in piece.out.name_out():
                cols.setdefault(key, []).append(out[piece.out.name_out().index(key)])
            times.append(t)
            states.append(X)
            x = X[:, -1]
        return ca.horzcat(*times), {k: ca.horzcat(*v) for k, v in cols.items()}, ca.horzcat(*states)

    def _numeric_samples(self, pp: np.ndarray, grid, name: str):
        """:meth:`_samples` at numbers, the same integrations and outputs evaluated into numpy arrays
        (:func:`evaluate`), not through CasADi's DM: converting the DM of a fine mesh's states and tensions element
        by element was 7 % of the three-segment route's dynamic sizing."""
        q = pp[self.moving]
        t0s, t1s = (np.asarray(v, float).ravel() for v in self._bounds(q))
        x = np.asarray(self._x0(q), float).ravel()
        times: list = []
        cols: dict[str, list] = {}
        states: list = []
        for k, tau in enumerate(grid):
            tau = np.asarray(tau, float)
            integ = self._integrator(k, tau, name, False)
            X = np.hstack([x[:, None], evaluate(integ, {"x0": x, "p": np.concatenate([q, [t0s[k], t1s[k]]])})["xf"]])
            t = t0s[k] + (t1s[k] - t0s[k]) * tau
            mapped = self._mapped(k, len(tau))
            out = evaluate(mapped, dict(zip(mapped.name_in(), (X, t, np.tile(pp[:, None], (1, len(tau)))))))
            for key, v in out.items():
                cols.setdefault(key, []).append(v)
            times.append(t)
            states.append(X)
            x = X[:, -1]
        return np.concatenate(times), {k: np.hstack(v) for k, v in cols.items()}, np.hstack(states)

    def _mapped(self, k: int, n: int) -> ca.Function:
        """Phase k's outputs at n samples (one Function per phase and count, kept)."""
        if (k, n) not in self._maps:
            self._maps[k, n] = self.sm.pieces[k].out.map(n)
        return self._maps[k, n]

    def _integrator(self, k: int, tau: np.ndarray, name: str, symbolic: bool) -> ca.Function:
        """cvodes on phase k with output at ``tau``; at numbers, built once per grid (:data:`KEPT` kept per
        path): the screening, the refinement's dense reading and the mesh's margins integrate the same grids
        at design after design."""
        if symbolic:
            return ca.integrator(f"{name}_{k}", "cvodes", self._dae[k], 0.0, list(tau[1:]), OPTS)
        key = (k, tau.tobytes())
        if key not in self._numeric:
            self._numeric[key] = ca.integrator(f"{name}_{k}", "cvodes", self._dae[k], 0.0, list(tau[1:]), OPTS)
            while len(self._numeric) > KEPT:
                self._numeric.pop(next(iter(self._numeric)))
        return self._numeric[key]

    # ------------------------------------------------------------------ exact minima between samples
    def step(self, k: int) -> ca.Function:
        """(x, t_a, h, pp) → the state at t_a + h in phase k (numbers)."""
        if k not in self._steps:
            x, pp = ca.SX.sym("x", self.sm.layout.nx), ca.SX.sym("pp", len(self.names))
            ta, h, s = ca.SX.sym("ta"), ca.SX.sym("h"), ca.SX.sym("s")
            dae = {"x": x, "t": s, "p": ca.vertcat(pp, ta, h), "ode": h * self.sm.pieces[k].f(x, ta + h * s, pp)}
            integ = ca.integrator(f"step_{k}", "cvodes", dae, 0.0, 1.0, OPTS)
            X, P, TA, H = ca.MX.sym("x", self.sm.layout.nx), ca.MX.sym("pp", len(self.names)), ca.MX.sym("ta"), \
                ca.MX.sym("h")
            self._steps[k] = ca.Function(f"step_{k}", [X, TA, H, P], [integ(x0=X, p=ca.vertcat(P, TA, H))["xf"]])
        return self._steps[k]

    def exact_minimum(self, k: int, x_a, t_a: float, span: float, value, pp) -> float:
        """The time of the least ``value(out)`` in phase k within [t_a, t_a + span], integrating from the
        state ``x_a`` at t_a (bounded Brent to 1e-10 s)."""
        out = self.sm.pieces[k].out
        step = self.step(k)

        def g(s):
            x = x_a if s <= 0 else step(x_a, t_a, s, pp)
            return float(value(out.call({"x": x, "t": t_a + s, "p": pp})))

        res = minimize_scalar(g, bounds=(0.0, span), method="bounded", options={"xatol": 1e-10})
        return t_a + float(res.x)


def evaluate(f: ca.Function, inputs: dict) -> dict[str, np.ndarray]:
    """``f`` at the numbers ``inputs`` (name → array of the input's shape; an input left out is zero, as in a call),
    each output a numpy array of its shape, written by CasADi into numpy's memory (:meth:`casadi.Function.buffer`)
    where the output is dense; a sparse output through DM."""
    buf, run = f.buffer()
    keep = []
    for name, value in inputs.items():
        i = f.index_in(name)
        a = np.asarray(value, float)
        if not f.sparsity_in(i).is_dense() or a.size != f.numel_in(i):
            raise ValueError(f"{f.name()}: input {name!r} must be dense, {f.size_in(i)}")
        a = np.ascontiguousarray(a.reshape(f.size_in(i)).T)      # column-major, as CasADi stores it
        keep.append(a)
        buf.set_arg(i, a.data)  # type: ignore[call-arg]  # SWIG takes the size from the buffer; refuses one too small
    outs = {}
    for i, name in enumerate(f.name_out()):
        rows, columns = f.size_out(i)
        outs[name] = np.empty((columns, rows))
        buf.set_res(i, outs[name].data)  # type: ignore[call-arg]
    run()
    sparse = [name for i, name in enumerate(f.name_out()) if not f.sparsity_out(i).is_dense()]
    if sparse:
        dm = f.call({k: ca.DM(np.asarray(v, float)) for k, v in inputs.items()})
        outs.update({k: np.asarray(dm[k]).T for k in sparse})
    return {k: np.ascontiguousarray(v.T) for k, v in outs.items()}
