"""The Koepe transient with elastic head ropes (issue 25, item 3) against independent truths.

* the lumped-mass model in scipy, tests/_koepe_lumped.py (it imports nothing of ropemodel), at the same mesh
  (8 elements per side, the same rope run allowed over the wheel): both solve the same discrete model, so they
  differ by their integrators' errors only (ropemodel's BDF at sim_rtol = 1e-8, the truth's LSODA at 1e-10;
  measured 1e-8 on the events' times and states).  Tolerance 1e-6: a hundred times the local tolerance, for
  its accumulation over the run.  The truth's history is interpolated linearly between its own steps (at most
  STEP = 2 ms apart: (ω δ)²/8 of a swing, 2.5 N at ω = 10 rad/s on 100 kN), so the tensions over the run are
  compared to 1e-5 of the static tension (measured 2.6e-6);
* the limit of stiff ropes: the ropes' acceleration where they start to slip tends to the rigid hoist's slip
  limit (the closed form of docs/physics.md §7, written out here in numpy) as EA grows;
* closed forms of the constant-deceleration control's stop; the energy balance W = ΔE + D;
* the Voigt lining's traction at rest (Hajduk 1992, eq. (19), koepe_lining) in the slip margin at the start.
"""

from __future__ import annotations

import json
import math
from importlib.resources import files

import numpy as np
import pytest
from _koepe_lumped import brake, constant_deceleration, drive_ramp, example_hoist, mesh, steady_force
from _koepe_lumped import simulate as lumped

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.dynamics import simulate
from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_lining as kl

G = 9.80665
E = math.exp(0.25 * math.pi)
Q_ARC, RHO, R = 4 * 8.6, 2 * 15.5, 2.25
#: koepe_braking's transient data: EA of one head rope [N], m_machine [kg], τ [s]
EA, M_MACHINE, TAU = 96.5e6, 39.5e3, 0.01
SLIPPING = {"M_brake": "1500 kN*m", "y_start": "400 m", "t_end": "6 s"}
#: the reference's largest step [s], so that its history interpolates to 1e-5 of the tensions between its steps
STEP = 2e-3


def rel(a, b):
    return abs(a / b - 1)


def scene(values: dict, **effects):
    """koepe_braking with other variants and values (SI)."""
    return rm.load_scene("koepe_braking").with_effects(effects, optional=tuple(values)).with_values(values)


def truth(sim, wheel, y_L0, v0, **kw):
    """The lumped model of the scene's hoist at the simulation's mesh, run to the wheel at rest."""
    s = sim.summary
    h = example_hoist(EA_head=EA, J=M_MACHINE * R * R, tau=TAU, N=s["segments"], reel=s["reel"], **kw)
    return h, lumped(h, y_L0, v0, wheel(h), t_end=s["t_end"], stop="rest", method="LSODA", rtol=1e-10, atol=1e-10,
                     max_step=STEP)


def event(sim, name):
    return next(e for e in sim.events if e.name == name)


@pytest.fixture(scope="module")
def slipping():
    """An emergency stop while hoisting, mid-shaft, with a brake too strong for the ropes: they slip toward E."""
    sim = simulate("koepe_braking", SLIPPING, progress=False)
    F_b = 2 * 1.5e6 / 4.5
    h, run = truth(sim, lambda h: brake(steady_force(h, mesh(h, 400.0, 10.0)), F_b, 0.3, 1.0), 400.0, 10.0)
    return sim, run


