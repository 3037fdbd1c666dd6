"""What moves the Koepe wheel in a transient: the brake (effect ``brake_control``) or the drive's ramp of a start.

A law gives the wheel's force at the rope radius F_w [N] (+ toward +x, the loaded conveyance rising), or the
wheel's acceleration, as phases (:class:`~ropemodel.effects.koepe_transient.profile.Phase`) in time; the wheel
contact (:mod:`.wheel`) asks it for the rope's and the wheel's accelerations (:meth:`WheelLaw.stick`,
:meth:`WheelLaw.slip`).  s = +1 hoisting, −1 lowering; v0 = s v_max.

``brake_control``
    ``torque`` (default)  constant torque: the drive's steady force F_0 gives way linearly in t_apply to the brake's
                          F_b = 2 M_brake/D against the motion, F_w = F_0 + (−s F_b − F_0) min(t/t_apply, 1); once
                          the wheel is at rest the brake holds it (event ``rest``; the holding torque is assumed
                          to suffice).  The wheel's inertia m_machine = J/R² must be given (> 0).
    ``deceleration``      constant-deceleration control: the wheel's deceleration rises linearly to a_brake in
                          t_apply and holds until the wheel is at rest; then the wheel is held.

The drive ramp of a start (:class:`DriveRamp`): the wheel's acceleration rises linearly to s a_drive in t_jerk,
holds, and falls to 0 in t_jerk, so that the wheel reaches v_max; then it runs at v_max.

Rigid-body mechanics for the nominal run and duration (the rigid hoist: every mass moving as one, M_total as
:func:`ropemodel.papers.koepe_slip.coasting_deceleration`), used only to place the start and size the mesh.
"""

from __future__ import annotations

import math
from typing import cast

from ropemodel.effects import domains as dom
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.koepe import MODEL, Q, tail_terms
from ropemodel.effects.koepe_brake import QUANTITIES as BRAKE_WINDOW
from ropemodel.effects.koepe_transient.profile import KoepeProfile, Phase
from ropemodel.effects.transient.base import Switch, TransientSubmodel
from ropemodel.errors import InputError
from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_slip as ks

define_effect(MODEL, "brake_control", "torque", "the brake's law in a braking transient: constant torque, or "
              "constant-deceleration control")

M_MACHINE = next(q for q in BRAKE_WINDOW if q.name == "m_machine")
T_APPLY = Q("t_apply", "s", "time the brake takes to apply (torque: the drive's force gives way linearly to the "
            "brake's; deceleration: the deceleration rises linearly to a_brake)", "s", low=0.0, low_open=True,
            high=100.0, range_source="100 s: far beyond any brake's application time (about a second)", guess=0.3,
            warn_high=2.0, usual_source="mine-hoist brakes apply in 0.1 to 1 s (judgement)")


class WheelLaw:
    """How the wheel moves: ``stick(v, pull, M)`` → (rope and wheel acceleration, F_w) while the ropes stick,
    pull [N] the ropes' net pull toward +x, M [kg] every mass moving with the wheel; ``slip(v, F_f, M_w)`` →
    (wheel acceleration, F_w) while they slip, F_f [N] the friction force of the wheel on the ropes."""

    force = True
    #: the wheel's speed after the manoeuvre, as a fraction of v_max (the run goes on at it until t_end)
    final_speed = 0.0

    def value(self, v):
        return v["phase"].f(v["t"])

    def stick(self, v, pull, M):
        if self.force and not v["phase"].held:
            F = self.value(v)
            return (pull + F) / M, F
        a = self.value(v)
        return a, M * a - pull

    def slip(self, v, F_f, M_w):
        if self.force and not v["phase"].held:
            F = self.value(v)
            return (F - F_f) / M_w, F
        a = self.value(v)
        return a, M_w * a + F_f


def law_of(setup) -> WheelLaw:
    """The law that moves the wheel in this transient (the profile's choice, :mod:`.profile`)."""
    return cast(KoepeProfile, setup.part("dynamics")).wheel_law


