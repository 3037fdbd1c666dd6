"""A long route held as route numbers per load case (issue 22, item 4: the model holds the route as vectors).

A route of more than ``VECTOR_ABOVE`` segments is reduced, for each load case, to a few numbers
(:mod:`ropemodel.papers.route_numbers`) that the model declares as parameters.  Truths: the segment form (every
segment's values the model's symbols, the route's sums built from them: the code path kept for short routes,
forced here on the same route by raising the threshold), and the least tension along a rope side written as a
loop over the joints on numbers (:func:`ropemodel.papers.route.least_rope_tension`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.effects import winch_route_vector
from ropemodel.errors import InputError
from ropemodel.papers import route as rt
from ropemodel.papers import route_numbers as rn
from ropemodel.trips import trip

G = rt.G_N


def _route(n: int, seed: int, low: float = -6.0) -> list[dict]:
    """n segments of 5 to 40 m at ``low`` to 25 deg (dips: a least tension inside the route), every third with its
    own mu_winding."""
    rng = np.random.default_rng(seed)
    return [{"length": f"{float(L)!r} m", "inclination": f"{float(a)!r} deg",
             **({"mu_winding": float(m)} if i % 3 == 0 else {})}
            for i, (L, a, m) in enumerate(zip(rng.uniform(5.0, 40.0, n), rng.uniform(low, 25.0, n),
                                              rng.uniform(0.03, 0.08, n)))]


RAW = {"effects": {"route": "segments", "dynamics": "trip", "inertia": "rigid", "power": "drive",
                   "rope_elasticity": "rigid", "checks": "design"},
       "parameters": {"mu_pm": 0.05, "mu_pl": 0.05, "G_m": "467 kN", "F_nwl": "250 kN", "q_l": "0.08 kN/m",
                      "q_lw": "5.8 mm/kN", "v_pj": "2.5 m/s", "t_ramp": "5 s", "eta": 0.85, "d": "42 mm",
                      "F_min": "1200 kN", "D": "3 m", "n_rope": 4.5, "F_S_min": "1 kN", "stroke": "2 m",
                      "L_ul": "333 m"}}


@pytest.fixture
def both(monkeypatch):
    """(vector form, segment form) of a 40-segment route with point A: the same scene read with the threshold
    below and above its segments."""
    raw = {**RAW, "route": _route(40, seed=5)}
    scenes = []
    for above in (0, 10**6):
        monkeypatch.setattr(winch_route_vector, "VECTOR_ABOVE", above)
        scenes.append(rm.from_dict(raw, emit=False))
    assert scenes[0].built.derived and not scenes[1].built.derived
    return scenes


def _equal(a: dict, b: dict, rel: float = 1e-12, abs_: float = 1e-9) -> None:
    for k, v in b.items():
        assert a[k] == pytest.approx(v, rel=rel, abs=abs_), k


def test_the_vector_forms_model_has_no_input_per_segment(both):
    vector, segments = both
    args = vector.built.arguments
    assert not any(k.startswith(("L_", "alpha_", "mu_w")) and k[-1].isdigit() for k in args)
    assert len(args) < 80 < len(segments.built.arguments)


def test_run_and_solve_equal_the_segment_form(both):
    """Every output's worst and where it governs (least tensions inside the route among them), and an inverse
    solve at a pinned place, equal to 1e-12; only the plain segments' mu_wi (outputs there, equal to mu_pl) are
    not listed."""
    (vec, seg) = (rm.run(s) for s in both)
    plain = {k for k in seg.values if k.startswith("mu_w") and k not in vec.values}
    assert set(seg.values) - plain == set(vec.values)
    assert all(seg.values[k] == seg.values["mu_pl"] for k in plain)
    _equal(vec.values, {k: v for k, v in seg.values.items() if k not in plain})
    assert vec.where == seg.where and "segment" in vec.where["route_margin_up"]
    solved = [rm.solve(s.with_values({"x_m": "300 m"}), given={"F_C_up": "500 kN"}, find=["G_m"]) for s in both]
    assert solved[0]["G_m"] == pytest.approx(solved[1]["G_m"], rel=1e-12)


def test_trip_and_elasticities_equal_the_segment_form(both):
    """The trip's summary both ways, and the elasticities at the worst case in μ_pl, t_ramp, L_ul (each enters the
    route numbers' coefficients linearly), q_l and G_m: the segment form's derivatives to 1e-10."""
    for way in ("up", "down"):
        _equal(trip(both[0], way).summary, trip(both[1], way).summary, abs_=1e-6)
    outputs = ["F_C_up", "route_margin_up", "route_margin_down", "T_l1", "G_l2"]
    params = ["mu_pl", "t_ramp", "L_ul", "q_l", "G_m"]
    vec, seg = (rm.elasticities(s, outputs=outputs, parameters=params) for s in both)
    assert list(vec["parameter"]) == list(seg["parameter"])
    np.testing.assert_allclose(vec["dy_dp"].to_numpy(float), seg["dy_dp"].to_numpy(float), rtol=1e-10, atol=1e-12)


def test_segment_values_are_set_by_name_and_differentiated_through_the_route_step(both):
    """``--set L_2=...`` (with_values) reaches the route numbers: the same results as the segment form set alike;
    a route number is not a parameter.  Elasticities in segments' values (the route numbers as expressions of them
    at the case's indices), at the worst case and at a pinned one: the segment form's derivatives to 1e-10; a
    plain segment's mu_wi (mu_pl there) is refused by name."""
    moved = [rm.run(s.with_values({"L_2": "55 m", "alpha_7": "-3 deg"})) for s in both]
    _equal(moved[0].values, {k: v for k, v in moved[1].values.items() if k in moved[0].values})
    assert moved[0]["F_C_up"] != rm.run(both[0])["F_C_up"]
    with pytest.raises(InputError, match="computed from the route's segments"):
        both[0].with_values({"route_sin": 1.0})
    outputs = ["F_C_up", "route_margin_up", "route_margin_down", "T_l1", "G_l2", "F_S_least_up"]
    params = ["alpha_2", "L_3", "mu_w1", "L_9", "alpha_9", "L_40"]
    for scenes, outs in ((both, outputs),
                         ([s.with_values({"x_m": "300 m", "a_h": "0.2 m/s^2"}) for s in both], [*outputs, "G_ml"])):
        vec, seg = (rm.elasticities(s, outputs=outs, parameters=params) for s in scenes)
        assert list(vec["parameter"]) == list(seg["parameter"])
        np.testing.assert_allclose(vec["dy_dp"].to_numpy(float), seg["dy_dp"].to_numpy(float), rtol=1e-10,
                                   atol=1e-9)
    with pytest.raises(InputError, match="mu_w2 is mu_pl on its segment"):
        rm.elasticities(both[0], outputs=["F_C_up"], parameters=["mu_w2"])