def test_slip_and_stop_agree_with_the_lumped_model(slipping):
    sim, run = slipping
    f, names = run.frame(), [name for _, name in run.events]
    assert names == ["slip toward E", "slipping toward E", "rest"]
    onset, rest = event(sim, "slip_E"), event(sim, "rest")
    assert rel(onset.t, run.events[0][0]) < 1e-6 and rel(rest.t, run.events[-1][0]) < 1e-6
    at_onset = f[(f["t [s]"] == run.events[0][0]) & (f["mode"] == 0)].iloc[0]
    assert rel(onset.values["a_rope [m/s^2]"], at_onset["a [m/s2]"]) < 1e-6
    for side in ("T_L", "T_E"):
        assert rel(onset.values[f"{side} [N]"], at_onset[f"{side} [N]"]) < 1e-6
        assert rel(rest.values[f"{side} [N]"], f[f"{side} [N]"].iloc[-1]) < 1e-6
    last = f.iloc[-1]
    assert rel(rest.values["x [m]"], last["x [m]"]) < 1e-6
    slip_truth = run.y[2, -1] - run.y[0, -1]                   # x_w − x: the wheel's run less the ropes'
    assert rel(rest.values["slip [m]"], slip_truth) < 1e-6
    h = sim.history[sim.history["t [s]"] <= run.events[-1][0]]
    for side in ("T_L", "T_E"):
        interpolated = np.interp(h["t [s]"], f["t [s]"], f[f"{side} [N]"])
        assert np.max(np.abs(interpolated - h[f"{side} [N]"])) < 1e-5 * sim.summary[f"{side}_start"]


def test_the_slip_report(slipping):
    sim, _ = slipping
    s = sim.summary
    first = s["slip_events"][0]
    assert s["slip"] and first["toward"] == "E" and first["t_start"] == pytest.approx(event(sim, "slip_E").t)
    assert first["distance"] == pytest.approx(abs(event(sim, "stick").values["slip [m]"]), rel=1e-12)
    assert s["slip_margin_min"] <= 1e-6 * s["T_L_start"]          # the margin is 0 while it slips
    assert s["t_worst"] == first["t_start"] and abs(s["worst"]["slip_margin"]) <= 1e-6 * s["T_L_start"]
    assert s["energy_residual"] < 1e-7


def rigid_slip_limit(y_L, v):
    """Largest deceleration while hoisting before the ropes slip toward the loaded side's partner E, rigid ropes
    (docs/physics.md §7: a = (e^{μα} F_D − F_U − (e^{μα} − 1) q v²)/(M_U + e^{μα} M_D + q R (e^{μα} − 1)/μ),
    U = E, D = L), with the tail loop's ρ v² on both sides (the elastic model has the moving loop's pull)."""
    T_L = G * (29.6e3 + 22e3 + Q_ARC * (56.7 + y_L) + RHO * (905.0 - y_L))
    T_E = G * (29.6e3 + Q_ARC * (56.7 + 905.0 - y_L) + RHO * y_L)
    F_U, F_D = T_E + RHO * v * v, T_L + RHO * v * v
    return (E * F_D - F_U - (E - 1) * Q_ARC * v * v) / (T_E / G + E * T_L / G + Q_ARC * R * (E - 1) / 0.25)


def test_the_elastic_stop_tends_to_the_rigid_slip_limit():
    """A brake ramped over 1 s until the ropes slip, mid-shaft: the ropes' deceleration at the onset of slip
    against the rigid limit at the instant's position and speed, for ropes 1, 10, 100 and 1000 times stiffer."""
    errors = []
    for factor in (1.0, 10.0, 100.0, 1000.0):
        sim = simulate("koepe_braking", {"EA_head": EA * factor, "M_brake": 3.0e6, "t_apply": 1.0,
                                         "y_start": 400.0, "t_end": 1.0}, progress=False)
        onset = event(sim, "slip_E")
        v = onset.values
        errors.append(rel(-v["a_rope [m/s^2]"], rigid_slip_limit(400.0 - v["x [m]"], v["v_rope [m/s]"])))
    assert all(later < earlier / 5 for earlier, later in zip(errors, errors[1:])), errors
    # measured: 0.36 at the real stiffness (the ropes' vibration), 0.022, 3.8e-5, 3.2e-6
    assert errors[0] > 0.1 and errors[-1] < 1e-5, errors


@pytest.mark.slow
def test_a_stop_without_slip_agrees_with_the_lumped_model():
    """koepe_braking as shipped: the stop at the top of the wind, no slip."""
    sim = simulate("koepe_braking", progress=False)
    s = sim.summary
    F_b = 2 * 600e3 / 4.5
    _, run = truth(sim, lambda h: brake(steady_force(h, mesh(h, s["y_start"], 10.0)), F_b, 0.3, 1.0),
                   s["y_start"], 10.0)
    f, rest = run.frame(), event(sim, "rest")
    assert not s["slip"] and [name for _, name in run.events] == ["rest"]
    assert rel(rest.t, run.events[0][0]) < 1e-6 and rel(rest.values["x [m]"], f["x [m]"].iloc[-1]) < 1e-6
    applied = sim.history.iloc[int(np.argmin(np.abs(sim.history["t [s]"] - 0.3)))]
    row = f[f["t [s]"] == 0.3].iloc[0]
    for side in ("T_L", "T_E"):
        assert rel(applied[f"{side} [N]"], row[f"{side} [N]"]) < 1e-6


