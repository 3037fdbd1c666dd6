"""The elastic head ropes and the tail ropes of a Koepe transient (effect ``head_elasticity``).

``segments`` (default): each side's head ropes cut into ``[numerics] segments`` Kelvin–Voigt elements
(:mod:`.mesh`): spring n·EA/ℓ, dashpot τ·n·EA/ℓ (τ = ``rope_damping``, stiffness-proportional: a mode of
circular frequency ω has the damping ratio τω/2).  The top element's length follows the rope run x over the
wheel, so each span's length changes with its conveyance's position.  Newton's second law for each lumped node
(not in the Koepe texts: the standard lumped-mass rope, as the winch's :mod:`ropemodel.effects.transient.chain`):

    m_i z̈_i = m_i g − T_i + T_{i+1},   T_i = k_i (e_i + τ ė_i),   k_i = n_head EA_head/ℓ_i,

node depths z = z0 ± x + w (states w, u = ẇ: the nodes' elastic displacements and speeds), e_i the elements'
elongations.  At the wheel's tangent point of each side the pull is A = T_1 + q ℓ_col g, the column's weight
added; the column, the ropes on the wheel (q R α) and a deflection sheave of the side (m_sheave, its J/r²,
lumped at the tangent point) move with the rope on the wheel.  S = ½ k_1 e_1²/ℓ_1, the strain energy per metre of
the rope carried onto the rigid arc, acts on the arc (O(T²/EA); it makes the energy balance exact).

Tail ropes (ρ = n_tail q_tail per metre; effect ``tail_ropes``): inextensible, a free loop of negligible turn
hanging from the conveyances, side lengths ℓ_t = (z_other − z_own + H + 2 h_loop)/2.  Lagrange's equations of the
loop (not in the Koepe texts; docs/physics.md §7, elastic ropes) add to each conveyance the mass ρ ℓ_t and the downward
force ρ (g ℓ_t + w²), w = (ż_L − ż_E)/2 the loop's speed along itself.  Their elasticity is left out: the loop
hangs free (no mass below it), so its stretch carries no load but its own weight; docs/physics.md §7, elastic ropes.

The shaft resistance F_r acts on the loaded conveyance against its speed, smoothed as F_r tanh(v/v_eps).  The
terminal events ``slack`` (a tension reaches 0: the linear rope model ends there) and ``run_out`` (a top
element's column used up: the mesh ends there, an error) stop the run.
"""

from __future__ import annotations

import casadi as ca

from ropemodel.effects.base import define_effect, register
from ropemodel.effects.koepe import MODEL, Q, tail_terms
from ropemodel.effects.koepe_transient import mesh as mh
from ropemodel.effects.transient.base import State, Switch, TransientSubmodel, event_table
from ropemodel.effects.transient.rope import ROPE_DAMPING, V_EPS
from ropemodel.errors import InputError
from ropemodel.papers.route import G_N

define_effect(MODEL, "head_elasticity", "segments", "head ropes in a transient: Kelvin-Voigt elements per side")

EA_HEAD = Q("EA_head", "N", "axial stiffness E·A of one head rope (the rope's modulus times its metallic area)", "MN",
            low=0.0, low_open=True, high=1e11, guess=9.6e7, positive=True,
            range_source="10^11 N: twice the stiffest rope (500 mm of steel, about 5e10 N)",
            warn_low=1e6, warn_high=1e9, usual_source="EN 12385 ropes of 10 to 90 mm, E·C·d² with E = 80 to 120 GPa")


def _split(vec, N: int) -> list[list]:
    """A vector state of 2N entries as two sides of N."""
    return [[vec[k * N + i] for i in range(N)] for k in range(2)]


