"""The Koepe scene (``model = "koepe"``) against the closed forms written out in tests/_koepe_truth.py.

Five hoists: with and without tail ropes, tail ropes heavier and lighter than the head ropes, one, two, four and
six head ropes, sheaves of different inertia in the two compartments, shaft resistance and a tail loop; both
end positions (the worst state is at the bottom for some, at the top for others: asserted, so the search over
the ends is exercised), loaded and empty.
"""

from __future__ import annotations

import math

import pytest

import ropemodel as rm
from _koepe_truth import ENDS, HOISTS, ISSUE, coasting, full, rel, rigid_slip, scene, slips, statics, tensions

TOL = 1e-12    # the closed forms are evaluated in the same double precision; measured: 2.2e-16


@pytest.mark.parametrize("name", list(HOISTS))
def test_static_tensions_ratio_and_anti_slip_factor(name):
    h = HOISTS[name]
    r = rm.run(scene(h))
    truth = statics(h)
    w = truth["worst"]
    for key, want in (("T_1", w["T_1"]), ("T_2", w["T_2"]), ("ratio_static", w["T_1"] / w["T_2"]),
                      ("traction_limit", math.exp(h["mu"] * h["alpha"])), ("sigma_static", w["sigma"]),
                      ("T_max", truth["T_max"]), ("dT_max", truth["dT_max"])):
        assert rel(r[key], want) < TOL, key
    assert r.where["sigma_static"].startswith(w["name"])
    assert r.where["T_max"].startswith(max(truth["rows"], key=lambda x: x["T_1"])["name"])


def test_the_worst_static_state_is_found_at_either_end():
    worst = {name: statics(h)["worst"]["name"] for name, h in HOISTS.items()}
    assert worst["issue"] == "loaded at the bottom"
    assert worst["tail heavier, 6 ropes"] == "loaded at the top"     # the tail ropes outweigh the head ropes


@pytest.mark.parametrize("name", list(HOISTS))
def test_the_four_slip_accelerations(name):
    h = HOISTS[name]
    r = rm.run(scene(h))
    truth = slips(h)
    for m, (a, state) in truth.items():
        assert rel(r[f"a_slip_{m}"], a) < TOL, m
        assert state in r.where[f"a_slip_{m}"], m
    # without shaft resistance, lowering swaps the two (docs/physics.md §7)
    if full(h)["F_r"] == 0:
        assert r["a_slip_hoist_accel"] == pytest.approx(r["a_slip_lower_decel"], rel=1e-14)
        assert r["a_slip_hoist_decel"] == pytest.approx(r["a_slip_lower_accel"], rel=1e-14)


def test_models_md_limit_without_the_ropes_on_the_wheel():
    """MODELS.md §5: with M = T/g and no rope on the wheel, a/g = (E T_2 − T_1)/(E T_2 + T_1).  The scene keeps
    the rope on the wheel: with the lightest head rope its domain allows (1 g/m, at 1 nm/s) that rope weighs
    q R (E − 1)/μ = 0.01 kg against the sides' 10^5 kg, so the printed form holds to about 1e-7."""
    h = dict(ISSUE, q_head=1e-3, v_max=1e-9, n_tail=0, q_tail=0.0, H=300.0)
    r = rm.run(scene(h))
    E = math.exp(h["mu"] * h["alpha"])
    ends = [tensions(h, f * h["H"], loaded) for _, f, loaded in ENDS]      # (T_L, T_E) of each end state
    accel = min((E * T_E - T_L) / (E * T_E + T_L) for T_L, T_E in ends)   # the loaded side rising faster
    decel = min((E * T_L - T_E) / (E * T_L + T_E) for T_L, T_E in ends)   # ... slower: the other side is high
    assert r["a_slip_hoist_accel"] / 9.80665 == pytest.approx(accel, rel=1e-6)
    assert r["a_slip_hoist_decel"] / 9.80665 == pytest.approx(decel, rel=1e-6)