def _same_sweep(vec, seg) -> None:
    assert list(vec.columns) == list(seg.columns)
    numbers = seg.select_dtypes("number").columns
    np.testing.assert_allclose(vec[numbers].to_numpy(), seg[numbers].to_numpy(), rtol=1e-12)
    others = [c for c in seg.columns if c not in numbers]
    assert vec[others].equals(seg[others])


#: sweeps of what the route numbers are computed from: μ_pl, the ramps (a_h), a segment's length, point A
ROUTE_SWEEPS = (("mu_pl", [0.02, 0.05, 0.12]), ("t_ramp", ["4 s", "5 s", "7 s"]), ("L_5", ["5 m", "20 m", "50 m"]),
                ("L_ul", ["100 m", "300 m", "500 m"]))


@pytest.mark.slow
def test_a_sweep_equals_the_segment_form(both):
    """A sweep at the worst case over parameters the route numbers do not read (each case's numbers), one at the
    worst over open cases over what they are computed from (each point and case its own numbers: μ_pl, a segment's
    length), and one at a pinned case over those and the case inputs (the numbers point by point): the segment
    form's columns (worsts and where they govern) to 1e-12."""
    outs = ["F_C_up", "route_margin_up", "F_S_least_down", "T_l1"]
    _same_sweep(*(rm.sweep(s, vary={"G_m": ["400 kN", "467 kN"], "q_l": ["0.07 kN/m", "0.09 kN/m"]}, outputs=outs,
                           si=True) for s in both))
    for name, values in (("mu_pl", [0.02, 0.12]), ("L_5", ["5 m", "50 m"])):
        _same_sweep(*(rm.sweep(s, vary={name: values}, outputs=outs, si=True, progress=False) for s in both))
    pinned = [s.with_values({"x_m": "300 m", "a_h": "0.3 m/s^2"}) for s in both]
    for name, values in (("mu_pl", [0.02, 0.12]), ("x_m", ["0 m", "10 m", "555 m", "882 m"]),
                         ("a_h", ["-0.5 m/s^2", "0.5 m/s^2"]), ("L_ul", ["100 m", "500 m"]),
                         ("alpha_2", ["-5 deg", "10 deg"]), ("L_5", ["5 m", "50 m"])):
        _same_sweep(*(rm.sweep(s, vary={name: values}, outputs=[*outs, "G_ml"], si=True) for s in pinned))


