"""The route step (ropemodel.papers.route_numbers): a route's suffix sums once, then the numbers at each place of the
load, and the least tensions the model forms from them (ropemodel.effects.winch_route_vector), against two
independent truths: a brute force over every joint written out here, and the library's float loops of
ropemodel.papers.route (3 segments and the 10 000-point profile of studies/route_scale.py)."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from _studies import load_study

from ropemodel.effects import winch_route_vector as wv
from ropemodel.papers import route as rt
from ropemodel.papers import route_numbers as rn

G = 9.80665
MU_PL, A_H, F_END, Q_L = 0.05, 0.4, 20e3, 80.0


def _route(seed: int, n: int):
    rng = np.random.default_rng(seed)
    L = rng.uniform(5.0, 400.0, n)
    if n > 2:
        L[1] = L[0]                                    # equal lengths: joints at exact multiples
    return L, np.radians(rng.uniform(-20.0, 20.0, n)), rng.uniform(0.02, 0.1, n)


def _places(L):
    """The drive, every joint, just before and after each, the middles, the return sheave and beyond it."""
    ends = np.cumsum(L)
    mids = ends - 0.5 * L
    return np.concatenate([[0.0, 1e-9], ends, np.nextafter(ends, 0.0), np.nextafter(ends, np.inf), mids,
                           [ends[-1] + 5.0, 2.0 * ends[-1]]])


def _brute(L, alpha, mu, x, s):
    """Every number of one place by loops over the joints (docs/physics.md §4), the least winding tension too
    (between the ends and over the whole side)."""
    n = len(L)
    xk = [sum(L[:k]) for k in range(n + 1)]                            # x_0 … x_n
    g = [math.sin(a) + s * (m * math.cos(a) + A_H / G) for a, m in zip(alpha, mu)]
    G_ = [sum(L[i] * g[i] for i in range(k, n)) for k in range(n + 1)]   # G_k = Σ_{i>k} L_i g_i (1-based i)
    x = min(x, xk[n])
    j = next((i for i in range(n) if x <= xk[i + 1]), n - 1)
    before = [G_[k] for k in range(1, n) if xk[k] < x]
    beyond = [G_[k] for k in range(1, n) if xk[k] >= x]
    B = sum(g[i] * max(min(xk[i + 1], xk[n]) - max(xk[i], x), 0.0) for i in range(n))
    load = 467e3 * (math.sin(alpha[j]) + s * (0.05 * math.cos(alpha[j]) + A_H / G))
    cands = [F_END + Q_L * G_[k] + (load if xk[k] < x else 0.0) for k in range(1, n)]
    cands += [F_END + Q_L * B + (load if x > 0.0 else 0.0), F_END + Q_L * B + (load if x >= xk[n] else 0.0)]
    H = [sum(L[i] * (math.sin(alpha[i]) - s * (MU_PL * math.cos(alpha[i]) + A_H / G)) for i in range(k, n))
         for k in range(n + 1)]
    return {"j": j, "x": x, "sin": math.sin(alpha[j]), "cos": math.cos(alpha[j]), "before": bool(before),
            "beyond": bool(beyond), "P": min(before) if before else None, "Q": min(beyond) if beyond else None,
            "B": B, "least": min(cands), "whole": min(cands + [F_END + Q_L * G_[0] + load, F_END]), "load": load,
            "S": min(H[1:n]) if n > 1 else min(H[0], H[n]), "S_whole": min(H)}


def _numbers(L, alpha, mu, places):
    """The route numbers at ``places``, every segment giving its own μ (numpy), with the route's totals."""
    sums = rn.route_sums(L, alpha, mu, np.ones(len(L), dtype=bool))
    whole = {"route_L_u": sums["ends"][-1], "route_sin": sums["A"][0], "route_mo": sums["mo"][0],
             "route_cp": sums["cp"][0], "route_cos": sums["C"][0]}
    return sums, rn.places(sums, places, A_H, MU_PL), whole


def _at(got, whole, i, x):
    """The model's values of place ``i`` (the route numbers as :func:`wv.least_winding` reads them)."""
    return {**whole, **{f"route_{k}": float(np.ravel(v)[i]) for k, v in got.items()}, "x_m": float(x), "mu_pl": MU_PL}


def _rise(v, prefix, way, s):
    c = {k: v[f"route_{prefix}_{k}_{way}"] for k in rn.WINDING}
    return c["A"] + s * (c["mo"] + MU_PL * c["cp"]) + s * (A_H / G) * c["X"]


def _beside(v, s):
    """The winding rise beside the load from its coefficients, linear in x on the load's segment."""
    x = min(v["x_m"], v["route_L_u"])
    return ((v["route_B_A"] - v["route_sin_j"] * x) + s * ((v["route_B_mo"] - v["route_mo_j"] * x)
            + MU_PL * (v["route_B_cp"] - v["route_cp_j"] * x)) + s * (A_H / G) * (v["route_L_u"] - x))


def _close(got, want):
    return abs(float(got) - want) <= 1e-12 * max(1.0, abs(want))


