"""Transients of a winch scene (issue 6): each test against an independent truth.

Truths used: the static model of Krauze et al. (2025) (settling), Newton's second law for an
inextensible rope (rigid ramp, slip onset and slip distance by scipy), closed-form natural
frequencies of one- and two-degree-of-freedom spring-mass systems, the continuum integral of
the rope's elongation at rest, and the energy balance of the model's own states.
"""

from __future__ import annotations

import math
from importlib import resources

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, curve_fit, least_squares

import ropemodel as rm
from ropemodel.dynamics import simulate

DATA = resources.files("ropemodel.data")
G_N = 9.80665            # standard gravity [m/s²]


def scene(name="winch_start.toml", effects=None, params=None, numerics=None):
    """A built-in dynamic scene with overrides (a parameter set to None is left out)."""
    import tomllib

    d = tomllib.loads(DATA.joinpath(name).read_text())
    d["effects"].update(effects or {})
    d["parameters"].update(params or {})
    d["parameters"] = {k: val for k, val in d["parameters"].items() if val is not None}
    d.setdefault("numerics", {}).update(numerics or {})
    return rm.from_dict(d, bare="si")


# --- settling on the static model -------------------------------------------------------------

@pytest.mark.parametrize("travel", ["up", "down"])
def test_start_settles_on_static_forces(travel):
    """Ends at constant speed: F_C, F_S on Krauze eq. (12)-(13) to 1e-9 by t = 200 s, default damping
    (measured 4e-14 up, 3e-13 down; the load mode decays with ζ ≈ 0.05: 3e-5 after 100 s)."""
    sc = scene(effects={"travel": travel}, params={"t_end": "200 s"})
    assert sc.parameters["rope_damping"] == 0.05                      # the default
    sim = simulate(sc)
    static = rm.run(rm.load_scene())                                  # the paper's Fig. 9 scene
    s = sim.summary
    assert not s["slip"] and not s["slack"]
    assert s["F_C_end"] == pytest.approx(static[f"F_C_{travel}"], rel=1e-9)
    assert s["F_S_end"] == pytest.approx(static[f"F_S_{travel}"], rel=1e-9)
    assert s["dynamic_factor"] == pytest.approx(s["F_C_max"] / static[f"F_C_{travel}"], rel=1e-12)


# --- rigid rope: Newton's second law ------------------------------------------------------------

@pytest.mark.parametrize("travel,sign", [("up", 1), ("down", -1)])
def test_rigid_ramp_gives_static_plus_mass_times_acceleration(travel, sign):
    """F_C = F_C,static + (G_m + q_l L_u)/g · a and F_S = F_S,static − q_l L_u/g · a (moving masses:
    load and winding rope on the C side, unwinding rope on the S side), to 1e-12 (measured 2e-16)."""
    sc = scene(effects={"travel": travel, "rope_elasticity": "rigid"}, params={"t_end": "8 s"})
    sim = simulate(sc)
    v = sc.parameters
    st = rm.run(sc)
    a = sign * v["v_pj"] / v["t_ramp"]
    h = sim.history
    ramp = h[(h["t [s]"] > 0.5) & (h["t [s]"] < v["t_ramp"] - 1e-9)]       # |v| >> v_eps: tanh = 1
    assert len(ramp) > 100
    F_C = st[f"F_C_{travel}"] + (v["G_m"] + v["q_l"] * v["L_u"]) / G_N * a
    F_S = st[f"F_S_{travel}"] - v["q_l"] * v["L_u"] / G_N * a
    np.testing.assert_allclose(ramp["F_C [N]"], F_C, rtol=1e-12)
    np.testing.assert_allclose(ramp["F_S [N]"], F_S, rtol=1e-12)
    after = h[h["t [s]"] > v["t_ramp"] + 1e-9]
    np.testing.assert_allclose(after["F_C [N]"], st[f"F_C_{travel}"], rtol=1e-12)
    assert sim.summary["moving_masses"]["load"] == pytest.approx(v["G_m"] / G_N)


