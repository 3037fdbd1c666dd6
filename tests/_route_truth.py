"""docs/physics.md §4 written out in numpy, independently of ropemodel: a route of straight segments, the rope
forces at the drum with the load anywhere and the ramps' rigid-body inertia, the tension along each rope side
evaluated at many points, and the worst of each over the load's places and the manoeuvres by brute force.

Conventions (docs/physics.md §4): x from the drive (0) to the return sheave (L_u); α > 0 rises toward the
drive; s = +1 hauling up, −1 lowering; a the acceleration in the direction of travel.  Each side is held at
F_nwl/2 at the return sheave; toward the drive its tension rises by q_l (sin α ± s (μ cos α + a/g)) per metre
(+ winding side, − unwinding side), and the winding side's load adds G_m (sin α_j + s (μ_pm cos α_j + a/g)) on
its drive side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

G = 9.80665
K, W, C = 0.356, 4090.0, 0.460          # 6x36-IWRC, EN 12385-4 (K, W [kg/m^3], C)


@dataclass(frozen=True)
class Route:
    """A haulage on a route of segments: lengths [m], inclinations [deg], the winding rope's resistance per
    segment, SI values otherwise."""

    lengths: tuple
    degrees: tuple
    mus: tuple
    G_m: float
    q_l: float
    F_nwl: float
    mu_pm: float = 0.05
    mu_pl: float = 0.05

    def with_(self, **kw) -> Route:
        return replace(self, **kw)

    @property
    def alphas(self) -> np.ndarray:
        return np.radians(self.degrees)

    @property
    def ends(self) -> np.ndarray:
        return np.cumsum(self.lengths)

    @property
    def L_u(self) -> float:
        return float(np.sum(self.lengths))

    def segment(self, x_m: float) -> int:
        """0-based index of the load's segment (a load on a joint: the one nearer the drive)."""
        return min(int(np.searchsorted(self.ends, x_m, side="left")), len(self.lengths) - 1)

    def pull(self, x_m: float, a: float, s: float) -> float:
        """J [N]: the load's weight, resistance and inertia along its segment."""
        al = self.alphas[self.segment(x_m)]
        return self.G_m * (math.sin(al) + s * (self.mu_pm * math.cos(al) + a / G))

    def rise(self, x, side: str, a: float, s: float) -> np.ndarray:
        """q_l ∫_x^{L_u} (sin α ± s (μ cos α + a/g)) dξ [N] at points x: the part of each segment beyond x."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        starts = self.ends - np.asarray(self.lengths)
        sign = 1.0 if side == "winding" else -1.0
        mu = np.asarray(self.mus) if side == "winding" else np.full(len(self.lengths), self.mu_pl)
        g = np.sin(self.alphas) + sign * s * (mu * np.cos(self.alphas) + a / G)
        beyond = np.clip(self.ends[None, :] - np.maximum(starts[None, :], x[:, None]), 0.0,
                         np.asarray(self.lengths)[None, :])
        return self.q_l * beyond @ g

    def tension(self, x, side: str, x_m: float, a: float, s: float) -> np.ndarray:
        """T(x) [N] of a side (the winding side: with the load at x_m, its pull on the drive side x < x_m)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        T = 0.5 * self.F_nwl + self.rise(x, side, a, s)
        if side == "winding":
            T = T + np.where(x < x_m, self.pull(x_m, a, s), 0.0)
        return T

    def drum(self, x_m: float, a: float, s: float) -> tuple[float, float]:
        """(F_C, F_S) [N] at the drum: the winding rope there carries the load's pull (eq. (12)-(13))."""
        return (float(0.5 * self.F_nwl + self.rise(0.0, "winding", a, s)[0] + self.pull(x_m, a, s)),
                float(0.5 * self.F_nwl + self.rise(0.0, "unwinding", a, s)[0]))

    def least(self, side: str, x_m: float, a: float, s: float, n: int = 20001) -> float:
        """The least tension of a side anywhere from the drum to the return sheave, by brute force: at n points
        along the route, at every joint, just either side of the load, and (the winding side) at the drum."""
        x = np.concatenate([np.linspace(0.0, self.L_u, n), self.ends, [0.0],
                            [max(x_m - 1e-9, 0.0), min(x_m + 1e-9, self.L_u), x_m]])
        T = float(np.min(self.tension(x, side, x_m, a, s)))
        return min(T, self.drum(x_m, a, s)[0]) if side == "winding" else T


def places(route: Route, n: int = 200) -> np.ndarray:
    """Many places of the load: a grid over the route and both sides of every joint."""
    eps = 1e-6
    joints = np.concatenate([[0.0], route.ends])
    return np.unique(np.clip(np.concatenate([np.linspace(0.0, route.L_u, n), joints - eps, joints, joints + eps]),
                             0.0, route.L_u))


def worst(route: Route, quantity, accelerations, sense=min, n: int = 200) -> tuple[float, float, float]:
    """(value, x_m, a) of the worst of ``quantity(route, x_m, a)`` over many places and the accelerations."""
    best = None
    for a in accelerations:
        for x in places(route, n):
            v = quantity(route, float(x), a)
            if best is None or sense(v, best[0]) == v and v != best[0]:
                best = (v, float(x), a)
    return best


def rope(d: float, grade: float = 1770e6, E: float = 100e9, L_u: float = 1.0) -> dict:
    """A 6x36-IWRC rope of diameter d [m]: q_l [N/m], F_min [N], q_lw [m/N] over L_u (EN 12385-4)."""
    return {"q_l": G * W * d * d, "F_min": K * d * d * grade, "q_lw": L_u / (E * C * d * d)}
