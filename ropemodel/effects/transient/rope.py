"""The rope of the transient (effect ``rope_elasticity``): a lumped loop of Kelvin–Voigt elements.

``segments`` (default): every rope span cut into ``[numerics] segments`` elements, the rope's mass
lumped on the nodes; ``spring``: one element per span; ``rigid``: an inextensible rope, one degree of
freedom (needs a tensioner that holds a constant force: the loop tension is F_nwl/2 per side).

States ``u``, ``v``: node displacements and speeds along the path (node 0 is the rope on the drum;
see :mod:`.chain`).  Element tension T = k (e + τ ė), k = EA/ℓ, EA = L_u/q_lw (Krauze et al. 2025
eq. (19)-(20)), τ = ``rope_damping`` the Kelvin–Voigt retardation time: stiffness-proportional, so a
mode of circular frequency ω has the damping ratio ζ = τω/2 (the Fig. 9 load on 1150 m of rope,
ω ≈ 1.9 rad/s: τ = 0.05 s gives ζ ≈ 0.05).  The default 0.05 s is an assumption, not a measured
value: set it for your rope.

``v_eps`` smooths the paper's Coulomb resistances (eq. (7)-(11)) as R·tanh(v/v_eps): R in motion
(tanh(2.5/0.01) = 1 to machine precision, so the steady state is the paper's exactly), zero at rest.
Near rest it acts as a viscous damper R/v_eps, and a load brought to rest creeps towards the
frictionless holding force with time constant ≈ R/(v_eps·k) (12 s for the Fig. 9 load on its rope),
where real friction would stick anywhere within ±R of it.

The node at the drum is moved by the drum contact (:mod:`.contact`): it publishes the rope-on-drum
acceleration ``a_rope_drum`` and speed ``u0dot``; this variant publishes the forces at the drum's
tangent points as functions of that acceleration (``F_C_at``, ``F_S_at``).  The terminal event
``slack`` ends a simulation where a tension reaches zero (the linear rope model no longer holds).
"""

from __future__ import annotations

from typing import ClassVar

import casadi as ca

from ropemodel.effects import domains as dom
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.transient.base import MODEL, State, Switch, TransientSubmodel, event_table
from ropemodel.effects.transient.chain import build_elastic, build_rigid
from ropemodel.effects.transient.route import route_of
from ropemodel.errors import InputError
from ropemodel.quantity import Quantity

define_effect(MODEL, "rope_elasticity", "segments", "rope model of the transient: rigid, spring or segments")

V_EPS = Quantity("v_eps", "m/s", "speed scale of the smoothed Coulomb resistance tanh(v/v_eps)", "m/s",
                 default=0.01, warn_high=0.1, guess=0.01, positive=True,
                 **dom.domain(1e-9, 100.0, "1 nm/s (Coulomb's law to the integrator's tolerance) to the fastest "
                                           "haulage"))
ROPE_DAMPING = Quantity("rope_damping", "s", "Kelvin-Voigt retardation time c/k of the rope (zeta = tau omega / 2)",
                        "s", default=0.05, warn_high=1.0, guess=0.05,
                        **dom.domain(0.0, 100.0, "0 to 100 s: a damping ratio tau omega/2 of 100 even for a rope's "
                                                 "slowest modes (omega about 2 rad/s), an overdamped creep"))

#: the force tolerance of the rope's spatial discretisation (dynamic sizing's mesh control,
#: :mod:`optimisation.dynamic.mesh`); the simulator itself takes ``[numerics] segments`` as given
MESH_TOL = Quantity("mesh_tol", "N", "tolerance on the forces of the rope's discretisation into elements: dynamic "
                    "sizing doubles [numerics] segments until the Richardson estimate of every force check's "
                    "discretisation error is within it, and backs each check off, at each place of the load, by "
                    "its estimate", "kN",
                    default=1000.0, guess=1000.0, warn_low=10.0, warn_high=1e5,
                    default_note="not given: 1 kN (0.2 % of the Fig. 9 load's weight, 467 kN; a force check's "
                                 "estimated error is at most this much)",
                    usual_source="engineering judgement: 0.1 % to 1 % of the load's weight of a haulage",
                    **dom.domain(1e-3, dom.FORCE_MAX, "1 mN (below any force a design check reads) to "
                                                     "10^9 N (the largest force of a scene)"))