def _rigid_slip_truth(v, ratio):
    """Slip onset and slip distance of an inextensible rope, from Newton's law solved by scipy."""
    m_C = (v["G_m"] + v["q_l"] * v["L_u"]) / G_N
    m_S = v["q_l"] * v["L_u"] / G_N
    sa, ca = math.sin(v["alpha_u"]), math.cos(v["alpha_u"])
    half = v["F_nwl"] / 2
    G_C, G_S = (v["G_m"] + v["q_l"] * v["L_u"]) * sa, v["q_l"] * v["L_u"] * sa
    R_C = (v["mu_pm"] * v["G_m"] + v["mu_pl"] * v["q_l"] * v["L_u"]) * ca
    R_S = v["mu_pl"] * v["q_l"] * v["L_u"] * ca
    acc = v["v_pj"] / v["t_ramp"]

    def th(s):
        return math.tanh(s / v["v_eps"])

    def stick_margin(t):
        s = acc * t
        F_C = half + G_C + R_C * th(s) + m_C * acc
        F_S = half + G_S - R_S * th(s) - m_S * acc
        return ratio * F_S - F_C

    t_slip = brentq(stick_margin, 0.0, v["t_ramp"], xtol=1e-14)

    def rhs(t, y):
        s = y[1]
        a = (ratio * (half + G_S - R_S * th(s)) - half - G_C - R_C * th(s)) / (m_C + ratio * m_S)
        return [min(acc * t, v["v_pj"]) - s, a]             # y = [slip, rope speed]

    def caught_up(t, y):
        return min(acc * t, v["v_pj"]) - y[1] if t > t_slip + 1e-9 else 1.0

    caught_up.terminal, caught_up.direction = True, -1
    opts = dict(method="LSODA", rtol=1e-12, atol=1e-12, events=caught_up)
    sol = solve_ivp(rhs, (t_slip, v["t_ramp"]), [0.0, acc * t_slip], **opts)   # the ramp's kink: split
    if not sol.t_events[0].size:
        sol = solve_ivp(rhs, (v["t_ramp"], v["t_end"]), sol.y[:, -1], **opts)
    return t_slip, sol.t_events[0][0], sol.y_events[0][0][0]


def test_rigid_slip_onset_and_distance_match_newton():
    """Too little traction: the slip is reported; its onset and its length match an independent solve."""
    sc = scene("winch_start_slip.toml", effects={"rope_elasticity": "rigid"}, params={"t_end": "40 s"},
               numerics={"sim_rtol": 1e-11})
    sim = simulate(sc)
    s = sim.summary
    assert s["slip"]
    t0, t1, dist = _rigid_slip_truth(sc.parameters, math.exp(sc.parameters["mu_d"] * sc.parameters["alpha_d"]))
    (ev,) = s["slip_events"]
    assert ev["t_start"] == pytest.approx(t0, rel=1e-9)          # measured 4e-11
    assert ev["t_end"] == pytest.approx(t1, rel=1e-8)            # 2e-10
    assert ev["distance"] == pytest.approx(dist, rel=1e-8)       # 2.5e-9
    assert "SLIP on the drum from t = " in sim.report()


VOIGT = {"Q": "2e-6 1/N", "lambda": "0.05 s", "D": "2.5 m"}


def test_voigt_lining_without_compliance_is_the_rigid_drum():
    """Q = 0: Hajduk's eq. (19) is Euler–Eytelwein, so the transient is the rigid drum's."""
    tight = {"sim_rtol": 1e-10}
    rigid = simulate(scene("winch_start_slip.toml", effects={"lining": "rigid"}, params={"t_end": "12 s"},
                           numerics=tight))
    voigt = simulate(scene("winch_start_slip.toml", effects={"lining": "voigt"},
                           params={**VOIGT, "Q": "0 1/N", "t_end": "12 s"}, numerics=tight))
    assert voigt.summary["slip_events"][0]["t_start"] == pytest.approx(rigid.summary["slip_events"][0]["t_start"],
                                                                       rel=1e-12)
    # the same model through two expression graphs: they differ by the integrator's global error,
    # which grows with sim_rtol (2.5e-7 at the default 1e-8); at 1e-10 both are within 1e-9
    h_v, h_r = voigt.history, rigid.history
    np.testing.assert_allclose(np.interp(h_r["t [s]"], h_v["t [s]"], h_v["F_C [N]"]), h_r["F_C [N]"], rtol=1e-9)