@pytest.mark.slow
def test_a_sweep_at_the_worst_of_what_the_numbers_read_equals_the_segment_form(both):
    """At the worst over open cases, sweeps of the ramps (t_ramp, v_pj: the manoeuvres' a_h), L_ul and a segment's
    inclination, and one marking a slack rope at some case (the physics checks of each case): the segment form's
    columns to 1e-12."""
    outs = ["F_C_up", "route_margin_up", "F_S_least_down", "T_l1"]
    for name, values in (("t_ramp", ["4 s", "7 s"]), ("v_pj", ["1 m/s", "3 m/s"]), ("L_ul", ["100 m", "500 m"]),
                         ("alpha_2", ["-5 deg", "10 deg"])):
        _same_sweep(*(rm.sweep(s, vary={name: values}, outputs=outs, si=True, progress=False) for s in both))
    marked = [rm.sweep(s, vary={"mu_pl": [0.01, 0.3], "F_nwl": ["1 kN", "250 kN"]}, outputs=outs, errors="mark",
                       progress=False) for s in both]
    assert not marked[1]["solved"].all() and marked[1]["solved"].any()
    _same_sweep(*marked)


@pytest.mark.slow
def test_a_sweep_of_a_120_segment_route_equals_the_segment_form(monkeypatch):
    """The route held as route numbers at its own size (120 segments, above VECTOR_ABOVE), swept at the worst over
    every place and manoeuvre over what its numbers are computed from: the segment form's columns to 1e-12."""
    raw = {**RAW, "route": _route(120, seed=5)}
    vec = rm.from_dict(raw, emit=False)
    monkeypatch.setattr(winch_route_vector, "VECTOR_ABOVE", 10**6)
    seg = rm.from_dict(raw, emit=False)
    assert vec.built.derived and not seg.built.derived
    for name, values in ROUTE_SWEEPS:
        _same_sweep(*(rm.sweep(s, vary={name: values}, outputs=["F_C_up", "route_margin_up", "T_l1"],
                               si=True, progress=False) for s in (vec, seg)))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_least_tensions_from_the_numbers_equal_the_loops(seed):
    """The least tension of each side from the route numbers (:func:`ropemodel.effects.winch_route_vector.
    least_winding`, ``least_unwinding`` on numbers: the least rise's coefficients at the case, combined in μ_pl and
    a_h as the model does) equals the loop over the joints on numbers, over the whole side and between its ends,
    at places on joints, inside segments, at both ends and beyond the route, for starts, stops and steady
    motion."""
    from ropemodel.effects import winch_route_vector as wv

    rng = np.random.default_rng(seed)
    n = 30
    L, alpha = rng.uniform(1.0, 30.0, n), np.radians(rng.uniform(-10.0, 20.0, n))
    own = rng.random(n) < 0.4
    mu = np.where(own, rng.uniform(0.02, 0.1, n), np.nan)
    ends = np.cumsum(L)
    x = np.concatenate([[0.0], ends, rng.uniform(0.0, ends[-1], 8), [ends[-1] + 5.0]])
    F_end, q, J = 20e3, 80.0, 35e3
    sums = rn.route_sums(L, alpha, np.nan_to_num(mu), own)
    whole = {"route_L_u": ends[-1], "route_sin": sums["A"][0], "route_mo": sums["mo"][0],
             "route_cp": sums["cp"][0], "route_cos": sums["C"][0]}
    for a_h in (0.0, 0.5, -0.7):
        for mu_pl in (0.03, 0.09):
            got = rn.places(sums, x, a_h, mu_pl)
            mus = np.where(own, mu, mu_pl)
            for way, s in rn.WAYS:
                wind = [rt.rope_gradient(al, m, s, a_h) for al, m in zip(alpha, mus)]
                unwind = [rt.rope_gradient(al, mu_pl, -s, a_h) for al in alpha]
                for i, xm in enumerate(x):
                    v = {**whole, **{f"route_{k}": float(np.ravel(got[k])[i]) for k in got}, "x_m": float(xm),
                         "mu_pl": mu_pl}
                    for between in (False, True):
                        truth = rt.least_rope_tension(F_end, q, list(L), wind, float(xm), J, between=between)
                        assert wv.least_winding(v, way, s, a_h, F_end, q, J, between) == pytest.approx(
                            truth, rel=1e-12, abs=1e-6), (a_h, mu_pl, way, xm, between)
                        truth = rt.least_rope_tension(F_end, q, list(L), unwind, between=between)
                        assert wv.least_unwinding(v, way, s, a_h, F_end, q, between) == pytest.approx(
                            truth, rel=1e-12, abs=1e-6), (a_h, mu_pl, way, between)


