"""Equations of motion of the lumped loop, one ODE per *mode*, as CasADi expressions.

State ``x = [u (n), v (n), z, ż, s_d, W, D, v_drum]``: node displacements and speeds along
the path (node 0 is the rope on the drum), the tensioner take-up z and its rate, the drum's
surface travel s_d (so that the slip is s_d − u_0), the work W the drum has done on the
rope, the energy D dissipated (rope damping, travel resistance, slip, stop impacts) and the
drum's surface speed: the energy balance W = ΔKE + ΔPE + D is checked on these states.

A mode is (drum, tensioner, drive); the drive modes are in :mod:`ropemodel.dynamics.drive`.

* drum ``stick``: the rope on the drum moves with it, u̇_0 = v_d(t), v̇_0 = a_d(t); the friction
  force the drum exerts follows.  ``slip_fwd`` (the drum runs ahead of the rope) and
  ``slip_back`` (the rope overruns the drum): the forces at the drum's tangent points obey
  Euler–Eytelwein at the onset of slip, F_tight = ρ F_slack (ρ = e^{μ_d α_d}), which gives the
  rope's acceleration on the drum explicitly (the wrapped rope itself is massless; the
  half-elements at the tangent points carry the mass).
* tensioner ``free``: (m_t/4) z̈ = F_nwl/2 − (T_a + T_b)/2, T_a, T_b the tensions of the two
  elements on the return sheave (each lengthened by z/2); ``at_end`` / ``at_start``: resting
  on a stop of the stroke (z = stroke or 0); ``fixed``: locked.

Each mode has switching functions that stay ≥ 0 while the mode holds; the hybrid
integrator (:mod:`ropemodel.dynamics.hybrid`) locates their zero crossings.  Every mode
is an explicit ODE (no algebraic constraint is left: stick is prescribed kinematics, the
carriage has a mass), so CasADi's BDF integrators (cvodes, idas) apply directly.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from ropemodel.dynamics.chain import Chain
from ropemodel.dynamics.drive import DRIVE_MODES
from ropemodel.papers import friction


@dataclass
class Layout:
    """Index ranges of the state vector."""

    n: int

    @property
    def nx(self) -> int:
        return 2 * self.n + 6

    @property
    def v_drum(self) -> int:
        """Index of the drum's surface speed (a state; follows the profile unless the motor is limited)."""
        return 2 * self.n + 5

    def split(self, x):
        n = self.n
        return x[:n], x[n:2 * n], x[2 * n], x[2 * n + 1], x[2 * n + 2], x[2 * n + 3], x[2 * n + 4], x[2 * n + 5]


class LoopSystem:
    """Symbolic forces of a :class:`Chain` with the scene's values (SI)."""

    def __init__(self, chain: Chain, values: dict, ratio):
        """``ratio(F_slack, v_drum)``: the traction ratio ρ the drum transmits at the onset of slip,
        as a function of the slack-side force [N] and the drum's surface speed [m/s] (a constant
        e^{μα} for a rigid drum, Hajduk's eq. (19) for a Voigt lining); works on CasADi symbols."""
        self.chain, self.values, self.ratio = chain, values, ratio
        self.layout = Layout(chain.n)
        self.x = ca.SX.sym("x", self.layout.nx)
        self.t = ca.SX.sym("t")
        u, v, z, zd, *_ = self.layout.split(self.x)
        self.torque_limited = False
        self.u, self.v, self.z, self.zd = u, v, z, zd
        eps = values["v_eps"]
        self.th = ca.tanh(v / eps)
        ch = chain
        self.T, self.e, self.edot = [], [], []
        for a, b, k, c, on_sheave in ch.elements:
            e = u[b] - u[a] + (z / 2 if on_sheave else 0)
            ed = v[b] - v[a] + (zd / 2 if on_sheave else 0)
            self.e.append(e)
            self.edot.append(ed)
            self.T.append(k * e + c * ed)
        # net force on every node except the drum friction
        F = [ca.SX(0) for _ in range(ch.n)]
        for (a, b, *_), T in zip(ch.elements, self.T):
            F[a] += T
            F[b] -= T
        for i in range(ch.n):
            F[i] += ch.weight[i] - ch.resistance[i] * self.th[i]
        self.F = F
        half = values["F_nwl"] / 2
        if ch.rigid:
            self.T_C_in = self.T_S_out = ca.SX(half)
        else:
            self.T_C_in = sum((T for (a, b, *_), T in zip(ch.elements, self.T) if b == 0), ca.SX(0))
            self.T_S_out = sum((T for (a, b, *_), T in zip(ch.elements, self.T) if a == 0), ca.SX(0))
        self.T_sheave = sum((T for (*_, s), T in zip(ch.elements, self.T) if s), ca.SX(0))

    # forces at the drum's tangent points for a drum-node acceleration a
    def F_C(self, a):
        mC, wC, rC = self.chain.drum_C
        return self.T_C_in + mC * a - wC + rC * self.th[0]

    def F_S(self, a):
        mS, wS, rS = self.chain.drum_S
        return self.T_S_out - mS * a + wS - rS * self.th[0]

    def energy(self):
        """Kinetic + potential energy [J] (gravity as the work of constant forces along p)."""
        ch, vals = self.chain, self.values
        ke = 0.5 * ca.dot(ca.DM(ch.mass), self.v ** 2)
        pe = -ca.dot(ca.DM(ch.weight), self.u)
        for (a, b, k, c, s), e in zip(ch.elements, self.e):
            pe += 0.5 * k * e ** 2
        if not ch.rigid:
            ke += vals["m_t"] * self.zd ** 2 / 8
            pe -= vals["F_nwl"] / 2 * self.z
        return ke + pe

    def damping_power(self):
        p = ca.SX(0)
        for (a, b, k, c, s), ed in zip(self.chain.elements, self.edot):
            p += c * ed ** 2
        return p + ca.dot(ca.DM(self.chain.resistance), self.th * self.v)


