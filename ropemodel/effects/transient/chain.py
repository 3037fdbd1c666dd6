"""The lumped rope loop of a winch scene: nodes (masses, weights, resistances) and Kelvin–Voigt elements.

Geometry (Krauze et al. 2025, Fig. 5): an endless rope.  The path coordinate p runs around the loop
in the direction the rope moves when the load is hauled up:

    drum (node 0) --S--> return sheave K_ZN --C2--> load --C1--> drum

``S`` is the unwinding rope (length L_u, it runs down the incline), ``C2`` the winding rope between
the return sheave and the load (L_u − x_m) and ``C1`` the winding rope between the load and the drum
(x_m).  A span of zero length is left out: at x_m = L_u the load sits at the return sheave, at x_m = 0 on
the drum's node (its mass, weight and resistance then join the winding half of the drum node: the load
is where the winding rope meets the drum).

The load at the return sheave (x_m = L_u) is attached to the rope at the sheave's winding-side
tangent point, so it moves with the carriage as well as with the rope: with the rope at the sheave as
the node's coordinate, the load's position would be u − z/2, coupling its mass to the carriage's.  The
node's coordinate is the load's instead: the unwinding span's last element then takes the whole
take-up z (the rope at the sheave is at u + z/2 and the carriage adds z/2 of path on the unwinding
side), the winding span's first element none, and that element's rope mass at the sheave goes to its
other node with its weight and resistance.  The carriage feels only the unwinding side's tension,
2·T_S (the frictionless sheave carries the same tension on both tangent points, the load's pull is
the winding rope's): at rest T_S = F_nwl/2 and the winding rope carries the load, as eq. (12)-(13).
Displacements ``u`` are along p (Eulerian nodes at fixed places on the route, the standard lumped
model of conveyor and haulage ropes: over a transient of tens of seconds the load moves a small part
of the route, so the spans' lengths are frozen at their initial values).

Moving masses: the load G_m/g and the rope q_l ℓ/g of every element, lumped half on each end node.
Weights along the route and resistances come from the route (:mod:`.route`), the Coulomb resistances
to be smoothed as R·tanh(v/v_eps) by the rope model.  Masses, weights, resistances and stiffnesses
are Python lists of floats or CasADi symbols (never numpy arrays), so that the symbolic smooth mode
can build the chain from symbolic parameters; the geometry (L_u, x_m, segments) is numeric.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from ropemodel.effects.transient.route import Loads, Route


class Element(NamedTuple):
    """Kelvin–Voigt element between nodes a and b: tension k·e + c·ė, e = u_b − u_a + take_up·z, where
    ``take_up`` is the element's share of the tensioner's take-up z (the carriage moving by z/2 lengthens
    the rope's path by z/2 on each side of the return sheave: ½ for the two elements that wrap it)."""

    a: int
    b: int
    k: object
    c: object
    take_up: float = 0.0


@dataclass
class Chain:
    """Nodes and elements of the loop (SI).

    Node 0 is the rope on the drum; its mass, weight and resistance are split into the winding half
    (``drum_C``) and the unwinding half (``drum_S``), so that the forces at the drum's two tangent
    points F_C and F_S can be reported.  ``rigid``: an inextensible loop (one node, no element).
    """

    mass: list
    weight: list               # force of gravity along +p [N]
    resistance: list           # Coulomb resistance magnitude in motion [N]
    drum_C: Loads
    drum_S: Loads
    elements: list = field(default_factory=list)
    load: int = 0
    sheave: int | None = None
    rigid: bool = False
    masses: dict = field(default_factory=dict)
    contact: dict = field(default_factory=dict)   # drum contact stiffnesses [N/m], when a contact adds any

    @property
    def n(self) -> int:
        return len(self.mass)


class _Nodes:
    """Accumulates loads on nodes; node 0's are kept per half (winding "C", unwinding "S")."""

    def __init__(self):
        self.mass, self.weight, self.resistance = [0.0], [0.0], [0.0]
        self.half = {"C": [0.0, 0.0, 0.0], "S": [0.0, 0.0, 0.0]}

    def new(self) -> int:
        for lst in (self.mass, self.weight, self.resistance):
            lst.append(0.0)
        return len(self.mass) - 1

    def add(self, node: int, half: str, m, w, r) -> None:
        if node == 0:
            acc = self.half[half]
            acc[0], acc[1], acc[2] = acc[0] + m, acc[1] + w, acc[2] + r
        else:
            self.mass[node] += m
            self.weight[node] += w
            self.resistance[node] += r

    def drum(self, half: str) -> Loads:
        return Loads(*self.half[half])


def spans(L_u: float, x_m: float) -> list[tuple[str, float, float]]:
    """The loop's spans (name, s where it starts, s where it ends) in the order of p; s from the drive.
    Zero-length spans are left out."""
    out = [("S", 0.0, L_u), ("C2", L_u, x_m), ("C1", x_m, 0.0)]
    return [sp for sp in out if sp[1] != sp[2]]


def build_elastic(values: dict, route: Route, L_u: float, x_m: float, segments: int) -> Chain:
    """The loop cut into ``segments`` elements per span.

    EA = L_u/q_lw (q_lw: elongation of L_u of installed rope per newton, Krauze eq. (19)-(20)); the
    damping c = τ·k with τ = ``rope_damping``.  The weight and resistance of an element on the return
    sheave go to its far node, so that the rope at the sheave's tangent points is at F_nwl/2 per side
    in steady motion, as in the paper's eq. (12)-(13) (the wrapped rope carries no weight across it).
    """
    EA = values["L_u"] / values["q_lw"]
    tau = values["rope_damping"]
    nodes, elements = _Nodes(), []
    sheave = segments                       # S always has `segments` elements: its last node is the sheave
    parts = spans(L_u, x_m)
    load_at_sheave = all(name != "C2" for name, *_ in parts)
    load, cur = sheave, 0                   # the load sits at the sheave unless a span C2 leads to it
    for p, (name, s_a, s_b) in enumerate(parts):
        step = (s_b - s_a) / segments
        k = EA / abs(step)
        c = tau * k
        for j in range(segments):
            b = 0 if (p == len(parts) - 1 and j == segments - 1) else nodes.new()
            share = _take_up(cur, b, sheave, load_at_sheave)
            s0, s1 = sorted((s_a + j * step, s_a + (j + 1) * step))
            m, w, r = route.rope("unwinding" if name == "S" else "winding", s0, s1)
            w = w if step > 0 else -w                     # weight along +p
            for node in (cur, b):
                f = 0.5 if share == 0.0 else (0.0 if node == sheave else 1.0)    # sheave's loads: far node
                fm = 0.5 if share < 1.0 else (0.0 if node == sheave else 1.0)
                nodes.add(node, "S" if name == "S" else "C", fm * m, f * w, f * r)
            elements.append(Element(cur, b, k, c, share))
            cur = b
        if name == "C2":
            load = cur
    m, w, r = route.load(x_m)
    nodes.add(load, "C", m, -w, r)                        # the winding rope pulls the load towards the drive
    drum_C, drum_S = nodes.drum("C"), nodes.drum("S")
    nodes.mass[0], nodes.weight[0], nodes.resistance[0] = (drum_C[i] + drum_S[i] for i in range(3))
    return Chain(nodes.mass, nodes.weight, nodes.resistance, drum_C, drum_S, elements, load, sheave,
                 False, _masses(route, L_u, x_m))


def _take_up(a: int, b: int, sheave: int, load_at_sheave: bool) -> float:
    """An element's share of the take-up: ½ on each side of the sheave; with the load at the sheave the
    whole take-up on the unwinding side (the element ending at the sheave) and none on the winding side."""
    if sheave not in (a, b):
        return 0.0
    if not load_at_sheave:
        return 0.5
    return 1.0 if b == sheave else 0.0


def build_rigid(route: Route, L_u: float, x_m: float) -> Chain:
    """Inextensible rope: one body.  Winding half = load + winding rope, unwinding half = unwinding rope.

    Forces (Krauze et al. 2025 eq. (12)-(13) plus inertia): F_C = F_nwl/2 + G_lmC + (T_m + T_l)·th
    + (G_m + q_l L_u)/g · a and F_S = F_nwl/2 + G_ls − T_ls·th − q_l L_u/g · a.
    """
    load, rope_C, rope_S = route.load(x_m), route.rope("winding", 0.0, L_u), route.rope("unwinding", 0.0, L_u)
    drum_C = Loads(load.mass + rope_C.mass, -(load.weight + rope_C.weight), load.resistance + rope_C.resistance)
    drum_S = Loads(*rope_S)
    return Chain([drum_C.mass + drum_S.mass], [drum_C.weight + drum_S.weight],
                 [drum_C.resistance + drum_S.resistance], drum_C, drum_S, [], 0, None, True,
                 _masses(route, L_u, x_m))


def _masses(route: Route, L_u: float, x_m: float) -> dict:
    return {"load": route.load(x_m).mass, "rope_winding": route.rope("winding", 0.0, L_u).mass,
            "rope_unwinding": route.rope("unwinding", 0.0, L_u).mass}
