"""Inverse solves round-trip with the forward model; ill-posed questions are refused by name."""

import math

import pytest

import ropemodel as rm
from ropemodel.cli import main


@pytest.mark.parametrize("given, find", [
    ("dF_up", "G_m"),        # heaviest load a given stroke allows
    ("F_C_up", "L_u"),       # longest route for a given rope force
    ("F_S_up", "F_nwl"),     # pretension for a given unwinding force
    ("F_C_down", "alpha_u"), # nonlinear (sin/cos): Newton
    ("dF_down", "q_lw"),
    ("N_p_up", "v_pj"),
])
def test_round_trip(fig9, given, find):
    forward = rm.run(fig9)
    # perturb the target, solve, and feed the answer back through the forward model
    target = forward[given] * 1.1
    inv = rm.solve(fig9, {given: target}, [find])
    back = rm.run(fig9.with_values({find: inv[find]}))
    assert back[given] == pytest.approx(target, rel=1e-10)
    # unperturbed target gives back the scene's own value
    same = rm.solve(fig9, {given: forward[given]}, [find])
    assert same[find] == pytest.approx(fig9.parameters[find], rel=1e-9)


def test_heaviest_load_for_1000mm_stroke(fig9):
    """Closed form: dF_up = q_lw (F_C_up + F_S_up + F_nwl) (eq. (19)-(23)) with eq. (12)-(13) written out,
    F_C_up + F_S_up = F_nwl + G_m (sin α + μ_pm cos α) + 2 q_l L_u sin α (the ropes' resistances cancel),
    is linear in G_m."""
    p = fig9.parameters
    a = p["alpha_u"]
    rest = p["q_lw"] * (2 * p["F_nwl"] + 2 * p["q_l"] * p["L_u"] * math.sin(a))
    G_max = (1.0 - rest) / (p["q_lw"] * (math.sin(a) + p["mu_pm"] * math.cos(a)))
    assert rm.solve(fig9, {"dF_up": "1000 mm"}, ["G_m"])["G_m"] == pytest.approx(G_max, rel=1e-12)


def test_two_unknowns_two_givens(fig9):
    r = rm.solve(fig9, {"F_C_up": "200 kN", "F_S_up": "35 kN"}, ["G_m", "F_nwl"])
    back = rm.run(fig9.with_values({"G_m": r["G_m"], "F_nwl": r["F_nwl"]}))
    assert back["F_C_up"] == pytest.approx(200e3, rel=1e-12)
    assert back["F_S_up"] == pytest.approx(35e3, rel=1e-12)


def test_over_determined_named(fig9):
    with pytest.raises(rm.IllPosedError, match=r"over-determined: F_C_up given.*--find"):
        rm.solve(fig9, {"F_C_up": 2e5}, [])


def test_under_determined_named(fig9):
    with pytest.raises(rm.IllPosedError, match=r"under-determined.*G_m, L_u"):
        rm.solve(fig9, {"F_C_up": 2e5}, ["G_m", "L_u"])


def test_structurally_singular_pair_named(fig9):
    # F_nwl cannot be found from G_ml: the square count matches but the structure does not
    with pytest.raises(rm.IllPosedError, match=r"G_ml given"):
        rm.solve(fig9, {"G_ml": 1e5}, ["F_nwl"])


def test_solution_outside_valid_range(fig9):
    # a rope force below what the route alone needs asks for a negative load: the answer says the
    # least F_C_up any load gives, the route's own share 0.5 F_nwl + G_l + T_l (eq. 13 with G_m at the least
    # of its domain, 1 mN)
    route_only = 10e3 + 80 * 1150 * (math.sin(math.radians(16)) + 0.05 * math.cos(math.radians(16)))
    with pytest.raises(rm.SolveError, match=rf"F_C_up = 20 kN is out of reach: for G_m in \[1e-06, 1e\+06\] kN, "
                                            rf"F_C_up stays within \[{route_only / 1e3:.6g} kN, .*at G_m = 1e-06 kN"):
        rm.solve(fig9, {"F_C_up": "20 kN"}, ["G_m"])


def test_cli_solve(capsys):
    assert main(["solve", "example", "--given", "dF_up=1000mm", "--find", "G_m", "--json"]) == 0
    assert '"G_m": 252383.09' in capsys.readouterr().out


def test_cli_ill_posed_exit_2(capsys):
    assert main(["solve", "example", "--given", "F_C_up=250kN"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "F_C_up" in err and "Traceback" not in err