def test_an_overwind_is_named():
    """The controlled stop of 26.4925 m (below) started 10 m below the top runs 16.4925 m past it."""
    s = simulate(scene({"a_brake": 2.0, "y_start": 10.0}, brake_control="deceleration"), progress=False).summary
    assert s["overwind"] == pytest.approx(26.4925 - 10.0, rel=1e-7)


def test_constant_deceleration_stops_where_the_closed_form_says():
    """Deceleration 2 m/s² reached in 0.3 s from 10 m/s: at rest after t_j + (v0 − d t_j/2)/d = 5.15 s, having run
    v0 t_j − d t_j²/6 + (v0 − d t_j/2)²/(2d) = 26.4925 m (the ropes stick: the wheel's run is theirs)."""
    sim = simulate(scene({"a_brake": 2.0}, brake_control="deceleration"), progress=False)
    h, s = sim.history, sim.summary
    v0, d, t_j = 10.0, 2.0, 0.3
    t_s = t_j + (v0 - d * t_j / 2) / d
    run = v0 * t_j - d * t_j ** 2 / 6 + (v0 - d * t_j / 2) ** 2 / (2 * d)
    assert s["t_rest"] == pytest.approx(t_s, rel=1e-9) and not s["slip"]
    at_rest = h[h["t [s]"] >= t_s].iloc[0]
    assert at_rest["x [m]"] == pytest.approx(run, rel=1e-7)         # ten times sim_rtol
    t = h["t [s]"].to_numpy()
    speed = np.where(t < t_j, v0 - d * t ** 2 / (2 * t_j), np.maximum(v0 - d * t_j / 2 - d * (t - t_j), 0.0))
    assert np.max(np.abs(h["v_wheel [m/s]"] - speed)) < 1e-7 * v0
    assert s["energy_residual"] < 1e-7


def test_the_voigt_lining_holds_less_at_the_start():
    """With lining = "voigt" the slip margin at the start is Hajduk's traction at rest (eq. (19), fully crept)
    on the low side: ρ (T_E − q v²) − (T_L − q v²), the tensions at the wheel in the steady motion."""
    values = {"Q_R": 5e-8, "lambda_R": 0.5}
    sim = simulate(scene(values, lining="voigt"), progress=False)
    s = sim.summary
    T_L, T_E, c = s["T_L_start"], s["T_E_start"], Q_ARC * 100.0
    rho = kl.voigt_traction_ratio(T_E, 4, 0.25, math.pi, R, 0.0, 5e-8, 0.5, 0.0, 0.0)
    assert 1.0 < rho < E
    assert s["slip_margin_start"] == pytest.approx(rho * (T_E - c) - (T_L - c), rel=1e-9)


def stretched_static(y_L, v0=0.0, F_r=0.0):
    """The tensions (T_L, T_E) [N] at the wheel in steady motion at v0 with the loaded conveyance at y_L, the head
    ropes stretched: a span of length L under an end load W stretches (W L + q g L²/2)/(n EA), and the tail loop's
    sides follow the stretched depths, ℓ_t = (z_other − z_own + H)/2 (h_loop = 0).  W: the conveyance, its tail
    rope ρ ℓ_t and the moving loop's ρ v0², and on side L the shaft resistance F_r against a rising conveyance.
    Fixed point, to machine precision."""
    L = np.array([56.7 + y_L, 56.7 + 905.0 - y_L])
    m = np.array([29.6e3 + 22e3, 29.6e3])
    z = L.copy()
    for _ in range(60):
        l_t = (z[::-1] - z + 905.0) / 2
        W = G * (m + RHO * l_t) + RHO * v0 * v0 + np.array([F_r, 0.0])
        z = L + (W * L + Q_ARC * G * L * L / 2) / (4 * EA)
    return tuple(W + Q_ARC * G * L)