@register(MODEL, "head_elasticity", "segments")
class HeadRopeSegments(TransientSubmodel):
    """Each side's head ropes in ``[numerics] segments`` Kelvin–Voigt elements; the tail loop's mass and pull."""

    description = "elastic head ropes: [numerics] segments Kelvin-Voigt elements per side; rigid tail loop"
    citations = ("delavergne2003",)
    quantities = (EA_HEAD, ROPE_DAMPING, V_EPS)
    reads = ("F_r",)
    order = 10

    def bind(self, setup):
        super().bind(setup)
        nums, prof = setup.numbers, setup.part("dynamics")
        p = {k: float(nums[k]) for k in ("H", "H_head", "m_conveyance", "m_payload", "n_head", "q_head", "EA_head")}
        p.update(zip(("n_tail", "q_tail", "h_loop"), (float(x) for x in tail_terms(self, nums))))
        v0 = float(setup.speed0)
        resistance = float(nums["F_r"]) * (1.0 if v0 > 0 else -1.0 if v0 < 0 else 0.0)
        grows = 1 if setup.direction > 0 else 0          # hoisting lengthens side E's span, lowering side L's
        self.mesh = mh.build_mesh(p, prof.y_start, v0, prof.reel, setup.options["segments"], resistance, grows)

    def states(self):
        n = 2 * self.mesh.N
        return (State("x", doc="rope run over the wheel from side L to side E [m]"),
                State("v", doc="speed of the ropes on the wheel [m/s]"),
                State("w", n, "the nodes' elastic displacements, sides L then E [m]"),
                State("u", n, "the nodes' elastic speeds [m/s]"))

    def initial_values(self, speed):
        return {"v": speed}

    def steady_force(self) -> float:
        """The wheel's force [N] that keeps the initial steady motion: A_L + S_L − A_E − S_E at x = 0."""
        me, out = self.mesh, 0.0
        for k, sign in ((0, 1.0), (1, -1.0)):
            kel, e = me.nEA / me.top[k], me.e0[k, 0]
            out += sign * (kel * e + me.q * me.column(k, 0.0) * G_N + 0.5 * kel * e * e / me.top[k])
        return float(out)

    def publish(self, v, mode):
        me, vals, N = self.mesh, self.values, self.mesh.N
        x, vel, W, U = v["x"], v["v"], _split(v["w"], N), _split(v["u"], N)
        tau = vals["rope_damping"]
        T, z, zd, E, K = [], [], [], [], []
        for k in range(2):
            l1 = me.top[k] + mh.SGN[k] * x
            kel = [me.nEA / l1] + [me.nEA / me.delta[k]] * (N - 1)
            e = [me.e0[k, i] + W[k][i] - (W[k][i - 1] if i else 0) for i in range(N)]
            ed = [U[k][i] - (U[k][i - 1] if i else 0) for i in range(N)]
            T.append([kel[i] * (e[i] + tau * ed[i]) for i in range(N)])
            z.append([me.z0[k, i] + mh.SGN[k] * x + W[k][i] for i in range(N)])
            zd.append([mh.SGN[k] * vel + U[k][i] for i in range(N)])
            E.append((e, ed))
            K.append(kel)
        self._publish_nodes(v, T, z, zd)
        cols = [me.column(k, x) for k in range(2)]
        sheave = (vals["m_sheave_a"], vals["m_sheave_b"])
        v.publish(rope_T=T, rope_e=E, rope_k=K, rope_z=z, rope_zd=zd, col=cols,
                  A=[T[k][0] + me.q * cols[k] * G_N for k in range(2)],
                  m_col=[me.q * cols[k] + sheave[k] for k in range(2)],
                  S=[0.5 * K[k][0] * E[k][0][0] ** 2 / (me.top[k] + mh.SGN[k] * x) for k in range(2)],
                  m_arc=me.q * vals["D"] / 2 * vals["alpha"], q_arc=me.q)

    def _publish_nodes(self, v, T, z, zd):
        """The nodes' accelerations z̈ (Newton's second law), the tail loop's terms and the shaft resistance."""
        me, N = self.mesh, self.mesh.N
        inertia = [[float(me.m[k, i]) for i in range(N)] for k in range(2)]
        net = [[me.m[k, i] * G_N - T[k][i] + (T[k][i + 1] if i + 1 < N else 0) for i in range(N)] for k in range(2)]
        l_t = [(z[1 - k][-1] - z[k][-1] + me.L_t) / 2 for k in range(2)]
        if me.rho > 0:
            loop = 0.25 * (zd[0][-1] - zd[1][-1]) ** 2
            for k in range(2):
                inertia[k][-1] = inertia[k][-1] + me.rho * l_t[k]
                net[k][-1] = net[k][-1] + me.rho * (G_N * l_t[k] + loop)
        v_L = -zd[0][-1]
        resistance = self.values["F_r"] * ca.tanh(v_L / self.values["v_eps"])
        net[0][-1] = net[0][-1] + resistance
        v.publish(zdd=[[net[k][i] / inertia[k][i] for i in range(N)] for k in range(2)], tail_l=l_t,
                  v_L=v_L, resistance=resistance)

    def set_rhs(self, v, mode):
        a, N = v["a_rope"], self.mesh.N
        U = _split(v["u"], N)
        return {"x": v["v"], "v": a, "w": [U[k][i] for k in range(2) for i in range(N)],
                "u": [v["zdd"][k][i] - mh.SGN[k] * a for k in range(2) for i in range(N)]}

    def add_events_from(self, v, mode):
        T_min = ca.mmin(ca.vertcat(v["T_L"], v["T_E"], *v["rope_T"][0], *v["rope_T"][1]))
        v.publish(T_min=T_min)
        return [Switch("slack", T_min, self.setup.f_scale, self.effect, None),
                Switch("run_out", ca.fmin(*v["col"]), 1.0, self.effect, None)]

    def energy(self, v, mode):
        me, z, zd, N = self.mesh, v["rope_z"], v["rope_zd"], self.mesh.N
        out = 0.5 * (v["m_arc"] + v["m_col"][0] + v["m_col"][1]) * v["v"] ** 2
        for k in range(2):
            e, _ = v["rope_e"][k]
            out += sum(0.5 * me.m[k, i] * zd[k][i] ** 2 - G_N * me.m[k, i] * z[k][i] for i in range(N))
            out += sum(0.5 * v["rope_k"][k][i] * e[i] ** 2 for i in range(N)) - 0.5 * me.q * G_N * v["col"][k] ** 2
            if me.rho > 0:
                l_t = v["tail_l"][k]
                out += 0.5 * me.rho * l_t * zd[k][-1] ** 2 - me.rho * G_N * l_t * (z[k][-1] + l_t / 2)
        return out

    def dissipation(self, v, mode):
        tau, out = self.values["rope_damping"], v["resistance"] * v["v_L"]
        for k in range(2):
            _, ed = v["rope_e"][k]
            out += sum(tau * kel * d ** 2 for kel, d in zip(v["rope_k"][k], ed))
        return out

    def outputs(self, v, mode):
        H_head = self.values["H_head"]
        return {"x [m]": v["x"], "v_rope [m/s]": v["v"], "y_L [m]": v["rope_z"][0][-1] - H_head,
                "y_E [m]": v["rope_z"][1][-1] - H_head, "v_L [m/s]": v["v_L"], "T_min [N]": v["T_min"]}

    def moving_masses(self):
        me = self.mesh
        return {"side_L": float(me.m[0].sum()), "side_E": float(me.m[1].sum()), "tail_loop": me.rho * me.L_t}

    def check_start(self, out: dict) -> None:
        if out["T_min [N]"] < 0:
            raise InputError(f"a head rope is slack at the start (least tension {out['T_min [N]'] / 1e3:.4g} kN)")

    def summary(self, run):
        h, ends = run.history, event_table(run.events, ("slack", "run_out"))
        names = {e["event"] for e in ends}
        return {"slack": "slack" in names, "run_out": "run_out" in names,
                "t_stopped": ends[0]["t"] if ends else None, "n_nodes": 2 * self.mesh.N,
                "segments": self.mesh.N, "T_min": float(h["T_min [N]"].min()),
                "t_T_min": float(h["t [s]"].iloc[int(h["T_min [N]"].to_numpy().argmin())])}
