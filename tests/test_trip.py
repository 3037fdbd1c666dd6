"""A whole trip: against an exact reference written here, the energy balance against the rigid-rope
transient, and the signs of power (four-quadrant: > 0 the drive motors, < 0 it brakes).

Truths written in this file, numpy only:
* the route's forces from docs/physics.md §4 (sums over segments, the load's segment, the ramps'
  rigid-body inertia), with the signed power P_drum = (F_C − F_S) u, u > 0 up the slope;
* a reference integrated in the *distance* travelled, where the library integrates in time: on each
  stretch between a ramp's end and a joint the forces are constant, so the drum's work is
  s (F_C − F_S) Δd exactly, the drive's energy that /η or ·η by the sign, and ∫ N_p² dt =
  c² (F_C − F_S)² ∫ |u| dd with |u| = √(2 a d) on a ramp, v_pj between (closed forms);
* the energy balance: the drum's net work = the load's potential energy change (±G_m H) + the work of
  every resistance (load: μ_pm G_m Σ L_i cos α_i; each rope side: its resistance over L_u).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.dynamics import simulate
from ropemodel.trips import Piece, prepare, summarise, trip

G = 9.80665
Q_LW = 5.8e-6   # m/N, route_segments.toml
SEGMENTS = [(400.0, 22.0, 0.06), (650.0, 9.0, None), (300.0, 3.0, None)]   # route_segments.toml
LOAD = dict(G_m=467e3, q_l=80.0, mu_pm=0.05, mu_pl=0.05, v_pj=2.5, t_ramp=5.0, eta=0.85)
#: routes where the drive's power changes sign within a trip: name → (segments, t_ramp [s], F_nwl [N])
ROUTES = {
    "three segments": (SEGMENTS, 5.0, 20e3),      # down: brakes on 22° and 9°, motors on 3°
    "steep then 1 deg": ([(500.0, 15.0, None), (800.0, 1.0, None)], 5.0, 20e3),   # down: brakes, then motors
    # both ways: motors, and brakes in the stop (0.83 m/s²; the pretension keeps the rope taut in the ramps)
    "1 deg": ([(1200.0, 1.0, None)], 3.0, 200e3),
}


def _scene(segments, t_ramp=5.0, F_nwl=20e3, braking=None):
    raw = dict(rm.load_scene("route_segments").raw)
    raw["route"] = [{"length": f"{L!r} m", "inclination": f"{a!r} deg", **({} if mu is None else {"mu_winding": mu})}
                    for L, a, mu in segments]
    raw["parameters"] = {**raw["parameters"], "t_ramp": f"{t_ramp!r} s", "F_nwl": f"{F_nwl!r} N"}
    if braking:
        raw["effects"] = {**raw["effects"], "braking": braking}
    return rm.from_dict(raw, emit=False)


def _forces(x, a, s, segments=SEGMENTS, F_nwl=20e3):
    """F_C, F_S [N] with the load at x [m] from the drive, acceleration a [m/s²] along travel, travel sign s."""
    p = LOAD
    L = np.array([g[0] for g in segments])
    al = np.radians([g[1] for g in segments])
    mu = np.array([p["mu_pl"] if g[2] is None else g[2] for g in segments])
    j = min(int(np.searchsorted(np.cumsum(L), x, side="left")), len(L) - 1)
    rope_weight = p["q_l"] * np.sum(L * np.sin(al))
    L_u = L.sum()
    m_C, m_S = (p["G_m"] + p["q_l"] * L_u) / G, p["q_l"] * L_u / G
    F_S = 0.5 * F_nwl + rope_weight - s * (p["mu_pl"] * p["q_l"] * np.sum(L * np.cos(al)) + m_S * a)
    F_C = (0.5 * F_nwl + rope_weight + p["G_m"] * math.sin(al[j])
           + s * (p["mu_pm"] * p["G_m"] * math.cos(al[j]) + p["q_l"] * np.sum(mu * L * np.cos(al)) + m_C * a))
    return F_C, F_S


def _by_distance(direction, segments=SEGMENTS, t_ramp=5.0, F_nwl=20e3):
    """The trip integrated over the distance d travelled, in closed form on each stretch (see the docstring)."""
    p, s = LOAD, (1.0 if direction == "up" else -1.0)
    eta, v = p["eta"], p["v_pj"]
    acc = v / t_ramp
    L_u = sum(g[0] for g in segments)
    d_r = 0.5 * v * t_ramp                   # the distance of each ramp
    assert L_u > 2 * d_r
    joints = np.cumsum([g[0] for g in segments])[:-1]
    joints_d = L_u - joints if direction == "up" else joints
    cuts = np.unique(np.concatenate([[0.0, d_r, L_u - d_r, L_u], joints_d]))

    def speed(d):
        return math.sqrt(2 * acc * d) if d < d_r else v if d <= L_u - d_r else math.sqrt(2 * acc * (L_u - d))

    def speed_integral(d0, d1):            # ∫ |u| dd over [d0, d1] inside one phase
        if d1 <= d_r:
            return math.sqrt(2 * acc) * 2 / 3 * (d1 ** 1.5 - d0 ** 1.5)
        if d0 >= L_u - d_r:
            return math.sqrt(2 * acc) * 2 / 3 * ((L_u - d0) ** 1.5 - (L_u - d1) ** 1.5)
        return v * (d1 - d0)

    out = dict(E_trip=0.0, E_brake=0.0, W_drum=0.0, P_max=0.0, P_brake_max=0.0, square=0.0,
               F_C_max=-math.inf, F_S_min=math.inf, stroke_needed=0.0)
    for d0, d1 in zip(cuts[:-1], cuts[1:]):
        mid = 0.5 * (d0 + d1)
        a = acc if mid < d_r else -acc if mid > L_u - d_r else 0.0
        F_C, F_S = _forces(L_u - mid if direction == "up" else mid, a, s, segments, F_nwl)
        pull = s * (F_C - F_S)               # P_drum / |u|: > 0 motoring, < 0 braking
        c = 1 / eta if pull > 0 else eta     # the drive train's efficiency on the right side
        out["W_drum"] += pull * (d1 - d0)
        out["E_trip" if pull > 0 else "E_brake"] += abs(pull) * c * (d1 - d0)
        for d in (d0, d1):
            N = c * pull * speed(d)
            out["P_max"], out["P_brake_max"] = max(out["P_max"], N), min(out["P_brake_max"], N)
        out["square"] += (c * pull) ** 2 * speed_integral(d0, d1)
        out["F_C_max"], out["F_S_min"] = max(out["F_C_max"], F_C), min(out["F_S_min"], F_S)
        out["stroke_needed"] = max(out["stroke_needed"], Q_LW * (F_C + F_S + F_nwl))   # eq. (19)-(23)
    out["t_trip"] = L_u / v + t_ramp
    out["P_rms"] = math.sqrt(out.pop("square") / out["t_trip"])
    return out


def _balance(direction, segments=SEGMENTS):
    """The drum's net work over a trip from rest to rest: ±G_m H plus the work of every resistance."""
    p, s = LOAD, (1.0 if direction == "up" else -1.0)
    L = np.array([g[0] for g in segments])
    al = np.radians([g[1] for g in segments])
    mu = np.array([p["mu_pl"] if g[2] is None else g[2] for g in segments])
    H = np.sum(L * np.sin(al))
    load = p["mu_pm"] * p["G_m"] * np.sum(L * np.cos(al))
    ropes = (p["q_l"] * np.sum(mu * L * np.cos(al)) + p["mu_pl"] * p["q_l"] * np.sum(L * np.cos(al))) * L.sum()
    return s * p["G_m"] * H + load + ropes


