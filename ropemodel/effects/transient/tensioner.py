"""The return sheave's tensioner in the transient (effect ``tensioner``).

States ``z`` (the take-up: the rope length the tensioner has taken in, the loop's elongation, the
paper's measure of stroke ΔF, Krauze et al. 2025 eq. (23)) and ``zd``.  The carriage travels z/2
(180° wrap on the return sheave) and lengthens the rope's path by z/2 on each side of the sheave
(each element's share of z: :class:`~ropemodel.effects.transient.chain.Element`).

``constant_force`` (default): the carriage (mass ``m_t``) is pulled with F_nwl,
(m_t/4) z̈ = F_nwl/2 − T_sheave/2, T_sheave = Σ 2·share·T the rope's pull on the sheave (the tension
of both elements on it; twice the unwinding side's with the load at the sheave).  Modes
``free``, ``at_end`` / ``at_start`` (resting on a stop of the stroke, z = ``stroke`` or 0; reaching a
stop dissipates the carriage's kinetic energy, ``release`` frees it when the net force pulls it off),
and ``fixed`` when the rope is inextensible (the force acts on the loop directly).  Without a
``stroke`` the stroke is unlimited: there is no end stop, and the summary gives the take-up used.
``fixed``: the carriage is locked where F_nwl put it with the haulage at rest (a fixed take-up).
"""

from __future__ import annotations

import math

from ropemodel.effects import domains as dom
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.transient.base import MODEL, State, Switch, TransientSubmodel, event_table
from ropemodel.effects.winch import STROKE
from ropemodel.quantity import Quantity

define_effect(MODEL, "tensioner", "constant_force", "return-sheave tensioner of the transient")

M_T = Quantity("m_t", "kg", "mass of the return sheave and its carriage", "kg", default=1000.0, guess=1000.0,
               **dom.domain(1.0, 1e6, "1 kg to 1000 t: a thousand times a usual carriage (about 1 t)"))
STROKE_EVENTS = ("stroke_end", "stroke_start", "release")


class Tensioner(TransientSubmodel):
    """States z, ż and the stroke report; subclasses give the modes."""

    order = 20
    column = "tensioner"
    constant_force = False

    def states(self):
        return (State("z", doc="take-up [m]"), State("zd", doc="take-up rate [m/s]"))

    def set_rhs(self, v, mode):
        return {"z": 0 * v["zd"], "zd": 0 * v["zd"]}

    def outputs(self, v, mode):
        return {"take_up [m]": v["z"], "carriage [m]": v["z"] / 2}

    def summary(self, run):
        return {"stroke_used": float(run.history["take_up [m]"].max()), "stroke": None, "stroke_unlimited": False,
                "stroke_exhausted": False, "stroke_events": []}

    def report(self, s):
        return [f"  tensioner take-up {s['stroke_used'] * 1e3:.1f} mm (locked)"]


@register(MODEL, "tensioner", "constant_force")
class ConstantForceTensioner(Tensioner):
    """Return sheave on a carriage pulled with F_nwl (Krauze et al. 2025), free within its stroke."""

    description = "carriage pulled with F_nwl, stroke limits [0, stroke]"
    quantities = (M_T, STROKE)
    elastic_only = ("m_t",)         # an inextensible loop holds the carriage still (``self.loop``)
    constant_force = True
    smooth = "free"

    def bind(self, setup):
        super().bind(setup)
        self.limited = math.isfinite(setup.numbers["stroke"])
        self.loop = not setup.chain.rigid          # an elastic loop: the carriage moves

    def modes(self):
        return ("free", "at_end", "at_start") if self.loop else ("fixed",)

    def initial_mode(self, ic):
        if not self.loop or self.setup.symbolic:
            return self.modes()[0]
        z = ic.value(ic.solve({self.effect: "free"}), "z")
        stroke = self.setup.numbers["stroke"]
        if self.limited and z > stroke:
            ic.pin("z", stroke)
            return "at_end"
        if z < 0:
            ic.pin("z", 0.0)
            return "at_start"
        return "free"

    def steady(self, v, mode):
        return [("z", self.values["F_nwl"] - v["T_sheave"])] if mode == "free" else []

    def set_rhs(self, v, mode):
        if mode != "free":
            return super().set_rhs(v, mode)
        return {"z": v["zd"], "zd": 2 * (self.values["F_nwl"] - v["T_sheave"]) / self.values["m_t"]}

    def add_events_from(self, v, mode):
        f = self.setup.f_scale
        F_net = self.values["F_nwl"] - v["T_sheave"]
        if mode == "free":
            out = [Switch("stroke_start", v["z"], 1.0, self.effect, "at_start", self._impact(v, 0.0))]
            if self.limited:
                out.insert(0, Switch("stroke_end", self.values["stroke"] - v["z"], 1.0, self.effect, "at_end",
                                     self._impact(v, self.values["stroke"])))
            return out
        if mode == "at_end":
            return [Switch("release", F_net, f, self.effect, "free")]
        if mode == "at_start":
            return [Switch("release", -F_net, f, self.effect, "free")]
        return []

    def _impact(self, v, z):
        """The carriage stops on a stop of the stroke: its kinetic energy m_t ż²/8 is dissipated."""
        return {"D": v["D"] + self.values["m_t"] * v["zd"] ** 2 / 8, "zd": 0.0, "z": z}

    def energy(self, v, mode):
        if not self.loop:
            return 0
        return self.values["m_t"] * v["zd"] ** 2 / 8 - self.values["F_nwl"] / 2 * v["z"]

    def moving_masses(self):
        return {"carriage": self.values["m_t"]} if self.loop else {}

    def summary(self, run):
        h, events = run.history, event_table(run.events, STROKE_EVENTS)
        return {"stroke_used": float(h["take_up [m]"].max()),
                "stroke": float(self.setup.numbers["stroke"]) if self.limited else None,
                "stroke_unlimited": not self.limited,
                "stroke_exhausted": (any(e["event"] == "stroke_end" for e in events)
                                     or bool((h["tensioner"] == "at_end").any())),
                "stroke_events": events}

    def report(self, s):
        used = f"  tensioner take-up max {s['stroke_used'] * 1e3:.1f} mm"
        lines = [f"{used} of {s['stroke'] * 1e3:.1f} mm" if s["stroke"] is not None
                 else f"{used} (stroke unlimited: none given)"]
        what = {"stroke_end": "RAN OUT OF STROKE (carriage on its end stop)",
                "stroke_start": "carriage on its start stop", "release": "carriage free again"}
        return lines + [f"  t = {ev['t']:.3f} s: tensioner {what[ev['event']]}" for ev in s["stroke_events"]]


@register(MODEL, "tensioner", "fixed")
class FixedTensioner(Tensioner):
    """Return sheave locked where F_nwl put it with the haulage at rest (a fixed take-up)."""

    description = "carriage locked at its position at rest under F_nwl"
    smooth = "fixed"
    slack_hint = " (the fixed tensioner locks the take-up where F_nwl set it at rest)"

    def modes(self):
        return ("fixed",)

    def initial_mode(self, ic):
        rest = ic.solve(speed=0.0, extra=lambda v: [("z", self.values["F_nwl"] - v["T_sheave"])])
        ic.pin("z", ic.value(rest, "z"))
        return "fixed"