class Rope(TransientSubmodel):
    """The lumped loop: node forces, tensions, forces at the drum's tangent points, the slack event."""

    citations = ("krauze2025",)
    quantities: ClassVar[tuple[Quantity, ...]] = (V_EPS,)
    order = 10
    #: the rope stretches (what a contact compliance in series needs)
    elastic: ClassVar[bool] = True
    structural = ("L_u", "L_ul", "x_m")

    def bind(self, setup):
        super().bind(setup)
        if setup.route is None:
            setup.route = route_of(setup)
        setup.chain = self.build(setup)

    def build(self, setup):
        raise NotImplementedError

    @property
    def chain(self):
        return self.setup.chain

    def states(self):
        n = self.chain.n
        return (State("u", n, "node displacements along the path [m]"), State("v", n, "node speeds [m/s]"))

    def initial_values(self, speed):
        return {"v": [speed] * self.chain.n}

    def publish(self, v, mode):
        """The rope's quantities: the same for the same states and chain, so built once per transient and kept for
        the next phase of the drive profile and the start's equilibrium, which publish them again (element by
        element: a fifth of building the smooth mode of a 32-element span)."""
        reads = (self.chain, *(v.get(k) for k in ("u", "v", "z", "zd")))
        kept = getattr(self, "_published", None)
        if kept is None or not all(_same(a, b) for a, b in zip(kept[0], reads)):
            self._published = kept = (reads, self._quantities(v))
        v.publish(**kept[1])

    def _quantities(self, v) -> dict:
        ch, u, vel = self.chain, v["u"], v["v"]
        th = ca.tanh(vel / self.values["v_eps"])
        e = [u[el.b] - u[el.a] + el.take_up * v["z"] for el in ch.elements]
        edot = [vel[el.b] - vel[el.a] + el.take_up * v["zd"] for el in ch.elements]
        T = [el.k * ei + el.c * ed for el, ei, ed in zip(ch.elements, e, edot)]
        F = [ch.weight[i] - ch.resistance[i] * th[i] for i in range(ch.n)]
        for el, Ti in zip(ch.elements, T):
            F[el.a] += Ti
            F[el.b] -= Ti
        T_C_in, T_S_out = self._tangent_tensions(T)
        mC, wC, rC = ch.drum_C
        mS, wS, rS = ch.drum_S
        return dict(th=th, strain=e, strain_rate=edot, T=T, F_nodes=F,
                    T_sheave=sum((2 * el.take_up * Ti for el, Ti in zip(ch.elements, T) if el.take_up), ca.SX(0)),
                    F_C_at=lambda a: T_C_in + mC * a - wC + rC * th[0],
                    F_S_at=lambda a: T_S_out - mS * a + wS - rS * th[0],
                    drum_inertia=mC + mS, v_rope_drum=vel[0], v_load=vel[ch.load])

    def _tangent_tensions(self, T):
        """Tensions of the elements that end on the drum (winding side) and start from it (unwinding)."""
        els = self.chain.elements
        return (sum((Ti for el, Ti in zip(els, T) if el.b == 0), ca.SX(0)),
                sum((Ti for el, Ti in zip(els, T) if el.a == 0), ca.SX(0)))

    def steady(self, v, mode):
        return [(("u", i), v["F_nodes"][i]) for i in range(1, self.chain.n)]

    def set_rhs(self, v, mode):
        ch, vel, F = self.chain, v["v"], v["F_nodes"]
        return {"u": [v["u0dot"]] + [vel[i] for i in range(1, ch.n)],
                "v": [v["a_rope_drum"]] + [F[i] / ch.mass[i] for i in range(1, ch.n)]}

    def add_events_from(self, v, mode):
        v.publish(T_min=ca.mmin(ca.vertcat(v["F_C"], v["F_S"], *v["T"])))
        return [Switch("slack", v["T_min"], self.setup.f_scale, self.effect, None)]

    def energy(self, v, mode):
        ch = self.chain
        out = sum(0.5 * ch.mass[i] * v["v"][i] ** 2 - ch.weight[i] * v["u"][i] for i in range(ch.n))
        return out + sum(0.5 * el.k * ei ** 2 for el, ei in zip(ch.elements, v["strain"]))

    def dissipation(self, v, mode):
        """The power the rope dissipates: like its quantities (:meth:`publish`), the same in every phase, made once."""
        kept = getattr(self, "_dissipated", None)
        if kept is None or kept[0] is not v["strain_rate"]:
            ch = self.chain
            damping = sum(el.c * ed ** 2 for el, ed in zip(ch.elements, v["strain_rate"]))
            kept = self._dissipated = (v["strain_rate"], damping + sum(ch.resistance[i] * v["th"][i] * v["v"][i]
                                                                       for i in range(ch.n)))
        return kept[1]

    def outputs(self, v, mode):
        return {"v_load [m/s]": v["v_load"], "T_sheave [N]": v["T_sheave"], "T_min [N]": v["T_min"]}

    def moving_masses(self):
        return dict(self.chain.masses)

    def check_start(self, out: dict) -> None:
        """A rope slack at the start is bad input (not a transient to simulate)."""
        # at rest the tensioner holds F_nwl/2 on each side of the return sheave (Krauze et al. 2025, eq. (12)-(13));
        # the rigid rope's T_min holds only the drum's tangent points
        T0 = min(out["T_min [N]"], 0.5 * float(self.setup.numbers["F_nwl"]))
        zero = 1e-9 * self.setup.f_scale     # a tension within round-off of 0 is none: the rope is slack
        if T0 <= zero:
            hints = "".join(p.slack_hint for p in self.setup.parts.values())
            shown = T0 / 1e3 if abs(T0) > zero else 0.0
            raise InputError(f"the rope is slack at the start (least tension {shown:.3g} kN){hints}: increase F_nwl "
                             f"(now {self.setup.numbers['F_nwl'] / 1e3:g} kN) or check the stroke")

    def summary(self, run):
        slack = event_table(run.events, ("slack",))
        return {"slack": bool(slack), "t_slack": slack[0]["t"] if slack else None,
                "T_min": float(run.history["T_min [N]"].min()), "n_nodes": self.chain.n}

    def ending(self, s):
        if not s["slack"]:
            return []
        return [f"  STOPPED at t = {s['t_slack']:.3f} s: the rope went slack (a tension reached 0); the linear rope "
                f"model does not hold beyond, the results end there"]