@pytest.mark.parametrize("direction", ["up", "down"])
@pytest.mark.parametrize("route", list(ROUTES))
def test_trip_matches_the_exact_reference_by_distance(route, direction):
    segments, t_ramp, F_nwl = ROUTES[route]
    got = trip(_scene(segments, t_ramp, F_nwl), direction).summary
    ref = _by_distance(direction, segments, t_ramp, F_nwl)
    assert set(got) == {"t_trip", "F_C_max", "F_S_min", "P_max", "P_brake_max", "P_rms", "E_trip", "E_regen",
                        "W_drum", "stroke_needed"}
    for k in ("t_trip", "F_C_max", "F_S_min", "P_max", "P_brake_max", "P_rms", "E_trip", "W_drum",
              "stroke_needed"):
        assert got[k] == pytest.approx(ref[k], rel=1e-10, abs=1e-6), k    # both exact: rounding only
    assert got["E_regen"] == pytest.approx(ref["E_brake"], rel=1e-10, abs=1e-6)


def test_the_routes_change_the_sign_of_power_within_a_trip():
    """What the routes are for: the reference (not the library) motors and brakes within each such trip."""
    for route, (segments, t_ramp, F_nwl) in ROUTES.items():
        for direction in ("up", "down") if route == "1 deg" else ("down",):
            ref = _by_distance(direction, segments, t_ramp, F_nwl)
            assert ref["E_trip"] > 0 and ref["E_brake"] > 0 and ref["P_max"] > 0 > ref["P_brake_max"], route


