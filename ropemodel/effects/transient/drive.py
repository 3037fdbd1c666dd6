"""The drive of the drum (effect ``drive``): a prescribed speed profile, or a motor whose force at the rim is limited.

A drive publishes the drum's surface speed ``v_d`` seen by the rope, the common acceleration of drum
and rope while the rope sticks (``a_stick``) and the drum's acceleration while the rope slips, given
the friction force F_fr the drum exerts on the rope (``drum_acc``).  State ``v_drum``: the drum's
surface speed (it follows the profile unless the motor is at its limit).

``speed`` (default): the drum follows the drive's speed ramp exactly (mode ``profile``: v_d = v(t),
a = a(t)).  ``torque_limited``: the same while the force the motor needs at the rim,
F_req = F_fr + m_drive·a_d, stays within ±F_drive_max (switching functions ``torque_pos``,
``torque_neg``); else (modes ``limited_pos`` / ``limited_neg``) the motor gives ±F_drive_max and the
drum, inertia m_drive = J/R² reduced to the rim, accelerates as that force and the rope allow,
m_drive·a = ±F_drive_max − F_fr, until its speed meets the profile's again (``on_profile``).
``F_drive_max`` is the motor's torque limit over the drum radius (through the gearing), the same in
driving and braking; no speed-dependent motor curve is modelled.  Not in Krauze et al. (2025).
"""

from __future__ import annotations

from ropemodel.effects import domains as dom
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.transient.base import MODEL, State, Switch, TransientSubmodel, event_table
from ropemodel.quantity import Quantity

define_effect(MODEL, "drive", "speed", "drive of the transient: prescribed speed ramp, or a torque-limited motor")

DRIVE_EVENTS = ("torque_pos", "torque_neg", "on_profile")


class Drive(TransientSubmodel):
    """The drum's speed state, the profile mode and the drive report."""

    order = 30
    column = "drive"
    smooth = "profile"

    def states(self):
        return (State("v_drum", doc="the drum's surface speed [m/s]"),)

    def modes(self):
        return ("profile",)

    def initial_values(self, speed):
        return {"v_drum": speed}

    def publish(self, v, mode):
        a = v["a_ramp"]
        v.publish(v_d=v["v_ramp"], a_stick=a, drum_acc=lambda F_fr: a)

    def set_rhs(self, v, mode):
        return {"v_drum": v["a_drum"]}

    def outputs(self, v, mode):
        return {"v_drum [m/s]": v["v_d"]}

    def summary(self, run):
        return {"torque_limited": bool((run.history["drive"] != "profile").any()),
                "drive_events": event_table(run.events, DRIVE_EVENTS)}

    def report(self, s):
        what = {"torque_pos": "motor at its torque limit (driving): the drum falls behind the ramp",
                "torque_neg": "motor at its torque limit (braking): the drum runs ahead of the ramp",
                "on_profile": "drum back on the speed ramp"}
        return [f"  t = {ev['t']:.3f} s: {what[ev['event']]}" for ev in s["drive_events"]]


@register(MODEL, "drive", "speed")
class SpeedDrive(Drive):
    """The drum's surface speed is prescribed by the ramp (a stiff speed-controlled drive)."""

    description = "drum speed follows the ramp exactly"


@register(MODEL, "drive", "torque_limited")
class TorqueLimitedDrive(Drive):
    """Speed-controlled drive whose motor force at the drum rim is limited to ±F_drive_max.

    F_drive_max = motor torque limit × gear ratio / drum radius; m_drive = the inertia of drum, gearing
    and motor reduced to the rim (J/R²).  Both required (no default), parameters only of this variant.
    """

    description = "motor force at the rim limited to F_drive_max; drum inertia m_drive"
    gathered = False
    quantities = (
        Quantity("F_drive_max", "N", "largest force the motor gives at the drum rim (torque limit / radius)",
                 "kN", guess=3e5, positive=True, **dom.FORCE_POSITIVE),
        Quantity("m_drive", "kg", "inertia of drum, gearing and motor reduced to the drum rim (J/R^2)", "kg",
                 guess=1e4, positive=True, **dom.domain(1.0, 1e8, "1 kg to 10^8 kg: a thousand times the largest "
                                                                  "hoist drives (about 10^5 kg at the rim)")),
    )
    SIGN = {"limited_pos": +1, "limited_neg": -1}

    def modes(self):
        return ("profile", "limited_pos", "limited_neg")

    def publish(self, v, mode):
        if mode == "profile":
            return super().publish(v, mode)
        F, m = self.SIGN[mode] * self.values["F_drive_max"], self.values["m_drive"]
        # sticking: m a = F − F_fr(a), F_fr(a) = F_C(a) − F_S(a) = F_fr(0) + (m_C + m_S) a
        a_stick = (F - (v["F_C_at"](0.0) - v["F_S_at"](0.0))) / (m + v["drum_inertia"])
        v.publish(v_d=v["v_drum"], a_stick=a_stick, drum_acc=lambda F_fr: (F - F_fr) / m)

    def add_events_from(self, v, mode):
        f, back = self.setup.f_scale, {"v_drum": v["v_ramp"]}     # the drum leaves or rejoins at the ramp's speed
        if mode == "profile":
            F_req = v["F_fr"] + self.values["m_drive"] * v["a_drum"]
            return [Switch("torque_pos", self.values["F_drive_max"] - F_req, f, self.effect, "limited_pos", back),
                    Switch("torque_neg", self.values["F_drive_max"] + F_req, f, self.effect, "limited_neg", back)]
        return [Switch("on_profile", self.SIGN[mode] * (v["v_ramp"] - v["v_d"]), self.setup.v_scale, self.effect,
                       "profile", back)]

    def moving_masses(self):
        return {"drum": self.values["m_drive"]}
