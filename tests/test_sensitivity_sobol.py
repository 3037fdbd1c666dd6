"""Sobol indices against analytic values: the Ishigami function and a linear scene output."""

import json
import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main as cli
from ropemodel.sensitivities import sobol, sobol_indices

pytest.importorskip("SALib")


def ishigami_indices(a, b):
    """Analytic first-order and total indices of the Ishigami function, x_i ~ U(-pi, pi)
    (Ishigami & Homma 1990; Sobol' & Levitan 1999): V1 = (1 + b pi^4/5)^2 / 2, V2 = a^2/8,
    V13 = b^2 pi^8 (1/18 - 1/50), V = V1 + V2 + V13."""
    pi = math.pi
    V1 = 0.5 * (1 + b * pi ** 4 / 5) ** 2
    V2 = a ** 2 / 8
    V13 = b ** 2 * pi ** 8 * (1 / 18 - 1 / 50)
    V = V1 + V2 + V13
    return {"x1": (V1 / V, (V1 + V13) / V), "x2": (V2 / V, V2 / V), "x3": (0.0, V13 / V)}


def test_ishigami_indices_are_reproduced():
    a, b = 7.0, 0.1

    def f(c):
        return {"y": np.sin(c["x1"]) + a * np.sin(c["x2"]) ** 2 + b * c["x3"] ** 4 * np.sin(c["x1"])}

    res = sobol_indices(f, {k: (-math.pi, math.pi) for k in ("x1", "x2", "x3")}, n=2 ** 13, seed=3)
    exact = ishigami_indices(a, b)
    assert exact["x1"][0] == pytest.approx(0.3139, abs=1e-4)  # the published values
    assert exact["x3"][1] == pytest.approx(0.2437, abs=1e-4)
    for r in res.itertuples():
        s1, st = exact[r.parameter]
        # within the estimator's own 95 % bootstrap interval (doubled: the bootstrap under-covers at the tails)
        assert abs(r.S1 - s1) <= 2 * r.S1_conf, (r.parameter, r.S1, s1, r.S1_conf)
        assert abs(r.ST - st) <= 2 * r.ST_conf, (r.parameter, r.ST, st, r.ST_conf)
        assert r.S1_conf < 0.05 and r.ST_conf < 0.05


def test_linear_scene_output_has_analytic_indices(fig9):
    """F_C_up (eq. 13, upward) is linear in G_m and F_nwl: S_i = c_i^2 Var_i / sum, ST_i = S_i."""
    p = fig9.parameters
    a = p["alpha_u"]
    c = {"G_m": math.sin(a) + p["mu_pm"] * math.cos(a), "F_nwl": 0.5}
    ranges = {"G_m": (300e3, 500e3), "F_nwl": (10e3, 90e3)}
    var = {k: c[k] ** 2 * (hi - lo) ** 2 / 12 for k, (lo, hi) in ranges.items()}
    res = sobol(fig9, {"G_m": "300kN:500kN", "F_nwl": (10e3, 90e3)}, outputs=["F_C_up", "mu_pl1"], n=2 ** 12)
    for r in res[res["output"] == "F_C_up"].itertuples():
        exact = var[r.parameter] / sum(var.values())
        assert abs(r.S1 - exact) <= 2 * r.S1_conf and abs(r.ST - exact) <= 2 * r.ST_conf
        assert r.S1_conf < 0.05 and r.ST_conf < 0.05     # the interval is small enough to tell
    const = res[res["output"] == "mu_pl1"]
    assert not const["defined"].any() and const["S1"].isna().all()
    assert (const["note"] == "output does not vary over the ranges").all()


def test_bad_ranges_are_refused(fig9):
    with pytest.raises(rm.InputError, match="low < high"):
        sobol(fig9, {"G_m": "500kN:300kN"})
    with pytest.raises(rm.InputError, match=r"alpha_u \(high end of its range\) = 100 deg is outside the valid range"):
        sobol(fig9, {"alpha_u": "10deg:100deg"}, n=8)
    with pytest.raises(rm.InputError, match="not an input"):
        sobol(fig9, {"F_C_up": "1:2"})


def test_cli_sobol_json(fig9, capsys):
    """The command line gives the indices of the API (the built-in example, the same ranges, samples and
    seed): each range reaches its own parameter, in SI."""
    assert cli(["sensitivity", "--sobol", "G_m=300kN:500kN", "--sobol", "alpha_u=10deg:20deg",
                "--outputs", "F_C_up", "--samples", "64", "--json"]) == 0
    rows = {r["parameter"]: r for r in json.loads(capsys.readouterr().out)}
    api = sobol(fig9, {"G_m": (300e3, 500e3), "alpha_u": (math.radians(10), math.radians(20))}, outputs=["F_C_up"],
                n=64, seed=0).set_index("parameter")
    assert set(rows) == {"G_m", "alpha_u"}
    for k, r in rows.items():
        for col in ("S1", "ST"):
            assert r[col] == pytest.approx(api.loc[k, col], rel=1e-9, abs=1e-12), (k, col)
    assert cli(["sensitivity", "--sobol", "G_m=300kN"]) == 2
