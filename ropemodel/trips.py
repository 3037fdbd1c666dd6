"""A whole trip of the haulage along its route: forces, power and energy, exactly, piece by piece.

An upward trip (``travel = "up"``) takes the load from the return sheave end of the route
(x_m = L_u) to the drive (x_m = 0); a downward trip the other way.  The drive ramps linearly to
``v_pj`` in ``t_ramp``, runs at ``v_pj``, and ramps down to rest in ``t_ramp`` (a route shorter
than ``v_pj·t_ramp`` never reaches full speed: a triangular profile at the same acceleration).

Forces are the scene's own (its compiled equations, :class:`ropemodel.problem.Problem`): the
paper's quasi-static forces on the load's segment (:mod:`ropemodel.papers.route`) plus the
rigid-body inertia of the ramps (effect ``inertia = "rigid"``: the winding side gains
(G_m + q_l L_u)/g·a, the unwinding side loses q_l L_u/g·a).  Between the phase boundaries and
the instants the load crosses a joint of the route, every force is constant and the speed is
linear in time, so the drive power is linear in time and every integral is exact (no time step):

* mechanical power (F_C − F_S)·v; the drive's power P = that /η while motoring, ·η while it
  brakes (the power it would return);
* ``E_trip`` = ∫ max(P, 0) dt (motoring energy drawn), ``E_regen`` = ∫ max(−P, 0) dt;
* ``P_rms`` = √(∫ P² dt / t_trip) (the motor's thermal rating), ``P_max`` = max P;
* ``stroke_needed`` = the largest tensioner stroke of eq. (19)-(23) over the trip, ramps included.

The history (:attr:`Trip.history`) samples the trip for pictures and files; the summary comes
from the exact pieces, not from the samples.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from ropemodel.errors import InputError
from ropemodel.papers import route as rt
from ropemodel.scene import Scene, SceneLike, as_scene


#: samples of the history per phase (the summary does not depend on them)
SAMPLES = 200
#: summary keys → unit, in report order
SUMMARY = {"t_trip": "s", "F_C_max": "N", "F_S_min": "N", "P_max": "W", "P_rms": "W", "E_trip": "J",
           "E_regen": "J", "stroke_needed": "m"}


@dataclass(frozen=True)
class Piece:
    """A stretch of the trip with constant forces: [t0, t1], speed v0 → v1, acceleration a, the load's
    position at its middle, the forces and the tensioner stroke (eq. (23)) there."""

    t0: float
    t1: float
    v0: float
    v1: float
    a: float
    x_mid: float
    F_C: float
    F_S: float
    stroke: float


@dataclass
class Trip:
    """A trip: :attr:`pieces` (exact), :attr:`summary` (SI), :attr:`history` (a DataFrame of samples).

    ``phases`` are (t0, t1, v0, a) of the speed profile; the load starts at ``start`` [m] from the
    drive and moves toward it (``sign`` +1, upward) or away (−1).
    """

    scene: Scene
    direction: str
    eta: float
    phases: list[tuple[float, float, float, float]]
    start: float
    sign: float
    pieces: list[Piece] = field(default_factory=list)
    summary: dict = field(default_factory=dict)

    def position(self, t: float) -> float:
        """The load's distance from the drive at time t [m]."""
        return self.start - self.sign * rt.distance_travelled(self.phases, t)

    @property
    def history(self):
        """Samples of the trip (pandas DataFrame): ``t [s]``, ``x_m [m]``, ``v [m/s]``, ``a [m/s^2]``,
        ``F_C [N]``, ``F_S [N]``, ``P [W]``; both ends of every piece are included."""
        import pandas as pd

        rows = []
        for p in self.pieces:
            n = max(2, int(SAMPLES * len(self.phases) * (p.t1 - p.t0) / self.summary["t_trip"]))
            for t in np.linspace(p.t0, p.t1, n):
                v = p.v0 + p.a * (t - p.t0)
                rows.append((t, self.position(t), v, p.a, p.F_C, p.F_S, _power((p.F_C - p.F_S) * v, self.eta)))
        return pd.DataFrame(rows, columns=["t [s]", "x_m [m]", "v [m/s]", "a [m/s^2]", "F_C [N]", "F_S [N]", "P [W]"])

    def to_json(self) -> str:
        """The summary (SI) as one JSON object, with the direction and the pieces' count."""
        return json.dumps({**self.summary, "direction": self.direction, "pieces": len(self.pieces)}, indent=2,
                          allow_nan=False)

    def report(self) -> str:
        """A readable summary in kN, kW, kWh, s, mm."""
        s = self.summary
        return "\n".join([
            f"{self.scene.name}: trip {self.direction}, {s['t_trip']:.1f} s",
            f"  F_C max {s['F_C_max'] / 1e3:10.2f} kN   F_S min {s['F_S_min'] / 1e3:8.2f} kN",
            f"  P max   {s['P_max'] / 1e3:10.2f} kW   P rms   {s['P_rms'] / 1e3:8.2f} kW",
            f"  E trip  {s['E_trip'] / 3.6e6:10.4f} kWh  E regen {s['E_regen'] / 3.6e6:8.4f} kWh",
            f"  stroke needed {s['stroke_needed'] * 1e3:.1f} mm (eq. (23), largest over the trip, ramps included)",
        ])


