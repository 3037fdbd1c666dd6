"""The equations of the lumped-mass Koepe model of tests/_koepe_lumped.py (its docstring states the model).

State vector s: [x, ẋ, x_w, ẋ_w, w (2N), ẇ (2N), brake work, damping, friction dissipation]: x the rope run over
the wheel from side L to side E [m] and x_w the wheel's surface [m]; w the nodes' elastic displacements [m]
(rows L, E; node depth z = z0 ∓ x + w, the upper sign for side L); work and dissipations [J].
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

G_N = 9.80665
SGN = np.array([-1.0, 1.0])      # side L (index 0) rises, side E (1) sinks as x grows


@dataclass(frozen=True)
class Hoist:
    """The hoist [SI]: winding distance H, head rope H_head to a conveyance at the top [m]; masses [kg]; n_head
    ropes of q_head [kg/m] and EA_head [N] each; friction mu [-] over alpha [rad] on a wheel of radius R [m] and
    inertia J [kg m²] (with drive and discs); n_tail tail ropes of q_tail [kg/m], loop h_loop [m] per side;
    Kelvin–Voigt retardation time tau [s]; N elements per head-rope span; reel [m] rope allowed over the wheel."""

    H: float
    H_head: float
    m_conveyance: float
    m_payload: float
    n_head: int
    q_head: float
    EA_head: float
    mu: float
    alpha: float
    R: float
    J: float
    n_tail: int = 0
    q_tail: float = 0.0
    h_loop: float = 0.0
    tau: float = 0.0
    N: int = 8
    reel: float = 0.0
    arc_rope: bool = True
    g: float = G_N

    def __post_init__(self):
        bad = [f"{name} = {getattr(self, name)!r} must be {rule}" for name, ok, rule in (
            ("H", self.H > 0, "> 0 m"), ("H_head", self.H_head >= 0, ">= 0 m"), ("N", self.N >= 1, ">= 1"),
            ("m_conveyance", self.m_conveyance > 0, "> 0 kg"), ("m_payload", self.m_payload >= 0, ">= 0 kg"),
            ("n_head", self.n_head >= 1, ">= 1"), ("q_head", self.q_head > 0, "> 0 kg/m"),
            ("EA_head", self.EA_head > 0, "> 0 N"), ("mu", self.mu > 0, "> 0"), ("alpha", self.alpha > 0, "> 0 rad"),
            ("R", self.R > 0, "> 0 m"), ("J", self.J >= 0, ">= 0 kg m²"), ("tau", self.tau >= 0, ">= 0 s"),
            ("n_tail", self.n_tail >= 0, ">= 0"), ("q_tail", self.q_tail >= 0, ">= 0 kg/m"),
            ("h_loop", self.h_loop >= 0, ">= 0 m"), ("reel", self.reel >= 0, ">= 0 m")) if not ok]
        if bad:
            raise ValueError("; ".join(bad))

    @property
    def q(self) -> float:
        return self.n_head * self.q_head

    @property
    def m_arc(self) -> float:
        return self.q * self.R * self.alpha if self.arc_rope else 0.0


@dataclass(frozen=True)
class Wheel:
    """How the wheel moves: kind "force" (f(t, v_w) = torque/R [N], toward +x) or "kinematic" (f(t) = its
    acceleration [m/s²]); breakpoints [s] where f has a kink (the integration restarts there)."""

    kind: str
    f: Callable
    breakpoints: tuple = ()


@dataclass(frozen=True)
class Mesh:
    """Per side (row 0: L, row 1: E): top element's initial length top [m], the others' delta [m], node masses
    m [kg] (node N the conveyance), initial elongations e0 [m] and depths z0 [m]; the tail's total length L_t."""

    top: np.ndarray
    delta: np.ndarray
    m: np.ndarray
    e0: np.ndarray
    z0: np.ndarray
    L_t: float