def _drum_stick(sys: LoopSystem, drive):
    a = drive.stick_acc()
    F_C, F_S = sys.F_C(a), sys.F_S(a)
    return a, drive.v_d, a, {"slip_fwd": sys.ratio(F_S, drive.v_d) * F_S - F_C,
                             "slip_back": sys.ratio(F_C, drive.v_d) * F_C - F_S}


NEWTON_STEPS = 4


def _slip_acceleration(sys: LoopSystem, tight, slack, v_d):
    """Drum-node acceleration a with tight(a) = ρ(slack(a))·slack(a), Euler–Eytelwein at slip.

    tight and slack are linear in a; with a constant ρ one step of Newton from any start is exact,
    with a force-dependent ρ (Voigt lining) the unrolled Newton steps converge quadratically from
    the constant-ρ solution (ρ changes little with the half-element inertia in slack(a)).
    """
    a = ca.SX.sym("a")
    t0, t1 = tight(0.0), tight(1.0) - tight(0.0)
    s0, s1 = slack(0.0), slack(1.0) - slack(0.0)
    rho0 = sys.ratio(s0, v_d)
    x = (rho0 * s0 - t0) / (t1 - rho0 * s1)
    if not ca.depends_on(sys.ratio(a, v_d), a):
        return x                                   # constant ratio: the linear solution is exact
    r = tight(a) - sys.ratio(slack(a), v_d) * slack(a)
    dr = ca.jacobian(r, a)
    for _ in range(NEWTON_STEPS):
        x = x - ca.substitute(r, a, x) / ca.substitute(dr, a, x)
    return x


def _drum_slip_fwd(sys: LoopSystem, drive):
    """The drum runs ahead of the rope: the winding side is tight, F_C = ρ(F_S)·F_S."""
    a = _slip_acceleration(sys, sys.F_C, sys.F_S, drive.v_d)
    return a, sys.v[0], drive.drum_acc(sys.F_C(a) - sys.F_S(a)), {"stick": drive.v_d - sys.v[0]}


def _drum_slip_back(sys: LoopSystem, drive):
    """The rope overruns the drum: the unwinding side is tight, F_S = ρ(F_C)·F_C."""
    a = _slip_acceleration(sys, sys.F_S, sys.F_C, drive.v_d)
    return a, sys.v[0], drive.drum_acc(sys.F_C(a) - sys.F_S(a)), {"stick": sys.v[0] - drive.v_d}


#: drum mode → (system, drive) → (rope-on-drum acceleration, u̇_0, drum acceleration, switching functions)
DRUM_MODES = {"stick": _drum_stick, "slip_fwd": _drum_slip_fwd, "slip_back": _drum_slip_back}


def _tens_free(sys: LoopSystem):
    vals = sys.values
    return sys.zd, 2 * (vals["F_nwl"] - sys.T_sheave) / vals["m_t"], {
        "stroke_end": vals["stroke"] - sys.z, "stroke_start": sys.z}


def _tens_at_end(sys: LoopSystem):
    return ca.SX(0), ca.SX(0), {"release": sys.values["F_nwl"] - sys.T_sheave}


def _tens_at_start(sys: LoopSystem):
    return ca.SX(0), ca.SX(0), {"release": sys.T_sheave - sys.values["F_nwl"]}


def _tens_fixed(sys: LoopSystem):
    return ca.SX(0), ca.SX(0), {}


#: tensioner mode → system → (ż, z̈, switching functions)
TENSIONER_MODES = {"free": _tens_free, "at_end": _tens_at_end, "at_start": _tens_at_start, "fixed": _tens_fixed}

#: output columns of :meth:`ModeFunctions.out` (SI)
OUT = ("v_drum", "v_rope_drum", "v_load", "F_C", "F_S", "T_sheave", "F_drum", "E", "T_min")


@dataclass
class ModeFunctions:
    """The compiled pieces of one (phase, drum mode, tensioner mode)."""

    ode: ca.SX
    rhs: ca.Function          # (x, t) → ẋ
    out: ca.Function          # (x, t) → OUT
    g: ca.Function            # (x, t) → switching functions (scaled, ≥ 0 while the mode holds)
    g_names: tuple[str, ...]


