"""The head ropes on the Koepe wheel in a transient (effect ``wheel_contact``): stick or slip, judged at every instant.

``rigid`` (default): the ropes on the arc stick to the wheel or slip on it as a whole (no creep).  With the
pulls A_L, A_E at the tangent points (:mod:`.ropes`; T_L = A_L + m_col,L ẍ, T_E = A_E − m_col,E ẍ, ẍ the ropes'
acceleration toward side E) and the arc rope q = n_head q_head per metre moving at v, sticking holds while, for
the high side h = L and h = E (docs/physics.md §7, the slip condition of :mod:`ropemodel.papers.koepe_slip`
written for each side):

    g_h = ρ (T_l − q v²) − (T_h − q v²) + (ρ − 1) q R a_θ/μ >= 0,    a_θ = ∓ẍ (toward h),

ρ the lining's traction limit at the low side's tension: e^{μα} for ``lining = "rigid"`` (Euler–Eytelwein); for
``lining = "voigt"`` Hajduk's (1992) eq. (19) at rest (:meth:`ropemodel.effects.koepe_wheel.VoigtWheel.limit`,
the lining fully crept: the least it holds).  The Voigt lining's creep along the arc in time (Hajduk's arc ODE)
is not in the transient, and its arc-inertia term uses the Euler–Eytelwein form with ρ: both say so in
docs/physics.md §7, elastic ropes.

Modes ``stick`` (the wheel and the ropes on it move together: the wheel's law gives ẍ with every mass moving
with the wheel, its inertia m_machine = J/R² included), ``slip_L`` and ``slip_E`` (slipping toward the high side:
g_h = 0 fixes ẍ; the friction F_f acts back on the wheel, m_machine ẍ_w = F_w − F_f).  Back to ``stick`` when the
speeds meet (and at once to slip again if a g is then below 0).  Newton's second law on the wheel and the arc
rope: m_arc ẍ = T_E − T_L + S_E − S_L + F_f (not in the Koepe texts).
"""

from __future__ import annotations

import casadi as ca

from ropemodel.effects.base import define_effect, register
from ropemodel.effects.koepe import MODEL
from ropemodel.effects.koepe_transient.control import M_MACHINE, law_of
from ropemodel.effects.transient.base import State, Switch, TransientSubmodel
from ropemodel.errors import InputError

define_effect(MODEL, "wheel_contact", "rigid", "head ropes on the wheel in a transient: stick or slip as a whole")

SLIP = {"slip_L": -1, "slip_E": +1}
#: Newton steps for the slip acceleration when the traction limit depends on the tension (a Voigt lining)
NEWTON_STEPS = 6