def test_lowering_on_route_segments_brakes():
    """The issue's numbers: lowering on the shipped route the drive draws 3.34 MJ (on the 3° segment,
    where the load must be pulled) and returns 70.05 MJ; the drum does −79.57 MJ of work."""
    got = trip(rm.load_scene("route_segments"), "down").summary
    assert got["E_trip"] / 1e6 == pytest.approx(3.34, abs=0.005)      # the README's figures
    assert got["E_trip"] / 3.6e6 == pytest.approx(0.93, abs=0.005)
    assert got["E_regen"] / 1e6 == pytest.approx(70.05, abs=0.005)
    assert got["E_regen"] / 3.6e6 == pytest.approx(19.46, abs=0.005)
    assert got["W_drum"] / 1e6 == pytest.approx(-79.57, abs=0.005)
    assert got["P_brake_max"] / 1e3 == pytest.approx(-302.8, abs=0.05)
    H = sum(L * math.sin(math.radians(a)) for L, a, _ in SEGMENTS)
    assert -LOAD["G_m"] * H / 1e6 == pytest.approx(-124.8, abs=0.05)     # the potential energy lost
    # steady on the 22° segment: P_drum = −(F_C − F_S) v_pj, times η while braking; the stop's inertia is elsewhere
    F_C, F_S = _forces(200.0, 0.0, -1.0)
    assert got["P_brake_max"] == pytest.approx(-(F_C - F_S) * 2.5 * 0.85, rel=1e-12)


def test_the_readme_shows_the_trip_as_printed(capsys):
    """The downward trip the documentation shows (the winch page, "Routes as they are built") is the command's
    output (its numbers are the reference's, above)."""
    from _docs_text import section

    readme = section("Routes as they are built: segments, trips, energy per trip")
    shown = readme.split("$ ropemodel trip route_segments --direction down\n", 1)[1].split("```", 1)[0]
    assert main(["trip", "route_segments", "--direction", "down"]) == 0
    assert capsys.readouterr().out == shown


def test_energy_is_the_work_of_the_steady_forces_when_power_keeps_its_sign():
    """Upward the drive always motors: E_trip = Σ_j (F_C − F_S)_j L_j / η with steady-motion forces (the
    ramps' kinetic energy comes back in the stop) — exact, no time step."""
    got = trip(rm.load_scene("route_segments"), "up").summary
    assert got["E_regen"] == 0.0 and got["P_brake_max"] == 0.0
    work, start = 0.0, 0.0
    for L, _, _ in SEGMENTS:
        F_C, F_S = _forces(start + L / 2, 0.0, 1.0)
        work += (F_C - F_S) * L
        start += L
    assert got["E_trip"] == pytest.approx(work / LOAD["eta"], rel=1e-12)


@pytest.mark.parametrize("route, direction", [("three segments", "up"), ("three segments", "down"),
                                              ("steep then 1 deg", "down")])
def test_energy_balance_against_the_rigid_transient(route, direction):
    """The drum's work = the load's potential energy change + friction, three ways: written out here, the
    trip's exact W_drum (and its energies through η), and simulate()'s W_drum of the same trip with a rigid
    rope.  simulate() runs at its default sim_rtol = 1e-8: its W_drum is an integral carried by the
    integrator, within 1e-6 of the closed form here (2.2e-7 up, 3.6e-8 down measured), and it starts and
    stops through the smoothed Coulomb resistance (v_eps = 1 cm/s)."""
    segments, t_ramp, F_nwl = ROUTES[route]
    scene = _scene(segments, t_ramp, F_nwl)
    W = _balance(direction, segments)
    got = trip(scene, direction).summary
    assert got["W_drum"] == pytest.approx(W, rel=1e-12)
    eta = LOAD["eta"]   # the drive's energies go through η on the right side: W = η E_trip − E_regen / η
    assert eta * got["E_trip"] - got["E_regen"] / eta == pytest.approx(W, rel=1e-12)
    raw = {**scene.raw, "effects": {**scene.raw["effects"], "travel": direction}}
    sim = simulate(rm.from_dict(raw, emit=False))
    assert sim.history["W_drum [J]"].iloc[-1] == pytest.approx(W, rel=1e-6)
    if direction == "down":
        assert W < 0      # the load drives the drum: its potential energy exceeds friction