def test_voigt_lining_slip_onset_matches_an_independent_solve():
    """Rigid rope on a Voigt-lined drum: the drum slips when F_C = s·F_S, s from ln s + q s c = μα
    (Hajduk 1992 eq. (19), q = Q F_S, c = 1 − e^{−α/(λω)}, ω = 2v/D) solved here by brentq."""
    sc = scene("winch_start.toml", effects={"lining": "voigt", "rope_elasticity": "rigid"},
               params={**VOIGT, "mu_d": 0.25, "alpha_d": "540 deg", "t_end": "6 s"})
    v = sc.parameters
    s = simulate(sc).summary
    assert s["slip"]
    m_C = (v["G_m"] + v["q_l"] * v["L_u"]) / G_N
    m_S = v["q_l"] * v["L_u"] / G_N
    sa, ca_ = math.sin(v["alpha_u"]), math.cos(v["alpha_u"])
    acc = v["v_pj"] / v["t_ramp"]

    def ratio(F_S, speed):
        k = v["lambda"] * 2 * speed / v["D"]
        c = 1 - math.exp(-v["alpha_d"] / k) if k > 0 else 1.0
        mua = v["mu_d"] * v["alpha_d"]
        return brentq(lambda x: math.log(x) + v["Q"] * F_S * x * c - mua, 1e-12, math.exp(mua) * 1.0000001,
                      xtol=1e-15, rtol=1e-15)

    def margin(t):
        th = math.tanh(acc * t / v["v_eps"])
        F_C = v["F_nwl"] / 2 + (v["G_m"] + v["q_l"] * v["L_u"]) * sa + (
            v["mu_pm"] * v["G_m"] + v["mu_pl"] * v["q_l"] * v["L_u"]) * ca_ * th + m_C * acc
        F_S = v["F_nwl"] / 2 + v["q_l"] * v["L_u"] * sa - v["mu_pl"] * v["q_l"] * v["L_u"] * ca_ * th - m_S * acc
        return ratio(F_S, acc * t) * F_S - F_C

    t_slip = brentq(margin, 1e-9, v["t_ramp"], xtol=1e-14)
    assert s["slip_events"][0]["t_start"] == pytest.approx(t_slip, rel=1e-9)        # measured 5e-11
    assert s["traction_ratio"] < math.exp(v["mu_d"] * v["alpha_d"])    # the lining costs traction


def test_slip_from_rest_is_reported():
    """A lining so compliant that the drum cannot hold the load at rest: slip from t = 0."""
    sim = simulate(scene("winch_start.toml", effects={"lining": "voigt", "rope_elasticity": "rigid"},
                         params={**VOIGT, "Q": "2e-5 1/N", "t_end": "5 s"}))
    s = sim.summary
    assert s["slip"] and s["slip_events"][0]["t_start"] == 0.0
    assert (sim.history["v_load [m/s]"].iloc[1:] < 0).all()          # the load runs back down


def test_elastic_slip_is_reported_with_time_and_distance():
    sim = simulate(scene("winch_start_slip.toml", params={"t_end": "30 s"}))
    s = sim.summary
    assert s["slip"] and s["slip_events"][0]["t_start"] > 0 and s["slip_events"][0]["distance"] > 0
    h = sim.history
    # while stuck the rope on the drum moves with the drum; while slipping the drum runs ahead
    stuck = h[h["drum"] == "stick"]
    assert np.abs(stuck["slip_speed [m/s]"]).max() < 1e-9
    assert (h.loc[h["drum"] == "slip_fwd", "slip_speed [m/s]"] >= -1e-9).all()
    assert s["slip_distance"] == pytest.approx(sum(e["distance"] for e in s["slip_events"]), rel=1e-9)


