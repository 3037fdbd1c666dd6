"""Krauze et al. (2025): the paper's Fig. 9 worked example, case 2 by hand, equation functions.

Reference values: Krauze, Mucha, Wydro, Klempka (2025), Fig. 9, as tabulated in
shared/docs/physics.md §1 (kN for forces, mm for elongations, printed to 0.01).
"""

import json
import math
import subprocess
import sys

import casadi as ca
import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.papers import krauze2025 as kr

# Fig. 9 of Krauze et al. (2025): name -> (value, unit)
FIG9 = {
    "G_ml": 128.72, "G_l1": 14.33, "G_l2": 11.03, "G_l": 25.36, "G_mo": 448.91, "G_ls": 25.36,
    "T_m": 22.45, "T_l1": 2.50, "T_l2": 1.92, "T_l": 4.42, "T_ls": 4.42, "G_lmC": 154.08,
    "F_S_down": 39.78, "F_S_up": 30.94, "F_C_down": 137.21, "F_C_up": 190.95,
    "dF_C_down": 795.84, "dF_C_up": 1107.50, "dF_S_down": 230.73, "dF_S_up": 179.43,
    "dF_CS_down": 1026.57, "dF_CS_up": 1286.94, "dF_nwl": 116.00,
    "dF_down": 1142.57, "dF_up": 1402.94,
}
SCALE = {n: (1e-3 if not n.startswith("dF") else 1e3) for n in FIG9}  # SI -> kN or mm


def _check_fig9(values_si):
    assert len(FIG9) == 25
    for name, printed in FIG9.items():
        shown = values_si[name] * SCALE[name]
        # every printed digit: within half a unit of the last printed place (0.005)
        assert abs(shown - printed) <= 0.005 + 1e-9, (name, shown, printed)


def test_fig9_api(fig9):
    _check_fig9(rm.run(fig9).values)


def test_fig9_cli_json(capsys):
    assert main(["run", "--json"]) == 0
    _check_fig9(json.loads(capsys.readouterr().out))


def test_fig9_console_script():
    """The installed console script, as a user runs it."""
    out = subprocess.run([sys.executable, "-m", "ropemodel", "run", "--json"], capture_output=True, text=True,
                         check=True).stdout
    _check_fig9(json.loads(out))


def test_fig9_stroke_shortfall(fig9):
    # the paper's conclusion: the installed 1000 mm stroke is 403 mm short (upward travel)
    assert round(rm.run(fig9)["dF_up"] * 1e3 - 1000.0) == 403


def test_series_has_units(fig9):
    s = rm.run(fig9).to_series()
    assert s["F_C_up [kN]"] == pytest.approx(190.9485, abs=1e-4)
    assert s["dF_up [mm]"] == pytest.approx(1402.935, abs=1e-3)
    assert s["alpha_u [deg]"] == pytest.approx(16.0)


def test_drive_power_by_hand(fig9):
    # signed: P_drum = s (F_C - F_S) v_pj (s = -1 lowering); N_p = P_drum/eta motoring, P_drum eta braking;
    # eta = 1 in the example scene (tests/test_trip_power.py writes eq. (12)-(13) out by hand)
    r = rm.run(fig9)
    for d, s in (("up", 1.0), ("down", -1.0)):
        assert r[f"N_p_{d}"] == pytest.approx(s * (r[f"F_C_{d}"] - r[f"F_S_{d}"]) * 2.5, rel=1e-14)
    r2 = rm.run(fig9.with_values({"eta": 0.8}))
    assert r2["N_p_up"] == pytest.approx(r["N_p_up"] / 0.8, rel=1e-14)
    assert r2["N_p_down"] == pytest.approx(r["N_p_down"] * 0.8, rel=1e-14)


CASE2 = """
[scene]
name = "case 2"
[effects]
resistance = "case2"
[parameters]
L_u = "800 m"
L_ul = "300 m"
alpha_u = "12 deg"
mu_pm = 0.04
mu_pl = 0.06
mu_pl1 = 0.03
mu_pl2 = 0.09
G_m = "300 kN"
F_nwl = "15 kN"
q_l = "0.06 kN/m"
q_lw = "4 mm/kN"
"""


