"""Koepe hoist statics and rigid slip (ropemodel.papers.koepe, koepe_slip) against independent truths.

Truths written here: the tensions by bookkeeping of what hangs below each tangent point (coordinates from the
wheel down), a brute-force grid over the wind, and for the slip accelerations Newton's law on every body (each
side's conveyance, head rope, tail rope, the loop's turn, a deflection sheave) with the arc's equilibrium
integrated along the wrap by scipy, bisected on the acceleration at which the rope starts to slip.
"""

import math

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_slip as ks

G = 9.80665

# name: conveyance, payload [kg], H, H_head [m], n_head, q_head [kg/m], n_tail, q_tail [kg/m], loop's vertical
# part h_v below the lower position and turn radius r_turn [m] (the library's h_loop = h_v + π r_turn/2),
# mu, wrap [deg], R [m], deflection sheave (side, J [kg m²], r [m]), shaft resistance F_r [N]
HOISTS = {
    "issue example (4 head, 2 tail, unequal)": (29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5, 0.0, 0.0,
                                                0.25, 180.0, 2.25, None, 0.0),
    "no tail ropes, one rope": (8e3, 6e3, 400.0, 40.0, 1, 12.0, 0, 0.0, 0.0, 0.0, 0.3, 190.0, 1.6, None, 0.0),
    "balanced tail ropes, loop": (15e3, 12e3, 700.0, 45.0, 6, 5.5, 2, 16.5, 6.0, 1.0, 0.22, 200.0, 2.0,
                                  ("E", 8000.0, 1.5), 3000.0),
    "overbalanced tail, deflection on L": (20e3, 18e3, 1100.0, 60.0, 6, 7.2, 3, 16.0, 8.0, 1.2, 0.25, 195.0,
                                           2.5, ("L", 12000.0, 1.8), 5000.0),
    "deep, 8 ropes, heavy loop": (45e3, 35e3, 1600.0, 70.0, 8, 9.1, 4, 18.0, 12.0, 1.5, 0.28, 180.0, 3.25,
                                  None, 8000.0),
}


def h_loop_of(h_v, r_turn):
    """The library's h_loop: the vertical part plus half the loop's turn (each side carries half of it)."""
    return h_v + math.pi * r_turn / 2


def bookkeeping(hoist, y_L, payload=True):
    """(T_L, T_E) from what hangs below each tangent point, z measured down from the wheel."""
    mc, mp, H, H_head, nh, qh, nt, qt, h_v, r_turn = hoist[:10]
    z_L, z_E = H_head + y_L, H_head + H - y_L          # conveyances
    z_loop = H_head + H + h_loop_of(h_v, r_turn)       # the loop's equivalent bottom
    T_L = G * ((mc + (mp if payload else 0.0)) + nh * qh * z_L + nt * qt * (z_loop - z_L))
    T_E = G * (mc + nh * qh * z_E + nt * qt * (z_loop - z_E))
    return T_L, T_E


def library_tensions(hoist, y_L, payload=True):
    mc, mp, H, H_head, nh, qh, nt, qt, h_v, r_turn = hoist[:10]
    return kp.side_tensions(y_L, mc, mp if payload else 0.0, H, H_head, nh, qh, nt, qt, h_loop_of(h_v, r_turn))


@pytest.mark.parametrize("name", HOISTS)
def test_side_tensions_against_bookkeeping_over_the_wind(name):
    hoist = HOISTS[name]
    y = np.linspace(0.0, hoist[2], 41)
    for payload in (True, False):
        T_L, T_E = library_tensions(hoist, y, payload)
        ref_L, ref_E = bookkeeping(hoist, y, payload)
        np.testing.assert_allclose(T_L, ref_L, rtol=1e-14)
        np.testing.assert_allclose(T_E, ref_E, rtol=1e-14)


def test_balanced_tail_ropes_make_the_tensions_independent_of_position():
    hoist = HOISTS["balanced tail ropes, loop"]
    assert hoist[4] * hoist[5] == pytest.approx(hoist[6] * hoist[7], rel=1e-15)
    T_L, T_E = library_tensions(hoist, np.linspace(0.0, hoist[2], 11))
    assert np.ptp(T_L) < 1e-9 * T_L[0] and np.ptp(T_E) < 1e-9 * T_E[0]
    assert T_L[0] - T_E[0] == pytest.approx(G * hoist[1], rel=1e-12)   # only the payload is out of balance


