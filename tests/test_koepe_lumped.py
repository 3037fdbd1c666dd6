"""The lumped-mass Koepe model (tests/_koepe_lumped.py) against truths of its own: the rigid limit, closed-form
natural frequencies, the energy balance, steady tensions written out, Euler–Eytelwein while slipping, and
convergence in the number of nodes.

The rigid limit is the one place these tests call ropemodel (koepe_slip's rigid window), as the second method:
the lumped model imports nothing of it.
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from _koepe_lumped import (Hoist, Wheel, brake, constant_deceleration, drive_ramp, example_hoist, initial_state,
                           mesh, natural_frequencies, simulate, steady_force)
from scipy.optimize import brentq

from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_slip as ks

G = 9.80665
RHO = 2 * 15.5               # the example's tail ropes [kg/m]


def slip_onset(h: Hoist, y_L0: float, v0: float, rate: float):
    """From steady motion at v0, the wheel's force moves from the steady one at rate [N/s] (braking) until the
    ropes slip: the wheel's acceleration then, the rope run x and the speed v [SI]."""
    F_0 = steady_force(h, mesh(h, y_L0, v0))
    run = simulate(h, y_L0, v0, Wheel("force", lambda t, v: F_0 + rate * t), t_end=6.0, stop="slip",
                   method="LSODA", rtol=1e-10, atol=1e-10)
    assert run.events and run.events[-1][1].startswith("slip"), run.events
    last = run.frame().iloc[-1]
    return last["a [m/s2]"], last["x [m]"], last["v [m/s]"], run.events[-1][1]


def rigid_window(h: Hoist, y_L: float, v: float, manoeuvre: str) -> float:
    """koepe_slip's slip limit at the loaded conveyance's depth y_L and speed v, the free loop's ρ v² added to both
    sides (the lumped model has it, the rigid library leaves it out: a closed form written here)."""
    T_L, T_E = kp.side_tensions(y_L, h.m_conveyance, h.m_payload, h.H, h.H_head, h.n_head, h.q_head, h.n_tail,
                                h.q_tail)
    F_U, F_D, M_U, M_D = ks.manoeuvre_sides(T_L + RHO * v * v, T_E + RHO * v * v, T_L / G, T_E / G)[manoeuvre]
    return float(ks.slip_acceleration(F_U, F_D, M_U, M_D, h.mu, h.alpha, h.m_arc / (h.R * h.alpha), h.R, v))


@pytest.mark.parametrize("factors", [(1.0, 100.0, 1e4)])
def test_slip_onset_converges_to_the_rigid_window_lowering(factors):
    """An emergency stop while lowering the load near the bottom: the brake force rises until the ropes slip toward
    the loaded side.  The wheel's deceleration then tends to koepe_slip's a_slip_lower_decel as EA grows."""
    errors = []
    for f in factors:
        h = example_hoist(N=4, reel=20.0, EA_head=example_hoist().EA_head * f)
        a, x, v, event = slip_onset(h, 800.0, -10.0, 2.5e5)
        assert event == "slip toward L"
        errors.append(abs(a / rigid_window(h, 800.0 - x, v, "lower_decel") - 1))
    assert all(e2 < e1 / 20 for e1, e2 in zip(errors, errors[1:])), errors
    # _koepe_lumped's docstring: 4 % off at the real stiffness (the elastic ropes), 2e-6 at 100×, 1e-8 at 10⁴×
    assert round(errors[0], 2) == 0.04 and errors[1] < 3e-6 and errors[2] < 2e-8, errors


@pytest.mark.slow
@pytest.mark.parametrize("arc_rope, y_L0, v0, rate, manoeuvre, event", [
    (True, 200.0, 10.0, -5e5, "hoist_decel", "slip toward E"),
    (False, 800.0, -10.0, 2.5e5, "lower_decel", "slip toward L"),
    (False, 600.0, 0.0, 4e5, "hoist_accel", "slip toward L")])
def test_slip_onset_converges_to_the_rigid_window(arc_rope, y_L0, v0, rate, manoeuvre, event):
    errors = []
    for f in (1.0, 10.0, 100.0, 1e3, 1e4):
        h = example_hoist(N=4, reel=20.0, EA_head=example_hoist().EA_head * f, arc_rope=arc_rope)
        a, x, v, got = slip_onset(h, y_L0, v0, rate)
        assert got == event
        errors.append(abs(abs(a) / rigid_window(h, y_L0 - x, v, manoeuvre) - 1))
    assert all(e2 < e1 for e1, e2 in zip(errors, errors[1:])) and errors[-1] < 1e-6, errors


