"""The lumped rope loop of a winch scene: nodes (masses, weights, resistances) and elements.

Geometry (Krauze et al. 2025, Fig. 5): an endless rope.  The path coordinate p runs
around the loop in the direction the rope moves when the load is hauled up:

    drum (node 0) --S--> return sheave K_ZN --C2--> load --C1--> drum

``S`` is the unwinding rope (length L_u, it runs down the incline), ``C2`` the winding
rope between the return sheave and the load (L_u − x_m) and ``C1`` the winding rope
between the load and the drum (x_m).  A span of zero length is left out (the load then
sits at the return sheave).  Displacements ``u`` are along p (Eulerian nodes at fixed
places on the route, the standard lumped model of conveyor and haulage ropes: over a
transient of tens of seconds the load moves a small part of the route, so the spans'
lengths are frozen at their initial values).

Moving masses (stated, as the issue asks): the load G_m/g; the rope q_l ℓ/g of every
element, lumped half on each end node; the return sheave's carriage m_t (constant-force
tensioner).  The drum's inertia enters only with a torque-limited drive
(:mod:`ropemodel.dynamics.drive`), else its speed is prescribed; the sheaves' rotational
inertia is neglected.  Gravity is g = 9.80665 m/s².

Forces on the nodes come from the paper's resistances (eq. (7)-(11)): weight along the
incline (eq. (1), (3), (4), (6)) and travel resistance μ·(normal weight), the Coulomb
resistance smoothed as R·tanh(v/v_eps) so that it is zero at rest and R in motion
(v ≫ v_eps).  Winding-rope resistance uses μ_pl2 within L_ul of the drive (point A of
the paper) and μ_pl1 beyond it; the unwinding rope uses μ_pl.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ropemodel.errors import InputError
from ropemodel.papers import krauze2025 as kr

G_N = 9.80665  # standard gravity [m/s²]


@dataclass
class Chain:
    """Nodes and Kelvin–Voigt elements of the loop (SI).

    Node 0 is the rope on the drum; its mass, weight and resistance are split into the
    winding-side half (``drum_C``) and the unwinding-side half (``drum_S``), so that the
    forces at the drum's two tangent points F_C and F_S can be reported.
    ``elements``: (a, b, k, c, sheave) — tension k·e + c·ė with e = u_b − u_a (+ z/2 when
    ``sheave``, the two elements on the return sheave).
    ``rigid``: no elements; the sheave-side tensions are F_nwl/2 on both sides.
    """

    mass: np.ndarray
    weight: np.ndarray          # force of gravity along +p [N]
    resistance: np.ndarray      # Coulomb resistance magnitude in motion [N]
    drum_C: tuple[float, float, float]   # (mass, weight along +p, resistance) of the winding half
    drum_S: tuple[float, float, float]   # same for the unwinding half
    elements: list[tuple[int, int, float, float, bool]] = field(default_factory=list)
    load: int = 0
    sheave: int | None = None
    rigid: bool = False
    masses: dict = field(default_factory=dict)
    contact: dict = field(default_factory=dict)   # drum contact stiffnesses (drum_contact = "capstan")

    @property
    def n(self) -> int:
        return len(self.mass)


def _mu_winding(v, s0, s1):
    """Mean winding-rope resistance coefficient over distances [s0, s1] from the drive."""
    a, L = v["L_ul"], s1 - s0
    if L <= 0:
        return v["mu_pl2"]
    near = max(0.0, min(s1, a) - s0)
    return (v["mu_pl2"] * near + v["mu_pl1"] * (L - near)) / L


def build_elastic(v: dict, segments: int) -> Chain:
    """The loop cut into ``segments`` elements per span (``spring``: segments = 1)."""
    L_u, x_m, q_l, a = v["L_u"], v["x_m"], v["q_l"], v["alpha_u"]
    EA = L_u / v["q_lw"]          # q_lw: elongation of L_u of installed rope per newton, eq. (19)
    tau = v["rope_damping"]
    # spans: (length, gravity sign along +p, distance from drive at span start, step sign)
    spans = [("S", L_u, +1.0), ("C2", L_u - x_m, -1.0), ("C1", x_m, -1.0)]
    nodes_m, nodes_w, nodes_r = [0.0], [0.0], [0.0]
    drum_C = [0.0, 0.0, 0.0]
    drum_S = [0.0, 0.0, 0.0]
    elements = []
    sheave = load = None
    sheave_idx = segments          # S always has `segments` elements: its last node is the sheave
    cur = 0
    s_from_drive = {"S": None, "C2": L_u, "C1": x_m}
    for name, length, gsign in spans:
        if length <= 0.0:
            continue
        n = segments
        ell = length / n
        k = EA / ell
        for j in range(n):
            last_of_loop = name == "C1" and j == n - 1
            b = 0 if last_of_loop else len(nodes_m)
            if not last_of_loop:
                nodes_m.append(0.0)
                nodes_w.append(0.0)
                nodes_r.append(0.0)
            if name == "S":
                mu = v["mu_pl"]
            else:
                s0 = s_from_drive[name] - (j + 1) * ell
                mu = _mu_winding(v, s0, s0 + ell)
            m_e = q_l * ell / G_N
            w_e = gsign * kr.rope_weight_along_incline(q_l, ell, a)      # eq. (3), (4), (6) per element
            r_e = kr.rope_resistance(mu, q_l, ell, a)                     # eq. (8), (9), (11) per element
            # weight and resistance of an element on the return sheave go to its far node, so that
            # the rope at the sheave's tangent points is at F_nwl/2 per side in steady motion, as in
            # the paper's eq. (12)-(13) (the wrapped rope carries no weight across the sheave)
            shares = {cur: 0.5, b: 0.5}
            if sheave_idx in shares:
                shares = {cur: 0.0 if cur == sheave_idx else 1.0, b: 0.0 if b == sheave_idx else 1.0}
            for node in (cur, b):
                f = shares[node]
                if node == 0:
                    target = drum_S if name == "S" else drum_C
                    target[0] += m_e / 2
                    target[1] += f * w_e
                    target[2] += f * r_e
                else:
                    nodes_m[node] += m_e / 2
                    nodes_w[node] += f * w_e
                    nodes_r[node] += f * r_e
            elements.append((cur, b, k, tau * k, False))
            cur = b
        if name == "S":
            sheave = cur
        if name == "C2":
            load = cur
    if load is None:
        load = sheave
    nodes_m[load] += v["G_m"] / G_N
    nodes_w[load] += -kr.load_weight_along_incline(v["G_m"], a)           # eq. (1)
    nodes_r[load] += kr.load_resistance(v["mu_pm"], v["G_m"], a)          # eq. (7)
    # exactly two elements touch the sheave node: the last of S and the first after it
    elements = [(e[0], e[1], e[2], e[3], e[1] == sheave or e[0] == sheave) for e in elements]
    mass = np.array(nodes_m)
    mass[0] = drum_C[0] + drum_S[0]
    weight = np.array(nodes_w)
    weight[0] = drum_C[1] + drum_S[1]
    res = np.array(nodes_r)
    res[0] = drum_C[2] + drum_S[2]
    if np.any(mass <= 0):
        raise InputError("every node of the rope model needs a mass: q_l must be > 0")
    masses = {"load": v["G_m"] / G_N, "rope_winding": q_l * L_u / G_N, "rope_unwinding": q_l * L_u / G_N}
    return Chain(mass, weight, res, tuple(drum_C), tuple(drum_S), elements, load, sheave, False, masses)


def build_rigid(v: dict, segments: int) -> Chain:
    """Inextensible rope: one body.  Winding half = load + winding rope, unwinding half = unwinding rope.

    Forces (Krauze et al. 2025 eq. (12)-(13) plus inertia): F_C = F_nwl/2 + G_lmC + (T_m + T_l)·th
    + (G_m + q_l L_u)/g · a and F_S = F_nwl/2 + G_ls − T_ls·th − q_l L_u/g · a.
    """
    L_u, q_l = v["L_u"], v["q_l"]
    m_C = v["G_m"] / G_N + q_l * L_u / G_N
    m_S = q_l * L_u / G_N
    w_C, w_S = -v["G_lmC"], v["G_ls"]              # eq. (14), (6) from the static model
    r_C, r_S = v["T_m"] + v["T_l"], v["T_ls"]      # eq. (7) + (10), (11)
    masses = {"load": v["G_m"] / G_N, "rope_winding": q_l * L_u / G_N, "rope_unwinding": m_S}
    return Chain(np.array([m_C + m_S]), np.array([w_C + w_S]), np.array([r_C + r_S]),
                 (m_C, w_C, r_C), (m_S, w_S, r_S), [], 0, None, True, masses)


#: rope_elasticity variant → chain builder (values, segments) → Chain
BUILDERS = {
    "segments": build_elastic,
    "spring": lambda v, n: build_elastic(v, 1),
    "rigid": build_rigid,
}