def test_rope_lengths_are_conserved():
    y = np.linspace(0.0, 905.0, 7)
    heads = kp.head_rope_length(56.7, y) + kp.head_rope_length(56.7, 905.0 - y)
    tails = kp.tail_rope_length(905.0, 4.0, y) + kp.tail_rope_length(905.0, 4.0, 905.0 - y)
    np.testing.assert_allclose(heads, 2 * 56.7 + 905.0, rtol=1e-15)
    np.testing.assert_allclose(tails, 905.0 + 2 * 4.0, rtol=1e-15)


@pytest.mark.parametrize("name", HOISTS)
def test_the_static_cases_hold_the_worst_over_a_grid_of_positions(name):
    hoist = HOISTS[name]
    mc, mp, H, H_head, nh, qh, nt, qt, h_v, r_turn = hoist[:10]
    cases = kp.static_cases(mc, mp, H, H_head, nh, qh, nt, qt, h_loop_of(h_v, r_turn))
    y = np.linspace(0.0, H, 2001)
    grid = [bookkeeping(hoist, y, payload) for payload in (True, False)]
    ratio = max(np.max(np.maximum(a, b) / np.minimum(a, b)) for a, b in grid)
    high = max(np.max(np.maximum(a, b)) for a, b in grid)
    assert max(c.ratio for c in cases) == pytest.approx(ratio, rel=1e-13)
    assert max(c.T_1 for c in cases) == pytest.approx(high, rel=1e-13)
    for case in cases:
        ref_L, ref_E = bookkeeping(hoist, case.y_L, case.m_payload > 0)
        assert (case.T_L, case.T_E) == pytest.approx((ref_L, ref_E), rel=1e-14)
        assert case.high_side == ("loaded" if ref_L >= ref_E else "other")


def test_ratio_anti_slip_factor_and_margins_closed_forms():
    rng = np.random.default_rng(3)
    T_a, T_b = rng.uniform(1e5, 1e6, 500), rng.uniform(1e5, 1e6, 500)
    mu, alpha = rng.uniform(0.1, 0.4, 500), rng.uniform(2.5, 3.8, 500)
    E = np.exp(mu * alpha)
    T_1, T_2 = np.maximum(T_a, T_b), np.minimum(T_a, T_b)
    np.testing.assert_allclose(kp.static_ratio(T_a, T_b), T_1 / T_2, rtol=1e-15)
    sigma = kp.anti_slip_factor(T_1, T_2, E)
    np.testing.assert_allclose(sigma, (E - 1) * T_2 / (T_1 - T_2), rtol=1e-14)
    for sigma_min in (1.0, 1.25, 1.75):
        assert np.array_equal(kp.anti_slip_margin(T_1, T_2, E, sigma_min) >= 0, sigma >= sigma_min)
    margin_L, margin_E = kp.traction_margins(T_a, T_b, E)
    assert np.array_equal((margin_L >= 0) & (margin_E >= 0), T_1 / T_2 <= E)


def test_anti_slip_factor_is_one_at_the_traction_limit_and_infinite_in_balance():
    E = math.exp(0.25 * math.pi)
    assert kp.anti_slip_factor(E * 4e5, 4e5, E) == pytest.approx(1.0, rel=1e-14)
    assert kp.anti_slip_factor(4e5, 4e5, E) == math.inf
    T = ca.SX.sym("T")
    f = ca.Function("f", [T], [kp.anti_slip_factor(T, 4e5, E), ca.jacobian(kp.anti_slip_factor(T, 4e5, E), T)])
    value, slope = (float(v) for v in f(4e5))
    assert value == math.inf and slope == 0.0
    value, slope = (float(v) for v in f(5e5))
    assert value == pytest.approx((E - 1) * 4e5 / 1e5) and slope == pytest.approx(-(E - 1) * 4e5 / 1e10)


def test_a_hoist_without_tail_ropes_slips_at_rest_and_the_report_names_it():
    # 1000 m, 20 t conveyances, 15 t payload, 4 x 8.6 kg/m, mu 0.25 over 180 deg
    E = math.exp(0.25 * math.pi)
    cases = kp.static_cases(20e3, 15e3, 1000.0, 50.0, 4, 8.6)
    verdict = kp.slip_at_rest(cases, E)
    T_1, T_2 = G * (35e3 + 34.4 * 1050), G * (20e3 + 34.4 * 50)
    assert verdict.slips and verdict.case.name == "loaded at the bottom"
    assert (verdict.case.T_1, verdict.case.T_2, verdict.limit) == pytest.approx((T_1, T_2, E), rel=1e-14)
    for number in (f"{T_1 / T_2:.4g}", f"{E:.4g}", f"{T_1 / 1e3:.4g} kN", f"{T_2 / 1e3:.4g} kN"):
        assert number in verdict.message
    # the same hoist with balancing tail ropes holds, and a Voigt-like limit as a function of T_2 is evaluated
    held = kp.slip_at_rest(kp.static_cases(20e3, 15e3, 1000.0, 50.0, 4, 8.6, 2, 17.2), E)
    assert not held.slips and held.message == ""
    assert kp.slip_at_rest(cases, lambda T_2: 1.0 + 0.0 * T_2).limit == 1.0