def element_lengths(h: Hoist, y_L0: float):
    spans = np.array([h.H_head + y_L0, h.H_head + h.H - y_L0])
    top = np.minimum(spans / h.N + 2 * h.reel, spans)
    if h.N > 1 and np.any(top >= spans):
        raise ValueError(f"reel = {h.reel} m leaves no rope for the other {h.N - 1} elements of the shorter span "
                         f"({spans.min():.4g} m): reel < {spans.min() * (1 - 1 / h.N) / 2:.4g} m, or N = 1")
    delta = (spans - top) / max(h.N - 1, 1)
    lengths = np.hstack([top[:, None], np.repeat(delta[:, None], h.N - 1, axis=1)])
    return top, delta, lengths


def mesh(h: Hoist, y_L0: float, v0: float = 0.0) -> Mesh:
    """The spans cut into elements, in the steady state at speed v0 [m/s] (tail lengths iterated to the stretch)."""
    top, delta, lengths = element_lengths(h, y_L0)
    m = h.q * (lengths + np.hstack([lengths[:, 1:], np.zeros((2, 1))])) / 2
    m[:, -1] += h.m_conveyance
    m[0, -1] += h.m_payload
    L_t, rho = h.H + 2 * h.h_loop, h.n_tail * h.q_tail
    k = h.n_head * h.EA_head / lengths
    z_N = np.array([h.H_head + y_L0, h.H_head + h.H - y_L0])
    for _ in range(50):
        l_t = (z_N[::-1] - z_N + L_t) / 2 if rho else np.zeros(2)
        F = np.cumsum((m * h.g)[:, ::-1], axis=1)[:, ::-1] + (rho * (h.g * l_t + v0**2))[:, None]
        e0 = F / k
        z0 = np.cumsum(lengths + e0, axis=1)
        if np.allclose(z0[:, -1], z_N, rtol=0, atol=1e-13 * z_N.max()):
            break
        z_N = z0[:, -1]
    return Mesh(top, delta, m, e0, z0, L_t)


def unpack(h: Hoist, s):
    N = h.N
    return s[0], s[1], s[2], s[3], s[4:4 + 2 * N].reshape(2, N), s[4 + 2 * N:4 + 4 * N].reshape(2, N)


def spans(h: Hoist, me: Mesh, x, v, w, u):
    """Element forces, node accelerations, and per side the pull A at the tangent point but the column's inertia
    (T = A ± m_col ẍ) and S = ½ k_1 e_1²/ℓ_1, the strain energy per metre carried onto the rigid arc: O(T²/EA)."""
    l1 = me.top + SGN * x
    k = h.n_head * h.EA_head / np.hstack([l1[:, None], np.repeat(me.delta[:, None], h.N - 1, axis=1)])
    e = me.e0 + np.diff(w, prepend=0.0, axis=1)
    edot = np.diff(u, prepend=0.0, axis=1)
    taut = e > 0
    F_el = np.where(taut, k * e, 0.0)
    F = np.where(taut, np.maximum(F_el + h.tau * k * edot, 0.0), 0.0)
    z, zdot = me.z0 + SGN[:, None] * x + w, SGN[:, None] * v + u
    net = me.m * h.g - F + np.hstack([F[:, 1:], np.zeros((2, 1))])
    inertia, rho = me.m.copy(), h.n_tail * h.q_tail
    l_t = (z[::-1, -1] - z[:, -1] + me.L_t) / 2
    if rho:
        inertia[:, -1] += rho * l_t
        net[:, -1] += rho * (h.g * l_t + 0.25 * (zdot[0, -1] - zdot[1, -1]) ** 2)
    l_col = l1 - me.top / 2
    A = F[:, 0] + h.q * l_col * h.g
    S = np.where(taut[:, 0], 0.5 * F_el[:, 0] * e[:, 0] / l1, 0.0)
    return {"zdd": net / inertia, "A": A, "S": S, "m_col": h.q * l_col, "l_col": l_col, "F": F, "F_el": F_el,
            "edot": edot, "e": e, "k": k, "z": z, "zdot": zdot, "l_t": l_t}


def tensions(h: Hoist, sp, xdd):
    return sp["A"][0] + sp["m_col"][0] * xdd, sp["A"][1] - sp["m_col"][1] * xdd


