"""An independent lumped-mass model of a Koepe hoist braking or starting, in scipy only: the truth the elastic
transient of issue 25 (item 3) is tested against.  It imports nothing of ropemodel.  Its equations are in
tests/_koepe_lumped_equations.py; this module holds the wheel's profiles, the integration with its events, the
results, the energy and the natural frequencies.  SI throughout (m, s, kg, N, J); depths positive downward.

What it models:

* **Head ropes**: each side's n_head ropes as one span of axial stiffness n_head·EA_head over its current length,
  from the wheel's tangent point (depth 0) to the conveyance, cut into N Kelvin–Voigt elements (spring EA/ℓ,
  dashpot τ·EA/ℓ; a rope that would push is slack: the force is max(0, k e + c ė) while e > 0, else 0).  The
  rope's mass, q = n_head·q_head per metre of unstretched rope, is lumped half of each element on each end; node
  N is the conveyance (m_conveyance, + m_payload on side L).  The top element's unstretched length is
  ℓ_1 = ℓ_top ∓ x (x the rope run over the wheel; side L shortens while hoisting), the others are fixed.  Of the
  top element's material, ℓ_top/2 is lumped on node 1; the rest, a column of ℓ_1 − ℓ_top/2, hangs from the
  tangent point and moves with the rope on the wheel (its weight and inertia load the tangent tension; the
  two columns add up to ℓ_top, so every node mass is constant).  ``reel`` [m]: the top elements start 2·reel
  longer, so that that much rope may run over the wheel from either side; a column used up stops with an error.
* **Tail ropes** (ρ = n_tail·q_tail per metre): inextensible, in a free loop hanging from the two conveyances
  (turn of negligible size); side lengths ℓ_t = (y_other − y_own + H + 2 h_loop)/2 from the conveyances'
  depths.  Lagrange's equations of the loop add to each conveyance the mass ρ ℓ_t and the downward force
  ρ g ℓ_t + ρ w², w = (ẏ_other − ẏ_own)/2 the loop's speed along itself (the known moving-loop result; the rigid
  ropemodel.papers.koepe leaves ρ w² out: 12.4 kN on both sides at 20 m/s here).
* **The rope on the wheel** (m_arc = n_head q_head R α; 0 with arc_rope=False) is rigid; with the columns it
  moves at x (positive: rope runs from side L over the wheel to side E, the loaded conveyance rises).  Sticking,
  the wheel moves with it and its inertia J/R² (J [kg m²]: wheel, drive, brake discs) adds.  Tangent tensions
  T_L = A_L + m_col,L ẍ, T_E = A_E − m_col,E ẍ, A = F_1 + m_col g.  Slip is judged at every instant by
  Euler–Eytelwein on the arc, with the arc rope's inertia (accelerating at a_θ toward the high side h) and
  centrifugal force (q_a = m_arc/(R α)): sticking holds while, for h = L and h = E,
  g_h = e^{μα}(T_l − q_a v²) − (T_h − q_a v²) + (e^{μα} − 1) q_a R a_θ/μ >= 0,
  which is T_high/T_low <= e^{μα} when m_arc = 0.  Where a g_h reaches 0 an event switches to slipping toward
  h: g_h = 0 then fixes the rope's acceleration, the friction F_f acts back on the wheel; where the relative
  speed ẋ − ẋ_w returns to 0 it sticks if both g >= 0, else slips the other way.
* **The wheel**: a force at the rope radius F_w(t, ẋ_w) = torque/R [N], + toward +x (``Wheel("force", f)``,
  :func:`brake`), or a prescribed acceleration (:func:`constant_deceleration`, :func:`drive_ramp`,
  ``Wheel("kinematic", a)``) whose force is computed.
* Left out: shaft resistance, tail-rope elasticity, bending, the rope's creep on the arc (rigid arc: stick or
  gross slip), deflection sheaves, the arc rope's weight.  O(T/EA) choices: x counts unstretched rope and the
  wheel's surface moves with it; the strain energy carried onto the rigid arc, S = ½ k_1 e_1²/ℓ_1 per side,
  acts on the arc (not in T); the tail loop shifts with the sides' stretch.  All vanish as EA → ∞.

It is a Lagrangian system with constant masses: brake work = Δ(kinetic + elastic + gravity energy) + damping
+ friction dissipation, to the integrator's tolerance (:func:`energy`; ``Run.frame()`` has every term).

Accuracy, measured by tests/test_koepe_lumped.py on the issue's hoist (:func:`example_hoist`): the wheel's
acceleration at the onset of slip tends to koepe_slip's rigid window as EA grows (lowering stop: 4 % off at the
real EA, 2e-6 at 100×, 1e-8 at 10⁴×); the first natural frequency converges to the continuous rope's at second
order in 1/N (3.4e-4 at N = 8); tangent tensions in a transient converge at first order (the column moves with
the wheel: 0.3 % at N = 8 against the extrapolated limit, 0.07 % at N = 32).  DOP853 (the default) suits soft
cases; use method="LSODA" for stiff ones (large N, stiff ropes, large τ).

Use::

    h = example_hoist(N=8, reel=30.0)          # or Hoist(H=..., ...): the fields' units are in its docstring
    run = simulate(h, y_L0=800.0, v0=-10.0, wheel=constant_deceleration(-10.0, 1.8, 0.5), t_end=8.0)
    run.frame()    # t [s], x [m], v [m/s], v_w [m/s], a [m/s2], a_w, T_L [N], T_E [N], F_w [N], F_f [N],
                   # y_L, y_E [m] (the conveyances' depths below their upper positions, stretch included),
                   # v_L [m/s] (loaded conveyance, + up), mode (0 stick, ±1 slipping toward E/L),
                   # W_brake, D_damping, D_friction, energy [J]
    run.events     # [(t [s], "slip toward L" | "slipping toward L" | "relative speed 0" | "stick" | "rest"), ...]

The initial state is the steady state at v0 [m/s] (+: hoisting; 0: at rest) with the loaded conveyance y_L0 [m]
below its upper position; H_head + y are the spans' unstretched lengths, as in the rigid model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from _koepe_lumped_equations import (G_N, SGN, Hoist, Mesh, Wheel, arc, energy, margins, mesh, rhs, spans, tensions,
                                     unpack)

__all__ = ["G_N", "Hoist", "Mesh", "Run", "Wheel", "brake", "constant_deceleration", "drive_ramp", "energy",
           "example_hoist", "initial_state", "mesh", "natural_frequencies", "simulate", "steady_force"]


def example_hoist(**changes) -> Hoist:
    """Issue 25's example hoist with what it does not give assumed: EA_head = 100 GPa × C d² of its 8.6 kg/m ropes
    (6x19 IWRC, C = 0.449, d = 46.4 mm by EN 12385-4's W = 0.400 kg/(100 m mm²); makers quote 80–120 GPa),
    J = 2.0e5 kg m² (wheel, drive and discs), τ = 0.01 s, N = 8, reel = 30 m; ``changes`` override fields."""
    d2 = 8.6 / 4000.0
    h = Hoist(H=905.0, H_head=56.7, m_conveyance=29.6e3, m_payload=22e3, n_head=4, q_head=8.6,
              EA_head=1.0e11 * 0.449 * d2, mu=0.25, alpha=math.pi, R=2.25, J=2.0e5, n_tail=2, q_tail=15.5,
              tau=0.01, N=8, reel=30.0)
    return replace(h, **changes)


def brake(F_0: float, F_brake: float, t_apply: float, direction: float) -> Wheel:
    """The drive's force F_0 [N] gives way linearly in t_apply [s] to a brake of F_brake [N] against the initial
    motion (direction = sign of v0); run with ``stop="rest"``: a brake holds once the wheel is at rest."""
    return Wheel("force", lambda t, v: F_0 + (-math.copysign(F_brake, direction) - F_0) * min(t / t_apply, 1.0),
                 (t_apply,))


def constant_deceleration(v0: float, d: float, t_jerk: float) -> Wheel:
    """Constant-deceleration control: the wheel's deceleration rises linearly to d [m/s²] in t_jerk [s], holds
    until the wheel is at rest, then the wheel is held (a = 0)."""
    s, v = math.copysign(1.0, v0), abs(v0)
    t_s = math.sqrt(2 * v * t_jerk / d) if v <= d * t_jerk / 2 else t_jerk + (v - d * t_jerk / 2) / d
    return Wheel("kinematic", lambda t: 0.0 if t >= t_s else -s * d * min(t / t_jerk, 1.0), (t_jerk, t_s))


def drive_ramp(v_target: float, a: float, t_jerk: float) -> Wheel:
    """A start from rest to v_target [m/s] (sign: direction) at a [m/s²], each change of a taking t_jerk [s]."""
    s, t_c = math.copysign(1.0, v_target), abs(v_target) / a - t_jerk
    if t_c < 0:
        raise ValueError(f"drive_ramp: |v_target| = {abs(v_target)} m/s is below a·t_jerk = {a * t_jerk} m/s")
    knots = np.array([0.0, t_jerk, t_jerk + t_c, 2 * t_jerk + t_c])
    return Wheel("kinematic", lambda t: s * float(np.interp(t, knots, [0.0, a, a, 0.0])), tuple(knots[1:]))


def _events(h: Hoist, me: Mesh, wheel: Wheel, mode: int, stop: str, v0: float):
    """Terminal events of a mode, with their names: Euler–Eytelwein's margins (stick), the relative speed (slip),
    a column used up, the wheel at rest (stop = "rest")."""
    def ee(t, s):
        x, v, xw, vw, w, u = unpack(h, s)
        sp = spans(h, me, x, v, w, u)
        return margins(h, sp, v, arc(h, wheel, 0, t, v, vw, sp)[0])

    table = ([("slip toward L", lambda t, s: ee(t, s)[0], -1), ("slip toward E", lambda t, s: ee(t, s)[1], -1)]
             if mode == 0 else [("relative speed 0", lambda t, s: s[1] - s[3], -mode)])
    table.append(("column used up", lambda t, s: float(np.min(me.top / 2 + SGN * s[0])), -1))
    if stop == "rest":
        table.append(("rest", lambda t, s: s[3], -math.copysign(1.0, v0)))
    for _, ev, direction in table:
        ev.terminal, ev.direction = True, direction
    return [ev for _, ev, _ in table], [name for name, _, _ in table]


def _decide(h: Hoist, me: Mesh, wheel: Wheel, t, s) -> int:
    """The mode after the relative speed reached 0: stick if Euler–Eytelwein holds both ways, else slip."""
    x, v, xw, vw, w, u = unpack(h, s)
    sp = spans(h, me, x, v, w, u)
    g_L, g_E = margins(h, sp, v, arc(h, wheel, 0, t, v, vw, sp)[0])
    tol = 1e-10 * float(np.abs(sp["A"]).sum())
    if g_L >= -tol and g_E >= -tol:
        return 0
    return -1 if g_L < g_E else 1


@dataclass
class Run:
    """A simulation: the hoist, its mesh, the wheel, times t [s], states y (rows: x, v, x_w, v_w, w (2N),
    ẇ (2N), brake work, damping, friction dissipation), the mode at each time (0 stick, +1/−1 slipping toward
    E/L) and the events [(t [s], name)]."""

    hoist: Hoist
    mesh: Mesh
    wheel: Wheel
    t: np.ndarray
    y: np.ndarray
    modes: np.ndarray
    events: list

    def frame(self) -> pd.DataFrame:
        """One row per time: tangent tensions, forces, positions, speeds, energies [SI]."""
        h, me, rows = self.hoist, self.mesh, []
        for t, s, mode in zip(self.t, self.y.T, self.modes):
            x, v, xw, vw, w, u = unpack(h, s)
            sp = spans(h, me, x, v, w, u)
            xdd, xwdd, F_w, F_f = arc(h, self.wheel, int(mode), t, v, vw, sp)
            T_L, T_E = tensions(h, sp, xdd)
            rows.append({"t [s]": t, "x [m]": x, "v [m/s]": v, "v_w [m/s]": vw, "a [m/s2]": xdd,
                         "a_w [m/s2]": xwdd, "T_L [N]": T_L, "T_E [N]": T_E, "F_w [N]": F_w, "F_f [N]": F_f,
                         "y_L [m]": sp["z"][0, -1] - h.H_head, "y_E [m]": sp["z"][1, -1] - h.H_head,
                         "v_L [m/s]": -sp["zdot"][0, -1], "mode": int(mode), "W_brake [J]": s[-3],
                         "D_damping [J]": s[-2], "D_friction [J]": s[-1], "energy [J]": energy(h, me, s)})
        return pd.DataFrame(rows)


def steady_force(h: Hoist, me: Mesh) -> float:
    """The wheel's force [N] that keeps the initial steady state (at rest: the holding force)."""
    s = initial_state(h, me, 0.0)
    sp = spans(h, me, 0.0, 0.0, *unpack(h, s)[4:])
    return float(sp["A"][0] + sp["S"][0] - sp["A"][1] - sp["S"][1])


def initial_state(h: Hoist, me: Mesh, v0: float) -> np.ndarray:
    """The state vector of the steady state at v0 [m/s] (elastic displacements 0 by the mesh's construction)."""
    return np.concatenate([[0.0, v0, 0.0, v0], np.zeros(4 * h.N + 3)])


def simulate(h: Hoist, y_L0: float, v0: float, wheel: Wheel, t_end: float, stop: str = "end",
             method: str = "DOP853", rtol: float = 1e-9, atol: float = 1e-10, max_step: float = np.inf) -> Run:
    """Integrate from the steady state at v0 [m/s] (+: hoisting) with the loaded conveyance at y_L0 [m] below its
    upper position, to t_end [s] or, with stop = "slip" / "rest", to the first slip or to the wheel at rest."""
    bad = [problem for problem, wrong in (
        (f"y_L0 = {y_L0} m must lie in [0, H = {h.H}] m", not 0 <= y_L0 <= h.H),
        (f"t_end = {t_end} s must be > 0", not t_end > 0),
        (f"stop = {stop!r} must be 'end', 'slip' or 'rest'", stop not in ("end", "slip", "rest")),
        (f"wheel.kind = {wheel.kind!r} must be 'force' or 'kinematic'", wheel.kind not in ("force", "kinematic")))
        if wrong]
    if bad:
        raise ValueError("; ".join(bad))
    me = mesh(h, y_L0, v0)
    s, t, mode = initial_state(h, me, v0), 0.0, 0
    ts, ys, modes, events = [np.array([0.0])], [s[:, None]], [np.array([0])], []
    if min(margins(h, spans(h, me, 0.0, v0, *unpack(h, s)[4:]), v0, 0.0)) < 0:
        raise ValueError("the ropes slip on the wheel in the initial steady state")
    marks = sorted({b for b in wheel.breakpoints if 0 < b < t_end} | {t_end})
    while t < t_end:
        t_next = next(b for b in marks if b > t)
        evs, names = _events(h, me, wheel, mode, stop, v0)
        sol = solve_ivp(rhs(h, me, wheel, mode), (t, t_next), s, method=method, events=evs, rtol=rtol,
                        atol=atol, max_step=max_step)
        if sol.status < 0:
            raise RuntimeError(f"integration failed at t = {t} s: {sol.message}")
        ts.append(sol.t[1:])
        ys.append(sol.y[:, 1:])
        modes.append(np.full(sol.t.size - 1, mode))
        t, s = float(sol.t[-1]), sol.y[:, -1]
        if sol.status == 1:
            name = names[next(i for i, te in enumerate(sol.t_events) if te.size)]
            events.append((t, name))
            if name == "column used up":
                raise ValueError(f"at t = {t:.4g} s the rope run over the wheel used up a top element: raise reel")
            if name == "rest" or (stop == "slip" and name.startswith("slip")):
                break
            mode = {"slip toward E": 1, "slip toward L": -1}.get(name)
            mode = _decide(h, me, wheel, t, s) if mode is None else mode
            events.append((t, {0: "stick", 1: "slipping toward E", -1: "slipping toward L"}[mode]))
    return Run(h, me, wheel, np.concatenate(ts), np.hstack(ys), np.concatenate(modes), events)


def natural_frequencies(h: Hoist, y_L0: float) -> np.ndarray:
    """Angular frequencies [rad/s] of small free vibrations about the static state with the wheel locked
    (x = x_w = 0), ascending: eigenvalues of the stiffness −∂ẅ/∂w (central differences; exact for a linear
    system: taut ropes, no tail loop, no damping)."""
    me = mesh(h, y_L0)
    still = Wheel("kinematic", lambda t: 0.0)
    s0, n = initial_state(h, me, 0.0), 2 * h.N
    K, f = np.empty((n, n)), rhs(h, me, still, 0)
    for j in range(n):
        step = 1e-6 * max(1.0, float(np.abs(me.e0).max()))
        plus, minus = s0.copy(), s0.copy()
        plus[4 + j] += step
        minus[4 + j] -= step
        K[:, j] = -(f(0.0, plus) - f(0.0, minus))[4 + n:4 + 2 * n] / (2 * step)
    return np.sqrt(np.sort(np.linalg.eigvals(K).real))
