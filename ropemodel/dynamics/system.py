"""The system of one transient, assembled from its variants: equations per mode, initial state, events.

A *mode* (:class:`~ropemodel.effects.transient.base.Mode`) is one mode per variant.  In a mode, every
variant publishes its quantities in assembly order, then gives the right-hand side of its own states
and its switching functions (:class:`~ropemodel.effects.transient.base.Switch`); the system adds the
bookkeeping of the energy balance: the drum's work on the rope W (Ẇ = F_fr·v_d) and the energy
dissipated D (Ḋ = the sum of what the variants dissipate), so that W = ΔE + D can be checked, E the
kinetic + potential energy the variants hold.  Every mode is an explicit ODE (no algebraic constraint
is left: a sticking rope is prescribed kinematics, the carriage has a mass), so CasADi's BDF
integrators (cvodes, idas) apply directly.

This module names no variant: what a variant does is asked of it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from ropemodel.effects.transient.base import Layout, Mode, State, Switch, Variables
from ropemodel.errors import SolveError

#: a switching function below −TOL at a mode's start fires at once (the mode is not consistent)
TOL = 1e-9
#: most events fired at one instant before the modes are declared chattering
MAX_SETTLE = 20
ACCOUNTING = (State("W", doc="work of the drum on the rope [J]"), State("D", doc="energy dissipated [J]"))


@dataclass(frozen=True)
class Event:
    """A located event: time, switching function, the mode after it, the state after it and the history
    columns there (``values``, label → SI number)."""

    t: float
    name: str
    mode: Mode | None                       # None after a terminal event
    state: np.ndarray = field(repr=False)
    values: dict = field(repr=False, default_factory=dict)


@dataclass(frozen=True)
class Settled:
    """A consistent state after events at one instant: state, mode, the events fired, whether one ended the run."""

    x: np.ndarray
    mode: Mode
    events: tuple = ()
    terminal: bool = False


@dataclass
class ModeFunctions:
    """The compiled pieces of one mode in one phase of the drive profile."""

    ode: ca.SX
    rhs: ca.Function            # (x, t) → ẋ
    out: ca.Function            # (x, t) → history columns
    out_names: tuple[str, ...]
    g: ca.Function              # (x, t) → switching functions, each divided by its scale (≥ 0 while it holds)
    switches: tuple[Switch, ...]
    resets: tuple[ca.Function, ...]
    project: ca.Function        # (x, t) → the mode's consistent state (the variants' projections)

    @property
    def g_names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.switches)


class TransientSystem:
    """The variants of one transient (bound to their :class:`~ropemodel.effects.transient.base.Setup`)."""

    def __init__(self, setup, parts):
        self.setup, self.parts, self.phases = setup, list(parts), setup.phases
        self.layout = Layout([s for p in self.parts for s in p.states()] + list(ACCOUNTING))
        self.x = ca.SX.sym("x", self.layout.nx)
        self.t = ca.SX.sym("t")
        self._functions: dict = {}

    def smooth_mode(self) -> Mode:
        """Each variant in its smooth mode (rope sticking, tensioner free, drive on its ramp); a variant that has
        no such mode here is in the one it has (the tensioner of an inextensible rope, ``fixed``)."""
        return Mode.of({p.effect: p.smooth if p.smooth in p.modes() else p.modes()[0] for p in self.parts})

    def variables(self, phase, mode: Mode) -> Variables:
        """The states, t, and what every variant publishes in ``mode`` during ``phase``."""
        v = Variables(self.layout.split(self.x))
        v.publish(t=self.t, phase=phase)
        for p in self.parts:
            p.publish(v, mode[p.effect])
        return v

    def assemble(self, phase, mode: Mode, v: Variables | None = None, energy: bool = True):
        """(ẋ in layout order, switches, history columns) of ``mode`` in ``phase``, as SX in (x, t); ``v``: what
        :meth:`variables` published for them, when the caller has it (and reads more of it afterwards); ``energy``
        False: without the column of the energy the variants hold, ``E [J]`` (a sum over every element of the rope
        that only the energy balance reads: 16 % of building the smooth mode of a 32-element span)."""
        v = self.variables(phase, mode) if v is None else v
        rhs = {}
        for p in self.parts:
            rhs.update(p.set_rhs(v, mode[p.effect]))
        rhs["W"] = v["F_fr"] * v["v_d"]
        rhs["D"] = sum((p.dissipation(v, mode[p.effect]) for p in self.parts), ca.SX(0))
        switches = tuple(s for p in self.parts for s in p.add_events_from(v, mode[p.effect]))
        outputs = {}
        for p in self.parts:
            outputs.update(p.outputs(v, mode[p.effect]))
        outputs["W_drum [J]"] = v["W"]
        if energy:
            outputs["E [J]"] = sum((p.energy(v, mode[p.effect]) for p in self.parts), ca.SX(0))
        outputs["D [J]"] = v["D"]
        project = {}
        for p in self.parts:
            project.update(p.project(v, mode[p.effect]))
        return self._ode(rhs), switches, outputs, project

    def _ode(self, rhs: dict) -> ca.SX:
        parts = []
        for s in self.layout.states:
            if s.name not in rhs:
                raise RuntimeError(f"no variant gives the time derivative of the state {s.name!r}")
            value = rhs[s.name]
            parts += list(value) if isinstance(value, (list, tuple)) else [value]
        return ca.vertcat(*[ca.SX(p) if isinstance(p, (int, float)) else p for p in parts])

    def functions(self, k: int, mode: Mode) -> ModeFunctions:
        """The compiled functions of ``mode`` in phase ``k`` (built on first use only)."""
        key = (k, mode)
        if key not in self._functions:
            self._functions[key] = self._compile(self.phases[k], mode)
        return self._functions[key]

    def _compile(self, phase, mode: Mode) -> ModeFunctions:
        x, t = self.x, self.t
        ode, switches, outputs, project = self.assemble(phase, mode)
        g = ca.vertcat(*[s.g / s.scale for s in switches]) if switches else ca.SX(0, 1)
        return ModeFunctions(
            ode,
            ca.Function("rhs", [x, t], [ode], ["x", "t"], ["xdot"]),
            ca.Function("out", [x, t], [ca.vertcat(*outputs.values())], ["x", "t"], ["out"]),
            tuple(outputs),
            ca.Function("g", [x, t], [g], ["x", "t"], ["g"]),
            switches,
            tuple(self._jump(f"reset_{s.name}", s.reset) for s in switches),
            self._jump("project", project),
        )

    def _jump(self, name: str, updates: dict) -> ca.Function:
        """(x, t) → x with the states in ``updates`` (reference → SX in (x, t)) replaced."""
        comps = [self.x[i] for i in range(self.layout.nx)]
        for ref, expr in updates.items():
            comps[self.layout.index(ref)] = expr
        return ca.Function(name, [self.x, self.t], [ca.vertcat(*comps)], ["x", "t"], ["x_plus"])

    def values(self, k: int, mode: Mode, x, t: float) -> dict:
        """History columns at one state (label → SI number)."""
        fns = self.functions(k, mode)
        return dict(zip(fns.out_names, np.array(fns.out(x, t)).ravel()))

    # --- the start -----------------------------------------------------------------------------

    def initial(self):
        """The state and mode at t = 0: each variant picks its mode (solving equilibria if it needs to),
        then the equilibrium of that mode at the profile's initial speed; a start no variant can
        simulate (e.g. a slack rope) is refused."""
        ic = Initial(self)
        mode = Mode.of({p.effect: p.initial_mode(ic) for p in self.parts})
        x0 = ic.solve(dict(mode.items))
        if not self.setup.symbolic:
            out = self.values(0, mode, x0, 0.0)
            for p in self.parts:
                p.check_start(out)
        return x0, mode

    # --- events --------------------------------------------------------------------------------

    def settle(self, x, t: float, k: int, mode: Mode, events=()) -> Settled:
        """Fire every switching function below −TOL (in assembly order) until the mode is consistent, then
        project the state onto the mode (the variants' :meth:`project`).

        A terminal function below −TOL ends the run here: e.g. the rope at the return sheave left slack
        when the carriage stops on its end stop (its damping force is lost with the carriage's speed).
        """
        events = list(events)
        for _ in range(MAX_SETTLE):
            fns = self.functions(k, mode)
            low = np.flatnonzero(np.array(fns.g(x, t)).ravel() < -TOL)
            if not low.size:
                return Settled(np.array(fns.project(x, t)).ravel(), mode, tuple(events), False)
            x, mode, event = self._fire(k, mode, int(low[0]), x, t)
            events.append(event)
            if event.mode is None:
                return Settled(x, mode, tuple(events), True)
        raise SolveError(f"the modes chatter at t = {t:.6g} s (more than {MAX_SETTLE} events at one instant: "
                         f"{', '.join(e.name for e in events[-4:])}); refine the model or check the traction")

    def transition(self, k: int, mode: Mode, i: int, x, t: float) -> Settled:
        """The located event of switching function ``i``: reset, new mode, then a consistent mode."""
        x, mode, event = self._fire(k, mode, i, x, t)
        if event.mode is None:
            return Settled(x, mode, (event,), True)
        return self.settle(x, t, k, mode, (event,))

    def _fire(self, k: int, mode: Mode, i: int, x, t: float):
        fns = self.functions(k, mode)
        switch = fns.switches[i]
        if switch.target is None:               # terminal
            return x, mode, Event(float(t), switch.name, None, np.array(x, float), self.values(k, mode, x, t))
        x = np.array(fns.resets[i](x, t)).ravel()
        mode = mode.replace(switch.effect, switch.target)
        return x, mode, Event(float(t), switch.name, mode, x.copy(), self.values(k, mode, x, t))


class Initial:
    """Initial conditions: equilibria of the assembled system (a linear solve, symbolic for symbolic
    values), with states the variants pin (e.g. the take-up on an end stop of the stroke)."""

    def __init__(self, system: TransientSystem):
        self.system = system
        self.pins: dict[str, Any] = {}          # state name -> value (float, or SX when symbolic)

    def pin(self, ref, value) -> None:
        self.pins[ref] = value

    def value(self, x, name: str):
        return x[self.system.layout.index(name)]

    def solve(self, modes: dict | None = None, speed=None, extra=None):
        """Every node at the profile's initial speed (or ``speed``), u_0 = 0, the forces in balance.

        modes: effect → mode for the variants' ``steady`` contributions (others: their smooth mode);
        extra(v): more (reference, residual) pairs.  Returns a numpy array, or SX for symbolic values.
        """
        sys, lay = self.system, self.system.layout
        speed = sys.setup.speed0 if speed is None else speed
        mode = Mode.of({**dict(sys.smooth_mode().items), **(modes or {})})
        comps = [ca.SX(0)] * lay.nx
        for p in sys.parts:
            for ref, value in p.initial_values(speed).items():
                _assign(lay, comps, ref, value)
        for ref, value in self.pins.items():
            _assign(lay, comps, ref, value)
        v = sys.variables(sys.phases[0], mode)
        pairs = [pair for p in sys.parts for pair in p.steady(v, mode[p.effect])] + list(extra(v) if extra else [])
        if pairs:
            xs = ca.SX.sym("xs", len(pairs))
            for j, (ref, _) in enumerate(pairs):
                comps[lay.index(ref)] = xs[j]
            r = ca.substitute(ca.vertcat(*[res for _, res in pairs]), ca.vertcat(sys.x, sys.t),
                              ca.vertcat(*comps, 0.0))
            sol = _linear_solve(ca.jacobian(r, xs), ca.substitute(r, xs, ca.DM.zeros(len(pairs))),
                                sys.setup.symbolic)
            for j, (ref, _) in enumerate(pairs):
                comps[lay.index(ref)] = sol[j]
        x0 = ca.vertcat(*comps)
        return x0 if sys.setup.symbolic else np.array(ca.evalf(x0)).ravel()


def _assign(layout: Layout, comps: list, ref, value) -> None:
    """Set one state (``ref`` a name or (name, i)) or every component of a vector state (a list, also of one
    component: the rigid rope's single node)."""
    if isinstance(ref, str) and (layout.size(ref) > 1 or isinstance(value, (list, tuple))):
        for i, item in enumerate(value):
            comps[layout.index((ref, i))] = item
    else:
        comps[layout.index(ref)] = value


def _linear_solve(J, r0, symbolic: bool):
    """x with J x + r0 = 0: symbolic or in numbers (numpy).

    Symbolic by sparse Householder QR on a fill-reducing order (``qr_sparse``): the equilibrium couples each node
    to its neighbours only, so the factors stay banded and the expression grows as n; ``ca.solve``'s QR of the
    whole block grew as n^3 (measured on a tridiagonal system of 390 states: 1.8 s and 769 318 instructions
    against 0.003 s and 23 217, the same solution)."""
    if symbolic:
        return ca.qr_solve(-r0, *ca.qr_sparse(J))
    Jm, r = (np.array(ca.evalf(a)) for a in (J, r0))
    return np.linalg.solve(Jm, -r.ravel())