@pytest.mark.parametrize("n, seed", [(1, 0), (2, 1), (3, 2), (7, 3), (25, 4)])
def test_numbers_at_every_place_equal_a_brute_force_over_the_joints(n, seed):
    L, alpha, mu = _route(seed, n)
    places = _places(L)
    _, got, whole = _numbers(L, alpha, mu, places)
    for way, s in rn.WAYS:
        for i, x in enumerate(places):
            b = _brute(L, alpha, mu, float(x), s)
            v = _at(got, whole, i, x)
            assert int(got["j"][i]) == b["j"] and bool(v["route_before"]) == b["before"], (way, x)
            assert bool(v["route_beyond"]) == b["beyond"], (way, x)
            checks = [("sin", v["route_sin_j"], b["sin"]), ("cos", v["route_cos_j"], b["cos"]),
                      ("B", _beside(v, s), b["B"]),
                      ("least", wv.least_winding(v, way, s, A_H, F_END, Q_L, b["load"], True), b["least"]),
                      ("whole", wv.least_winding(v, way, s, A_H, F_END, Q_L, b["load"]), b["whole"]),
                      ("S", (wv.least_unwinding(v, way, s, A_H, F_END, Q_L, True) - F_END) / Q_L, b["S"]),
                      ("S_whole", (wv.least_unwinding(v, way, s, A_H, F_END, Q_L) - F_END) / Q_L, b["S_whole"])]
            checks += [("P", _rise(v, "P", way, s), b["P"])] if b["before"] else []
            checks += [("Q", _rise(v, "Q", way, s), b["Q"])] if b["beyond"] else []
            for key, value, want in checks:
                assert _close(value, want), (way, key, x, float(value), want)


@pytest.mark.parametrize("n, seed", [(1, 0), (3, 2), (7, 3)])
def test_the_numbers_as_expressions_of_the_segments_equal_the_numbers(n, seed):
    """:func:`rn.through` (the numbers as CasADi expressions of the segments' values, at the indices chosen at the
    case: what a sensitivity in a segment's value reads) equals :func:`rn.places` at every place."""
    L, alpha, mu = _route(seed, n)
    places = _places(L)
    own = np.ones(n, dtype=bool)
    _, got, _ = _numbers(L, alpha, mu, places)
    for i in range(places.size):
        at = {k: np.ravel(v)[i] for k, v in got.items()}
        expr = rn.through(ca.DM(L), ca.DM(alpha), ca.DM(mu), own, at)
        for k, value in expr.items():
            assert _close(float(value), float(at[k])), (k, places[i])


def _profile_route(points: int):
    x, h = load_study("route_scale").profile(points)
    dx, dh = np.diff(x), np.diff(h)
    L = np.hypot(dx, dh)
    return L, np.arctan2(-dh, dx), 0.05 + 0.01 * np.sin(np.arange(L.size))     # varied μ: a wrong index shows


def _library(L, alpha, mu, x, s):
    """The same numbers from ropemodel.papers.route's float loops (lists of floats)."""
    L, alpha, mu = list(L), list(alpha), list(mu)
    wind = [rt.rope_gradient(a, m, s, A_H) for a, m in zip(alpha, mu)]
    unwind = [rt.rope_gradient(a, MU_PL, -s, A_H) for a in alpha]
    a_j = rt.at_position(x, L, alpha)
    load = rt.load_pull(467e3 * math.sin(a_j), 0.05 * 467e3 * math.cos(a_j), 467e3, s, A_H)
    return {"sin": math.sin(a_j), "cos": math.cos(a_j), "B": rt.rope_tension(min(x, sum(L)), 0.0, 1.0, L, wind),
            "least": rt.least_rope_tension(F_END, Q_L, L, wind, x, load, between=True), "load": load,
            "whole": rt.least_rope_tension(F_END, Q_L, L, wind, x, load),
            "S": rt.least_rope_tension(0.0, 1.0, L, unwind, between=True), "G": rt.tension_at_joints(0.0, 1.0, L, wind)}


@pytest.mark.parametrize("points", [4, pytest.param(10_000, marks=pytest.mark.slow)])   # 10 000: the loops' 7 s
def test_the_numbers_equal_the_float_loops_of_the_segment_form(points):
    L, alpha, mu = _profile_route(points)
    ends = np.cumsum(L)
    pick = np.unique(np.linspace(0, L.size - 1, min(L.size, 4)).astype(int))
    places = np.concatenate([[0.0], ends[pick], (ends - 0.5 * L)[pick], [ends[-1] + 1.0]])
    sums, got, whole = _numbers(L, alpha, mu, places)
    totals = {"route_sin": rt.rope_weight_along_route(1.0, list(L), list(alpha)),
              "route_mo": rt.rope_resistance_along_route(1.0, list(L), list(alpha), list(mu)),
              "route_cos": rt.rope_resistance_along_route(1.0, list(L), list(alpha), [1.0] * L.size),
              "route_L_u": rt.route_length(list(L))}
    assert all(_close(whole[k], v) for k, v in totals.items())
    for way, s in rn.WAYS:
        lib = [_library(L, alpha, mu, float(x), s) for x in places]
        G_ = rn.rises(sums, s, A_H, MU_PL)[0]
        assert np.max(np.abs(G_ - lib[0]["G"]) / np.maximum(1.0, np.abs(lib[0]["G"]))) <= 1e-12
        for i, b in enumerate(lib):
            v = _at(got, whole, i, places[i])
            assert _close((wv.least_unwinding(v, way, s, A_H, F_END, Q_L, True) - F_END) / Q_L, b["S"])
            for key, value, want in (("sin", v["route_sin_j"], b["sin"]), ("cos", v["route_cos_j"], b["cos"]),
                                     ("B", _beside(v, s), b["B"]),
                                     ("least", wv.least_winding(v, way, s, A_H, F_END, Q_L, b["load"], True),
                                      b["least"]),
                                     ("whole", wv.least_winding(v, way, s, A_H, F_END, Q_L, b["load"]), b["whole"])):
                assert _close(value, want), (points, way, key, places[i], float(value), want)
