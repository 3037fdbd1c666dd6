"""State events of the transient are located, not stepped over (issue 6).

Truths: Newton's law of an inextensible rope solved by scipy's solve_ivp with events (a slip
episode shorter than the output step), brute-force sampling of a cubic (the Hermite test), and
the same scene simulated with a fine output step (events independent of sim_dt).
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import ropemodel as rm
from ropemodel.dynamics import simulate
from ropemodel.dynamics.hybrid import hermite_min

DATA = resources.files("ropemodel.data")
G_N = 9.80665            # standard gravity [m/s²]


def scene(name, effects=None, params=None, numerics=None):
    d = tomllib.loads(DATA.joinpath(name).read_text())
    d["effects"].update(effects or {})
    d["parameters"].update(params or {})
    d.setdefault("numerics", {}).update(numerics or {})
    return rm.from_dict(d, bare="si")


def _short_slip_case(eps=1e-3):
    """Rigid rope, cosine ramp: the stick margin dips below zero only near the peak acceleration,
    for ε of it: the traction e^{μα} is set so that the drum slips at a* = (1 − ε) a_max."""
    base = scene("winch_start_slip.toml", effects={"rope_elasticity": "rigid", "ramp": "cosine"})
    v = base.parameters
    m_C, m_S = (v["G_m"] + v["q_l"] * v["L_u"]) / G_N, v["q_l"] * v["L_u"] / G_N
    sa, ca_ = math.sin(v["alpha_u"]), math.cos(v["alpha_u"])
    half = v["F_nwl"] / 2
    G_C, G_S = (v["G_m"] + v["q_l"] * v["L_u"]) * sa, v["q_l"] * v["L_u"] * sa
    R_C = (v["mu_pm"] * v["G_m"] + v["mu_pl"] * v["q_l"] * v["L_u"]) * ca_
    R_S = v["mu_pl"] * v["q_l"] * v["L_u"] * ca_
    T, V = v["t_ramp"], v["v_pj"]
    a_max = math.pi / 2 * V / T
    a_s = a_max * (1 - eps)
    rho = (half + G_C + R_C + m_C * a_s) / (half + G_S - R_S - m_S * a_s)

    def th(s):
        return math.tanh(s / v["v_eps"])

    def vd(t):
        return V * 0.5 * (1 - math.cos(math.pi * min(t, T) / T))

    def ad(t):
        return a_max * math.sin(math.pi * t / T) if t < T else 0.0

    def margin(t):
        s = vd(t)
        return rho * (half + G_S - R_S * th(s) - m_S * ad(t)) - (half + G_C + R_C * th(s) + m_C * ad(t))

    t0 = brentq(margin, 1.0, T / 2, xtol=1e-15)

    def rhs(t, y):                                        # y = [slip, rope speed]
        a = (rho * (half + G_S - R_S * th(y[1])) - half - G_C - R_C * th(y[1])) / (m_C + rho * m_S)
        return [vd(t) - y[1], a]

    def caught_up(t, y):
        return vd(t) - y[1] if t > t0 + 1e-9 else 1.0

    caught_up.terminal, caught_up.direction = True, -1
    sol = solve_ivp(rhs, (t0, T), [0.0, vd(t0)], method="DOP853", rtol=1e-13, atol=1e-15, events=caught_up)
    t1, dist = sol.t_events[0][0], sol.y_events[0][0][0]
    return math.log(rho) / v["alpha_d"], t0, t1, dist


@pytest.mark.parametrize("eps,duration,tol_end,tol_dist", [(1e-3, 0.21, 2e-7, 1e-5), (1e-5, 0.021, 5e-5, 2e-2)])
def test_slip_shorter_than_the_output_step_is_located(eps, duration, tol_end, tol_dist):
    """A slip episode (0.21 s for ε = 1e-3; 21 ms and 0.9 nm for ε = 1e-5, where the slip speed never
    exceeds the arming threshold at a detection point) inside one 0.7 s output step: no output sees it,
    the switching function is positive at both ends of the step; it is found, and its start, end and
    length match scipy.  The end is where the drum's and the rope's speeds meet at a shallow angle:
    its time carries the speeds' integration error over that slope (it converges with sim_rtol:
    ε = 1e-5, |Δt_end| = 4.6e-5, 1.1e-5, 2.8e-6 s at rtol 1e-11, 1e-12, 1e-13).  Measured at rtol 1e-12,
    ε = 1e-3: start 1.9e-14 s, end 1.1e-7 s, length 6.4e-6."""
    mu_d, t0, t1, dist = _short_slip_case(eps)
    assert t1 - t0 == pytest.approx(duration, rel=0.02)
    dt = 0.7
    assert math.floor(t0 / dt) == math.floor(t1 / dt)             # both crossings inside one output step
    sim = simulate(scene("winch_start_slip.toml", effects={"rope_elasticity": "rigid", "ramp": "cosine"},
                         params={"mu_d": mu_d, "t_end": "8 s"}, numerics={"sim_dt": dt, "sim_rtol": 1e-12}))
    s = sim.summary
    assert s["slip"]
    (ev,) = s["slip_events"]
    assert ev["t_start"] == pytest.approx(t0, abs=1e-12)
    assert ev["t_end"] == pytest.approx(t1, abs=tol_end)
    assert ev["distance"] == pytest.approx(dist, rel=tol_dist)
    assert s["slip_distance"] == pytest.approx(dist, rel=tol_dist)
    h = sim.history
    outputs = h["t [s]"].to_numpy()
    assert not ((outputs > t0 + 1e-9) & (outputs < t1 - 1e-9) & (h["drum"] == "stick")).any()


def test_events_do_not_depend_on_the_output_step():
    """Elastic rope with slip and stroke events: sim_dt = 0.5 s finds the same events at the same times
    as sim_dt = 0.01 s."""
    for name in ("winch_start_slip.toml", "winch_start_stroke.toml"):
        runs = [simulate(scene(name, params={"t_end": "20 s"}, numerics={"sim_dt": dt, "sim_rtol": 1e-10}))
                for dt in (0.01, 0.5)]
        fine, coarse = ([(e.name, e.t) for e in r.events] for r in runs)
        assert [n for n, _ in fine] == [n for n, _ in coarse] and fine
        np.testing.assert_allclose([t for _, t in coarse], [t for _, t in fine], rtol=1e-7)


def _hermite(u, g0, g1, d0, d1):
    """The cubic Hermite interpolant in its basis functions (values g0, g1, slopes d0, d1 per unit u)."""
    return ((2 * u ** 3 - 3 * u ** 2 + 1) * g0 + (u ** 3 - 2 * u ** 2 + u) * d0
            + (-2 * u ** 3 + 3 * u ** 2) * g1 + (u ** 3 - u ** 2) * d1)


def _sampled_min(g0, g1, d0, d1, n=1001):
    """The least value of each cubic on [0, 1] by sampling, to a proven bound: on a grid of step h a cell
    [u_k, u_k+1] holds no value below min(H_k, H_k+1) - M h²/8 (M >= |H''| on [0, 1]), so every cell whose
    bound reaches the grid's least value is sampled again at step h/(n-1): the error is then below
    M h²/(8 (n-1)²), below 1e-11 here.  Independent of the roots of H' that hermite_min solves for."""
    u = np.linspace(0.0, 1.0, n)[:, None]
    H = _hermite(u, g0, g1, d0, d1)
    h = 1.0 / (n - 1)
    M = 6 * np.abs(g0) + 4 * np.abs(d0) + 6 * np.abs(g1) + 4 * np.abs(d1)     # |H''| on [0, 1]
    cell_low = np.minimum(H[:-1], H[1:]) - M * h * h / 8
    k, j = np.nonzero(cell_low <= H.min(axis=0))
    fine = (k[:, None] + np.linspace(0.0, 1.0, n)) * h
    low = H.min(axis=0)
    np.minimum.at(low, j, _hermite(fine, *(a[j, None] for a in (g0, g1, d0, d1))).min(axis=1))
    return low


def test_hermite_minimum_against_sampling():
    rng = np.random.default_rng(6)
    g0, g1, d0, d1 = rng.normal(size=(4, 500))
    low, u = hermite_min(g0, g1, d0, d1)
    np.testing.assert_allclose(low, _sampled_min(g0, g1, d0, d1), atol=1e-9)
    assert ((u >= 0) & (u <= 1)).all()
    np.testing.assert_allclose(_hermite(u, g0, g1, d0, d1), low, atol=1e-12)     # the place has the value