def _power(mechanical: float, eta: float) -> float:
    """The drive's power: /η while motoring, ·η while braking (what it would return)."""
    return mechanical / eta if mechanical >= 0 else mechanical * eta


#: the effects a trip needs: the whole-trip profile, the ramps' inertia in the forces, the drive's power
TRIP_EFFECTS = {"dynamics": "trip", "inertia": "rigid", "power": "drive"}


def prepare(scene: Scene) -> Scene:
    """The scene as a trip needs it (:data:`TRIP_EFFECTS`; a scene that says nothing of them works): read
    again with those effects, every value it was given kept (:meth:`~ropemodel.scene.Scene.with_effects`)."""
    if scene.model != "winch":
        raise InputError(f"a trip is for winch scenes; this scene's model is {scene.model!r}")
    if all(scene.effects.get(k) == v for k, v in TRIP_EFFECTS.items()):
        return scene
    return scene.with_effects(TRIP_EFFECTS)


def reads(scene: Scene) -> tuple[set[str], dict[str, str]]:
    """What a trip of the (prepared) ``scene`` is computed from: the parameters of its forces and stroke in
    both directions, the speed profile and the efficiency; and those it sets itself (name → how)."""
    forces = [f"{f}_{d}" for f in ("F_C", "F_S", "dF") for d in ("up", "down")]
    used = scene.built.inputs_of([f for f in forces if f in scene.built.defined_by]) | {"v_pj", "t_ramp", "eta"}
    return used, {"x_m": "the trip moves the load along the whole route",
                  "a_h": "the trip's ramps set the acceleration (v_pj/t_ramp)"}


def trip(scene: SceneLike, direction: str | None = None) -> Trip:
    """The trip of a winch scene along its route (see the module docstring).

    Parameters
    ----------
    scene : Scene or str or Path
        A winch scene with ``v_pj`` and ``t_ramp`` (and ``eta``, default 1), a straight route or a
        route of ``[[route]]`` segments; a TOML scene file or a built-in scene's name is loaded first.
        It is read as a trip needs it (:func:`prepare`: the ramps' inertia in the forces, the drive's
        power), whatever its own effects say; every value it was given is kept.
    direction : {"up", "down"}, optional
        The trip's direction; default the scene's ``travel`` effect, else up.

    Returns
    -------
    Trip
        ``summary`` with ``t_trip`` [s], ``F_C_max`` [N], ``F_S_min`` [N], ``P_max`` [W], ``P_rms`` [W],
        ``E_trip`` [J], ``E_regen`` [J], ``stroke_needed`` [m]; ``history`` (samples).

    Raises
    ------
    InputError
        Not a winch scene, a bad direction, a missing speed or ramp time.
    SolveError
        A rope goes slack somewhere on the trip (the least F_nwl that keeps it taut is named).

    Examples
    --------
    The paper's incline (Fig. 9) as a whole upward trip, 1150 m at 2.5 m/s with 5 s ramps: the
    start's inertia adds (G_m + q_l L_u)/g · 0.5 m/s² = 28.5 kN to the paper's 190.95 kN.

    >>> import ropemodel as rm
    >>> t = trip(rm.load_scene("trip_fig9"))
    >>> round(t.summary["t_trip"], 1), round(t.summary["F_C_max"] / 1e3, 2)
    (465.0, 219.45)
    """
    from ropemodel.problem import Problem

    scene = prepare(as_scene(scene))
    direction = direction or scene.effects.get("travel", "up")
    if direction not in ("up", "down"):
        raise InputError(f"direction {direction!r}: a trip goes up or down")
    v = scene.parameters
    problem = Problem(scene)
    L_u = v["L_u"] if "L_u" in v else sum(_segment_lengths(v))
    eta = v.get("eta", 1.0)
    if L_u <= 0 or v["v_pj"] <= 0 or v["t_ramp"] <= 0:
        raise InputError("a trip needs a route, a speed and a ramp time > 0")
    phases = rt.trip_phases(L_u, v["v_pj"], v["t_ramp"])
    start, sign = (L_u, 1.0) if direction == "up" else (0.0, -1.0)
    out = Trip(scene, direction, eta, phases, start, sign)
    out.pieces = _pieces(problem, out, _cuts(scene, out, L_u))
    _taut(out, v["F_nwl"])
    out.summary = summarise(out.pieces, eta)
    return out