def test_the_steady_motion_braking_starts_from():
    """Hoisting at 10 m/s with 20 kN of shaft resistance: the tensions at the wheel are the stretched static ones
    with the moving tail loop's ρ v² on both sides and F_r on the loaded side."""
    s = simulate("koepe_braking", {"F_r": 2e4, "y_start": 400.0, "t_end": 0.5}, progress=False).summary
    T_L, T_E = stretched_static(400.0, 10.0, 2e4)
    assert s["T_L_start"] == pytest.approx(T_L, rel=1e-10) and s["T_E_start"] == pytest.approx(T_E, rel=1e-10)


def test_a_lowering_stop_that_slips_toward_the_loaded_side_agrees_with_the_lumped_model():
    """Lowering at 10 m/s, the controller decelerating at 3 m/s² (reached in 0.3 s), above the rigid slip limit
    while lowering (2.07 m/s²): the ropes slip toward the loaded side until the speeds meet again."""
    sim = simulate(scene({"a_brake": 3.0, "y_start": 600.0, "t_end": 5.0}, travel="lower",
                         brake_control="deceleration"), progress=False)
    s = sim.summary
    h = example_hoist(EA_head=EA, J=M_MACHINE * R * R, tau=TAU, N=s["segments"], reel=s["reel"])
    run = lumped(h, 600.0, -10.0, constant_deceleration(-10.0, 3.0, 0.3), t_end=5.0, method="LSODA", rtol=1e-10,
                 atol=1e-10, max_step=STEP)
    assert [name for _, name in run.events] == ["slip toward L", "slipping toward L", "relative speed 0", "stick"]
    assert [e.name for e in sim.events] == ["slip_L", "stick"]
    assert rel(sim.events[0].t, run.events[0][0]) < 1e-6 and rel(sim.events[1].t, run.events[2][0]) < 1e-6
    f = run.frame()
    i = int(np.flatnonzero(run.t == run.events[2][0])[-1])
    stuck = f.iloc[i]
    assert rel(sim.events[1].values["slip [m]"], run.y[2, i] - run.y[0, i]) < 1e-6      # x_w − x: 7.3 m
    h = sim.history
    before = h[(h["t [s]"] == sim.events[1].t) & (h["wheel"] == "slip_L")].iloc[0]   # the instant, still slipping
    smooth = ~h["t [s]"].isin([e.t for e in sim.events])        # a tension jumps where the ropes stick again
    for side in ("T_L", "T_E"):
        assert rel(before[f"{side} [N]"], stuck[f"{side} [N]"]) < 1e-6
        interpolated = np.interp(h["t [s]"][smooth], f["t [s]"], f[f"{side} [N]"])
        assert np.max(np.abs(interpolated - h[f"{side} [N]"][smooth])) < 1e-5 * s[f"{side}_start"]


def test_a_start_follows_the_drive_ramp():
    """From rest at the bottom, 0.8 m/s² reached in 1 s: the wheel's speed is the ramp's, the ropes stick, the
    tensions start at the static ones of koepe.side_tensions."""
    sim = simulate(scene({"a_drive": 0.8, "t_jerk": 1.0, "t_end": 3.0}, dynamics="start"), progress=False)
    h, s = sim.history, sim.summary
    t = h["t [s]"].to_numpy()
    speed = np.where(t < 1.0, 0.4 * t ** 2, 0.4 + 0.8 * (t - 1.0))
    assert np.max(np.abs(h["v_wheel [m/s]"] - speed)) < 1e-7 * 10.0 and not s["slip"]     # ten times sim_rtol
    T_L, T_E = stretched_static(905.0)
    assert s["T_L_start"] == pytest.approx(T_L, rel=1e-10) and s["T_E_start"] == pytest.approx(T_E, rel=1e-10)
    rigid = kp.side_tensions(905.0, 29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5)
    assert 0 < rigid[0] - s["T_L_start"] < 1e-3 * rigid[0]     # the loop follows the stretched ropes: O(T/EA)
    assert s["energy_residual"] < 1e-7