def test_the_statics_take_casadi_symbols():
    y, mp = ca.SX.sym("y"), ca.SX.sym("mp")
    T_L, T_E = kp.side_tensions(y, 29.6e3, mp, 905.0, 56.7, 4, 8.6, 2, 15.5, 3.0)
    f = ca.Function("f", [y, mp], [T_L, T_E, kp.static_ratio(T_L, T_E)])
    for y_L in (0.0, 300.0, 905.0):
        ref = kp.side_tensions(y_L, 29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5, 3.0)
        out = [float(v) for v in f(y_L, 22e3)]
        assert out == pytest.approx([*ref, max(ref) / min(ref)], rel=1e-14)


# --- rigid dynamics: Newton's law on every body, the arc integrated, bisection ---------------------------------


def wheel_tensions(hoist, y_L, a_L, moving_up):
    """(T_L, T_E) at the wheel while the loaded conveyance accelerates upward at a_L, by Newton's law on each body
    from the loop upward.  moving_up: the loaded conveyance's velocity (the shaft resistance opposes it)."""
    mc, mp, H, H_head, nh, qh, nt, qt, h_v, r_turn, _, _, _, deflection, F_r = hoist
    m_turn = nt * qt * math.pi * r_turn
    # the free loop: vertical equilibrium and the turn's tangential acceleration
    loop = {"L": m_turn * (G + a_L) / 2, "E": m_turn * (G - a_L) / 2}
    out = {}
    for side, a, depth, m in (("L", a_L, y_L, mc + mp), ("E", -a_L, H - y_L, mc)):
        tail = nt * qt * (H - depth + h_v)
        T = loop[side] + tail * (G + a)                       # top of the tail ropes
        T += m * (G + a)                                       # the conveyance
        if side == "L":
            T += F_r if moving_up else -F_r                    # resistance against its velocity
        T += nh * qh * (H_head + depth) * (G + a)              # the head ropes
        if deflection is not None and deflection[0] == side:
            T += deflection[1] / deflection[2] ** 2 * a        # torque J a/r over the radius r
        out[side] = T
    return out["L"], out["E"]


def arc_holds(T_low, a_toward_high, mu, alpha, q, R, v):
    """The most the arc lets the high side pull with T_low on the other: dT/dθ = μ(T − q v²) + q R a_θ."""
    sol = solve_ivp(lambda th, T: mu * (T - q * v * v) + q * R * a_toward_high, (0.0, alpha), [T_low],
                    rtol=1e-12, atol=1e-9)
    return sol.y[0, -1]


#: manoeuvre: (loaded conveyance moving up?, the side that slips toward, sign of a_L per unit manoeuvre)
BRUTE = {"hoist_accel": (True, "L", +1), "hoist_decel": (True, "E", -1),
         "lower_accel": (False, "E", -1), "lower_decel": (False, "L", +1)}


def brute_force_slip(hoist, y_L, manoeuvre, q, v):
    moving_up, high, sign = BRUTE[manoeuvre]
    mu, alpha, R = hoist[10], math.radians(hoist[11]), hoist[12]

    def excess(a):   # what the arc could hold minus what the high side pulls; decreasing in a
        T_L, T_E = wheel_tensions(hoist, y_L, sign * a, moving_up)
        T_hi, T_lo = (T_L, T_E) if high == "L" else (T_E, T_L)
        return arc_holds(T_lo, -a, mu, alpha, q, R, v) - T_hi   # the ropes run away from the high side

    return brentq(excess, -40.0, 40.0, xtol=1e-13, rtol=1e-14)