def _taut(trip: Trip, F_nwl: float) -> None:
    """:class:`SolveError` where a rope would have to push somewhere on the trip (it is slack)."""
    from ropemodel.errors import SolveError

    worst = min(trip.pieces, key=lambda p: min(p.F_C, p.F_S))
    least = min(worst.F_C, worst.F_S)
    if least > 0.0:
        return
    side = "winding" if worst.F_C <= worst.F_S else "unwinding"
    raise SolveError(f"the {side} rope would have to push ({least / 1e3:.6g} kN) at t = {worst.t0:.6g} s of the "
                     f"{trip.direction}ward trip, the load at x_m = {trip.position(worst.t0):.6g} m: it is slack and "
                     f"the model no longer holds; every rope stays taut with "
                     f"F_nwl > {(F_nwl - 2 * least) / 1e3:.6g} kN")


def _segment_lengths(values: dict) -> list[float]:
    """L_1, L_2, … of a route of segments (none on a straight route)."""
    out, i = [], 1
    while f"L_{i}" in values:
        out.append(values[f"L_{i}"])
        i += 1
    return out


def _cuts(scene, trip: Trip, L_u: float) -> list[float]:
    """Times of the phase boundaries and of the load crossing a joint of the route, in order."""
    times = {t for t0, t1, _, _ in trip.phases for t in (t0, t1)}
    ends = list(np.cumsum(_segment_lengths(scene.parameters)))
    for end in ends[:-1]:
        times.add(rt.time_at_distance(trip.phases, trip.sign * (trip.start - end)))
    return sorted(times)


def _pieces(problem, trip: Trip, cuts) -> list[Piece]:
    """Every stretch between two cuts, its forces evaluated at its middle (one compiled call for all)."""
    phases, direction = trip.phases, trip.direction
    spans = [(t0, t1) for t0, t1 in zip(cuts[:-1], cuts[1:]) if t1 > t0]
    mids = [0.5 * (t0 + t1) for t0, t1 in spans]
    acc = np.array([next(a for p0, p1, _, a in phases if p0 <= tm <= p1) for tm in mids])
    x = np.array([trip.position(tm) for tm in mids])
    cols = {"a_h": acc}
    if "x_m" in problem.knowns:
        cols["x_m"] = x
    out = problem.evaluate(cols)
    F_C, F_S = out[f"F_C_{direction}"], out[f"F_S_{direction}"]
    stroke = out.get(f"dF_{direction}", np.full(len(spans), np.nan))
    pieces = []
    for k, (t0, t1) in enumerate(spans):
        p = next(q for q in phases if q[0] <= mids[k] <= q[1])
        v0 = p[2] + p[3] * (t0 - p[0])
        pieces.append(Piece(t0, t1, v0, v0 + p[3] * (t1 - t0), p[3], float(x[k]), float(F_C[k]), float(F_S[k]),
                            float(stroke[k])))
    return pieces


def summarise(pieces: list[Piece], eta: float) -> dict:
    """The trip's summary from its pieces, exactly (power linear in time on each piece)."""
    E_pos = E_neg = P2 = 0.0
    P_max = -math.inf
    for p in pieces:
        dF = p.F_C - p.F_S
        P0, P1 = _power(dF * p.v0, eta), _power(dF * p.v1, eta)   # one sign per piece: v >= 0, dF fixed
        dt = p.t1 - p.t0
        E = 0.5 * (P0 + P1) * dt
        E_pos += max(E, 0.0)
        E_neg += max(-E, 0.0)
        P2 += dt * (P0 * P0 + P0 * P1 + P1 * P1) / 3.0
        P_max = max(P_max, P0, P1)
    t_trip = pieces[-1].t1 - pieces[0].t0
    return {"t_trip": t_trip, "F_C_max": max(p.F_C for p in pieces), "F_S_min": min(p.F_S for p in pieces),
            "P_max": P_max, "P_rms": math.sqrt(P2 / t_trip), "E_trip": E_pos, "E_regen": E_neg,
            "stroke_needed": max(p.stroke for p in pieces)}