def margins(h: Hoist, sp, v, xdd):
    """(g_L, g_E): Euler–Eytelwein's margins against slip toward L and toward E [N]; both >= 0 while sticking."""
    T_L, T_E = tensions(h, sp, xdd)
    qa, E = h.m_arc / (h.R * h.alpha), math.exp(h.mu * h.alpha)
    c = (E - 1) * qa * h.R / h.mu
    return (E * (T_E - qa * v * v) - (T_L - qa * v * v) - c * xdd,
            E * (T_L - qa * v * v) - (T_E - qa * v * v) + c * xdd)


def arc(h: Hoist, wheel: Wheel, mode: int, t, v, vw, sp):
    """(ẍ, ẍ_w, F_w, F_f) in mode 0 (stick) or ±1 (slipping toward E or L)."""
    M_w, M_a = h.J / h.R**2, h.m_arc + sp["m_col"].sum()
    pull = sp["A"][1] + sp["S"][1] - sp["A"][0] - sp["S"][0]
    if mode == 0:
        if wheel.kind == "force":
            F_w = wheel.f(t, vw)
            xdd = (pull + F_w) / (M_w + M_a)
        else:
            xdd = wheel.f(t)
            F_w = (M_w + M_a) * xdd - pull
        return xdd, xdd, F_w, F_w - M_w * xdd
    qa, E = h.m_arc / (h.R * h.alpha), math.exp(h.mu * h.alpha)
    hi, lo = (1, 0) if mode > 0 else (0, 1)
    xdd = mode * (sp["A"][hi] - E * sp["A"][lo] + (E - 1) * qa * v * v) / (
        sp["m_col"][hi] + E * sp["m_col"][lo] + (E - 1) * qa * h.R / h.mu)
    T_L, T_E = tensions(h, sp, xdd)
    F_f = h.m_arc * xdd - (T_E - T_L) - (sp["S"][1] - sp["S"][0])
    if wheel.kind == "force":
        if M_w == 0:
            raise ValueError("a slipping rope needs the wheel's inertia J > 0 when the wheel is force-driven")
        F_w = wheel.f(t, vw)
        return xdd, (F_w - F_f) / M_w, F_w, F_f
    xwdd = wheel.f(t)
    return xdd, xwdd, M_w * xwdd + F_f, F_f


def rhs(h: Hoist, me: Mesh, wheel: Wheel, mode: int):
    def f(t, s):
        x, v, xw, vw, w, u = unpack(h, s)
        sp = spans(h, me, x, v, w, u)
        xdd, xwdd, F_w, F_f = arc(h, wheel, mode, t, v, vw, sp)
        damping = float(np.sum((sp["F"] - sp["F_el"]) * sp["edot"]))
        return np.concatenate([[v, xdd, vw, xwdd], u.ravel(), (sp["zdd"] - SGN[:, None] * xdd).ravel(),
                               [F_w * vw, damping, -F_f * (v - vw) if mode else 0.0]])
    return f


def energy(h: Hoist, me: Mesh, s) -> float:
    """Mechanical energy [J]: kinetic + elastic + gravity (all nodes, the columns, the tail loop; depths from
    the tangent points).  Brake work − damping − friction dissipation is its change."""
    x, v, xw, vw, w, u = unpack(h, s)
    sp = spans(h, me, x, v, w, u)
    kinetic = 0.5 * (h.J / h.R**2 * vw**2 + (h.m_arc + sp["m_col"].sum()) * v**2 + np.sum(me.m * sp["zdot"]**2))
    elastic = 0.5 * np.sum(sp["F_el"] * np.maximum(sp["e"], 0.0))
    gravity = -h.g * np.sum(me.m * sp["z"]) - 0.5 * h.q * h.g * np.sum(sp["l_col"] ** 2)
    if rho := h.n_tail * h.q_tail:
        y, l_t = sp["z"][:, -1], sp["l_t"]
        kinetic += 0.5 * rho * np.sum(l_t * sp["zdot"][:, -1] ** 2)
        gravity -= rho * h.g * np.sum(l_t * (y + l_t / 2))
    return float(kinetic + elastic + gravity)