def library_slip(hoist, y_L, manoeuvre, q, v):
    mc, mp, H, H_head, nh, qh, nt, qt, h_v, r_turn, mu, wrap, R, deflection, F_r = hoist
    T_L, T_E = kp.side_tensions(y_L, mc, mp, H, H_head, nh, qh, nt, qt, h_loop_of(h_v, r_turn))
    extra = {"L": 0.0, "E": 0.0}
    if deflection is not None:
        extra[deflection[0]] = kp.sheave_equivalent_mass(deflection[1], deflection[2])
    M_L, M_E = kp.side_mass(T_L, extra["L"]), kp.side_mass(T_E, extra["E"])
    function = getattr(ks, f"a_slip_{manoeuvre}")
    return function(T_L, T_E, M_L, M_E, mu, math.radians(wrap), q_arc=q, R=R, v=v, F_r=F_r)


@pytest.mark.parametrize("name", HOISTS)
@pytest.mark.parametrize("manoeuvre", ks.MANOEUVRES)
def test_slip_accelerations_against_newton_and_the_integrated_arc(name, manoeuvre):
    hoist = HOISTS[name]
    q = hoist[4] * hoist[5]
    for y_L in (0.0, hoist[2]):                                # both ends of the wind
        for q_arc, v in ((0.0, 0.0), (q, 0.0), (q, 14.0)):   # MODELS.md's form, the rope on the wheel, at speed
            ref = brute_force_slip(hoist, y_L, manoeuvre, q_arc, v)
            assert library_slip(hoist, y_L, manoeuvre, q_arc, v) == pytest.approx(ref, rel=1e-9, abs=1e-10)


@pytest.mark.parametrize("name", HOISTS)
def test_the_slip_limits_are_least_at_an_end_of_the_wind(name):
    hoist = HOISTS[name]
    q = hoist[4] * hoist[5]
    y = np.linspace(0.0, hoist[2], 501)
    for manoeuvre in ks.MANOEUVRES:
        grid = library_slip(hoist, y, manoeuvre, q, 10.0)
        ends = [library_slip(hoist, y_L, manoeuvre, q, 10.0) for y_L in (0.0, hoist[2])]
        assert np.min(grid) == pytest.approx(min(ends), rel=1e-14, abs=1e-14)


def test_models_md_closed_forms_with_masses_t_over_g():
    rng = np.random.default_rng(5)
    T_1, T_2 = rng.uniform(4e5, 9e5, 200), rng.uniform(1e5, 4e5, 200)
    E = np.exp(0.25 * np.pi)
    accel = ks.a_slip_hoist_accel(T_1, T_2, T_1 / G, T_2 / G, 0.25, np.pi)
    decel = ks.a_slip_hoist_decel(T_1, T_2, T_1 / G, T_2 / G, 0.25, np.pi)
    np.testing.assert_allclose(accel / G, (E * T_2 - T_1) / (E * T_2 + T_1), rtol=1e-13)
    np.testing.assert_allclose(decel / G, (E * T_1 - T_2) / (E * T_1 + T_2), rtol=1e-13)
    # "lowering swaps the two" without shaft resistance
    np.testing.assert_array_equal(ks.a_slip_lower_decel(T_1, T_2, T_1 / G, T_2 / G, 0.25, np.pi), accel)
    np.testing.assert_array_equal(ks.a_slip_lower_accel(T_1, T_2, T_1 / G, T_2 / G, 0.25, np.pi), decel)


def test_the_dynamic_anti_slip_factor_is_one_at_each_slip_limit():
    T_L, T_E = kp.side_tensions(905.0, 29.6e3, 22e3, 905.0, 56.7, 4, 8.6, 2, 15.5)
    M_L, M_E, E = kp.side_mass(T_L), kp.side_mass(T_E, 900.0), math.exp(0.25 * math.pi)
    for F_U, F_D, M_U, M_D in ks.manoeuvre_sides(T_L, T_E, M_L, M_E, 3e3).values():
        a = ks.slip_acceleration(F_U, F_D, M_U, M_D, 0.25, math.pi)
        T_U, T_D = ks.side_tension_dynamic(F_U, M_U, a), ks.side_tension_dynamic(F_D, M_D, -a)
        assert kp.anti_slip_factor(T_U, T_D, E) == pytest.approx(1.0, rel=1e-13)