def test_the_rope_on_the_wheel_and_its_speed_cost_traction():
    """A limit that cannot be the library's output: the same hoist with a faster wheel holds less, and the
    centrifugal term is exactly (E − 1) q Δ(v²) in the numerator."""
    slow, fast = rm.run(scene(dict(ISSUE, v_max=1.0))), rm.run(scene(dict(ISSUE, v_max=15.0)))
    assert fast["a_slip_hoist_accel"] < slow["a_slip_hoist_accel"]
    h = dict(ISSUE, v_max=15.0)
    assert rel(fast["a_slip_hoist_accel"], slips(h)["hoist_accel"][0]) < TOL
    E, q = math.exp(ISSUE["mu"] * ISSUE["alpha"]), ISSUE["n_head"] * ISSUE["q_head"]
    assert rel(fast["traction_limit_run"], E - (E - 1) * q * 15.0**2 / fast["T_2"]) < TOL


def test_design_checks():
    h = dict(ISSUE, d_head=0.046, F_min_head=1.33e6, F_min_tail=2.0e6, n_safety_head=6.0, n_safety_tail=7.0,
             D_ratio_min=90.0, D_min=1.2, T_rated=9e5, dT_rated=2.8e5, sigma_static_min=1.75)
    r = rm.run(scene(h, checks="design"))
    s = statics(ISSUE)
    F_tail = 9.80665 * 15.5 * 905.0
    want = {"head_safety_margin": 4 * 1.33e6 / (6.0 * s["T_max"]) - 1, "tail_safety_margin": 2e6 / (7 * F_tail) - 1,
            "wheel_margin": 4.5 / (90 * 0.046) - 1, "wheel_size_margin": 4.5 - 1.2,
            "pull_margin": 9e5 / s["T_max"] - 1, "difference_margin": 2.8e5 / s["dT_max"] - 1,
            "antislip_margin": s["worst"]["sigma"] / 1.75 - 1, "F_tail": F_tail}
    for key, value in want.items():
        assert rel(r[key], value) < TOL, key
    # no tail ropes: no tail check; ratings not given: not checked (unlimited, JSON null)
    bare = {k: v for k, v in h.items() if k not in ("n_tail", "q_tail", "F_min_tail", "n_safety_tail", "T_rated")}
    r = rm.run(scene(dict(bare, n_tail=0, H=300.0), checks="design"))
    assert "tail_safety_margin" not in r.values and r["pull_margin"] == math.inf
    assert '"pull_margin": null' in r.to_json()


def test_braking_window():
    h = dict(ISSUE, a_brake_min=1.5, m_machine=2e4, F_r=4e3, m_sheave_a=1e3)
    r = rm.run(scene(h, brake="window"))
    s = slips(h)
    low_h, high_h = max(1.5, coasting(h, +1)), s["hoist_decel"][0]
    low_l, high_l = max(1.5, coasting(h, -1)), s["lower_decel"][0]
    for key, value in (("a_brake_low_hoist", low_h), ("a_brake_high_hoist", high_h), ("brake_margin_hoist",
                       high_h - low_h), ("a_brake_low_lower", low_l), ("a_brake_high_lower", high_l),
                       ("brake_margin_lower", high_l - low_l)):
        assert rel(r[key], value) < TOL, key
    assert coasting(h, +1) > 1.5 and "without brake (loaded at the bottom)" in r.where["a_brake_low_hoist"]
    # a largest deceleration below the slip limit bounds the window instead
    capped = rm.run(scene(dict(h, a_brake_max=2.0), brake="window"))
    assert capped["a_brake_high_lower"] == 2.0 and capped.where["a_brake_high_lower"] == "a_brake_max"