def rigid_mass(nums: dict, tail, y_L: float):
    """(T_L, T_E, M_total) of the rigid hoist with the loaded conveyance at y_L [m]: its static tensions [N] and
    every mass that moves [kg] (both sides T/g, the sheaves, the ropes on the wheel, the machine)."""
    T_L, T_E = kp.side_tensions(y_L, nums["m_conveyance"], nums["m_payload"], nums["H"], nums["H_head"],
                                nums["n_head"], nums["q_head"], *tail)
    arc = kp.arc_rope_mass(nums["n_head"], nums["q_head"], nums["D"] / 2.0, nums["alpha"])
    M = kp.side_mass(T_L, nums["m_sheave_a"]) + kp.side_mass(T_E, nums["m_sheave_b"]) + arc + nums["m_machine"]
    return float(T_L), float(T_E), float(M)


class BrakeControl(TransientSubmodel):
    """A brake's law (a variant of ``brake_control``); inert unless the profile brakes."""

    order = 1                  # before the profile, which asks it for its phases
    column = "brake"

    @property
    def active(self) -> bool:
        return law_of(self.setup) is self

    def free_deceleration(self, setup, y_L: float) -> float:
        """The rigid hoist's deceleration [m/s²] without drive or brake at y_L (koepe_slip.coasting_deceleration)."""
        nums = setup.numbers
        T_L, T_E, M = rigid_mass(nums, tail_terms(self, nums), y_L)
        return float(ks.coasting_deceleration(T_L, T_E, M, setup.direction, nums["F_r"]))

    def summary(self, run):
        return {"brake_control": self.variant} if self.active else {}


@register(MODEL, "brake_control", "torque")
class TorqueBrake(BrakeControl, WheelLaw):
    """Constant brake torque M_brake, applied in t_apply; the brake holds the wheel once it is at rest."""

    description = "constant brake torque M_brake applied in t_apply"
    quantities = (Q("M_brake", "N*m", "the brake's torque on the wheel's axle", "kN*m", low=0.0, low_open=True,
                    high=1e9, range_source=dom.TORQUE["range_source"], guess=2e6), T_APPLY, M_MACHINE)

    def modes(self):
        return ("moving", "held") if self.active else ("on",)

    def nominal(self, setup):
        nums = setup.numbers
        if not nums["m_machine"] > 0:
            raise InputError("brake_control = \"torque\" needs the wheel's inertia: m_machine = J/R^2 > 0 (the mass "
                             "equivalent to the wheel, rotor and brake discs); a torque on a wheel without inertia "
                             "moves a slipping wheel infinitely fast")
        F_b = 2 * nums["M_brake"] / nums["D"]
        d = min(F_b / rigid_mass(nums, tail_terms(self, nums), y)[2] + self.free_deceleration(setup, y)
                for y in (0.0, float(nums["H"])))
        if d <= 0:
            raise InputError(f"the brake cannot stop the hoist: M_brake = {nums['M_brake'] / 1e3:g} kN m gives "
                             f"{F_b / 1e3:.4g} kN at the rope, less than the out-of-balance load drives (rigid "
                             f"deceleration {d:.3g} m/s² at an end of the wind): raise M_brake")
        v0, t_a = float(nums["v_max"]), float(nums["t_apply"])
        return v0 * t_a + v0 * v0 / (2 * d), t_a + v0 / d

    def phases(self, setup, t_end):
        s, F_b, t_a = setup.direction, 2 * self.values["M_brake"] / self.values["D"], self.values["t_apply"]
        rope = setup.part("head_elasticity")
        ramp = Phase(0.0, min(t_a, t_end), lambda t: rope.steady_force() * (1 - t / t_a) - s * F_b * t / t_a)
        return [ramp, Phase(t_a, t_end, lambda t: -s * F_b + 0 * t)]

    def stick(self, v, pull, M):
        return WheelLaw.stick(self, v, pull, M) if v["brake_mode"] != "held" else (0 * pull, -pull)

    def slip(self, v, F_f, M_w):
        return WheelLaw.slip(self, v, F_f, M_w) if v["brake_mode"] != "held" else (0 * F_f, F_f)

    def publish(self, v, mode):
        v.publish(brake_mode=mode)

    def add_events_from(self, v, mode):
        if mode != "moving":
            return []
        return [Switch("rest", self.setup.direction * v["v_w"], self.setup.v_scale, self.effect, "held",
                       {"v_w": 0.0})]

    def project(self, v, mode):
        return {"v_w": 0.0} if mode == "held" else {}