def test_without_friction_the_slip_limits_are_the_free_motion():
    T_L, T_E, M_L, M_E, q, R, alpha = 8e5, 6e5, 9e4, 7e4, 40.0, 2.5, 3.3
    m_arc = q * R * alpha
    free = (T_E - T_L) / (M_L + M_E + m_arc)                 # an Atwood machine with the rope on the wheel
    assert ks.a_slip_hoist_accel(T_L, T_E, M_L, M_E, 0.0, alpha, q_arc=q, R=R) == pytest.approx(free, rel=1e-14)
    assert ks.a_slip_hoist_decel(T_L, T_E, M_L, M_E, 0.0, alpha, q_arc=q, R=R) == pytest.approx(-free, rel=1e-14)
    # and the first order in eps = mu alpha, from e^eps = 1 + eps and (e^eps - 1)/eps = 1 + eps/2:
    # a = (F_D (1 + eps) - F_U) / (M_U + M_D (1 + eps) + m_arc (1 + eps/2)); the next terms are O(eps) smaller
    for F_U, F_D, M_U, M_D, function in ((T_L, T_E, M_L, M_E, ks.a_slip_hoist_accel),
                                         (T_E, T_L, M_E, M_L, ks.a_slip_hoist_decel)):
        a0, M0 = (F_D - F_U) / (M_U + M_D + m_arc), M_U + M_D + m_arc
        slope = (F_D - a0 * (M_D + m_arc / 2)) / M0
        for mu in (1e-9, 1e-6):
            eps = mu * alpha
            a = function(T_L, T_E, M_L, M_E, mu, alpha, q_arc=q, R=R)
            # relative error: the next order, below eps, and rounding of a - a0 (1e-16 a0 / (eps slope) ~ 1e-7)
            assert (a - a0) / eps == pytest.approx(slope, rel=eps + 1e-7)


def test_the_slip_limits_take_casadi_symbols_with_finite_derivatives_at_mu_zero():
    mu, T_L = ca.SX.sym("mu"), ca.SX.sym("T_L")
    a = ks.a_slip_hoist_decel(T_L, 6e5, T_L / G, 6e5 / G, mu, 3.0, q_arc=40.0, R=2.5, v=10.0, F_r=2e3)
    f = ca.Function("f", [mu, T_L], [a, ca.gradient(a, mu)])
    for m in (0.0, 5e-5, 0.3):
        value, slope = (float(v) for v in f(m, 8e5))
        assert value == pytest.approx(ks.a_slip_hoist_decel(8e5, 6e5, 8e5 / G, 6e5 / G, m, 3.0, 40.0, 2.5, 10.0,
                                                            2e3), rel=1e-14)
        h = 1e-7
        fd = (ks.a_slip_hoist_decel(8e5, 6e5, 8e5 / G, 6e5 / G, m + h, 3.0, 40.0, 2.5, 10.0, 2e3)
              - ks.a_slip_hoist_decel(8e5, 6e5, 8e5 / G, 6e5 / G, m, 3.0, 40.0, 2.5, 10.0, 2e3)) / h
        assert math.isfinite(slope) and slope == pytest.approx(fd, rel=1e-5)


def test_coasting_deceleration_against_the_energy_balance():
    # hoisting: the loaded side rises by dx, the potential energy grows by (T_L - T_E) dx, the resistance
    # takes F_r dx; the kinetic energy M v^2/2 pays for both, so M v dv = -(T_L - T_E + F_r) dx
    T_L, T_E, M, F_r = 8.3e5, 5.8e5, 2.1e5, 4e3
    assert ks.coasting_deceleration(T_L, T_E, M, +1, F_r) == pytest.approx((T_L - T_E + F_r) / M, rel=1e-15)
    assert ks.coasting_deceleration(T_L, T_E, M, -1, F_r) == pytest.approx((T_E - T_L + F_r) / M, rel=1e-15)


def test_the_braking_window_is_an_interval_or_a_named_conflict():
    window = ks.braking_window_verdict("hoisting", d_slip=4.7, d_min=1.5, d_max=5.0, d_free=1.37)
    assert window.admissible and (window.low, window.high) == (1.5, 4.7)
    assert window.high_by.startswith("the slip limit (a_slip_hoist_decel)") and window.message == ""
    # the unbraked hoist decelerates faster than the ropes hold: no brake setting helps
    window = ks.braking_window_verdict("hoisting", d_slip=1.2, d_min=1.0, d_free=1.9)
    assert not window.admissible
    assert window.message == ("hoisting: no admissible brake deceleration: the deceleration without brake 1.9 m/s² "
                              "exceeds the slip limit (a_slip_hoist_decel) 1.2 m/s²")
    window = ks.braking_window_verdict("lowering", d_slip=2.0, d_min=2.5)
    assert not window.admissible and "the rule's least deceleration 2.5 m/s²" in window.message
    assert "a_slip_lower_decel" in window.message
    d = ca.SX.sym("d")
    low, high = ks.braking_window(d, 1.5, 5.0, 1.37)
    assert [float(v) for v in ca.Function("w", [d], [low, high])(4.7)] == [1.5, 4.7]
