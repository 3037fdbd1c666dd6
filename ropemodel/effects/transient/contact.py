"""The rope on the drum (effect ``drum_contact``): sticking, slipping, and the contact's compliance.

Modes of the rope on the drum, with the traction ratio ρ(F_slack, v_drum) the drum's ``lining``
transmits at the onset of slip (:meth:`ropemodel.effects.winch_lining.RigidLining.transient_traction`:
Euler–Eytelwein e^{μα}, or Hajduk's eq. (19) for a Voigt lining):

* ``stick``: the rope on the drum moves with it, u̇_0 = v_d(t), v̇_0 = a_d(t); the friction force the
  drum exerts follows.  Leaves by ``slip_fwd`` (F_S − F_C/ρ(F_S) < 0) or ``slip_back``
  (F_C − F_S/ρ(F_C) < 0): Euler–Eytelwein's F_tight > ρ F_slack, divided by ρ > 0 so that a drum of
  much friction (ρ = e^{μα} of 10^20 and more) keeps the switching function on the scale of the forces.
* ``slip_fwd`` (the drum runs ahead of the rope) and ``slip_back`` (the rope overruns the drum): the
  forces at the tangent points obey Euler–Eytelwein at the onset of slip, F_tight = ρ F_slack, which
  gives the rope's acceleration on the drum explicitly (the wrapped rope is massless; the half-elements
  at the tangent points carry the mass).  Back to ``stick`` when the speeds meet.

Without a lining (``lining = "none"``) the rope is fixed to the drum: no friction engagement, no slip,
one mode.  State ``s_d``: the drum's surface travel, so that the slip is s_d − u_0.

``rigid`` (default): the rope at the drum's tangent points moves with the drum surface while it
sticks.  ``capstan``: the wrapped rope's slip zone is a spring in series with the tight span
(:mod:`.capstan`, Li et al.).
"""

from __future__ import annotations

from typing import ClassVar

import casadi as ca

from ropemodel.effects import domains as dom
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.transient.base import MODEL, State, Switch, TransientSubmodel
from ropemodel.quantity import Quantity

define_effect(MODEL, "drum_contact", "rigid",
              "rope-on-drum contact of the transient: rigid, or capstan (Li et al. slip-zone stiffness in series)")

SLIP = ("slip_fwd", "slip_back")
#: the dynamic slip factor dynamic sizing checks through every manoeuvre (docs/physics.md §6, "Checks through a
#: manoeuvre"); the simulator itself switches to slip at the onset, ρ F_slack = F_tight, whatever its value
N_SLIP_DYNAMIC = Quantity(
    "n_slip_dynamic", "1", "required safety factor against slip of the rope on the drum through a start or stop "
    "(rho F_slack >= n_slip_dynamic F_tight at every instant; the static checks use n_slip)", guess=1.1,
    default=1.1, warn_high=2.0,
    default_note="not given: 1.1, engineering judgement (no rule or named practice for a haulage drum's "
                 "dynamic slip factor was found): a tenth of the drum's traction held back through a start or stop",
    usual_source="engineering judgement: 1 is the onset of slip; static slip factors are 1.25 to 2",
    **dom.domain(1.0, 1e3, "at least 1 (physics: below 1 the rope slips in the manoeuvre); 1000 bounds any rule; "
                           "the default 1.1 is engineering judgement, not a named practice"))
NEWTON_STEPS = 4


def traction_of(setup):
    """The lining's traction ratio ρ(F_slack, v_drum), or None when the drum has no friction lining."""
    lining = setup.submodels.get("lining")
    ratio = getattr(lining, "transient_traction", None)
    return None if ratio is None else ratio(setup.values)


def slip_acceleration(ratio, tight, slack, v_d):
    """Drum-node acceleration a with tight(a) = ρ(slack(a))·slack(a): Euler–Eytelwein at slip.

    tight and slack are affine in a; with a constant ρ the linear solution is exact, with a
    force-dependent ρ (Voigt lining) unrolled Newton steps converge quadratically from the
    constant-ρ solution (ρ changes little with the half-element inertia in slack(a)).
    """
    a = ca.SX.sym("a")
    t0, t1 = tight(0.0), tight(1.0) - tight(0.0)
    s0, s1 = slack(0.0), slack(1.0) - slack(0.0)
    rho0 = ratio(s0, v_d)
    x = (rho0 * s0 - t0) / (t1 - rho0 * s1)
    if not ca.depends_on(ratio(a, v_d), a):
        return x
    r = tight(a) - ratio(slack(a), v_d) * slack(a)
    dr = ca.jacobian(r, a)
    for _ in range(NEWTON_STEPS):
        x = x - ca.substitute(r, a, x) / ca.substitute(dr, a, x)
    return x