def test_a_start_agrees_with_the_lumped_model():
    """A start from rest mid-shaft, hoisting, 0.8 m/s² reached in 1 s, for 3 s: the tensions at the wheel at the
    ramp's knot (t = 1 s) and at the end, and over the run."""
    sim = simulate(scene({"a_drive": 0.8, "t_jerk": 1.0, "t_end": 3.0, "y_start": 500.0}, dynamics="start"),
                   progress=False)
    s, h = sim.summary, sim.history
    hoist = example_hoist(EA_head=EA, J=M_MACHINE * R * R, tau=TAU, N=s["segments"], reel=s["reel"])
    run = lumped(hoist, 500.0, 0.0, drive_ramp(10.0, 0.8, 1.0), t_end=3.0, method="LSODA", rtol=1e-10, atol=1e-10,
                 max_step=STEP)
    f = run.frame()
    for t in (1.0, 3.0):
        ours, theirs = (d.iloc[int(np.argmin(np.abs(d["t [s]"] - t)))] for d in (h, f))
        for side in ("T_L", "T_E"):
            assert rel(ours[f"{side} [N]"], theirs[f"{side} [N]"]) < 1e-6
    for side in ("T_L", "T_E"):
        interpolated = np.interp(h["t [s]"], f["t [s]"], f[f"{side} [N]"])
        assert np.max(np.abs(interpolated - h[f"{side} [N]"])) < 1e-5 * s[f"{side}_start"]


def test_simulate_on_the_command_line(capsys):
    assert main(["simulate", "koepe_braking"]) == 0
    text = capsys.readouterr().out
    assert "slip margin" in text and "the worst instant" in text and "no slip on the wheel" in text
    assert main(["simulate", "koepe_braking", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("T_L_max", "T_E_max", "T_min", "slip_margin_min", "t_worst", "worst", "slip", "t_rest"):
        assert key in out
    assert out["slip_margin_min"] > 0 and out["T_min"] > 0 and out["worst"]["slip_margin"] == out["slip_margin_min"]


@pytest.mark.parametrize("args, words", [
    (["simulate", "koepe_example"], "has no transient"),
    (["simulate", "koepe_braking", "--set", "t_apply=-1 s"], "t_apply"),
    (["simulate", "koepe_braking", "--set", "m_machine=0 kg"], "m_machine"),
    (["simulate", "koepe_braking", "--set", "y_start=2000 m", "--set", "t_apply=-1 s"], "y_start = 2000 m is below"),
])
def test_bad_input_exits_2(capsys, args, words):
    assert main(args) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_a_brake_too_weak_to_stop_a_lowering_exits_2(tmp_path, capsys):
    """Lowering, the loaded side pulls: 100 kN m (44 kN at the rope) cannot stop it (an out-of-balance of 216 kN)."""
    text = (files("ropemodel.data") / "koepe_braking.toml").read_text(encoding="utf-8")
    f = tmp_path / "weak.toml"
    f.write_text(text.replace('travel = "hoist"', 'travel = "lower"').replace('"600 kN*m"', '"100 kN*m"'),
                 encoding="utf-8")
    assert main(["simulate", str(f)]) == 2
    err = capsys.readouterr().err
    assert "the brake cannot stop the hoist" in err and "raise M_brake" in err


def test_the_transient_leaves_the_static_results_alone():
    static = rm.run("koepe_example", {"m_machine": M_MACHINE}).values
    dynamic = rm.run("koepe_braking").values
    for name in ("T_1", "T_2", "sigma_static", "a_slip_hoist_decel", "brake_margin_hoist"):
        assert dynamic[name] == static[name]


def test_the_readme_numbers_of_koepe_braking():
    """README, "Elastic ropes in braking and starting": the stop, the peak and the worst instant, to the digits
    it prints."""
    s = simulate("koepe_braking", progress=False).summary
    assert round(s["t_rest"], 3) == 4.157 and round(s["run"], 2) == 21.66
    assert round(s["T_L_max"] / 1e3, 1) == 956.5 and s["t_T_L_max"] > s["t_rest"]
    assert round(s["slip_margin_min"] / 1e3, 1) == 75.3 and round(s["slip_margin_start"] / 1e3, 1) == 544.6
    assert round(s["t_worst"], 3) == 5.217 and not s["slip"]
