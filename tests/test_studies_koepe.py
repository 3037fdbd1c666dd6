"""The Koepe lining study (studies/koepe_lining.py, fast mode) against truths written here.

Truths: the issue-25 hoist's static tensions written out (docs/physics.md §7); MODELS.md §5's rigid slip limit
a = g (e^{μα} T_D − T_U)/(T_U + e^{μα} T_D) for M = T/g; Hajduk's eq. (19), ln(T_U/T_D) + (T_U/n) C(α) = μα
with C = (Q_R + Q_T)(1 − e^{−α/k}), k = λ v/R, Q_R = h/(E R² a), Q_T = μ/(G R a), solved for the acceleration
by brentq; the window's floor max(d_min, (T_L − T_E)/(M_L + M_E)) over the wind.
"""

import math

import numpy as np
import pandas as pd
import pytest
from _studies import load_study
from scipy.optimize import brentq

G = 9.80665
H, H_HEAD, M_C, M_P, N, Q, N_T, Q_T_ROPE = 905.0, 56.7, 29.6e3, 22e3, 4, 8.6, 2, 15.5
MU, ALPHA, R = 0.25, math.pi, 2.25
E_EE = math.exp(MU * ALPHA)
A = math.sqrt(8.6 / 4000.0)        # 6x19 IWRC: W = 0.400 kg/(100 m mm²) (EN 12385-4), the contact width
Y = np.linspace(0.0, H, 3)         # the fast mode's positions of the loaded conveyance


def tensions(y, payload):
    T_L = G * (M_C + payload + N * Q * (H_HEAD + y) + N_T * Q_T_ROPE * (H - y))
    T_E = G * (M_C + N * Q * (H_HEAD + H - y) + N_T * Q_T_ROPE * y)
    return T_L, T_E


def sides(y, payload, direction):
    """(T_U, T_D) of the braking manoeuvre: hoisting, the other side becomes the high one; lowering, the loaded."""
    T_L, T_E = tensions(y, payload)
    return (T_E, T_L) if direction == "hoisting" else (T_L, T_E)


def hajduk_slip(T_U, T_D, E, lam, v):
    """Largest a with ln(T_U/T_D) + (T_U/n) C = μα, T_U = F_U + (F_U/g) a, T_D = F_D − (F_D/g) a, by brentq."""
    G_mod = E / 2.9
    Q_sum = 0.030 / (E * R**2 * A) + MU / (G_mod * R * A)
    k = lam * v / R
    C = Q_sum * (1.0 if k == 0 else -math.expm1(-ALPHA / k))

    def f(a):
        S, S_0 = T_U * (1 + a / G), T_D * (1 - a / G)
        return math.log(S / S_0) + S / N * C - MU * ALPHA
    return brentq(f, -G * 0.999, G * 0.999, xtol=1e-14, rtol=1e-15)


def ceiling(E, lam, v, direction):
    return min(hajduk_slip(*sides(y, p, direction), E, lam, v) for y in Y for p in (M_P, 0.0))


def rigid_ceiling(direction):
    def a(T_U, T_D):
        return G * (E_EE * T_D - T_U) / (T_U + E_EE * T_D)
    return min(a(*sides(y, p, direction)) for y in Y for p in (M_P, 0.0))


def floor(direction):
    if direction == "lowering":
        return 1.5
    coasting = [(T_L - T_E) / ((T_L + T_E) / G) for T_L, T_E in (tensions(y, p) for y in Y for p in (M_P, 0.0))]
    return max(1.5, max(coasting))


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    mod = load_study("koepe_lining")
    out = tmp_path_factory.mktemp("koepe_lining")
    summ = mod.main(out, fast=True)
    return mod, summ, pd.read_csv(out / "koepe_lining_window.csv"), pd.read_csv(out / "koepe_lining.csv"), out


def test_files_written(study):
    *_, out = study
    for name in ("koepe_lining.csv", "koepe_lining_window.csv", "koepe_lining_summary.csv", "koepe_lining.png"):
        assert (out / name).stat().st_size > 0


@pytest.mark.parametrize("direction", ["hoisting", "lowering"])
def test_the_Q_to_0_limit_is_the_rigid_window(study, direction):
    mod, _, window, limits, _ = study
    rigid = window[(window["lining"] == "rigid (Euler–Eytelwein)") & (window["direction"] == direction)]
    assert rigid["high [m/s2]"].to_numpy() == pytest.approx(rigid_ceiling(direction), rel=1e-12, abs=0)
    assert rigid["low [m/s2]"].to_numpy() == pytest.approx(floor(direction), rel=1e-12, abs=0)
    # a compliance 1e-9 of the stiffest lining's: within 1e-12 of the rigid window
    c = mod.cases(3)
    tiny = mod.slip_limits(c, np.array([0.0, 20.0]), 1e-22, 1e-22, 0.1)[mod.BRAKING[direction]].min(axis=0)
    assert tiny == pytest.approx(rigid_ceiling(direction), rel=1e-12, abs=0)