class DrumContact(TransientSubmodel):
    """Stick/slip of the rope on the drum; the forces at the tangent points; the slip report."""

    order = 40
    column = "drum"
    smooth = "stick"
    quantities: ClassVar[tuple[Quantity, ...]] = (N_SLIP_DYNAMIC,)
    sizing_only = ("n_slip_dynamic",)   # the simulator slips at the onset, rho F_slack = F_tight

    def bind(self, setup):
        super().bind(setup)
        self.ratio = traction_of(setup)

    def states(self):
        return (State("s_d", doc="the drum's surface travel [m]"),)

    def modes(self):
        return ("stick", *SLIP) if self.ratio is not None else ("stick",)

    def publish(self, v, mode):
        v_d, F_C, F_S = v["v_d"], v["F_C_at"], v["F_S_at"]
        if mode == "stick":
            a = v["a_stick"]
            u0dot, a_drum = v_d, a
        else:
            tight, slack = (F_C, F_S) if mode == "slip_fwd" else (F_S, F_C)
            a = slip_acceleration(self.ratio, tight, slack, v_d)
            u0dot, a_drum = v["v"][0], v["drum_acc"](F_C(a) - F_S(a))
        v.publish(a_rope_drum=a, u0dot=u0dot, a_drum=a_drum, F_C=F_C(a), F_S=F_S(a), F_fr=F_C(a) - F_S(a),
                  slip=v["s_d"] - v["u"][0])

    def set_rhs(self, v, mode):
        return {"s_d": v["v_d"]}

    def add_events_from(self, v, mode):
        if self.ratio is None:
            return []
        f, vs, v_d, v0 = self.setup.f_scale, self.setup.v_scale, v["v_d"], v["v"][0]
        if mode == "stick":
            return [Switch("slip_fwd", v["F_S"] - v["F_C"] / self.ratio(v["F_S"], v_d), f, self.effect, "slip_fwd"),
                    Switch("slip_back", v["F_C"] - v["F_S"] / self.ratio(v["F_C"], v_d), f, self.effect, "slip_back")]
        gap = v_d - v0 if mode == "slip_fwd" else v0 - v_d
        return [Switch("stick", gap, vs, self.effect, "stick", {("v", 0): v_d})]   # the rope takes the drum's speed

    def project(self, v, mode):
        return {("v", 0): v["v_d"]} if mode == "stick" else {}

    def dissipation(self, v, mode):
        return v["F_fr"] * (v["v_d"] - v["v"][0])

    def outputs(self, v, mode):
        return {"slip_speed [m/s]": v["v_d"] - v["v"][0], "slip [m]": v["slip"], "F_C [N]": v["F_C"],
                "F_S [N]": v["F_S"]}

    def summary(self, run):
        slips, start = [], None
        for ev in run.events:
            if ev.name in SLIP and start is None:
                start = ev
            elif ev.name == "stick" and start is not None:
                slips.append(_episode(start, ev))
                start = None
        if start is not None:
            slips.append(_episode(start, None, float(run.history["slip [m]"].iloc[-1])))
        F_S = self.setup.numbers[f"F_S_{self.setup.travel}"]
        return {"traction_ratio": None if self.ratio is None else float(self.ratio(F_S, self.setup.numbers["v_pj"])),
                "slip": bool(slips), "slip_distance": float(abs(run.history["slip [m]"].iloc[-1])),
                "slip_events": slips, "drum_contact": None}

    def report(self, s):
        if self.ratio is None:
            return ["  rope fixed to the drum (no lining: no slip modelled)"]
        lines = [f"  traction ratio {s['traction_ratio']:.4g} (at F_S static, v_pj)"]
        for sl in s["slip_events"]:
            end = f"{sl['t_end']:.3f} s" if sl["t_end"] is not None else "the end (still slipping)"
            lines.append(f"  SLIP on the drum from t = {sl['t_start']:.3f} s to {end}: {sl['distance'] * 1e3:.1f} mm "
                         f"({sl['kind']})")
        return lines + ([] if s["slip"] else ["  no slip on the drum"])


def _episode(start, end, slip_end=None):
    slip_end = end.values["slip [m]"] if end is not None else slip_end
    return {"t_start": float(start.t), "t_end": None if end is None else float(end.t),
            "distance": abs(slip_end - start.values["slip [m]"]),
            "kind": "drum ahead of the rope" if start.name == "slip_fwd" else "rope overruns the drum"}


@register(MODEL, "drum_contact", "rigid")
class RigidDrumContact(DrumContact):
    """The rope at the drum's tangent points moves with the drum surface while it sticks."""

    description = "rope on the drum rigidly attached while it sticks"
