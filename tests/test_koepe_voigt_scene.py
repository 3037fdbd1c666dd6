"""The Koepe scene with Hajduk's lining (``lining = "voigt"``) against eq. (19) solved by brentq here.

Truth (tests/_koepe_truth.py): the traction limit s = T_1/T_2 of eq. (19), ln s + s (T_2/n) C(α) = μα with
C(α) = Q_R (1 − e^{−α/k_R}) + Q_T (1 − e^{−α/k_T}), k = λ v/R, for the wheel's arc and speed (at rest: k = 0,
the lining fully crept); the slip acceleration by brentq on a where the high side reaches what eq. (19) holds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.problem import Problem
from _koepe_truth import (ENDS, HOISTS, ISSUE, crept, hajduk_ratio, manoeuvres, rel, scene, slips, statics,
                                tensions, voigt_slip)

LINING = dict(Q_R=2e-7, lambda_R=0.5, Q_T=1e-7, lambda_T=0.2)
TOL = 1e-11     # brentq to 1e-15 against Newton to rounding; measured: 1.2e-15 (five hoists), 7.4e-14 (500 random)


def limit_at(h, speed):
    """eq. (19)'s traction limit as a function of T_2, at the rope speed ``speed``."""
    R = h["D"] / 2
    C = h["Q_R"] * crept(h["alpha"], h["lambda_R"], speed, R) + h["Q_T"] * crept(h["alpha"], h["lambda_T"], speed, R)
    return lambda T_2: hajduk_ratio(T_2, h["n_head"], h["mu"], h["alpha"], C)


@pytest.mark.parametrize("name", list(HOISTS))
def test_static_traction_is_hajduks_closed_form_for_the_arc_and_speed(name):
    h = dict(HOISTS[name], **LINING)
    r = rm.run(scene(h, lining="voigt"))
    truth = statics(h, limit_at(h, 0.0))
    w = truth["worst"]
    assert rel(r["traction_limit"], limit_at(h, 0.0)(w["T_2"])) < TOL
    assert rel(r["traction_limit_run"], limit_at(h, h["v_max"])(w["T_2"])) < TOL
    for key, want in (("T_1", w["T_1"]), ("T_2", w["T_2"]), ("sigma_static", w["sigma"])):
        assert rel(r[key], want) < TOL, key
    # the creep costs traction: below Euler–Eytelwein at rest, and running gives some of it back
    assert r["traction_limit"] < r["traction_limit_run"] < math.exp(h["mu"] * h["alpha"])


@pytest.mark.parametrize("name", list(HOISTS))
def test_slip_accelerations_on_the_crept_lining(name):
    h = dict(HOISTS[name], **LINING)
    r = rm.run(scene(h, lining="voigt"))
    for m, (a, state) in slips(h, voigt_slip).items():
        assert rel(r[f"a_slip_{m}"], a) < TOL, m
        assert state in r.where[f"a_slip_{m}"]


def test_no_compliance_is_euler_eytelwein():
    """Q = 0: the lining is rigid; without the ropes on the wheel (the Voigt lining leaves them out) the slip limit
    is MODELS.md §5's a = (E F_D − F_U)/(M_U + E M_D) in every end state."""
    h = dict(ISSUE, Q_R=0.0, lambda_R=0.5)
    r = rm.run(scene(h, lining="voigt"))
    E = math.exp(h["mu"] * h["alpha"])
    assert r["traction_limit"] == pytest.approx(E, rel=1e-14)
    for m in ("hoist_accel", "hoist_decel", "lower_accel", "lower_decel"):
        want = min((E * F_D - F_U) / (M_U + E * M_D) for _, f, loaded in ENDS
                   for T_L, T_E in [tensions(h, f * h["H"], loaded)]
                   for F_U, F_D, M_U, M_D in [manoeuvres(h, T_L, T_E, T_L / 9.80665, T_E / 9.80665)[m]])
        assert r[f"a_slip_{m}"] == pytest.approx(want, rel=1e-13), m


def test_the_unrolled_newton_over_a_wide_range():
    """500 random hoists and linings in one compiled model (Problem.evaluate) against brentq: the unrolled Newton
    steps are enough across the usual ranges (compliances 1e-10 to 1e-6 per newton)."""
    rng = np.random.default_rng(25)
    n = 500
    cols = {"m_payload": rng.uniform(2e3, 3e4, n), "m_conveyance": rng.uniform(1e4, 4e4, n),
            "q_head": rng.uniform(3.0, 15.0, n), "mu": rng.uniform(0.15, 0.35, n),
            "Q_R": 10 ** rng.uniform(-10, -6, n), "Q_T": 10 ** rng.uniform(-10, -6, n)}
    out = Problem(scene(dict(ISSUE, **LINING), lining="voigt")).evaluate(cols)
    worst = 0.0
    for i in range(n):
        h = {**ISSUE, **LINING, **{k: float(v[i]) for k, v in cols.items()}}
        for m, (a, _) in slips(h, voigt_slip).items():
            worst = max(worst, rel(out[f"a_slip_{m}"][i], a))
    assert worst < TOL