def test_an_empty_window_names_the_conflict():
    """A deep wind without tail ropes: hoisting the load from the bottom, the hoist decelerates by itself faster
    (4.09 m/s²) than the empty hoist's ropes can take arriving at the top (0.60 m/s²): it slips in an emergency
    stop whatever the brake does, though it holds at rest (σ = 1.09)."""
    h = dict(H=1000.0, H_head=50.0, m_conveyance=30e3, m_payload=6e3, n_head=4, q_head=10.0, n_tail=0, mu=0.3,
             alpha=math.pi, D=4.0, v_max=10.0, a_brake_min=1.0)
    r = rm.run(scene(h, brake="window"))
    assert statics(h)["worst"]["sigma"] == pytest.approx(1.0896, abs=1e-4)
    assert rel(r["brake_margin_hoist"], slips(h)["hoist_decel"][0] - coasting(h, +1)) < TOL
    assert r["brake_margin_hoist"] < 0
    text = r.where["brake_margin_hoist"]
    assert text.startswith("hoisting: no admissible brake deceleration: the deceleration without brake")
    assert "exceeds the slip limit a_slip_hoist_decel" in text


def test_catalogue_head_ropes():
    """q_head and F_min_head from the diameter (EN 12385-4: W d², K d² R_r, 6x36-IWRC: W = 4090 kg/m³, K = 0.356)."""
    h = {k: v for k, v in ISSUE.items() if k != "q_head"}
    r = rm.run(scene(dict(h, d_head=0.046, rope_grade=1770e6), head_ropes="6x36-IWRC"))
    assert rel(r["q_head"], 4090 * 0.046**2) < TOL
    assert rel(r["F_min_head"], 0.356 * 0.046**2 * 1770e6) < TOL
    assert rel(r["T_1"], statics(dict(ISSUE, q_head=4090 * 0.046**2))["worst"]["T_1"]) < TOL


def test_slip_at_rest_is_no_result():
    """Without tail ropes a deep wind slips at rest: the ropes slip, no number (papers.koepe.slip_at_rest's case)."""
    h = dict(H=1000.0, H_head=50.0, m_conveyance=20e3, m_payload=15e3, n_head=4, q_head=8.6, n_tail=0, mu=0.25,
             alpha=math.pi, D=4.0, v_max=10.0)
    with pytest.raises(rm.SolveError, match=r"slip on the wheel at rest \(loaded at the bottom\): T_1/T_2 = 3\.274"):
        rm.run(scene(h))
    truth = statics(h)["worst"]
    assert truth["T_1"] / truth["T_2"] > math.exp(0.25 * math.pi)      # the truth agrees it slips


def test_rigid_slip_is_the_truths_formula():
    """The truth's formula itself against the physics module's example (docs/physics.md §7: 2.0964 m/s² with
    M = T/g and no rope on the wheel): the truth the tests above use is the right one."""
    h = dict(ISSUE, q_head=1e-12, v_max=0.0)
    T_L, T_E = 830451.0, 584530.0
    assert rigid_slip(h, T_L, T_E, T_L / 9.80665, T_E / 9.80665) == pytest.approx(2.0964, abs=5e-5)


def test_a_slack_rope_and_ropes_lifting_off_are_no_result():
    """Outside the physics, no number: the shaft resistance reaching the tension of conveyance L's side (its
    ropes would have to push, lowering), and the head ropes' centrifugal force q v² reaching the low side."""
    lowest = min(tensions(ISSUE, f * ISSUE["H"], loaded)[0] for _, f, loaded in ENDS)     # 584.53 kN, empty
    with pytest.raises(rm.SolveError, match=rf"go slack: .* \(700 kN against {lowest / 1e3:.4g} kN\)"):
        rm.run(scene(dict(ISSUE, F_r=7e5)))
    assert rm.run(scene(dict(ISSUE, F_r=0.99 * lowest)))["a_slip_hoist_accel"] < 0   # steady hoisting slips
    fast = dict(ISSUE, H=200.0, q_head=40.0, q_tail=80.0, v_max=80.0)       # balanced: no slip at rest
    c = 4 * 40.0 * 80.0**2
    assert statics(fast)["worst"]["sigma"] > 1 and min(r["T_2"] for r in statics(fast)["rows"]) < c
    with pytest.raises(rm.SolveError, match="the head ropes lift off the lining"):
        rm.run(scene(fast))
