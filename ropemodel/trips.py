"""A whole trip of the haulage along its route: forces, power and energy, exactly, piece by piece.

An upward trip (``travel = "up"``) takes the load from the return sheave end of the route
(x_m = L_u) to the drive (x_m = 0); a downward trip the other way.  The drive ramps linearly to
``v_pj`` in ``t_ramp``, runs at ``v_pj``, and ramps down to rest in ``t_ramp`` (a route shorter
than ``v_pj·t_ramp`` never reaches full speed: a triangular profile at the same acceleration).

Forces are the scene's own (its compiled equations, :class:`ropemodel.problem.Problem`): the
paper's quasi-static forces on the load's segment (:mod:`ropemodel.papers.route`) plus the
rigid-body inertia of the ramps (effect ``inertia = "rigid"``: the winding side gains
(G_m + q_l L_u)/g·a, the unwinding side loses q_l L_u/g·a, a the acceleration in the direction of
travel).  The load's motion is signed (physics reference §4): u > 0 up the slope (toward the drive),
du/dt its signed acceleration.  Between the phase boundaries and the instants the load crosses a
joint of the route every force is constant and u is linear in time, so every integral is exact (no
time step).  Powers are signed, four-quadrant: > 0 the drive motors, < 0 it brakes.

* the drum's power P_drum = (F_C − F_S)·u (:func:`ropemodel.papers.krauze2025.drum_power`); the
  drive's N_p = P_drum/η motoring, P_drum·η braking (:func:`~ropemodel.papers.krauze2025.drive_power`);
* ``E_trip`` = ∫ max(N_p, 0) dt, the energy drawn while motoring; the energy of braking
  ∫ max(−N_p, 0) dt is ``E_regen`` (returned to the supply) or ``E_dissipated`` (burnt in a braking
  resistor), as the scene's ``braking`` effect says (:mod:`ropemodel.effects.winch_braking`);
* ``P_max`` = the largest motoring N_p (≥ 0), ``P_brake_max`` = the largest braking N_p, negative
  like N_p (≤ 0; 0 where the drive never brakes), ``P_rms`` = √(∫ N_p² dt / t_trip) (the motor's
  thermal rating: it carries the braking power too);
* ``W_drum`` = ∫ P_drum dt, the drum's net work (signed): the load's potential energy change plus
  the work of the resistances (the ramps' kinetic energy comes back in the stop);
* what the scene's machine adds (its declaration's ``trips``: a winch's ``stroke_needed``, the largest
  tensioner stroke of eq. (19)-(23) over the trip, ramps included, left out when the scene computes no
  elongation; :mod:`ropemodel.machines.winch.trips`).

On a piece the forces are constant and u keeps its sign, so P_drum keeps its sign too; where a
piece's P_drum did cross zero the integration splits it there (η applies on each side), so it stays
exact either way.  The history (:attr:`Trip.history`) samples the trip for pictures and files; the
summary comes from the exact pieces, not from the samples.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ropemodel.errors import InputError
from ropemodel.machines import MACHINES
from ropemodel.machines.base import needing
from ropemodel.papers import krauze2025 as kr
from ropemodel.papers import route as rt
from ropemodel.scene import Scene, SceneLike, as_scene
from ropemodel.views.records import TripViews

#: samples of the history per phase (the summary does not depend on them)
SAMPLES = 200
#: summary keys → unit, in report order (the braking energy is under the scene's ``braking`` key)
SUMMARY = {"t_trip": "s", "F_C_max": "N", "F_S_min": "N", "P_max": "W", "P_brake_max": "W", "P_rms": "W",
           "E_trip": "J", "E_regen": "J", "E_dissipated": "J", "W_drum": "J",
           **{k: u for m in MACHINES.values() if m.trips for k, u in m.trips.SUMMARY.items()}}


@dataclass(frozen=True)
class Piece:
    """A stretch of the trip with constant forces: [t0, t1], the load's signed speed u0 → u1 [m/s] (> 0 up
    the slope, toward the drive) at the signed acceleration du_dt [m/s²], the load's position at the
    middle, the forces and the take-up the machine declares there (a winch: the tensioner stroke, eq. (23);
    NaN where the scene computes none)."""

    t0: float
    t1: float
    u0: float
    u1: float
    du_dt: float
    x_mid: float
    F_C: float
    F_S: float
    take_up: float

    def drum_power(self, t: float) -> float:
        """P_drum [W] at time t in the piece: (F_C − F_S)·u, > 0 motoring, < 0 braking."""
        return kr.drum_power(self.F_C, self.F_S, self.u0 + self.du_dt * (t - self.t0))


@dataclass
class Trip(TripViews):
    """A trip: :attr:`pieces` (exact), :attr:`summary` (SI), :attr:`history` (a DataFrame of samples).

    ``phases`` are (t0, t1, v0, a) of the speed profile along the direction of travel; the load starts
    at ``start`` [m] from the drive and moves toward it (``sign`` +1, upward) or away (−1).  ``braking``
    is the scene's variant of the ``braking`` effect (where braking energy goes).
    In Jupyter it shows its summary with units; ``to_series()``, ``to_frame()`` (the history) and
    ``plot()`` (the drive's power).
    """

    units: ClassVar[dict[str, str]] = SUMMARY

    scene: Scene
    direction: str
    eta: float
    phases: list[tuple[float, float, float, float]]
    start: float
    sign: float
    braking: Any                  # the scene's variant (class) of the braking effect
    pieces: list[Piece] = field(default_factory=list)
    summary: dict = field(default_factory=dict)

    def position(self, t: float) -> float:
        """The load's distance from the drive at time t [m]."""
        return self.start - self.sign * rt.distance_travelled(self.phases, t)

    @property
    def history(self):
        """Samples of the trip (pandas DataFrame): ``t [s]``, ``x_m [m]``, ``v [m/s]`` (the load's signed
        speed, > 0 up the slope), ``a [m/s^2]`` (its signed acceleration), ``F_C [N]``, ``F_S [N]``,
        ``P_drum [W]`` and ``N_p [W]`` (the drum's and the drive's power, > 0 motoring, < 0 braking); both
        ends of every piece are included."""
        import pandas as pd

        rows = []
        for p in self.pieces:
            n = max(2, int(SAMPLES * len(self.phases) * (p.t1 - p.t0) / self.summary["t_trip"]))
            for t in np.linspace(p.t0, p.t1, n):
                P = p.drum_power(t)
                rows.append((t, self.position(t), p.u0 + p.du_dt * (t - p.t0), p.du_dt, p.F_C, p.F_S, P,
                             kr.drive_power(P, self.eta)))
        return pd.DataFrame(rows, columns=["t [s]", "x_m [m]", "v [m/s]", "a [m/s^2]", "F_C [N]", "F_S [N]",
                                           "P_drum [W]", "N_p [W]"])

    def to_json(self) -> str:
        """The summary (SI) as one JSON object, with the direction, where braking energy goes and the
        pieces' count."""
        return json.dumps({**self.summary, "direction": self.direction, "braking": self.braking.variant,
                           "pieces": len(self.pieces)}, indent=2, allow_nan=False)

    def report(self) -> str:
        """A readable summary in kN, kW, kWh, s, mm; powers signed (> 0 motoring, < 0 braking)."""
        s, key = self.summary, self.braking.energy_key
        lines = [
            f"{self.scene.name}: trip {self.direction}, {s['t_trip']:.1f} s (power > 0 motoring, < 0 braking)",
            f"  F_C max      {s['F_C_max'] / 1e3:10.2f} kN    F_S min {s['F_S_min'] / 1e3:10.2f} kN",
            f"  P max        {s['P_max'] / 1e3:10.2f} kW    largest motoring power",
            f"  P brake max  {s['P_brake_max'] / 1e3:10.2f} kW    largest braking power",
            f"  P rms        {s['P_rms'] / 1e3:10.2f} kW    the motor's thermal rating",
            f"  E trip       {s['E_trip'] / 3.6e6:10.4f} kWh   drawn while motoring",
            f"  {key.replace('_', ' '):<12} {s[key] / 3.6e6:10.4f} kWh   {self.braking.destination} while braking "
            f"(braking = \"{self.braking.variant}\")",
            f"  W drum       {s['W_drum'] / 3.6e6:10.4f} kWh   the drum's net work: the load's potential energy "
            f"change plus friction",
        ]
        lines += needing("trips", self.scene, "a trip").lines(s)
        return "\n".join(lines)


#: the effects a trip needs: the whole-trip profile, the ramps' inertia in the forces, the drive's power
TRIP_EFFECTS = {"dynamics": "trip", "inertia": "rigid", "power": "drive"}


def prepare(scene: Scene) -> Scene:
    """The scene as a trip needs it (:data:`TRIP_EFFECTS`; a scene that says nothing of them works): read
    again with those effects, every value it was given kept (:meth:`~ropemodel.scene.Scene.with_effects`)."""
    needing("trips", scene, "a trip")
    if all(scene.effects.get(k) == v for k, v in TRIP_EFFECTS.items()):
        return scene
    return scene.with_effects(TRIP_EFFECTS)


def reads(scene: Scene) -> tuple[set[str], dict[str, str]]:
    """What a trip of the (prepared) ``scene`` is computed from: the parameters of its forces and stroke in
    both directions, the speed profile and the efficiency; and those it sets itself (name → how)."""
    forces = [f"{f}_{d}" for f in needing("trips", scene, "a trip").OUTPUTS for d in ("up", "down")]
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
        ``summary`` with ``t_trip`` [s], ``F_C_max`` [N], ``F_S_min`` [N], ``P_max`` [W] (≥ 0),
        ``P_brake_max`` [W] (≤ 0), ``P_rms`` [W], ``E_trip`` [J], ``E_regen`` or ``E_dissipated`` [J] (as the
        scene's ``braking`` effect says), ``W_drum`` [J] (signed) and, with the elongation effect,
        ``stroke_needed`` [m]; ``history`` (samples).

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

    Lowered, the load drives the drum all the way (steady, the paper's P_drum_down = −243.58 kW): the
    drive never motors, and brakes hardest as the stop begins, where it also takes the inertia of the
    load and both ropes, −(97.43 + 28.50 + 4.69) kN × 2.5 m/s = −326.6 kW (η = 1 here).

    >>> down = trip(rm.load_scene("trip_fig9"), "down").summary
    >>> down["E_trip"], round(down["P_brake_max"] / 1e3, 1), round(down["E_regen"] / 3.6e6, 2)
    (0.0, -326.6, 31.12)
    """
    from ropemodel.problem import Problem

    scene = prepare(as_scene(scene))
    direction = direction or scene.effects.get("travel", "up")
    if direction not in ("up", "down"):
        raise InputError(f"direction {direction!r}: a trip goes up or down")
    v = scene.parameters
    problem, machine = Problem(scene), needing("trips", scene, "a trip")
    L_u = machine.length(v)
    eta = v.get("eta", 1.0)
    if L_u <= 0 or v["v_pj"] <= 0 or v["t_ramp"] <= 0:
        raise InputError("a trip needs a route, a speed and a ramp time > 0")
    phases = rt.trip_phases(L_u, v["v_pj"], v["t_ramp"])
    start, sign = (L_u, 1.0) if direction == "up" else (0.0, -1.0)
    out = Trip(scene, direction, eta, phases, start, sign, _braking(scene))
    out.pieces = _pieces(problem, out, _cuts(machine.joints(v), out))
    _taut(out, machine.remedy(v, min(min(p.F_C, p.F_S) for p in out.pieces)))
    out.summary = {**summarise(out.pieces, eta, out.braking.energy_key),
                   **machine.summary([p.take_up for p in out.pieces])}
    return out


def _braking(scene):
    """The scene's ``braking`` variant (its class), from the registry."""
    from ropemodel.effects import effects_of

    spec = effects_of(scene.model)["braking"]
    return spec.variants[scene.effects.get("braking", spec.default)]


def _taut(trip: Trip, remedy: str) -> None:
    """:class:`SolveError` where a rope would have to push somewhere on the trip (it is slack), saying what
    keeps it taut (``remedy``: the machine's)."""
    from ropemodel.errors import SolveError

    worst = min(trip.pieces, key=lambda p: min(p.F_C, p.F_S))
    least = min(worst.F_C, worst.F_S)
    if least > 0.0:
        return
    side = "winding" if worst.F_C <= worst.F_S else "unwinding"
    raise SolveError(f"the {side} rope would have to push ({least / 1e3:.6g} kN) at t = {worst.t0:.6g} s of the "
                     f"{trip.direction}ward trip, the load at x_m = {trip.position(worst.t0):.6g} m: it is slack and "
                     f"the model no longer holds; every rope stays taut with {remedy}")


def _cuts(joints, trip: Trip) -> list[float]:
    """Times of the phase boundaries and of the load crossing a joint of the route (``joints``: their distances
    from the drive [m]), in order."""
    times = {t for t0, t1, _, _ in trip.phases for t in (t0, t1)}
    for end in joints:
        times.add(rt.time_at_distance(trip.phases, trip.sign * (trip.start - end)))
    return sorted(times)


def _pieces(problem, trip: Trip, cuts) -> list[Piece]:
    """Every stretch between two cuts, its forces evaluated at its middle (one compiled call for all).

    The phases give the speed and acceleration along the direction of travel (what the forces' inertia
    term a_h is); the pieces hold the load's signed speed and acceleration, u = s·v and du/dt = s·a."""
    phases, direction, s = trip.phases, trip.direction, trip.sign
    spans = [(t0, t1) for t0, t1 in zip(cuts[:-1], cuts[1:]) if t1 > t0]
    mids = [0.5 * (t0 + t1) for t0, t1 in spans]
    phase = [next(q for q in phases if q[0] <= tm <= q[1]) for tm in mids]
    x = np.array([trip.position(tm) for tm in mids])
    cols = {"a_h": np.array([q[3] for q in phase])}
    if "x_m" in problem.knowns:
        cols["x_m"] = x
    wanted = [f"{f}_{direction}" for f in ("F_C", "F_S", "dF") if f"{f}_{direction}" in problem.unknowns]
    out = problem.evaluate(cols, outputs=wanted)
    F_C, F_S = out[f"F_C_{direction}"], out[f"F_S_{direction}"]
    take_up = needing("trips", trip.scene, "a trip").take_up(out, direction, len(spans))
    pieces = []
    for k, ((t0, t1), (p0, _, v_start, a)) in enumerate(zip(spans, phase)):
        v0 = v_start + a * (t0 - p0)
        pieces.append(Piece(t0, t1, s * v0, s * (v0 + a * (t1 - t0)), s * a, float(x[k]), float(F_C[k]),
                            float(F_S[k]), float(take_up[k])))
    return pieces


def _signed_spans(p: Piece):
    """(t0, t1, P0, P1) of a piece's drum power, split where it crosses zero: one sign on each span.

    On a trip's piece u keeps its sign and the forces are constant, so there is one span; the split
    keeps the integration exact for any linear power."""
    P0, P1 = p.drum_power(p.t0), p.drum_power(p.t1)
    if P0 * P1 >= 0.0:
        return [(p.t0, p.t1, P0, P1)]
    tz = p.t0 + (p.t1 - p.t0) * P0 / (P0 - P1)
    return [(p.t0, tz, P0, 0.0), (tz, p.t1, 0.0, P1)]


def summarise(pieces: list[Piece], eta: float, braking_key: str = "E_regen") -> dict:
    """The trip's summary from its pieces, exactly (on each signed span the drive power is linear in time:
    its integral is the trapezoid's, its square's Simpson's).  ``braking_key`` names the energy of braking
    (``E_regen`` returned, ``E_dissipated`` burnt)."""
    drawn = braked = work = square = 0.0
    P_max = P_brake_max = 0.0
    for p in pieces:
        for t0, t1, P0, P1 in _signed_spans(p):
            N0, N1 = kr.drive_power(P0, eta), kr.drive_power(P1, eta)
            dt = t1 - t0
            E = 0.5 * (N0 + N1) * dt
            drawn, braked = drawn + max(E, 0.0), braked + max(-E, 0.0)
            work += 0.5 * (P0 + P1) * dt
            square += dt * (N0 * N0 + N0 * N1 + N1 * N1) / 3.0
            P_max, P_brake_max = max(P_max, N0, N1), min(P_brake_max, N0, N1)
    t_trip = pieces[-1].t1 - pieces[0].t0
    out = {"t_trip": t_trip, "F_C_max": max(p.F_C for p in pieces), "F_S_min": min(p.F_S for p in pieces),
           "P_max": P_max, "P_brake_max": P_brake_max, "P_rms": math.sqrt(square / t_trip), "E_trip": drawn,
           braking_key: braked, "W_drum": work}
    return {k: float(v) for k, v in out.items()}