# --- natural frequencies ------------------------------------------------------------------------

def _load_mode_fit(sim, t_ramp, v_pj, p0):
    """Fit v_load(t) after the ramp to v_pj + e^{−σt}(A cos ωt + B sin ωt): (ω, σ)."""
    h = sim.history
    sel = h["t [s]"] > t_ramp + 1e-9
    t, v = h.loc[sel, "t [s]"].to_numpy() - t_ramp, h.loc[sel, "v_load [m/s]"].to_numpy()

    def model(t, A, B, w, sigma):
        return v_pj + np.exp(-sigma * t) * (A * np.cos(w * t) + B * np.sin(w * t))

    p, _ = curve_fit(model, t, v, p0=[-0.01, 0.0, *p0], xtol=1e-14, ftol=1e-14)
    return p[2], p[3]


def test_single_spring_natural_frequency():
    """The load at the return sheave (x_m = L_u, the span C2 has zero length), one element per span, a
    fixed tensioner (F_nwl = 150 kN keeps the unwinding rope taut), the rope fixed to the drum (no lining):
    one mass m = G_m/g + q_l L_u/(2g) (the load and half the winding rope) between two
    springs k = EA/L_u with dampers c = τk to the (moving) drum.  After the ramp the load oscillates
    about v_pj with ω_d = sqrt(2k/m − σ²), σ = c/m (closed form), fitted to the history."""
    sc = scene(effects={"rope_elasticity": "spring", "tensioner": "fixed", "lining": "none"},
               params={"x_m": "1150 m", "F_nwl": "150 kN", "t_end": "25 s", "mu_d": None, "alpha_d": None},
               numerics={"sim_rtol": 1e-11, "sim_dt": 0.005})
    v = sc.parameters
    sim = simulate(sc)
    assert sim.summary["n_nodes"] == 2 and sim.summary["x_m"] == v["L_u"]
    m = (v["G_m"] + v["q_l"] * v["L_u"] / 2) / G_N
    k = (v["L_u"] / v["q_lw"]) / v["L_u"]
    c = v["rope_damping"] * k
    w_d = math.sqrt(2 * k / m - (c / m) ** 2)
    w, sigma = _load_mode_fit(sim, v["t_ramp"], v["v_pj"], [w_d * 1.01, c / m])
    assert w == pytest.approx(w_d, rel=1e-6)                        # measured 2e-7
    assert sigma == pytest.approx(c / m, rel=1e-5)                  # measured 5e-6