def continuum_frequency(EA, q, L, M):
    """First axial frequency [rad/s] of a rope (EA, q, length L) fixed at the top with an end mass M:
    β tan β = q L/M, ω = β √(EA/q)/L."""
    beta = brentq(lambda b: b * math.tan(b) - q * L / M, 1e-9, math.pi / 2 - 1e-12, xtol=1e-15)
    return beta * math.sqrt(EA / q) / L


def test_first_frequency_of_one_element_is_its_closed_form():
    """N = 1, the wheel locked, no tail ropes: each side is a spring EA/L with the conveyance and half the rope."""
    h = example_hoist(N=1, n_tail=0, reel=0.0, tau=0.0)
    y = 400.0
    want = sorted(math.sqrt(h.n_head * h.EA_head / L / (m + h.q * L / 2)) for L, m in (
        (h.H_head + y, h.m_conveyance + h.m_payload), (h.H_head + h.H - y, h.m_conveyance)))
    assert natural_frequencies(h, y) == pytest.approx(want, rel=1e-9)


def test_first_frequency_in_a_simulation():
    """The same hoist stopped from 5 cm/s and held: the loaded conveyance swings at the closed form's frequency."""
    h = example_hoist(N=1, n_tail=0, reel=0.0, tau=0.0)
    run = simulate(h, 400.0, 0.05, constant_deceleration(0.05, 1.0, 0.02), t_end=12.0, rtol=1e-11, atol=1e-12,
                   max_step=0.01)
    fr = run.frame()
    L, m = h.H_head + 400.0, h.m_conveyance + h.m_payload     # the spring is L − x long once the wheel is held
    omega = math.sqrt(h.n_head * h.EA_head / (L - fr["x [m]"].iloc[-1]) / (m + h.q * L / 2))
    held = fr[fr["t [s]"] > 0.1]
    t, v = held["t [s]"].to_numpy(), held["v_L [m/s]"].to_numpy()
    i = np.nonzero(np.sign(v[1:]) != np.sign(v[:-1]))[0]
    crossings = t[i] - v[i] * (t[i + 1] - t[i]) / (v[i + 1] - v[i])
    assert len(crossings) >= 10
    period = (crossings[-1] - crossings[0]) / (len(crossings) - 1) * 2
    assert 2 * math.pi / period == pytest.approx(omega, rel=1e-6)


def test_first_frequency_converges_to_the_continuum():
    """More elements: the first frequency tends to the continuous rope's (second order in 1/N)."""
    h0 = example_hoist(n_tail=0, reel=0.0, tau=0.0)
    want = continuum_frequency(h0.n_head * h0.EA_head, h0.q, h0.H_head + 400.0, h0.m_conveyance + h0.m_payload)
    errors = []
    for N in (4, 8, 16, 32, 64):
        omega = natural_frequencies(example_hoist(N=N, n_tail=0, reel=0.0, tau=0.0), 400.0)
        errors.append(abs(min(omega, key=lambda w: abs(w - want)) / want - 1))
    assert all(3.5 < e1 / e2 < 4.5 for e1, e2 in zip(errors, errors[1:])), errors
    assert round(errors[1], 5) == 3.4e-4 and errors[-1] < 1e-5, errors


def test_steady_tangent_tensions_are_the_static_ones_plus_the_loops():
    """Steady motion at v: the tangent tensions are g × everything hanging plus ρ v² of the tail loop (stiff ropes:
    the tail loop's shift by the ropes' stretch is 4e-9 of them)."""
    h = example_hoist(EA_head=example_hoist().EA_head * 1e4)
    for v in (0.0, 12.0):
        run = simulate(h, 300.0, v, Wheel("force", lambda t, w, F=steady_force(h, mesh(h, 300.0, v)): F),
                       t_end=1e-6)
        first = run.frame().iloc[0]
        y = 300.0
        T_L = G * (h.m_conveyance + h.m_payload + h.q * (h.H_head + y) + RHO * (h.H - y)) + RHO * v * v
        T_E = G * (h.m_conveyance + h.q * (h.H_head + h.H - y) + RHO * y) + RHO * v * v
        assert first["T_L [N]"] == pytest.approx(T_L, rel=1e-8) and first["T_E [N]"] == pytest.approx(T_E, rel=1e-8)
        assert first["a [m/s2]"] == pytest.approx(0.0, abs=1e-9)


@pytest.fixture(scope="module")
def hard_stop():
    """Lowering at 10 m/s, constant-deceleration control at 1.8 m/s² (jerk 0.5 s): the elastic ropes slip and stick
    again several times, and the ropes swing once the wheel is held."""
    h = example_hoist(N=4, arc_rope=False)
    return h, simulate(h, 800.0, -10.0, constant_deceleration(-10.0, 1.8, 0.5), t_end=7.0, rtol=1e-10, atol=1e-10)


