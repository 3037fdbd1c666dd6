"""The drive's power, signed (four-quadrant): Fig. 9 by hand, η on the right side of each sign, the
sign named wherever the power is shown, and the symbolic form safe on both sides.

Truth: Krauze et al. (2025) eq. (1)-(13) written out here for case 1 (μ_pl1 = μ_pl2 = μ_pl) with the
inputs of Fig. 9, and the force balance on the drum (docs/physics.md §1): P_drum = s (F_C − F_S) v_pj,
N_p = P_drum/η motoring, P_drum·η braking.
"""

from __future__ import annotations

import json
import math

import casadi as ca
import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.papers import krauze2025 as kr


def _fig9_drum_power():
    """P_drum [W] up and down for Fig. 9: eq. (12)-(13) by hand, s = +1 up, −1 down."""
    L_u, alpha, mu, G_m, F_nwl, v, q_l = 1150.0, math.radians(16.0), 0.05, 467e3, 20e3, 2.5, 80.0
    rope = q_l * L_u * math.sin(alpha)                       # G_l = G_ls, eq. (2)-(6)
    T_l = mu * q_l * L_u * math.cos(alpha)                   # T_l = T_ls, eq. (8)-(11), case 1
    T_m = mu * G_m * math.cos(alpha)                         # eq. (7)
    out = {}
    for d, s in (("up", 1.0), ("down", -1.0)):
        F_S = 0.5 * F_nwl + rope - s * T_l                   # eq. (12)
        F_C = 0.5 * F_nwl + G_m * math.sin(alpha) + rope + s * (T_m + T_l)   # eq. (13), (14)
        out[d] = s * (F_C - F_S) * v
    return out


def test_fig9_drive_power_is_signed(fig9):
    P = _fig9_drum_power()
    assert round(P["down"] / 1e3, 3) == -243.584 and round(P["up"] / 1e3, 3) == 400.029
    r = rm.run(fig9)                 # eta = 1: the drive's power is the drum's
    for d in ("up", "down"):
        assert r[f"P_drum_{d}"] == pytest.approx(P[d], rel=1e-12)
        assert r[f"N_p_{d}"] == pytest.approx(P[d], rel=1e-12)


@pytest.mark.parametrize("eta", [0.8, 0.5])
def test_efficiency_divides_motoring_and_multiplies_braking(fig9, eta):
    P = _fig9_drum_power()
    r = rm.run(fig9.with_values({"eta": eta}))
    assert r["N_p_up"] == pytest.approx(P["up"] / eta, rel=1e-12)      # motoring: the losses come on top
    assert r["N_p_down"] == pytest.approx(P["down"] * eta, rel=1e-12)  # braking: the losses are taken off
    assert r["P_drum_down"] == pytest.approx(P["down"], rel=1e-12)     # the drum's power does not see η
    if eta == 0.8:   # the README's figures
        assert (round(r["N_p_up"] / 1e3, 3), round(r["N_p_down"] / 1e3, 3)) == (500.037, -194.867)


def test_a_gentle_slope_motors_both_ways(fig9):
    """On 1° the load's weight along the slope is less than its resistance: lowering, the drive motors (a
    pretension of 60 kN keeps the winding rope taut)."""
    r = rm.run(fig9.with_values({"alpha_u": "1 deg", "eta": 0.8, "F_nwl": "60 kN"}))
    s, v = -1.0, 2.5
    P = s * (r["F_C_down"] - r["F_S_down"]) * v
    assert P > 0 and r["N_p_down"] == pytest.approx(P / 0.8, rel=1e-12)


def test_the_run_table_names_each_sign(capsys):
    assert main(["run"]) == 0
    lines = capsys.readouterr().out.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith("N_p "))
    assert float(lines[i].split()[1]) == pytest.approx(-243.584, abs=5e-4)
    assert lines[i + 1].split() == ["braking", "motoring"]       # under down, under up
    assert main(["run", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["N_p_down"] == pytest.approx(_fig9_drum_power()["down"], rel=1e-12)


def test_size_names_the_sign_of_its_power(capsys):
    assert main(["size", "winch_sizing_fig9"]) == 0
    out = capsys.readouterr().out
    up = next(line for line in out.splitlines() if line.startswith("N_p_up"))
    down = next(line for line in out.splitlines() if line.startswith("N_p_down"))
    assert up.split()[3] == "motoring" and float(up.split()[1]) > 0          # N_p_up  605.1  kW  motoring (at …)
    assert down.split()[3] == "braking" and float(down.split()[1]) < 0


def test_the_symbolic_drive_power_is_safe_on_both_sides():
    """max(P, 0)/η + min(P, 0)·η evaluates no branch that could fail: finite values and derivatives for
    either sign, and at P = 0, for every η in (0, 1]."""
    P, eta = ca.SX.sym("P"), ca.SX.sym("eta")
    N = kr.drive_power(P, eta)
    f = ca.Function("f", [P, eta], [N, ca.jacobian(N, ca.vertcat(P, eta))])
    for p in (-3e5, 0.0, 4e5):
        for e in (1e-12, 0.5, 1.0):
            value, grad = (np.array(x, dtype=float) for x in f(p, e))
            expected = p / e if p > 0 else p * e
            assert np.all(np.isfinite(value)) and np.all(np.isfinite(grad))
            assert value.item() == pytest.approx(expected, rel=1e-15, abs=0.0)
    # and on arrays as on floats
    assert np.array_equal(kr.drive_power(np.array([-2.0, 0.0, 2.0]), 0.5), [-1.0, 0.0, 4.0])