@pytest.mark.parametrize("contact", ["rigid", "capstan"])
def test_spring_scene_two_mode_frequencies(contact):
    """rope_elasticity = spring, fixed tensioner, no damping: the load's motion after the ramp is the sum
    of two modes; their frequencies, fitted to the simulated history, are the roots of
    det(K − ω² M) = 0 (closed form, 2 degrees of freedom: the rope on the return sheave and the load).
    drum_contact = "capstan": the load-to-drum span is in series with the contact spring of Li et al.
    eq. (12), K_1 = μ_d EA F_C/(R (F_C − F_S)) at the static forces (D = 2.5 m: K_1 ≈ 4800 k_1, a shift
    of the load's mode 1e-4, a thousand times the fit's tolerance)."""
    sc = scene(effects={"rope_elasticity": "spring", "tensioner": "fixed", "drum_contact": contact},
               params={"rope_damping": 0.0, "t_end": "25 s", "t_ramp": "5 s", "x_m": "700 m", "F_nwl": "80 kN",
                       **({"D": "2.5 m"} if contact == "capstan" else {})},
               numerics={"sim_rtol": 1e-11, "sim_dt": 0.01})
    v = sc.parameters
    sim = simulate(sc)
    assert not sim.summary["slack"]
    EA = v["L_u"] / v["q_lw"]
    k_S, k_2, k_1 = EA / v["L_u"], EA / (v["L_u"] - v["x_m"]), EA / v["x_m"]
    if contact == "capstan":
        st = rm.run(sc)
        K_1 = v["mu_d"] * EA * st["F_C_up"] / (v["D"] / 2 * (st["F_C_up"] - st["F_S_up"]))
        k_1 = 1 / (1 / k_1 + 1 / K_1)
    m_rope = v["q_l"] / G_N
    m_R = m_rope * (v["L_u"] + (v["L_u"] - v["x_m"])) / 2
    m_L = v["G_m"] / G_N + m_rope * (v["L_u"] - v["x_m"] + v["x_m"]) / 2
    K = np.array([[k_S + k_2, -k_2], [-k_2, k_1 + k_2]])
    # closed form of the 2x2 generalised eigenproblem
    a_, b_, c_ = m_R * m_L, -(K[0, 0] * m_L + K[1, 1] * m_R), K[0, 0] * K[1, 1] - K[0, 1] ** 2
    w2 = [(-b_ - s * math.sqrt(b_ * b_ - 4 * a_ * c_)) / (2 * a_) for s in (1, -1)]
    w = np.sqrt(w2)
    if contact == "capstan":                                          # the rigid drum's load mode, for scale
        k_r = EA / v["x_m"]
        b_r, c_r = -((k_S + k_2) * m_L + (k_r + k_2) * m_R), (k_S + k_2) * (k_r + k_2) - k_2 ** 2
        assert abs(math.sqrt((-b_r - math.sqrt(b_r * b_r - 4 * a_ * c_r)) / (2 * a_)) / w[0] - 1) > 1e-5
    h = sim.history
    sel = h["t [s]"] > v["t_ramp"] + 1e-9
    t = h.loc[sel, "t [s]"].to_numpy() - v["t_ramp"]
    y = h.loc[sel, "v_load [m/s]"].to_numpy() - v["v_pj"]

    def residual(freq):
        A = np.column_stack([np.cos(freq[0] * t), np.sin(freq[0] * t), np.cos(freq[1] * t), np.sin(freq[1] * t)])
        coef, *_ = np.linalg.lstsq(A, y, rcond=None)
        return A @ coef - y, coef

    fit = least_squares(lambda f: residual(f)[0], w * (1 + 1e-3), xtol=1e-15, ftol=1e-15, gtol=1e-15)
    res, coef = residual(fit.x)
    assert np.max(np.abs(res)) < 1e-5 * np.max(np.abs(y))          # two modes explain the motion
    assert min(np.hypot(coef[0], coef[1]), np.hypot(coef[2], coef[3])) > 1e-4   # both are excited
    assert fit.x[0] == pytest.approx(w[0], rel=1e-7)                # the load's mode (large amplitude)
    assert fit.x[1] == pytest.approx(w[1], rel=3e-6)                # the sheave's mode (small amplitude): 1.8e-6


# --- energy ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["winch_start.toml", "winch_start_slip.toml", "winch_start_stroke.toml",
                                  "winch_start_brake.toml"])
def test_energy_balance_to_integrator_tolerance(name):
    """Drum work = Δ(kinetic + potential) + dissipated (damping, resistance, slip, stop impacts)."""
    res = {}
    for rtol in (1e-6, 1e-9):
        sim = simulate(scene(name, params={"t_end": "10 s"}, numerics={"sim_rtol": rtol}))
        res[rtol] = sim.summary["energy_residual"]
        assert res[rtol] < 100 * rtol
    assert res[1e-9] < res[1e-6]


# --- convergence ----------------------------------------------------------------------------------

def test_rest_take_up_converges_to_the_continuum_integral():
    """Take-up at rest = loop elongation = ∫T dx / EA of the continuum (no resistance at rest): the
    lumped value converges at second order as segments are added (errors 4.7e-3, 1.2e-3, 2.9e-4 at
    4, 8, 16 segments)."""
    errs = []
    for n in (2, 4, 8, 16):
        sc = scene(params={"t_end": "1 s", "t_ramp": "1 s"}, numerics={"segments": n})
        sim = simulate(sc)
        v = sc.parameters
        z0 = sim.history["take_up [m]"].iloc[0]
        s, L, x, h = math.sin(v["alpha_u"]), v["L_u"], v["x_m"], v["F_nwl"] / 2
        EA = L / v["q_lw"]
        w = v["q_l"] * s
        C2 = L - x
        exact = (h * L + w * L ** 2 / 2                                 # unwinding rope
                 + h * C2 + w * C2 ** 2 / 2                             # sheave → load
                 + (h + w * C2 + v["G_m"] * s) * x + w * x ** 2 / 2) / EA  # load → drum
        errs.append(abs(z0 - exact) / exact)
    assert errs[-1] < 4e-4
    for e0, e1 in zip(errs, errs[1:]):
        assert e1 < 0.3 * e0