def mode_functions(sys: LoopSystem, phase, drum: str, tens: str, drive: str, f_scale: float,
                   v_scale: float) -> ModeFunctions:
    """Assemble ẋ, outputs and switching functions of one mode in one drive phase."""
    t, x = sys.t, sys.x
    drv = DRIVE_MODES[drive](sys, phase, t)
    v_d = drv.v_d
    a0, u0dot, a_drum, g_drum = DRUM_MODES[drum](sys, drv)
    zdot, zdd, g_tens = TENSIONER_MODES[tens](sys)
    ch = sys.chain
    acc = [a0] + [sys.F[i] / ch.mass[i] for i in range(1, ch.n)]
    udot = [u0dot] + [sys.v[i] for i in range(1, ch.n)]
    F_C, F_S = sys.F_C(a0), sys.F_S(a0)
    F_fr = F_C - F_S
    P_diss = sys.damping_power() + F_fr * (v_d - sys.v[0])
    ode = ca.vertcat(*udot, *acc, zdot, zdd, v_d, F_fr * v_d, P_diss, a_drum)
    T_min = ca.mmin(ca.vertcat(F_C, F_S, *sys.T))
    out = ca.vertcat(v_d, sys.v[0], sys.v[ch.load], F_C, F_S, sys.T_sheave, F_fr, sys.energy(), T_min)
    scale = {"slip_fwd": f_scale, "slip_back": f_scale, "stick": v_scale,
             "stroke_end": 1.0, "stroke_start": 1.0, "release": f_scale, "slack": f_scale,
             "torque_pos": f_scale, "torque_neg": f_scale, "on_profile": v_scale}
    gd = {**g_drum, **g_tens, "slack": T_min, **drv.g(F_fr, a_drum)}
    names = tuple(gd)
    g = ca.vertcat(*[gd[k] / scale[k] for k in names]) if names else ca.SX(0, 1)
    return ModeFunctions(
        ode,
        ca.Function("rhs", [x, t], [ode], ["x", "t"], ["xdot"]),
        ca.Function("out", [x, t], [out], ["x", "t"], ["out"]),
        ca.Function("g", [x, t], [g], ["x", "t"], ["g"]),
        names,
    )


def rigid_traction(values: dict):
    """Euler–Eytelwein ratio e^{μ_d α_d} of a rigid drum surface [-], whatever the forces."""
    rho = float(friction.euler_eytelwein_ratio(values["mu_d"], values["alpha_d"]))
    return lambda F_slack, v_drum: rho + 0 * F_slack


def voigt_traction(values: dict):
    """Traction ratio of a drum with an isotropic Voigt lining, Hajduk (1992) eq. (19) [-].

    ln s + q s (1 − e^{−α_d/k}) = μ_d α_d with q = Q·F_slack (the slack side enters the arc)
    and k = λω, ω = 2|v_drum|/D the drum's angular speed (ω → 0 is the limit of a slow drum,
    handled by :func:`ropemodel.papers.hajduk1992.tension_ratio`).
    """
    from ropemodel.papers import hajduk1992 as hj

    mu, alpha, Q, lam, D = (values[k] for k in ("mu_d", "alpha_d", "Q", "lambda", "D"))

    def rho(F_slack, v_drum):
        omega = 2.0 * ca.fabs(v_drum) / D if isinstance(v_drum, (ca.SX, ca.MX)) else 2.0 * abs(v_drum) / D
        return hj.tension_ratio(mu, alpha, Q * F_slack, lam * omega)

    return rho


def equilibrium(sys: LoopSystem, v0: float, z_free: bool, z_fixed: float = 0.0) -> np.ndarray:
    """Steady state: every node at speed v0 with u_0 = 0, forces in balance (a linear solve).

    ``z_free``: the constant-force tensioner balances F_nwl (z unknown), else z = ``z_fixed``.
    """
    lay = sys.layout
    n = lay.n
    x = np.zeros(lay.nx)
    x[n:2 * n] = v0
    x[lay.v_drum] = v0
    if n == 1:
        x[2 * n] = z_fixed
        return x
    unknown = list(range(1, n)) + ([2 * n] if z_free else [])
    res = [sys.F[i] for i in range(1, n)]
    if z_free:
        res.append(sys.values["F_nwl"] - sys.T_sheave)
    xs = ca.SX.sym("xs", len(unknown))
    full = ca.vertcat(*[xs[unknown.index(j)] if j in unknown else (z_fixed if j == 2 * n else x[j])
                        for j in range(lay.nx)])
    r = ca.substitute(ca.vertcat(*res), sys.x, full)
    J = ca.Function("J", [xs], [ca.jacobian(r, xs), r])
    Jm, r0 = J(np.zeros(len(unknown)))
    sol = np.linalg.solve(np.array(Jm), -np.array(r0).ravel())
    for k, j in enumerate(unknown):
        x[j] = sol[k]
    if not z_free:
        x[2 * n] = z_fixed
    return x
