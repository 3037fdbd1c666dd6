"""The slowest free oscillation of the rope loop (``ropemodel.dynamics.smooth.slowest_period``), which sets how
long dynamic sizing follows a manoeuvre by default.

Truths: closed-form natural frequencies of one- and two-degree-of-freedom spring-mass systems written out
here (the cases of ``tests/test_dynamics.py``'s fitted frequencies), in steady motion (a stop starts from
it: the resistances saturated, so they add no damping).
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.dynamics.smooth import slowest_period

G_N = 9.80665


def scene(effects, params):
    d = tomllib.loads(resources.files("ropemodel.data").joinpath("winch_start.toml").read_text())
    d["effects"].update({"dynamics": "stop", "rope_elasticity": "spring", "tensioner": "fixed", **effects})
    d["parameters"].update(params)
    d["parameters"] = {k: v for k, v in d["parameters"].items() if v is not None}
    return rm.from_dict(d, bare="si")


def test_one_mass_between_two_damped_springs():
    """The load at the return sheave, one element per span, a fixed tensioner, the rope fixed to the drum: one
    mass m = G_m/g + q_l L_u/(2g) between two springs k = EA/L_u with dampers c = τk to the drum,
    λ = −c/m ± i·sqrt(2k/m − (c/m)²)."""
    sc = scene({"lining": "none"}, {"x_m": "1150 m", "F_nwl": "150 kN", "mu_d": None, "alpha_d": None})
    v = sc.parameters
    m = (v["G_m"] + v["q_l"] * v["L_u"] / 2) / G_N
    k = (v["L_u"] / v["q_lw"]) / v["L_u"]
    c = v["rope_damping"] * k
    assert slowest_period(sc) == pytest.approx(2 * math.pi / math.sqrt(2 * k / m - (c / m) ** 2), rel=1e-9)


def test_two_masses_the_slower_mode():
    """The load at 700 m, no damping: the rope on the return sheave and the load, det(K − ω² M) = 0; the
    slower of the two modes."""
    sc = scene({}, {"rope_damping": 0.0, "x_m": "700 m", "F_nwl": "80 kN"})
    v = sc.parameters
    EA = v["L_u"] / v["q_lw"]
    k_S, k_2, k_1 = EA / v["L_u"], EA / (v["L_u"] - v["x_m"]), EA / v["x_m"]
    m_rope = v["q_l"] / G_N
    M = np.diag([m_rope * (v["L_u"] + (v["L_u"] - v["x_m"])) / 2, v["G_m"] / G_N + m_rope * v["L_u"] / 2])
    K = np.array([[k_S + k_2, -k_2], [-k_2, k_1 + k_2]])
    a, b, c = M[0, 0] * M[1, 1], -(K[0, 0] * M[1, 1] + K[1, 1] * M[0, 0]), K[0, 0] * K[1, 1] - K[0, 1] ** 2
    w_slow = math.sqrt((-b - math.sqrt(b * b - 4 * a * c)) / (2 * a))
    assert slowest_period(sc) == pytest.approx(2 * math.pi / w_slow, rel=1e-9)


def test_an_inextensible_rope_does_not_oscillate():
    assert slowest_period(scene({"rope_elasticity": "rigid", "tensioner": "constant_force"}, {})) is None