def _same(a, b) -> bool:
    """The same object, or the same CasADi expression node for node (two slices of one state vector)."""
    if a is b:
        return True
    if isinstance(a, ca.SX) and isinstance(b, ca.SX):
        return a.shape == b.shape and bool(ca.is_equal(a, b, 0))
    return False


@register(MODEL, "rope_elasticity", "segments")
class RopeSegments(Rope):
    """Each rope span cut into ``segments`` Kelvin–Voigt elements (stiffness EA/ℓ, EA = L_u/q_lw from
    Krauze et al. 2025 eq. (19)-(20)); the rope's mass q_l ℓ/g lumped half on each node."""

    description = "lumped-mass rope, [numerics] segments Kelvin-Voigt elements per span"
    quantities: ClassVar[tuple[Quantity, ...]] = (V_EPS, ROPE_DAMPING, MESH_TOL)
    sizing_only = ("mesh_tol",)          # the simulator takes [numerics] segments as given
    reads = ("q_lw",)                    # EA = L_u/q_lw, Krauze eq. (19)-(20) (the elongation effect's)

    def segments(self) -> int:
        return self.setup.options["segments"]

    def build(self, setup):
        nums = setup.numbers
        return build_elastic(setup.values, setup.route, float(nums["L_u"]), float(nums["x_m"]), self.segments())


@register(MODEL, "rope_elasticity", "spring")
class RopeSpring(RopeSegments):
    """Each rope span one Kelvin–Voigt element; its mass lumped half on each end."""

    description = "one Kelvin-Voigt spring per rope span"
    quantities = (V_EPS, ROPE_DAMPING)       # one element per span: no mesh to refine

    def segments(self):
        return 1


def _travelled(phases, k: int) -> float:
    """Distance [m] the drum's surface has moved by the start of phase k (exact: each phase's speed is
    linear in time, so its mean is the mean of its ends)."""
    return sum(abs(0.5 * (float(ph.v(ph.t0)) + float(ph.v(ph.t1))) * (ph.t1 - ph.t0)) for ph in phases[:k])


@register(MODEL, "rope_elasticity", "rigid")
class RopeRigid(Rope):
    """Inextensible rope: load and both rope sides move as one body; the tensioner's constant force
    F_nwl sets the loop tension, F_nwl/2 at each tangent point of the return sheave."""

    description = "inextensible rope, one degree of freedom"
    elastic = False

    def bind(self, setup):
        tensioner = setup.part("tensioner")
        if not getattr(tensioner, "constant_force", False):
            raise InputError(f"rope_elasticity = {self.variant!r} with tensioner = {tensioner.variant!r} is statically "
                             f"indeterminate (the loop tension is undefined); use a tensioner that holds a constant "
                             f"force, or an elastic rope")
        super().bind(setup)

    def build(self, setup):
        nums = setup.numbers
        self._phase = None
        chain = build_rigid(setup.route, float(nums["L_u"]), float(nums["x_m"]))
        self._moving = self._moving_load(setup, chain)
        return chain

    def _moving_load(self, setup, chain) -> dict:
        """For phases that move the load along the route (a trip): phase index → (the chain with the load
        where it is in that phase, the offset that keeps the potential energy −∫w du continuous)."""
        out, offset, w_prev = {}, 0.0, chain.weight[0]
        for k, phase in enumerate(setup.phases or ()):
            if getattr(phase, "x_load", None) is None:
                continue
            at = build_rigid(setup.route, float(setup.numbers["L_u"]), phase.x_load)
            u_start = setup.direction * _travelled(setup.phases, k)
            offset = offset + (at.weight[0] - w_prev) * u_start
            out[k], w_prev = (at, offset), at.weight[0]
        return out

    @property
    def chain(self):
        return self._moving[self._phase][0] if self._phase in getattr(self, "_moving", {}) else self.setup.chain

    def publish(self, v, mode):
        index = next((k for k, ph in enumerate(self.setup.phases or ()) if ph is v["phase"]), None)
        self._phase = index
        super().publish(v, mode)

    def energy(self, v, mode):
        pe_offset = self._moving[self._phase][1] if self._phase in self._moving else 0.0
        return super().energy(v, mode) + pe_offset

    def _tangent_tensions(self, T):
        half = self.values["F_nwl"] / 2
        return half, half