def test_point_A_splits_against_the_loops():
    """Point A's sums over [0, L_ul] from :func:`ropemodel.papers.route_numbers.split_at` (linear in L_ul on its
    segment) equal the loops :func:`ropemodel.papers.route.rope_weight_between` and ``rope_resistance_between``."""
    rng = np.random.default_rng(4)
    L, alpha = rng.uniform(1.0, 30.0, 25), np.radians(rng.uniform(-10.0, 20.0, 25))
    own = rng.random(25) < 0.5
    mu = np.where(own, rng.uniform(0.02, 0.1, 25), 0.0)
    sums = rn.route_sums(L, alpha, mu, own)
    for A in (0.0, float(np.cumsum(L)[6]), 123.4, float(np.sum(L))):
        c = rn.split_at(sums, A)
        mus = np.where(own, mu, 0.07)
        assert c["A_sin0"] + c["A_sin1"] * A == pytest.approx(rt.rope_weight_between(1.0, L, alpha, 0.0, A),
                                                            rel=1e-12, abs=1e-12)
        resistance = (c["A_mo0"] + c["A_mo1"] * A) + 0.07 * (c["A_cp0"] + c["A_cp1"] * A)
        assert resistance == pytest.approx(rt.rope_resistance_between(1.0, L, alpha, mus, 0.0, A), rel=1e-12,
                                           abs=1e-12)
    assert math.isfinite(sums["A"][0])


SIZING = ('[effects]\nroute = "segments"\nrope = "6x36-IWRC"\nlining = "rigid"\ndynamics = "trip"\n'
          '[parameters]\nmu_pm = 0.05\nmu_pl = 0.05\nG_m = "467 kN"\nv_pj = "2.5 m/s"\nt_ramp = "5 s"\n'
          'rope_grade = "1770 N/mm^2"\nrope_E = "100 kN/mm^2"\nmu_d = 0.2\nalpha_d = "540 deg"\nn_slip = 1.25\n'
          'n_rope = 4.5\nF_S_min = "5 kN"\nL_ul = "444 m"\n')