@pytest.mark.slow
def test_peak_force_converges_with_segments():
    peaks = [simulate(scene(params={"t_end": "15 s"}, numerics={"segments": n})).summary["F_C_max"]
             for n in (2, 4, 8, 16, 32)]
    d = np.abs(np.diff(peaks))
    assert all(d1 < d0 for d0, d1 in zip(d, d[1:]))
    assert d[-1] / peaks[-1] < 5e-4


def test_peak_force_converges_with_segments_fast():
    peaks = [simulate(scene(params={"t_end": "8 s"}, numerics={"segments": n})).summary["F_C_max"]
             for n in (2, 4, 8)]
    assert abs(peaks[2] - peaks[1]) < abs(peaks[1] - peaks[0])


# --- stroke ---------------------------------------------------------------------------------------

def test_tensioner_out_of_stroke_is_reported():
    """The paper's installed 1000 mm stroke runs out during the start-up; the carriage stops on its end stop
    at once and the rope at the return sheave is left slack (the elements next to the sheave, stiff because
    the load is 50 m from it, still stretch at the rope's speed there, and their damping turns the lost
    take-up rate into compression): the linear rope model ends there."""
    sim = simulate(scene("winch_start_stroke.toml", params={"t_end": "20 s"}))
    s = sim.summary
    assert s["stroke_exhausted"]
    assert [e.name for e in sim.events] == ["stroke_end", "slack"] and sim.events[0].t == sim.events[1].t
    ev = s["stroke_events"][0]
    assert ev["event"] == "stroke_end" and ev["t"] < sim.scene.parameters["t_ramp"]
    assert sim.events[1].values["T_min [N]"] < 0 < sim.history["T_min [N]"].min()      # the jump, not before
    h = sim.history
    assert h["take_up [m]"].iloc[-1] == pytest.approx(sim.scene.parameters["stroke"], rel=1e-12)
    # before the event the take-up stays within the stroke
    assert h["take_up [m]"].max() <= sim.scene.parameters["stroke"] + 1e-12
    assert s["stroke_used"] == pytest.approx(sim.scene.parameters["stroke"], rel=1e-12)
    assert s["slack"] and s["t_slack"] == ev["t"]
    report = sim.report()
    assert "RAN OUT OF STROKE" in report and report.splitlines()[-1].startswith("  STOPPED at t = ")


def test_carriage_on_its_end_stop_at_rest():
    """A stroke shorter than the take-up F_nwl would need at rest: the carriage starts on its end stop, the
    loop's elongation is the stroke, and the tension pulling the sheave 2h follows from the continuum,
    stroke = ∫T ds/EA with T = h + (weights) (second order in the element length: 3.3e-2, 8.3e-3,
    2.1e-3 at 4, 8, 16 segments)."""
    errs = []
    for n in (4, 8, 16):
        sc = scene("winch_start_stroke.toml", params={"F_nwl": "80 kN", "t_end": "1 s", "t_ramp": "1 s"},
                   numerics={"segments": n})
        h0 = simulate(sc).history.iloc[0]
        v = sc.parameters
        s, L, x = math.sin(v["alpha_u"]), v["L_u"], v["x_m"]
        w, C2 = v["q_l"] * s, L - x
        weights = w * L ** 2 / 2 + w * C2 ** 2 / 2 + (w * C2 + v["G_m"] * s) * x + w * x ** 2 / 2
        h = (v["stroke"] * L / v["q_lw"] - weights) / (2 * L)
        assert h0["tensioner"] == "at_end" and h0["take_up [m]"] == v["stroke"] and 0 < 2 * h < v["F_nwl"]
        errs.append(abs(h0["T_sheave [N]"] / (2 * h) - 1))
    assert errs[-1] < 3e-3 and errs[2] < 0.3 * errs[1] < 0.09 * errs[0]


