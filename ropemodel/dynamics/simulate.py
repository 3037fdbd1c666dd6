"""Assemble the transient of a winch scene from the effects it picks, and integrate it.

Only the chosen variants are built: the ``rope_elasticity`` variant picks the chain
builder (:data:`ropemodel.dynamics.chain.BUILDERS`), ``dynamics`` the drive profile
(:data:`ropemodel.dynamics.profile.PROFILES`), ``tensioner`` the carriage's modes
(:data:`INITIAL_TENSIONER`), ``lining`` the traction ratio (:data:`TRACTION`),
``drum_contact`` the drum's contact compliance (:data:`ropemodel.dynamics.contact.CONTACTS`); the
static model (:func:`ropemodel.problem.run`) gives the reference forces and the
resistance coefficients of the scene's ``resistance`` case.
"""

from __future__ import annotations

import numpy as np

from ropemodel.dynamics.chain import BUILDERS
from ropemodel.dynamics.contact import CONTACTS
from ropemodel.dynamics.drive import DRIVE_EVENTS
from ropemodel.dynamics.history import Simulation
from ropemodel.dynamics.hybrid import HybridIntegrator
from ropemodel.dynamics.profile import PROFILES
from ropemodel.dynamics.system import LoopSystem, equilibrium, mode_functions, rigid_traction, voigt_traction
from ropemodel.errors import InputError
from ropemodel.problem import run

DIRECTION = {"up": +1, "down": -1}
DRUM_TOL = 1e-9

#: tensioner variant → mode of the carriage at the start
INITIAL_TENSIONER = {"constant_force": "free", "fixed": "fixed"}


#: lining variant → traction ratio ρ(F_slack, v_drum) of the drum (``none``: the dynamic model
#: still needs mu_d and alpha_d, and uses the rigid-drum Euler–Eytelwein ratio)
TRACTION = {"none": rigid_traction, "rigid": rigid_traction, "voigt": voigt_traction}


