"""Sizing with the Voigt drum lining inside the NLP (Hajduk 1992 traction) against a hand search."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from test_sizing import Hand, optimum_at_steps

from optimisation import SizingProblem
from optimisation.ipopt import solve_continuous
from ropemodel.scene import load

SCENE = "winch_sizing_voigt"
G = 9.80665
K, W, C = 0.356, 4090.0, 0.460        # 6x36-IWRC, EN 12385-4


def traction(mu, alpha, q, k):
    """s from ln s + q s (1 - exp(-alpha/k)) = mu alpha (Hajduk 1992 eq. 19, isotropic), by bracketing."""
    c = q * (1 - math.exp(-alpha / k))
    return brentq(lambda s: math.log(s) + c * s - mu * alpha, 1e-300, math.exp(mu * alpha), xtol=1e-300,
                  rtol=1e-15)


class HandVoigt(Hand):
    """The hand search of test_sizing with Hajduk's traction in place of Euler-Eytelwein."""

    def __init__(self, P):
        self.P = P
        self.k = P["lambda"] * 2 * P["v_pj"] / P["D"]

    def F_lo(self, d):
        P = self.P
        need = 0.0
        for s, c in self.parts(d).values():
            need = max(need, 2 * (P["F_S_min"] - s))

            def phi(F, s=s, c=c):      # held minus needed: F_S traction(Q F_S) - n_slip F_C
                F_S = 0.5 * F + s
                return F_S * traction(P["mu_d"], P["alpha_d"], P["Q"] * F_S, self.k) - P["n_slip"] * (0.5 * F + c)

            F = 0.0
            while phi(F) < 0:          # the held force rises, then saturates at mu alpha / Q: first root
                F += 1e3
                assert F < 5e6, "no pretension holds the rope"
            lo = brentq(phi, max(F - 1e3, 0.0), F, xtol=1e-9, rtol=1e-15) if F > 0 else 0.0
            need = max(need, lo)
        return need

    def safety(self, d):
        F = self.F_lo(d)
        F_min = K * d * d * self.P["rope_grade"]
        return min(F_min / (self.P["n_rope"] * (0.5 * F + c)) - 1 for _, c in self.parts(d).values())


def test_voigt_optimum_equals_one_dimensional_search():
    scene = load(SCENE)
    problem = SizingProblem(scene)
    sol = solve_continuous(problem)
    assert sol.success and sol.lexicographic_ok
    got = problem.to_si(sol.xs)
    hand = HandVoigt(scene.parameters)
    d_star = brentq(hand.safety, 0.02, 0.08, xtol=1e-14, rtol=1e-14)
    assert got["d"] == pytest.approx(d_star, rel=1e-6)
    assert got["F_nwl"] == pytest.approx(hand.F_lo(d_star), rel=1e-6)
    assert "slip_margin_up" in sol.active
    # the lining matters here: Euler-Eytelwein (Q = 0) would need a smaller pretension at this d
    P = dict(scene.parameters)
    s, c = hand.parts(d_star)["up"]
    r = math.exp(P["mu_d"] * P["alpha_d"])
    assert 2 * (P["n_slip"] * c - r * s) / (r - P["n_slip"]) < 0.9 * got["F_nwl"]
    assert np.all(sol.g >= -1e-10)


def test_voigt_sensitivities_match_finite_differences():
    """KKT sensitivities through the lining's implicit traction (rootfinder inside the NLP)."""
    from optimisation.sensitivity import sensitivities

    problem = SizingProblem(load(SCENE))
    sol = solve_continuous(problem)
    sens = sensitivities(problem, sol)
    x_star = problem.to_si(sol.xs)
    for name in ("Q", "lambda", "mu_d", "G_m", "n_rope"):
        j = problem.params.index(name)
        h = 1e-5 * abs(problem.p0[j])
        xs = optimum_at_steps(problem, sol, j, h)
        for v in ("d", "F_nwl", "stroke"):
            fd = (xs[0][v] - xs[1][v]) / (2 * h)
            if name == "lambda":
                # k = lambda omega = 0.03 rad against a 3 pi wrap: exp(-alpha_d/k) ~ e^-300, no effect
                assert fd == 0.0 and abs(sens[name][v]) * problem.p0[j] / x_star[v] < 1e-12
                continue
            assert abs(fd) * abs(problem.p0[j]) / abs(x_star[v]) > 1e-6      # every one of these matters
            assert sens[name][v] == pytest.approx(fd, rel=3e-9), (name, v)   # as tests/test_sizing.py argues