def test_enough_stroke_is_not_reported():
    s = simulate(scene(params={"t_end": "20 s"})).summary
    assert not s["stroke_exhausted"] and s["stroke_used"] < s["stroke"]


# --- structure and input ------------------------------------------------------------------------

@pytest.mark.parametrize("elasticity,n_nodes", [("rigid", 1), ("spring", 3), ("segments", 24)])
def test_only_the_chosen_rope_model_is_built(elasticity, n_nodes):
    sim = simulate(scene(effects={"rope_elasticity": elasticity}, params={"t_end": "6 s"}))
    assert sim.summary["n_nodes"] == n_nodes


def test_dynamic_effects_leave_the_static_model_alone():
    """The dynamic effects add parameters, no equation: the static answers are the paper's Fig. 9."""
    from ropemodel.core.model import Model

    dyn, fig9 = scene(), rm.load_scene()
    static = Model("winch", {**dyn.effects, "dynamics": "none"})
    assert [str(e.residual) for e in dyn.built.equations] == [str(e.residual) for e in static.equations]
    r_dyn, r_st = rm.run(dyn), rm.run(fig9)
    for k in ("F_C_up", "F_C_down", "F_S_up", "F_S_down", "dF_up"):
        assert r_dyn[k] == r_st[k]


@pytest.mark.parametrize("change,match", [
    (dict(effects={"rope_elasticity": "rigid", "tensioner": "fixed"}), "statically indeterminate"),
    (dict(params={"x_m": "1200 m"}), "x_m"),
    (dict(params={"t_end": "2 s"}), "t_end"),
    (dict(params={"rope_damping": -0.1}), "rope_damping"),
    (dict(params={"F_nwl": "0 kN", "x_m": "100 m"}), "slack"),
    (dict(numerics={"segments": 0}), "segments"),
])
def test_bad_input_is_refused(change, match):
    with pytest.raises(rm.InputError, match=match):
        simulate(scene(**change))


def test_static_scene_has_no_transient(fig9):
    with pytest.raises(rm.InputError, match="dynamics"):
        simulate(fig9)


# --- torque-limited motor -------------------------------------------------------------------------

def test_torque_limited_start_of_a_rigid_rope_matches_newton():
    """The motor's rim force is capped below what the ramp needs: the drum and the (inextensible) loop
    accelerate at a = (F_max − F_fr(v))/(M + m_drive), F_fr(v) = G_lmC − G_ls + (T_m + T_l + T_ls)
    tanh(v/v_eps), until the drum meets the profile again; F_C = F_C,static + m_C a meanwhile."""
    F_max, m_d = 180e3, 1.0e4
    sc = scene(effects={"rope_elasticity": "rigid", "drive": "torque_limited"},
               params={"F_drive_max": F_max, "m_drive": m_d, "t_end": "14 s"}, numerics={"sim_rtol": 1e-11})
    sim = simulate(sc)
    v, st = sc.parameters, rm.run(sc)
    s = sim.summary
    assert s["torque_limited"] and [e["event"] for e in s["drive_events"]] == ["torque_pos", "on_profile"]
    m_C = (v["G_m"] + v["q_l"] * v["L_u"]) / G_N
    M = m_C + v["q_l"] * v["L_u"] / G_N
    R = st["T_m"] + st["T_l"] + st["T_ls"]
    F0 = st["G_lmC"] - st["G_ls"]
    acc = v["v_pj"] / v["t_ramp"]

    def need(t):                                      # rim force the ramp needs, rope stuck
        return F0 + R * math.tanh(acc * t / v["v_eps"]) + (M + m_d) * acc - F_max

    t_lim = brentq(need, 0.0, v["t_ramp"], xtol=1e-15)

    def rhs(t, y):
        return [(F_max - F0 - R * math.tanh(y[0] / v["v_eps"])) / (M + m_d)]

    def on_profile(t, y):
        return min(acc * t, v["v_pj"]) - y[0]

    on_profile.terminal, on_profile.direction = True, -1
    sol = solve_ivp(rhs, (t_lim, v["t_end"]), [acc * t_lim], method="LSODA", rtol=1e-12, atol=1e-13,
                    events=on_profile)
    t_back = sol.t_events[0][0]
    assert s["drive_events"][0]["t"] == pytest.approx(t_lim, rel=1e-8)
    assert s["drive_events"][1]["t"] == pytest.approx(t_back, rel=1e-7)
    h = sim.history
    lim = h[(h["t [s]"] > 1.0) & (h["t [s]"] < t_back - 0.1)]
    a_lim = (F_max - F0 - R) / (M + m_d)
    np.testing.assert_allclose(lim["F_C [N]"], st["F_C_up"] + m_C * a_lim, rtol=1e-8)
    assert s["energy_residual"] < 1e-8
    assert "torque limit" in sim.report()