def simulate(scene, values: dict | None = None) -> Simulation:
    """Simulate the transient of a scene with ``dynamics = "start"`` or ``"stop"``.

    ``values`` override scene parameters (SI numbers or unit strings).  Returns a
    :class:`~ropemodel.dynamics.history.Simulation` (history DataFrame, summary, events).
    """
    if values:
        scene = scene.with_values(values)
    eff = scene.effects
    if scene.model != "winch" or eff.get("dynamics", "none") not in PROFILES:
        raise InputError(f"scene {scene.name!r} has no transient: set [effects] dynamics = \"start\" or \"stop\" "
                         f"(model winch)")
    lining = eff.get("lining", "none")
    if lining not in TRACTION:
        raise InputError(f"lining = {lining!r} is not supported by the transient yet; supported: "
                         f"{', '.join(sorted(TRACTION))}")
    if eff["rope_elasticity"] == "rigid" and eff["tensioner"] == "fixed":
        raise InputError("rope_elasticity = \"rigid\" with tensioner = \"fixed\" is statically indeterminate "
                         "(the loop tension is undefined); use tensioner = \"constant_force\" or an elastic rope")
    static = run(scene)
    vals = dict(static.values)
    direction = eff["travel"]
    sign = DIRECTION[direction]
    num = scene.numerics
    chain = BUILDERS[eff["rope_elasticity"]](vals, num["segments"])
    chain = CONTACTS[eff.get("drum_contact", "rigid")](chain, vals, static[f"F_C_{direction}"],
                                                      static[f"F_S_{direction}"])
    ratio = TRACTION[lining](vals)
    sys = LoopSystem(chain, vals, ratio)
    sys.torque_limited = eff["drive"] == "torque_limited"
    phases, v0 = PROFILES[eff["dynamics"]](vals["v_pj"], vals["t_ramp"], vals["t_end"], sign, eff["ramp"])
    tens0 = INITIAL_TENSIONER[eff["tensioner"]] if not chain.rigid else "fixed"
    # initial state: at rest (start) or steady motion (stop); the fixed take-up is set at rest
    x_rest = equilibrium(sys, 0.0, z_free=not chain.rigid)
    z_rest = x_rest[2 * chain.n]
    x0 = equilibrium(sys, v0, z_free=(tens0 == "free"), z_fixed=z_rest)
    if tens0 == "free":
        for limit, mode in ((vals["stroke"], "at_end"), (0.0, "at_start")):
            if (mode == "at_end" and x0[2 * chain.n] > limit) or (mode == "at_start" and x0[2 * chain.n] < limit):
                x0 = equilibrium(sys, v0, z_free=False, z_fixed=limit)
                tens0 = mode
    T0 = float(np.array(mode_functions(sys, phases[0], "stick", tens0, "profile", 1.0, 1.0).out(x0, 0.0))[-1, 0])
    if T0 < 0:
        fixed = " (tensioner = \"fixed\" locks the take-up where F_nwl set it at rest)" if tens0 == "fixed" else ""
        raise InputError(f"the rope is slack at the start (least tension {T0 / 1e3:.3g} kN){fixed}: raise F_nwl "
                         f"(now {vals['F_nwl'] / 1e3:g} kN) or check the stroke")
    f_scale = max(abs(static[f"F_C_{direction}"]), 1.0)
    v_scale = max(vals["v_pj"], 1e-6)
    hyb = HybridIntegrator(sys, phases, num["sim_rtol"], num["sim_dt"], num["sim_integrator"], f_scale, v_scale,
                           atol_u=num["sim_rtol"] * 1e-1 * max(vals["L_u"] * vals["q_lw"] * f_scale, 1e-9))

    iv = sys.layout.v_drum

    def drum_speed(x, t, k, drive):
        return float(phases[k].v(t)) if drive == "profile" else float(x[iv])

    def g_of(x, t, k, mode):
        m = hyb.mode(k, mode)
        return dict(zip(m.fun.g_names, np.array(m.fun.g(x, t)).ravel()))

    def stick_or_slip(x, t, k, tens, drive):
        """The drum mode that holds at (x, t) for a rope not sliding on the drum."""
        g = g_of(x, t, k, ("stick", tens, drive))
        if g["slip_fwd"] < -DRUM_TOL:
            return "slip_fwd"
        if g["slip_back"] < -DRUM_TOL:
            return "slip_back"
        x[chain.n] = drum_speed(x, t, k, drive)
        return "stick"

    def choose(x, t, k, mode):
        """Consistent modes at the start and at a phase boundary (the drive's acceleration jumps)."""
        drum, tens, drive = mode
        if tens in ("at_end", "at_start") and g_of(x, t, k, ("stick", tens, drive))["release"] < -DRUM_TOL:
            tens = "free"
        if drive == "profile" and sys.torque_limited:
            g = g_of(x, t, k, ("stick" if drum == "stick" else drum, tens, drive))
            for name in ("torque_pos", "torque_neg"):
                if g[name] < -DRUM_TOL:
                    x[iv] = float(phases[k].v(t))
                    drive = DRIVE_EVENTS[name]
                    break
        if drum == "stick" or abs(x[chain.n] - drum_speed(x, t, k, drive)) <= DRUM_TOL * v_scale:
            drum = stick_or_slip(x, t, k, tens, drive)
        return drum, tens, drive

    def transition(name, x, t, k, mode):
        if name in TERMINAL:
            return None
        drum, tens, drive = mode
        x = TRANSITIONS[name](x.copy(), vals, chain.n)
        if name in DRIVE_EVENTS:
            x[iv] = float(phases[k].v(t))          # the drum leaves or rejoins the profile at its speed
            drive = DRIVE_EVENTS[name]
        drum = DRUM_EVENTS.get(name, drum)
        if name == "stick" or (name in DRIVE_EVENTS and drum == "stick"):
            drum = stick_or_slip(x, t, k, tens, drive)
        return x, (drum, TENS_EVENTS.get(name, tens), drive)

    # the ratio reported: at the static slack-side force of this direction, at full speed
    F_slack = static[f"F_S_{direction}"]
    sim = Simulation(scene, static, chain, sign, float(ratio(F_slack, vals["v_pj"])))
    events = hyb.run(x0, ("stick", tens0, "profile"), choose, transition, sim.record)
    sim.finish(events, sys)
    return sim


def _impact(x, vals, n, z):
    """Carriage stopped on a stop of the stroke: its kinetic energy is dissipated."""
    x[2 * n + 4] += vals["m_t"] * x[2 * n + 1] ** 2 / 8
    x[2 * n + 1] = 0.0
    x[2 * n] = z
    return x


def _keep(x, vals, n):
    return x


#: event → state reset (x, values, n) → x
TRANSITIONS = {
    "slip_fwd": _keep,
    "slip_back": _keep,
    "stick": _keep,
    "stroke_end": lambda x, vals, n: _impact(x, vals, n, vals["stroke"]),
    "stroke_start": lambda x, vals, n: _impact(x, vals, n, 0.0),
    "release": _keep,
    "torque_pos": _keep,
    "torque_neg": _keep,
    "on_profile": _keep,
}
#: events that end the simulation: a slack rope element (the linear rope model no longer holds)
TERMINAL = {"slack"}
#: drum events → the drum mode that follows
DRUM_EVENTS = {"slip_fwd": "slip_fwd", "slip_back": "slip_back", "stick": "stick"}
#: tensioner events → the carriage mode that follows
TENS_EVENTS = {"stroke_end": "at_end", "stroke_start": "at_start", "release": "free"}
