"""The S-curve ramp (``ramp = "scurve"``, the example of CONTRIBUTING.md) against Newton's law.

Truth: the jerk-limited drive written here in time (jerk +J, 0, −J; t_j from a_max (t_ramp − t_j) =
v_pj, a_max = J t_j), integrated by scipy, and an inextensible rope: F_C = F_nwl/2 + G_lmC
+ (T_m + T_l)·tanh(v/v_eps) + (G_m + q_l L_u)/g · a (Krauze et al. eq. (13) plus the moving mass).
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import ropemodel as rm
from ropemodel.dynamics import simulate

G_N = 9.80665            # standard gravity [m/s²]
SCENE = resources.files("ropemodel.data").joinpath("winch_start.toml")


def scurve_scene(jerk="1 m/s^3", **params):
    d = tomllib.loads(SCENE.read_text())
    d["effects"].update({"ramp": "scurve", "rope_elasticity": "rigid"})
    d["parameters"].update({"jerk_max": jerk, "t_end": "8 s", **params})
    d["numerics"]["sim_rtol"] = 1e-10
    return rm.from_dict(d, bare="si")


def drive(J, v_pj, T):
    """Speed and acceleration of the jerk-limited drive, integrated from its jerk by scipy (piece by piece:
    the jerk steps at t_j and T − t_j)."""
    t_j = (T - math.sqrt(T * T - 4 * v_pj / J)) / 2           # J t_j (T − t_j) = v_pj
    pieces, y = [], [0.0, 0.0]                                 # y = [a, v]
    for t0, t1, jerk in ((0.0, t_j, J), (t_j, T - t_j, 0.0), (T - t_j, T, -J)):
        sol = solve_ivp(lambda t, y, j=jerk: [j, y[0]], (t0, t1), y, method="DOP853", rtol=1e-13, atol=1e-15,
                        dense_output=True)
        pieces.append((t1, sol.sol))
        y = sol.y[:, -1]

    def state(t):
        t = np.minimum(np.asarray(t, float), T)
        out = np.zeros((2,) + t.shape)
        for t1, f in reversed(pieces):
            out = np.where(t <= t1, f(t), out)
        return out

    return lambda t: state(t)[1], lambda t: state(t)[0] * (np.asarray(t) < T)


def test_scurve_start_is_newtons_law():
    sc = scurve_scene()
    v, st = sc.parameters, rm.run(sc)
    h = simulate(sc).history
    speed, acc = drive(v["jerk_max"], v["v_pj"], v["t_ramp"])
    t = h["t [s]"].to_numpy()
    ramp = (t > 0.5) & (t < v["t_ramp"])      # from 0.5 s the speed is > 2 v_eps: the resistance is not at its
                                              # steepest, where the rope's speed carries the integrator's atol
    assert speed(v["t_ramp"]) == pytest.approx(v["v_pj"], rel=1e-12)           # the truth reaches v_pj
    np.testing.assert_allclose(h["v_drum [m/s]"], speed(t), rtol=1e-9, atol=1e-12)
    m_C = (v["G_m"] + v["q_l"] * v["L_u"]) / G_N
    F_C = (v["F_nwl"] / 2 + st["G_lmC"] + (st["T_m"] + st["T_l"]) * np.tanh(speed(t) / v["v_eps"])
           + m_C * acc(t))
    err = np.abs(h["F_C [N]"] - F_C) / F_C
    assert err[ramp].max() < 1e-10                                              # measured: 3e-16
    np.testing.assert_allclose(h["F_C [N]"][t > v["t_ramp"]], st["F_C_up"], rtol=1e-10)
    # the peak is the inextensible rope's at the largest acceleration a_max = J t_j
    assert h["F_C [N]"].max() == pytest.approx(st["F_C_up"] + m_C * float(np.max(acc(t))), rel=1e-6)


def test_scurve_needs_enough_jerk():
    with pytest.raises(rm.InputError, match="jerk_max >= 4 v_pj/t_ramp"):
        scurve_scene(jerk="0.3 m/s^3")          # 4 v_pj/t_ramp² = 0.4 m/s³
    with pytest.raises(rm.InputError, match="jerk_max"):
        d = tomllib.loads(SCENE.read_text())
        d["effects"]["ramp"] = "scurve"          # required by the variant
        rm.from_dict(d, bare="si")