@pytest.mark.parametrize("label, E, lam, v, direction", [
    ("K25-class, 920 MPa", 920e6, 0.35, 10.0, "lowering"), ("PU 42 Shore D, 90 MPa", 90e6, 0.1, 0.0, "hoisting"),
    ("rubber 65 Shore A, 5 MPa", 5e6, 3.0, 5.0, "lowering")])
def test_window_edge_is_hajduks_closed_form(study, label, E, lam, v, direction):
    _, _, window, _, _ = study
    row = window[(window["lining"] == label) & (window["lambda [s]"] == lam) & (window["v [m/s]"] == v)
                 & (window["direction"] == direction)]
    assert len(row) == 1
    assert row["high [m/s2]"].iloc[0] == pytest.approx(ceiling(E, lam, v, direction), rel=1e-10)
    assert bool(row["open"].iloc[0]) == (ceiling(E, lam, v, direction) >= floor(direction))


def test_the_lining_only_takes_and_speed_gives_back(study):
    _, _, window, limits, _ = study
    lined = limits[limits["lining"] != "rigid (Euler–Eytelwein)"]
    assert (lined["a_slip [m/s2]"] <= lined["rigid [m/s2]"] * (1 + 1e-12)).all()
    for _, g in lined.groupby(["lining", "lambda [s]", "manoeuvre"]):
        assert np.all(np.diff(g["a_slip [m/s2]"].to_numpy()) >= -1e-12)     # less creep at speed
    rest = lined[lined["v [m/s]"] == 0.0].groupby(["manoeuvre", "E [Pa]"])["a_slip [m/s2]"].first().unstack()
    assert (rest.diff(axis=1).iloc[:, 1:] > 0).all().all()                   # stiffer lining, larger limit


def test_claims(study):
    """The numbers studies/README.md states, each against the closed form here."""
    _, summ, _, _, _ = study
    s = summ.set_index(["lining", "direction"])
    low_share = s.loc[("K25-class, 920 MPa", "lowering"), "share taken at rest [-]"]
    soft_share = s.loc[("PU 42 Shore D, 90 MPa", "lowering"), "share taken at rest [-]"]
    for got, E in ((low_share, 920e6), (soft_share, 90e6)):
        want = (rigid_ceiling("lowering") - ceiling(E, 1.0, 0.0, "lowering")) / (rigid_ceiling("lowering") - 1.5)
        assert got == pytest.approx(want, rel=1e-9)
    assert round(100 * low_share, 1) == 1.5 and round(100 * soft_share, 1) == 15.5
    assert round(rigid_ceiling("lowering"), 2) == 2.10
    fast = s.loc[("K25-class, 920 MPa", "lowering"), "share taken at 20 m/s, lambda 0.35 s [-]"]
    assert fast == pytest.approx((rigid_ceiling("lowering") - ceiling(920e6, 0.35, 20.0, "lowering"))
                                 / (rigid_ceiling("lowering") - 1.5), rel=1e-9)
    assert round(100 * fast, 2) == 0.97
    assert s.loc[("rubber 65 Shore A, 5 MPa", "lowering"), "share taken at rest [-]"] > 1.0
    # the window closes at rest below E_c: the ceiling there meets the floor
    for direction, claim in (("lowering", 13.5e6), ("hoisting", 3.3e6)):
        E_c = s.loc[("K25-class, 920 MPa", direction), "E closing the window at rest [Pa]"]
        assert ceiling(E_c, 1.0, 0.0, direction) == pytest.approx(floor(direction), rel=1e-9)
        assert round(E_c, -5) == claim
        if direction == "lowering":
            assert round(90e6 / E_c, 1) == 6.7
    # rubber, λ = 3 s: the lowering window opens above 5.07 m/s
    v_open = s.loc[("rubber 65 Shore A, 5 MPa", "lowering"), "empty below [m/s], lambda 3 s"]
    assert ceiling(5e6, 3.0, v_open, "lowering") == pytest.approx(1.5, rel=1e-9)
    assert round(v_open, 2) == 5.07
    # with λ inside Hajduk's assumption the rubber's lowering window stays shut to 20 m/s; polymer liners never shut
    assert s.loc[("rubber 65 Shore A, 5 MPa", "lowering"), "empty below [m/s], lambda 0.35 s"] == math.inf
    polymer = summ[summ["lining"] != "rubber 65 Shore A, 5 MPa"]
    assert (polymer.filter(like="empty below") == 0.0).all().all()