def test_a_piece_whose_power_crosses_zero_is_split_there():
    """summarise() integrates a linear drum power that changes sign inside a piece exactly: u from −1 to
    +1 m/s over 2 s against F_C − F_S = 10 kN: braking for 1 s, then motoring for 1 s."""
    eta, dF = 0.8, 1e4
    piece = Piece(0.0, 2.0, -1.0, 1.0, 1.0, 0.0, dF + 5e3, 5e3, 0.1)
    got = summarise([piece], eta)
    triangle = 0.5 * dF * 1.0 * 1.0                       # ∫ |P_drum| dt over each second
    assert got["E_trip"] == pytest.approx(triangle / eta, rel=1e-14)
    assert got["E_regen"] == pytest.approx(triangle * eta, rel=1e-14)
    assert got["W_drum"] == pytest.approx(0.0, abs=1e-9)
    assert got["P_max"] == pytest.approx(dF / eta) and got["P_brake_max"] == pytest.approx(-dF * eta)
    rms = math.sqrt((dF ** 2 / 3 * (eta ** 2 + eta ** -2)) / 2.0)   # ∫ (c dF t)² dt over each second
    assert got["P_rms"] == pytest.approx(rms, rel=1e-14)


def test_dissipative_braking_names_its_energy(capsys):
    """braking = "dissipative": the same energy, named for where it goes, in JSON and in text."""
    regen = trip(rm.load_scene("route_segments"), "down").summary
    scene = _scene(SEGMENTS, braking="dissipative")
    burnt = trip(scene, "down").summary
    assert "E_regen" not in burnt and burnt["E_dissipated"] == pytest.approx(regen["E_regen"], rel=1e-14)
    assert main(["trip", "route_segments", "--direction", "down", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["braking"] == "regenerative" and data["E_regen"] == pytest.approx(regen["E_regen"])
    text = trip(scene, "down").report()
    assert "E dissipated" in text and "dissipated in the braking resistor while braking" in text
    assert "E regen" not in text


def test_the_text_says_what_each_sign_means(capsys):
    assert main(["trip", "route_segments", "--direction", "down"]) == 0
    out = capsys.readouterr().out
    assert "power > 0 motoring, < 0 braking" in out
    assert "returned to the supply while braking" in out
    brake = next(line for line in out.splitlines() if line.strip().startswith("P brake max"))
    assert float(brake.split()[3]) < 0


def test_the_rigid_rope_transient_is_the_same_trip():
    """simulate() of the trip with an inextensible rope: its F_C, F_S histories equal the trip's pieces to
    the integrator's tolerance (sim_rtol 1e-10; v_eps = 1 nm/s makes the smoothed Coulomb resistance the
    trip's full resistance after the first microseconds of motion)."""
    scene = rm.load_scene("route_segments")
    sim = simulate(rm.from_dict({**scene.raw, "numerics": {"sim_rtol": 1e-10}}, values={"v_eps": "1e-9 m/s"}))
    t_ref = trip(scene)
    h = sim.history
    cuts = sorted({p.t0 for p in t_ref.pieces} | {t_ref.pieces[-1].t1})
    checked = 0
    for t, F_C, F_S, v in zip(h["t [s]"], h["F_C [N]"], h["F_S [N]"], h["v_drum [m/s]"]):
        if abs(v) < 1e-6 or min(abs(t - c) for c in cuts) < 1e-6:
            continue   # at rest (no resistance yet) or on a cut, where the trip's forces jump
        piece = next(p for p in t_ref.pieces if p.t0 < t < p.t1)
        assert F_C == pytest.approx(piece.F_C, rel=1e-8)
        assert F_S == pytest.approx(piece.F_S, rel=1e-8)
        checked += 1
    assert checked > 1000
    assert sim.summary["F_C_max"] == pytest.approx(t_ref.summary["F_C_max"], rel=1e-8)


def test_a_short_route_is_a_triangle():
    """A route shorter than v_pj t_ramp = 12.5 m: never full speed; the trip takes 2 sqrt(L_u t_ramp / v_pj),
    and its top speed sqrt(L_u v_pj / t_ramp); a longer one L_u / v_pj + t_ramp.  Lowered, the speed is
    negative (down the slope)."""
    short = trip(rm.load_scene("trip_fig9").with_values({"L_u": "10 m", "L_ul": "5 m"}))
    assert short.summary["t_trip"] == pytest.approx(2 * math.sqrt(10 * 5 / 2.5), rel=1e-12)
    assert short.history["v [m/s]"].max() == pytest.approx(math.sqrt(10 * 2.5 / 5), rel=1e-12)
    down = trip(rm.load_scene("trip_fig9").with_values({"L_u": "10 m", "L_ul": "5 m"}), "down")
    assert down.history["v [m/s]"].min() == pytest.approx(-math.sqrt(10 * 2.5 / 5), rel=1e-12)
    longer = trip(rm.load_scene("trip_fig9").with_values({"L_u": "20 m", "L_ul": "5 m"}))
    assert longer.summary["t_trip"] == pytest.approx(20 / 2.5 + 5, rel=1e-12)


def test_cli_trip_json_and_history(tmp_path, capsys):
    out = tmp_path / "h.csv"
    assert main(["trip", "route_segments", "--json", "-o", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) == {"F_C_max", "F_S_min", "P_max", "P_brake_max", "P_rms", "E_trip", "E_regen", "W_drum",
                         "t_trip", "stroke_needed", "direction", "braking", "pieces"}
    import pandas as pd

    h = pd.read_csv(out)
    assert list(h.columns) == ["t [s]", "x_m [m]", "v [m/s]", "a [m/s^2]", "F_C [N]", "F_S [N]", "P_drum [W]",
                               "N_p [W]"]
    assert h["x_m [m]"].iloc[0] == pytest.approx(1350.0) and h["x_m [m]"].iloc[-1] == pytest.approx(0.0, abs=1e-9)
    # the drive's power from the drum's, η on the right side of each sign
    P = h["P_drum [W]"].to_numpy()
    assert np.allclose(h["N_p [W]"], np.where(P > 0, P / 0.85, P * 0.85), rtol=1e-14, atol=0.0)


def test_no_elongation_no_stroke_and_valid_json(capsys):
    """Without the elongation effect there is no stroke: the key is left out, never NaN in the JSON."""
    data = dict(rm.load_scene("route_segments").raw)
    data["effects"] = {**data["effects"], "elongation": "none"}
    t = trip(rm.from_dict(data, emit=False), "down")
    assert "stroke_needed" not in t.summary and "stroke" not in t.report()
    assert all(math.isfinite(v) for v in json.loads(t.to_json()).values() if isinstance(v, float))


@pytest.mark.parametrize("changes, message", [
    ({"rope_elasticity": "segments"}, r'dynamics = "trip" needs ramp = "linear" and rope_elasticity = "rigid"'),
    ({"ramp": "cosine"}, r'dynamics = "trip" needs ramp = "linear"'),
])
def test_trip_transient_needs_a_rigid_rope_and_linear_ramps(changes, message):
    data = dict(rm.load_scene("route_segments").raw)
    data["effects"] = {**data["effects"], **changes}
    with pytest.raises(rm.InputError, match=message):
        simulate(rm.from_dict(data))


def test_slack_rope_on_the_trip_is_refused():
    scene = rm.load_scene("route_segments")
    with pytest.raises(rm.SolveError, match=r"rope would have to push .* every rope stays taut with F_nwl >"):
        trip(scene.with_values({"alpha_1": "-20 deg", "alpha_2": "-20 deg", "alpha_3": "-20 deg"}), "down")


def test_prepare_switches_the_trip_effects_on(tmp_path):
    """A static scene with a speed and a ramp time makes a trip as it is: ropemodel trip sets the effects."""
    from test_scene_contract import FIG9_INPUT

    f = tmp_path / "s.toml"
    f.write_text(FIG9_INPUT + 't_ramp = "5 s"\n', encoding="utf-8")
    scene = prepare(rm.load_scene(f, emit=False))
    assert scene.effects["dynamics"] == "trip" and scene.effects["inertia"] == "rigid" and not scene.unused
    assert trip(scene).summary["F_C_max"] == pytest.approx(trip(rm.load_scene("trip_fig9")).summary["F_C_max"],
                                                            rel=1e-12)