def test_sizing_equals_the_segment_form(tmp_path, monkeypatch):
    """``size`` of a 30-segment route with point A and dips, the route numbers fed per load case (constants of the
    NLP, linear in its parameters): the segment form's design, continuous optimum and margins to 1e-10, and its
    sensitivities in every parameter but the segments' own (named as left out) to 1e-8."""
    from optimisation.design import size
    from ropemodel import budget

    head, params = SIZING.split("[parameters]\n")
    route = "".join("[[route]]\n" + "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in seg.items())
                    for seg in _route(30, seed=11, low=-4.0))
    (tmp_path / "s.toml").write_text(head + route + "[parameters]\n" + params)
    done = []
    with budget.lifted():
        for above in (0, 10**6):
            monkeypatch.setattr(winch_route_vector, "VECTOR_ABOVE", above)
            done.append(size(str(tmp_path / "s.toml")))
    vec, seg = done
    assert vec.feasible and vec.design == seg.design and vec.active == seg.active
    _equal(vec.continuous, seg.continuous, rel=1e-10, abs_=0.0)
    _equal(vec.margins, seg.margins, rel=1e-10, abs_=1e-6)
    assert set(seg.sensitivities) - set(vec.sensitivities) == {f"{k}_{i}" for k in ("L", "alpha") for i in
                                                               range(1, 31)} | {f"mu_w{i}" for i in range(1, 31, 3)}
    assert "30 segments" in vec.to_dict()["sensitivities_left_out"]
    for p, column in vec.sensitivities.items():
        for k, v in column.items():
            assert v == pytest.approx(seg.sensitivities[p][k], rel=1e-8, abs=1e-12), (p, k)


@pytest.mark.slow
def test_a_sizing_sweep_equals_the_segment_form(tmp_path, monkeypatch):
    """A sizing sweep of what the route numbers are computed from (μ_pl, the ramps, a segment's length, L_ul):
    each point's NLP has the numbers of its own values in each case; the segment form's designs to 1e-10."""
    from optimisation.sweep import sizing_sweep
    from optimisation.problem import load_sizing

    head, params = SIZING.split("[parameters]\n")
    route = "".join("[[route]]\n" + "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in seg.items())
                    for seg in _route(20, seed=11, low=-4.0))
    (tmp_path / "s.toml").write_text(head + route + "[parameters]\n" + params.replace("444 m", "222 m"))
    scenes = []
    for above in (0, 10**6):
        monkeypatch.setattr(winch_route_vector, "VECTOR_ABOVE", above)
        scenes.append(load_sizing(str(tmp_path / "s.toml"), emit=False))
    assert scenes[0].built.derived and not scenes[1].built.derived
    for name, values in (("mu_pl", [0.04, 0.06, 0.09]), ("t_ramp", ["4 s", "6 s", "8 s"]),
                         ("L_5", ["10 m", "30 m", "60 m"]), ("L_ul", ["100 m", "222 m", "300 m"])):
        vec, seg = (sizing_sweep(s, vary={name: values}, method="ipopt", progress=False) for s in scenes)
        assert vec["feasible"].all() and list(vec.columns) == list(seg.columns)
        for c in ("d [mm]", "F_nwl [kN]", "stroke [mm]"):
            np.testing.assert_allclose(vec[c].to_numpy(), seg[c].to_numpy(), rtol=1e-10, err_msg=f"{name}: {c}")


def test_a_transient_on_a_long_route_equals_the_segment_form(monkeypatch):
    """``simulate`` (a start, the rope model's segments from the route's, each segment's coefficient: mu_pl where
    it gives none, which the route numbers' form does not list per segment): the segment form's summary."""
    raw = {"effects": {**RAW["effects"], "dynamics": "start", "rope_elasticity": "segments"},
           "parameters": {**RAW["parameters"], "t_end": "6 s"}, "route": _route(40, seed=5)}
    done = []
    for above in (0, 10**6):
        monkeypatch.setattr(winch_route_vector, "VECTOR_ABOVE", above)
        done.append(rm.simulate(rm.from_dict(raw, emit=False), progress=False).summary)
    assert done[0].keys() == done[1].keys()
    numbers = {k: v for k, v in done[1].items() if isinstance(v, float)}
    assert len(numbers) > 5
    _equal(done[0], numbers, rel=1e-9, abs_=1e-9)
    assert {k: v for k, v in done[0].items() if k not in numbers} == {k: v for k, v in done[1].items()
                                                                      if k not in numbers}