def test_case2_by_hand():
    """Case 2 (eq. 17-18, first line of 18) evaluated by hand, kN and m."""
    r = rm.run(rm.from_toml(CASE2))
    a = math.radians(12)
    s, c = math.sin(a), math.cos(a)
    T_l = 0.06 * c * (0.03 * (800 - 300) + 0.09 * 300)          # eq. (17)
    G_lmC = (300 + 0.06 * 800) * s                                # eq. (14)
    F_C_up = 0.5 * 15 + G_lmC + 300 * 0.04 * c + T_l              # eq. (18), first line, upward
    F_C_down = 0.5 * 15 + G_lmC - 300 * 0.04 * c - T_l
    F_S_up = 0.5 * 15 + 0.06 * 800 * (s - 0.06 * c)               # eq. (12), upward
    F_S_down = 0.5 * 15 + 0.06 * 800 * (s + 0.06 * c)
    assert r["T_l"] == pytest.approx(T_l * 1e3, rel=1e-13)
    assert r["F_C_up"] == pytest.approx(F_C_up * 1e3, rel=1e-13)
    assert r["F_C_down"] == pytest.approx(F_C_down * 1e3, rel=1e-13)
    assert r["F_S_up"] == pytest.approx(F_S_up * 1e3, rel=1e-13)
    assert r["F_S_down"] == pytest.approx(F_S_down * 1e3, rel=1e-13)
    assert r["dF_up"] == pytest.approx(4e-3 * (F_C_up + F_S_up + 15), rel=1e-13)  # eq. (19)-(23), mm/kN * kN -> m


def test_case2_equal_coefficients_is_case1(fig9):
    p = {k: v for k, v in fig9.parameters.items() if k not in ("v_pj", "eta")}
    c2 = rm.from_dict({"effects": {"resistance": "case2"},
                       "parameters": {**p, "mu_pl1": p["mu_pl"], "mu_pl2": p["mu_pl"]}}, bare="si")
    r1, r2 = rm.run(fig9), rm.run(c2)
    for n in ("F_C_up", "F_C_down", "F_S_up", "dF_up"):
        assert r2[n] == pytest.approx(r1[n], rel=1e-14)


def test_equation_functions_on_scalars_arrays_symbols():
    """One function per equation: same numbers from floats, numpy arrays and CasADi symbols."""
    a = np.radians([0.0, 16.0, 30.0])
    G = 467e3
    arr = kr.load_weight_along_incline(G, a)
    assert arr.shape == (3,)
    assert arr[1] == pytest.approx(128.72e3, abs=5)                    # Fig. 9: G_ml = 128.72 kN
    assert kr.load_weight_along_incline(G, float(a[2])) == pytest.approx(G / 2, rel=1e-14)  # sin 30° = 1/2
    x = ca.SX.sym("x")
    f = ca.Function("f", [x], [kr.load_weight_along_incline(G, x)])
    assert float(f(a[1])) == pytest.approx(arr[1], rel=1e-15)
    # directions: F_C(up) - F_C(down) = 2 (T_m + T_l), F_S(down) - F_S(up) = 2 T_ls
    assert kr.winding_rope_force(20, 100, 3, 4, kr.UP) - kr.winding_rope_force(20, 100, 3, 4, kr.DOWN) == 14
    assert kr.unwinding_rope_force(20, 10, 2, kr.DOWN) - kr.unwinding_rope_force(20, 10, 2, kr.UP) == 4


def test_horizontal_route_limit(fig9):
    """alpha_u = 0: no weight components, forces are pretension ± resistances only.

    With the paper's 20 kN pretension the winding rope would have to push when lowering
    (F_C_down = 10 - 23.35 - 4.6 kN < 0): that is a slack rope, refused; 60 kN keeps every rope taut."""
    with pytest.raises(rm.SolveError, match=r"F_C_down = -17.95 kN: the winding rope would have to push "
                                            r"\(downward travel\).*F_nwl > 55.9 kN"):
        rm.run(fig9.with_values({"alpha_u": 0.0}))
    r = rm.run(fig9.with_values({"alpha_u": 0.0, "F_nwl": 60e3}))
    assert r["G_lmC"] == 0.0
    assert r["F_C_up"] == pytest.approx(30e3 + 0.05 * 467e3 + 0.05 * 80 * 1150, rel=1e-14)
    assert r["F_S_up"] == pytest.approx(30e3 - 0.05 * 80 * 1150, rel=1e-14)
    assert r["F_C_down"] == pytest.approx(30e3 - 0.05 * 467e3 - 0.05 * 80 * 1150, rel=1e-14)
