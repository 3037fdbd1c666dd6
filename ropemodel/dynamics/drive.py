"""The drive of the drum: a prescribed speed profile, or a motor whose force at the rim is limited.

A drive mode gives the drum's surface speed v_d seen by the rope, the common acceleration of
drum and rope while the rope sticks, the drum's acceleration while the rope slips (given the
friction force F_fr the drum exerts on the rope) and its switching functions:

* ``profile``: the drum follows the drive's speed ramp exactly (v_d = v(t), a_d = a(t)).  With a
  torque-limited motor the force it needs at the rim, F_req = F_fr + m_drive·a_d, must stay within
  ±F_drive_max (switching functions ``torque_pos``, ``torque_neg``).
* ``limited_pos`` / ``limited_neg``: the motor gives its largest force ±F_drive_max at the rim and
  the drum (inertia m_drive = J/R² reduced to the rim) accelerates as that force and the rope
  allow: m_drive·a = ±F_drive_max − F_fr.  The drum's speed is then the state v_drum; the drive
  returns to the profile when the drum's speed meets the profile's (``on_profile``).

``F_drive_max`` is the motor's torque limit over the drum radius (through the gearing), the same
in driving and braking; no speed-dependent motor curve is modelled.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import casadi as ca


@dataclass
class Drive:
    """Symbolic drive of one mode."""

    v_d: ca.SX
    stick_acc: Callable[[], ca.SX]
    drum_acc: Callable[[ca.SX], ca.SX]
    g: Callable[[ca.SX, ca.SX], dict]


def _profile(sys, phase, t):
    v_d, a_d = phase.v(t), phase.a(t)
    vals = sys.values

    def g(F_fr, a_drum):
        if not sys.torque_limited:
            return {}
        F_req = F_fr + vals["m_drive"] * a_drum
        return {"torque_pos": vals["F_drive_max"] - F_req, "torque_neg": vals["F_drive_max"] + F_req}

    return Drive(v_d, lambda: a_d, lambda F_fr: a_d, g)


def _limited(sign: int):
    def build(sys, phase, t):
        vals = sys.values
        F, m = sign * vals["F_drive_max"], vals["m_drive"]
        v_d = sys.x[sys.layout.v_drum]
        mC, mS = sys.chain.drum_C[0], sys.chain.drum_S[0]

        def stick_acc():
            # m a = F − F_fr(a), F_fr(a) = F_C(a) − F_S(a) = F_fr(0) + (m_C + m_S) a
            return (F - (sys.F_C(0.0) - sys.F_S(0.0))) / (m + mC + mS)

        return Drive(v_d, stick_acc, lambda F_fr: (F - F_fr) / m,
                     lambda F_fr, a: {"on_profile": sign * (phase.v(t) - v_d)})

    return build


#: drive mode → (system, phase, t) → :class:`Drive`
DRIVE_MODES = {"profile": _profile, "limited_pos": _limited(+1), "limited_neg": _limited(-1)}
#: drive events → the drive mode that follows
DRIVE_EVENTS = {"torque_pos": "limited_pos", "torque_neg": "limited_neg", "on_profile": "profile"}
