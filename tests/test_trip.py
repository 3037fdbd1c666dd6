"""A whole trip: against a reference written here (forces from docs/physics.md §4, fine time steps),
the work-energy identity, and the rigid-rope transient of the same trip.

Truths: the route sums and inertia terms written out in numpy in this file, integrated on a fine
uniform time grid (trapezoid, so its own error is stated); the identity E_trip = ∫(F_C − F_S) dx / η
for steady-motion forces where the power never changes sign; and ropemodel's own time-domain
simulation (an independent code path: CasADi BDF through the hybrid integrator).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.dynamics import simulate
from ropemodel.trips import prepare, trip

G = 9.80665
SEGMENTS = [(400.0, 22.0, 0.06), (650.0, 9.0, None), (300.0, 3.0, None)]   # route_segments.toml
LOAD = dict(G_m=467e3, q_l=80.0, F_nwl=30e3, mu_pm=0.05, mu_pl=0.05, v_pj=2.5, t_ramp=5.0, eta=0.85)


def _forces(x, a, s):
    """F_C, F_S [N] with the load at x [m] from the drive, acceleration a [m/s²], travel sign s (±1)."""
    p = LOAD
    L = np.array([g[0] for g in SEGMENTS])
    al = np.radians([g[1] for g in SEGMENTS])
    mu = np.array([p["mu_pl"] if g[2] is None else g[2] for g in SEGMENTS])
    j = min(int(np.searchsorted(np.cumsum(L), x, side="left")), len(L) - 1)
    rope_weight = p["q_l"] * np.sum(L * np.sin(al))
    L_u = L.sum()
    m_C, m_S = (p["G_m"] + p["q_l"] * L_u) / G, p["q_l"] * L_u / G
    F_S = 0.5 * p["F_nwl"] + rope_weight - s * (p["mu_pl"] * p["q_l"] * np.sum(L * np.cos(al)) + m_S * a)
    F_C = (0.5 * p["F_nwl"] + rope_weight + p["G_m"] * math.sin(al[j])
           + s * (p["mu_pm"] * p["G_m"] * math.cos(al[j]) + p["q_l"] * np.sum(mu * L * np.cos(al)) + m_C * a))
    return F_C, F_S


def _reference(direction, dt=2e-3):
    """Time-stepped trip written from scratch: speed profile, position, forces, power, trapezoid energies."""
    p, s = LOAD, (1.0 if direction == "up" else -1.0)
    L_u = sum(g[0] for g in SEGMENTS)
    acc = p["v_pj"] / p["t_ramp"]
    t_trip = L_u / p["v_pj"] + p["t_ramp"]
    t = np.arange(0.0, t_trip + dt / 2, dt)
    v = np.minimum.reduce([acc * t, np.full_like(t, p["v_pj"]), acc * (t_trip - t)])
    a = np.where(t < p["t_ramp"], acc, np.where(t > t_trip - p["t_ramp"], -acc, 0.0))
    dist = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    x = L_u - dist if direction == "up" else dist
    F = np.array([_forces(xi, ai, s) for xi, ai in zip(x, a)])
    mech = (F[:, 0] - F[:, 1]) * v
    P = np.where(mech >= 0, mech / p["eta"], mech * p["eta"])
    E_trip = np.trapezoid(np.maximum(P, 0), t)
    E_regen = np.trapezoid(np.maximum(-P, 0), t)
    return {"t_trip": t_trip, "F_C_max": F[:, 0].max(), "F_S_min": F[:, 1].min(), "P_max": P.max(),
            "E_trip": E_trip, "E_regen": E_regen, "P_rms": math.sqrt(np.trapezoid(P * P, t) / t_trip)}


@pytest.mark.parametrize("direction", ["up", "down"])
def test_trip_matches_a_time_stepped_reference(direction):
    got = trip(rm.load_scene("route_segments"), direction).summary
    ref = _reference(direction)
    assert got["t_trip"] == pytest.approx(ref["t_trip"], rel=1e-12)
    # the peak force (the start's inertia included) and the least F_S: exact in both
    assert got["F_C_max"] == pytest.approx(ref["F_C_max"], rel=1e-12)
    assert got["F_S_min"] == pytest.approx(ref["F_S_min"], rel=1e-12)
    # energies and RMS power: the reference's trapezoid on a 2 ms grid straddles each force jump at a
    # joint crossing and each kink of the speed: its error is below 1e-5 here (halving dt quarters it)
    for k in ("E_trip", "P_rms", "P_max"):
        assert got[k] == pytest.approx(ref[k], rel=1e-5)
    assert got["E_regen"] == pytest.approx(ref["E_regen"], rel=1e-5, abs=1.0)


def test_energy_is_the_work_of_the_steady_forces_when_power_keeps_its_sign():
    """Upward the drive always motors: E_trip = Σ_j (F_C − F_S)_j L_j / η with steady-motion forces (the
    ramps' kinetic energy comes back in the stop) — exact, no time step."""
    got = trip(rm.load_scene("route_segments"), "up").summary
    assert got["E_regen"] == 0.0
    work, start = 0.0, 0.0
    for L, _, _ in SEGMENTS:
        F_C, F_S = _forces(start + L / 2, 0.0, 1.0)
        work += (F_C - F_S) * L
        start += L
    assert got["E_trip"] == pytest.approx(work / LOAD["eta"], rel=1e-12)


def test_downward_trip_returns_energy():
    got = trip(rm.load_scene("route_segments"), "down").summary
    assert got["E_regen"] > 0.0 and got["P_max"] > 0.0


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
    and its top speed sqrt(L_u v_pj / t_ramp); a longer one L_u / v_pj + t_ramp."""
    short = trip(rm.load_scene("trip_fig9").with_values({"L_u": "10 m", "L_ul": "5 m"}))
    assert short.summary["t_trip"] == pytest.approx(2 * math.sqrt(10 * 5 / 2.5), rel=1e-12)
    assert short.history["v [m/s]"].max() == pytest.approx(math.sqrt(10 * 2.5 / 5), rel=1e-12)
    longer = trip(rm.load_scene("trip_fig9").with_values({"L_u": "20 m", "L_ul": "5 m"}))
    assert longer.summary["t_trip"] == pytest.approx(20 / 2.5 + 5, rel=1e-12)


def test_cli_trip_json_and_history(tmp_path, capsys):
    out = tmp_path / "h.csv"
    assert main(["trip", "route_segments", "--json", "-o", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) >= {"F_C_max", "F_S_min", "P_max", "P_rms", "E_trip", "E_regen", "t_trip", "stroke_needed"}
    import pandas as pd

    h = pd.read_csv(out)
    assert list(h.columns) == ["t [s]", "x_m [m]", "v [m/s]", "a [m/s^2]", "F_C [N]", "F_S [N]", "P [W]"]
    assert h["x_m [m]"].iloc[0] == pytest.approx(1350.0) and h["x_m [m]"].iloc[-1] == pytest.approx(0.0, abs=1e-9)


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