def test_torque_limit_above_the_need_changes_nothing():
    base = simulate(scene(params={"t_end": "10 s"}))
    lim = simulate(scene(effects={"drive": "torque_limited"},
                         params={"F_drive_max": "1000 kN", "m_drive": "10000 kg", "t_end": "10 s"}))
    assert not lim.summary["torque_limited"]
    np.testing.assert_allclose(lim.history["F_C [N]"], base.history["F_C [N]"], rtol=1e-12)


@pytest.mark.parametrize("params", [{"F_drive_max": "180 kN"}, {"F_drive_max": "180 kN", "m_drive": 0.0}])
def test_torque_limited_drive_needs_an_inertia(params):
    with pytest.raises(rm.InputError, match="m_drive"):
        simulate(scene(effects={"drive": "torque_limited"}, params=params))


def test_speed_drive_has_no_motor_parameters():
    assert "F_drive_max" not in scene().parameters and "m_drive" not in scene().parameters


def test_brake_too_weak_to_hold_a_lowered_load_is_reported():
    """Lowering the Fig. 9 load needs F_C − F_S ≈ 97 kN of holding force at the rim; a 60 kN limit
    cannot brake it: limited from t = 0 and the load speeds up instead of stopping."""
    sim = simulate(scene("winch_start_brake.toml", effects={"drive": "torque_limited"},
                         params={"F_drive_max": "60 kN", "m_drive": "10000 kg", "t_end": "6 s"}))
    s = sim.summary
    assert s["drive_events"][0] == {"t": 0.0, "event": "torque_pos"}
    assert s["v_load_end"] < -sim.scene.parameters["v_pj"]


# --- ramp shape -----------------------------------------------------------------------------------

def test_rigid_cosine_ramp_gives_static_plus_mass_times_its_acceleration():
    """Cosine ramp: a(t) = (π/2)(v_pj/t_ramp) sin(π t/t_ramp); F_C = F_C,static + (G_m + q_l L_u)/g · a(t)."""
    sc = scene(effects={"rope_elasticity": "rigid", "ramp": "cosine"}, params={"t_end": "6 s"})
    v, st = sc.parameters, rm.run(sc)
    h = simulate(sc).history
    ramp = h[(h["t [s]"] > 1.0) & (h["t [s]"] < v["t_ramp"])]         # |v| > 20 v_eps: tanh = 1
    a = 0.5 * math.pi * v["v_pj"] / v["t_ramp"] * np.sin(math.pi * ramp["t [s]"] / v["t_ramp"])
    np.testing.assert_allclose(ramp["v_drum [m/s]"],
                               v["v_pj"] * 0.5 * (1 - np.cos(math.pi * ramp["t [s]"] / v["t_ramp"])), rtol=1e-12)
    np.testing.assert_allclose(ramp["F_C [N]"], st["F_C_up"] + (v["G_m"] + v["q_l"] * v["L_u"]) / G_N * a, rtol=1e-12)