@register(MODEL, "wheel_contact", "rigid")
class WheelContact(TransientSubmodel):
    """Stick and slip of the head ropes on the wheel; the wheel's speed and travel; the slip report."""

    description = "ropes stick to the wheel or slip on it as a whole; slip judged at every instant"
    quantities = (M_MACHINE,)
    reads = ("mu", "alpha", "D")
    order = 40
    column = "wheel"
    smooth = "stick"

    def bind(self, setup):
        super().bind(setup)
        lining, vals = setup.submodels["lining"], setup.values
        low, high = (float(lining.limit(vals, T, 0.0)) for T in (1e4, 1e7))
        constant = abs(high - low) <= 1e-14 * abs(low)          # Euler–Eytelwein: e^{μα} whatever the tension
        self.ratio = (lambda T_low: low + 0 * T_low) if constant else (lambda T_low: lining.limit(vals, T_low, 0.0))

    def states(self):
        return (State("x_w", doc="the wheel's surface travel [m]"), State("v_w", doc="the wheel's surface speed [m/s]"))

    def modes(self):
        return ("stick", *SLIP)

    def initial_values(self, speed):
        return {"v_w": speed}

    def margins(self, v, T_L, T_E, a):
        """(g_L, g_E) [N]: the slip conditions toward side L and toward side E, >= 0 while sticking."""
        q, vel, vals = v["q_arc"], v["v"], self.values
        c = q * vals["D"] / 2 / vals["mu"]
        rE, rL = self.ratio(T_E), self.ratio(T_L)
        g_L = rE * (T_E - q * vel ** 2) - (T_L - q * vel ** 2) - (rE - 1) * c * a
        g_E = rL * (T_L - q * vel ** 2) - (T_E - q * vel ** 2) + (rL - 1) * c * a
        return g_L, g_E

    def tensions(self, v, a):
        return v["A"][0] + v["m_col"][0] * a, v["A"][1] - v["m_col"][1] * a

    def slip_acceleration(self, v, sign: int):
        """ẍ with g_h = 0 for the high side h (sign −1: L, +1: E): exact in one Newton step for a constant ρ."""
        a = ca.SX.sym("a")
        T_L, T_E = self.tensions(v, a)
        r = self.margins(v, T_L, T_E, a)[0 if sign < 0 else 1]
        dr = ca.jacobian(r, a)
        x = ca.SX(0.0)
        for _ in range(NEWTON_STEPS if ca.depends_on(self.ratio(a), a) else 1):
            x = x - ca.substitute(r, a, x) / ca.substitute(dr, a, x)
        return x

    def publish(self, v, mode):
        law, S, M_w = law_of(self.setup), v["S"], self.values["m_machine"]
        if mode == "stick":
            M = M_w + v["m_arc"] + v["m_col"][0] + v["m_col"][1]
            a, F_w = law.stick(v, v["A"][1] + S[1] - v["A"][0] - S[0], M)
            a_w, F_f = a, F_w - M_w * a
            T_L, T_E = self.tensions(v, a)
        else:
            a = self.slip_acceleration(v, SLIP[mode])
            T_L, T_E = self.tensions(v, a)
            F_f = v["m_arc"] * a - (T_E - T_L) - (S[1] - S[0])
            a_w, F_w = law.slip(v, F_f, M_w)
        g_L, g_E = self.margins(v, T_L, T_E, a)
        v.publish(a_rope=a, a_w=a_w, F_w=F_w, F_f=F_f, T_L=T_L, T_E=T_E, g_L=g_L, g_E=g_E, F_fr=F_w, v_d=v["v_w"])

    def set_rhs(self, v, mode):
        return {"x_w": v["v_w"], "v_w": v["a_w"]}

    def add_events_from(self, v, mode):
        f = self.setup.f_scale
        if mode == "stick":
            return [Switch(name, v["g_L" if s < 0 else "g_E"], f, self.effect, name) for name, s in SLIP.items()]
        gap = SLIP[mode] * (v["v"] - v["v_w"])
        return [Switch("stick", gap, self.setup.v_scale, self.effect, "stick", {"v": v["v_w"]})]

    def project(self, v, mode):
        return {"v": v["v_w"]} if mode == "stick" else {}

    def energy(self, v, mode):
        return 0.5 * self.values["m_machine"] * v["v_w"] ** 2

    def dissipation(self, v, mode):
        return v["F_f"] * (v["v_w"] - v["v"])

    def outputs(self, v, mode):
        return {"T_L [N]": v["T_L"], "T_E [N]": v["T_E"], "slip_margin [N]": ca.fmin(v["g_L"], v["g_E"]),
                "v_wheel [m/s]": v["v_w"], "a_rope [m/s^2]": v["a_rope"], "a_wheel [m/s^2]": v["a_w"],
                "F_wheel [N]": v["F_w"], "slip_speed [m/s]": v["v"] - v["v_w"], "slip [m]": v["x_w"] - v["x"]}

    def moving_masses(self):
        return {"machine": float(self.setup.numbers["m_machine"])}

    def check_start(self, out: dict) -> None:
        if out["slip_margin [N]"] < 0:
            raise InputError(f"the head ropes slip on the wheel in the steady state the transient starts from (slip "
                             f"margin {out['slip_margin [N]'] / 1e3:.4g} kN): see `ropemodel run` for the static "
                             f"slip check")

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
        return {"slip": bool(slips), "slip_events": slips,
                "slip_distance": float(abs(run.history["slip [m]"].iloc[-1]))}

    def report(self, s):
        lines = []
        for sl in s["slip_events"]:
            end = f"{sl['t_end']:.3f} s" if sl["t_end"] is not None else "the end (still slipping)"
            lines.append(f"  SLIP on the wheel toward side {sl['toward']} from t = {sl['t_start']:.3f} s to {end}: "
                         f"{sl['distance'] * 1e3:.1f} mm (rope acceleration at the onset {sl['a_onset']:.4g} m/s²)")
        return lines or ["  no slip on the wheel"]


def _episode(start, end, slip_end=None):
    slip_end = end.values["slip [m]"] if end is not None else slip_end
    return {"t_start": float(start.t), "t_end": None if end is None else float(end.t),
            "distance": float(abs(slip_end - start.values["slip [m]"])), "toward": start.name[-1],
            "a_onset": float(start.values["a_rope [m/s^2]"])}