def stop_time(v0: float, d: float, t_j: float) -> float:
    """When a wheel at v0 [m/s] is at rest under a deceleration rising linearly to d [m/s²] in t_j [s]."""
    if v0 <= d * t_j / 2:
        return math.sqrt(2 * v0 * t_j / d)
    return t_j + (v0 - d * t_j / 2) / d


@register(MODEL, "brake_control", "deceleration")
class DecelerationControl(BrakeControl, WheelLaw):
    """Constant-deceleration control: the wheel decelerates at a_brake (reached in t_apply) until at rest."""

    description = "constant-deceleration control: a_brake reached in t_apply, held to rest"
    force = False
    quantities = (Q("a_brake", "m/s^2", "the deceleration the brake's controller holds", "m/s^2", low=0.0,
                    low_open=True, high=100.0, guess=2.0), T_APPLY, M_MACHINE)

    def nominal(self, setup):
        v0, d, t_j = (float(setup.numbers[k]) for k in ("v_max", "a_brake", "t_apply"))
        t_s = stop_time(v0, d, t_j)
        ramp = min(t_s, t_j)
        run = v0 * ramp - d * ramp ** 3 / (6 * t_j)
        v1 = v0 - d * ramp * ramp / (2 * t_j)
        return run + v1 * v1 / (2 * d), t_s

    def phases(self, setup, t_end):
        s, d, t_j = setup.direction, self.values["a_brake"], self.values["t_apply"]
        t_s = min(stop_time(float(setup.numbers["v_max"]), float(d), float(t_j)), t_end)
        out = [Phase(0.0, min(t_j, t_s), lambda t: -s * d * t / t_j)]
        if t_s > t_j:
            out.append(Phase(t_j, t_s, lambda t: -s * d + 0 * t))
        return out + [Phase(t_s, t_end, lambda t: 0 * t, held=True)]

    def project(self, v, mode):
        return {"v_w": 0.0} if self.active and v["phase"].held else {}


class DriveRamp(WheelLaw):
    """The start's drive ramp (not a variant: the law of ``dynamics = "start"``)."""

    force = False
    final_speed = 1.0

    def __init__(self, setup):
        self.setup = setup

    def _times(self):
        nums = self.setup.numbers
        v0, a, t_j = float(nums["v_max"]), float(nums["a_drive"]), float(nums["t_jerk"])
        t_c = v0 / a - t_j
        if t_c < 0:
            raise InputError(f"the start cannot reach v_max = {v0:g} m/s: a_drive t_jerk = {a * t_j:.4g} m/s exceeds "
                             f"it; valid: t_jerk <= v_max/a_drive = {v0 / a:.4g} s")
        return v0, a, t_j, t_c

    def nominal(self, setup):
        v0, a, t_j, t_c = self._times()
        t_ramp = 2 * t_j + t_c
        return v0 * t_ramp / 2, t_ramp

    def phases(self, setup, t_end):
        s, vals = setup.direction, setup.values
        a, t_j = vals["a_drive"], vals["t_jerk"]
        _, _, _, t_c = self._times()
        t1, t2, t3 = t_j, t_j + t_c, 2 * t_j + t_c
        pieces = [Phase(0.0, t1, lambda t: s * a * t / t_j), Phase(t1, t2, lambda t: s * a + 0 * t),
                  Phase(t2, t3, lambda t: s * a * (1 - (t - t2) / t_j)), Phase(t3, t_end, lambda t: 0 * t)]
        return [Phase(p.t0, min(p.t1, t_end), p.f, p.held) for p in pieces if p.t0 < t_end]
