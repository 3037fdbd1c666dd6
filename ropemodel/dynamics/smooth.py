"""The smooth mode of a transient as CasADi Functions of symbolic scene parameters (for dynamic sizing).

The *smooth mode* is the regime without events: the rope sticking on the drum, the tensioner free
within its stroke (or locked, for a fixed take-up), the drive following its ramp.  Dynamic sizing puts
it in an IPOPT NLP with exact derivatives, the parameters it sizes (e.g. the rope diameter ``d`` of a
catalogue rope, the pretension ``F_nwl``, the ``stroke``, the ramp time ``t_ramp``) as symbols, and the
events of the other modes as path constraints: no slip (``slip_fwd`` ≥ 0), the stroke not exhausted
(``stroke − take_up`` ≥ 0), no slack rope (``T_min`` ≥ 0).

::

    sm = smooth_mode(scene, ["d", "F_nwl", "t_ramp"])
    x0 = sm.x0(sm.p0)                       # the equilibrium at the start, x0(p)
    xdot = sm.f(x0, 0.0, sm.p0)             # f(x, t, p) -> xdot, over the whole profile [0, t_end]
    sm.out(x0, 0.0, sm.p0)                  # F_C, F_S, take_up, T_min, T [, slip_fwd, slip_back]
    sm.bounds(sm.p0)                        # the phases' ends [s] as functions of p (t_ramp may be a symbol)
    sm.pieces[k].f(x, t, p)                 # phase k's own smooth right-hand side (no if_else)

The variants build the same equations as :func:`~ropemodel.dynamics.simulate` does, from symbolic
values: the static model's outputs (q_l, q_lw of a catalogue rope, the forces the drum contact is
linearised at, ...) through its compiled forward Function, the initial equilibrium as a symbolic
linear solve.  The drive profile is one piecewise expression over [0, t_end] (``if_else`` at the
phases' ends, each branch finite everywhere); ``pieces`` gives each phase's own expressions (smooth up
to and past its ends), which an integrator restarted at the phases' ends (``bounds``) needs: the
hybrid simulator does the same, and an integrator stepping over a step of the drive's acceleration
loses order there.  ``out`` also gives every element tension ``T`` of the rope loop (its least,
``T_min``, is a minimum: not smooth where two tensions cross; ``T >= 0`` element by element is).
Parameters that fix the structure (route geometry, the load's position: each variant's ``structural``
names, a route's segment lengths) must stay numbers.  :func:`slowest_period` gives the period of the
loop's slowest free oscillation from the same equations (how long dynamic sizing follows a manoeuvre).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import casadi as ca
import numpy as np

from ropemodel.core.compile import forward_of
from ropemodel.dynamics.assemble import bind, chosen, declared, structural, transient_parts
from ropemodel.effects.transient.base import Layout, Setup
from ropemodel.errors import InputError
from ropemodel.problem import run

#: history columns of the smooth mode's ``out`` (label → output name) and switching functions kept raw
OUTPUTS = {"F_C [N]": "F_C", "F_S [N]": "F_S", "take_up [m]": "take_up", "T_min [N]": "T_min"}
SWITCHES = ("slip_fwd", "slip_back")


class Piece(NamedTuple):
    """One phase of the profile: f (x, t, p) → xdot and out (x, t, p) → as :attr:`SmoothMode.out`, with
    the phase's own drive speed and acceleration (smooth expressions, valid past the phase's ends)."""

    f: ca.Function
    out: ca.Function


class SmoothMode(NamedTuple):
    """CasADi Functions of the smooth mode.

    f: (x, t, p) → xdot; out: (x, t, p) → F_C [N], F_S [N], take_up [m], T_min [N] (least tension of the
    rope), T [N] (every element's tension; empty for a rigid rope) and, with a friction lining,
    slip_fwd = F_S − F_C/ρ(F_S) and slip_back = F_C − F_S/ρ(F_C) [N] (≥ 0: no slip); x0: (p) → the
    state at t = 0.  params: the names in p; p0: their scene values (SI); layout: the named states of x;
    t_end [s] and phase_ends [s] (at p0: where the profile has kinks); pieces: one :class:`Piece` per
    phase; bounds: (p) → the phases' starts and ends [s] (``t0``, ``t1``, one entry per phase).  f and out
    are None when :func:`smooth_mode` was asked for the pieces only (``whole=False``).
    """

    f: ca.Function | None
    out: ca.Function | None
    x0: ca.Function
    params: tuple
    p0: np.ndarray
    layout: Layout
    t_end: float
    phase_ends: tuple
    pieces: tuple
    bounds: ca.Function


def smooth_mode(scene, params, whole: bool = True) -> SmoothMode:
    """The smooth mode of ``scene``'s transient with the scene parameters ``params`` as symbols; ``whole``
    False: without f and out over the whole profile (an integrator restarted at the phases' ends needs only
    the pieces, and each is built element by element of the rope: measured on the shipped sizing scene at 32
    elements a span, 17 % of the build)."""
    params = tuple(params)
    submodels = chosen(scene)
    parts = transient_parts(scene, submodels)
    _check_params(scene, params, structural(submodels))
    p = ca.SX.sym("p", len(params))
    static = run(scene)
    setup = Setup(_symbolic_values(scene, params, p), dict(static.values), dict(scene.numerics),
                  {q.effect: q for q in parts}, submodels)
    transient = declared(scene)
    system = bind(setup, parts, transient)
    profile: Any = next(q for q in parts if isinstance(q, transient.profile))   # the declared profile class
    f, out = _functions(system, profile.whole(), p, "") if whole else (None, None)
    pieces = tuple(Piece(*_functions(system, ph, p, f"_{k}")) for k, ph in enumerate(setup.phases))
    x0, _ = system.initial()
    p0 = np.array([scene.parameters[n] for n in params], float)
    ends = tuple(float(ca.evalf(ca.substitute(ph.t1, p, p0))) for ph in setup.phases)
    t0s = ca.vertcat(*[ph.t0 for ph in setup.phases])
    t1s = ca.vertcat(*[ph.t1 for ph in setup.phases])
    return SmoothMode(f, out, ca.Function("x0", [p], [x0], ["p"], ["x0"]),
                      params, p0, system.layout, ends[-1], ends, pieces,
                      ca.Function("bounds", [p], [t0s, t1s], ["p"], ["t0", "t1"]))


def _functions(system, phase, p, suffix: str):
    """(f, out) of the smooth mode in ``phase`` as Functions of (x, t, p)."""
    mode = system.smooth_mode()
    v = system.variables(phase, mode)       # published once: element by element of the rope (16 % of a build)
    ode, switches, outputs, _ = system.assemble(phase, mode, v, energy=False)     # no check reads the energy
    tensions = v.get("T", [])
    x, t = system.x, system.t
    raw = {s.name: s.g for s in switches if s.name in SWITCHES}
    names = [OUTPUTS[k] for k in OUTPUTS] + ["T"] + [n for n in SWITCHES if n in raw]
    exprs = [outputs[k] for k in OUTPUTS] + [ca.vertcat(*tensions)] + [raw[n] for n in SWITCHES if n in raw]
    return (ca.Function(f"f{suffix}", [x, t, p], [ode], ["x", "t", "p"], ["xdot"]),
            ca.Function(f"out{suffix}", [x, t, p], exprs, ["x", "t", "p"], names))


def _check_params(scene, params, fixed: set) -> None:
    bad = [f"{n} is not a parameter of scene {scene.name!r}" for n in params if n not in scene.parameters]
    bad += [f"{n} fixes the structure of the transient (the route's geometry, where the load is): it must "
            f"stay a number" for n in params if n in fixed]
    if len(set(params)) != len(params):
        bad.append("a parameter is named twice")
    if bad:
        raise InputError(problems=bad)


def _symbolic_values(scene, params, p) -> dict:
    """The scene's parameters with ``params`` replaced by symbols, and the static model's outputs in terms
    of them (through its compiled forward Function, which must be explicit: SX)."""
    forward = forward_of(scene.built)
    if not forward.is_a("SXFunction"):
        raise InputError(f"scene {scene.name!r}: the static model solves an implicit block or calls an integrator, "
                         f"so its outputs are not closed-form expressions of the parameters; the symbolic smooth "
                         f"mode needs an explicit static model")
    values = dict(scene.parameters)
    values.update({n: p[i] for i, n in enumerate(params)})
    model = scene.built
    if model.derived:       # a long route's numbers, through the segments' values among params
        edges = {n: values[n] for n in params if n in model.edge_set}
        values.update(model.derive_through(scene.parameters, edges) if edges else model.derive(scene.parameters))
    statics = forward(**{k: values[k] for k in forward.name_in()})
    return {**values, **statics}


def slowest_period(scene) -> float | None:
    """The period [s] of the slowest free oscillation of ``scene``'s transient about the state it starts from,
    2π/min |Im λ| over the eigenvalues λ of the smooth mode's Jacobian ∂f/∂x there (None: no mode
    oscillates, e.g. an inextensible rope).  For a stop, the steady motion at v_pj: the drive's speed
    prescribed, the resistances saturated (tanh(v/v_eps) = 1), so only the rope's Kelvin–Voigt damping and
    the tensioner act (at rest the smoothed resistances would act as heavy viscous dampers).  The
    accounting states (work, dissipation) and the drive's own give zero eigenvalues."""
    sm = smooth_mode(scene, ())
    x, t, p = ca.SX.sym("x", sm.layout.nx), ca.SX.sym("t"), ca.SX.sym("p", 0)
    jacobian = ca.Function("loop_jacobian", [x, t, p], [ca.jacobian(sm.pieces[0].f(x, t, p), x)])
    lam = np.linalg.eigvals(np.asarray(jacobian(sm.x0(sm.p0), 0.0, sm.p0), float))
    omega = np.abs(lam.imag)
    omega = omega[omega > 1e-9 * max(1.0, float(np.abs(lam).max()))]
    return 2 * math.pi / float(omega.min()) if omega.size else None