def test_energy_balance(hard_stop):
    h, run = hard_stop
    fr = run.frame()
    residual = fr["energy [J]"] - fr["energy [J]"].iloc[0] - fr["W_brake [J]"] + fr["D_damping [J]"] \
        + fr["D_friction [J]"]
    scale = fr["W_brake [J]"].abs().max()
    assert scale > 1e6 and fr["D_friction [J]"].iloc[-1] > 1e3 and fr["D_damping [J]"].iloc[-1] > 1e3
    assert np.all(np.diff(fr["D_friction [J]"]) >= 0) and np.all(np.diff(fr["D_damping [J]"]) >= 0)
    assert residual.abs().max() < 1e-8 * scale


def test_euler_eytelwein_holds_while_slipping(hard_stop):
    """Without the arc's rope, T_high/T_low = e^{μα} exactly while slipping and <= e^{μα} while sticking."""
    h, run = hard_stop
    fr = run.frame()
    assert any(name == "slip toward L" for _, name in run.events)
    ratio = np.maximum(fr["T_L [N]"], fr["T_E [N]"]) / np.minimum(fr["T_L [N]"], fr["T_E [N]"])
    E = math.exp(h.mu * h.alpha)
    assert np.abs(ratio[fr["mode"] != 0] / E - 1).max() < 1e-12
    assert np.all(ratio[fr["mode"] == 0] <= E * (1 + 1e-9))
    slipping = fr[fr["mode"] != 0]
    assert np.all(slipping["v [m/s]"] - slipping["v_w [m/s]"] <= 1e-12)     # the rope runs back toward L


@pytest.mark.slow
def test_convergence_with_the_number_of_nodes():
    """The tangent tension of the loaded side when the wheel stops (a stop at 1.2 m/s² from 6 m/s, lowering):
    the change halves with each doubling of N (first order: the top element's material moves with the wheel)."""
    values = []
    for N in (2, 4, 8, 16, 32):
        wheel = constant_deceleration(-6.0, 1.2, 0.5)
        run = simulate(example_hoist(N=N, reel=20.0), 800.0, -6.0, wheel, t_end=wheel.breakpoints[1],
                       method="LSODA", rtol=1e-9, atol=1e-10)
        values.append(run.frame()["T_L [N]"].iloc[-1])
    steps = np.abs(np.diff(values))
    assert all(1.6 < s1 / s2 < 3.0 for s1, s2 in zip(steps, steps[1:])), steps
    limit = 2 * values[-1] - values[-2]     # first order: the error left is about the last step
    # _koepe_lumped's docstring: 0.3 % at N = 8, 0.07 % at N = 32
    assert round(abs(values[2] / limit - 1), 3) == 0.003 and round(abs(values[4] / limit - 1), 4) == 0.0007


def test_a_brake_and_a_drive_ramp():
    """A constant brake torque stops the hoist (work = the energy it took), and a drive ramp reaches its speed."""
    h = example_hoist(N=2)
    F_0 = steady_force(h, mesh(h, 400.0, 8.0))
    run = simulate(h, 400.0, 8.0, brake(F_0, 2.5e5, 0.4, 8.0), t_end=20.0, stop="rest")
    assert run.events[-1][1] == "rest" and abs(run.y[3, -1]) < 1e-9
    assert run.frame()["W_brake [J]"].iloc[-1] < 0
    start = simulate(replace(h, reel=10.0), 905.0, 0.0, drive_ramp(6.0, 0.8, 0.5), t_end=12.0)
    assert start.y[3, -1] == pytest.approx(6.0, rel=1e-9) and not [e for e in start.events if "slip" in e[1]]


def test_bad_input_names_every_problem():
    with pytest.raises(ValueError) as err:
        Hoist(H=-1.0, H_head=56.7, m_conveyance=0.0, m_payload=0.0, n_head=4, q_head=8.6, EA_head=1e8, mu=0.25,
              alpha=math.pi, R=2.25, J=0.0, N=0)
    assert all(f"{name} = " in str(err.value) for name in ("H", "m_conveyance", "N"))
    with pytest.raises(ValueError) as err:
        simulate(example_hoist(), 1000.0, 0.0, Wheel("torque", lambda t, v: 0.0), t_end=0.0, stop="never")
    assert all(name in str(err.value) for name in ("y_L0", "t_end", "stop", "wheel.kind"))
    with pytest.raises(ValueError, match="reel"):
        mesh(example_hoist(reel=200.0), 800.0)
    h = example_hoist(N=2, reel=1.0)
    with pytest.raises(ValueError, match="raise reel"):
        simulate(h, 800.0, -10.0, constant_deceleration(-10.0, 1.0, 0.5), t_end=20.0)
    assert initial_state(h, mesh(h, 800.0), 2.0)[[1, 3]].tolist() == [2.0, 2.0]
