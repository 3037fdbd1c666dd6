"""The route step (ropemodel.papers.route_tables): tables once per route, then the numbers at each place of the load,
in numpy and in CasADi MX, against two independent truths: a brute force over every joint written out here, and the
library's float loops of ropemodel.papers.route (3 segments and the 10 000-point profile of studies/route_scale.py)."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from _studies import load_study

from ropemodel.papers import route as rt
from ropemodel.papers import route_tables as tb

G = 9.80665
MU_PL, A_H, F_END, Q_L = 0.05, 0.4, 20e3, 80.0
WAYS = (("up", 1.0), ("down", -1.0))


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
    """Every number of one place by loops over the joints (docs/physics.md §4), the least winding tension too."""
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
            "B": B, "least": min(cands), "load": load, "S": min(H[1:n]) if n > 1 else min(H[0], H[n])}


def _mx(L, alpha, mu, places):
    """at_places on MX: the route's values and the places as symbols, evaluated once."""
    n, N = len(L), len(places)
    Ls, As, Ms, X, J = (ca.MX.sym(k, m) for k, m in (("L", n), ("a", n), ("mu", n), ("x", N), ("J", N)))
    for_each = {}
    t = tb.tables(Ls, As, Ms, MU_PL, A_H)
    p = tb.at_places(t, X)
    for way, _ in WAYS:
        for_each[f"least_{way}"] = tb.least_winding_tension(p, way, F_END, Q_L, J)
    names = [k for k in p] + list(for_each) + [f"S_{w}" for w, _ in WAYS]
    f = ca.Function("f", [Ls, As, Ms, X, J], [*p.values(), *for_each.values(), t["S_up"], t["S_down"]])
    return f, names


def _functions(L, alpha, mu, places, loads, way):
    """The named Functions (tables_function, places_function), their outputs as numpy, the least from them."""
    T = tb.tables_function(len(L))
    t = T(L=L, alpha=alpha, mu=mu, mu_pl=MU_PL, a_h=A_H)
    p = tb.places_function(len(L), len(places))(**{"t_" + k: v for k, v in t.items()}, x_m=places)
    got = {k: np.array(v).ravel() for k, v in p.items()}
    got[f"least_{way}"] = np.asarray(tb.least_winding_tension(got, way, F_END, Q_L, loads))
    return got


@pytest.mark.parametrize("n, seed", [(1, 0), (2, 1), (3, 2), (7, 3), (25, 4)])
def test_numbers_at_every_place_equal_a_brute_force_over_the_joints(n, seed):
    L, alpha, mu = _route(seed, n)
    places = _places(L)
    t = tb.tables(L, alpha, mu, MU_PL, A_H)
    p = tb.at_places(t, places)
    f, names = _mx(L, alpha, mu, places)
    for way, s in WAYS:
        truth = [_brute(L, alpha, mu, x, s) for x in places]
        loads = np.array([b["load"] for b in truth])
        least = np.asarray(tb.least_winding_tension(p, way, F_END, Q_L, loads))
        got_mx = dict(zip(names, (np.array(v).ravel() for v in f(L, alpha, mu, places, loads))))
        named = _functions(L, alpha, mu, places, loads, way)
        for got in (dict(p, **{f"least_{way}": least}), got_mx, named):
            for i, b in enumerate(truth):
                assert int(got["j"][i]) == b["j"] and bool(got["before"][i]) == b["before"]
                assert bool(got["beyond"][i]) == b["beyond"] and bool(got["joints"][i]) == (n > 1)
                assert bool(got["inside0"][i]) == (b["x"] > 0.0) and bool(got["insideL"][i]) == (b["x"] < sum(L))
                checks = [("x", b["x"]), ("sin", b["sin"]), ("cos", b["cos"]), (f"B_{way}", b["B"]),
                          (f"least_{way}", b["least"])]
                checks += [(f"P_{way}", b["P"])] if b["before"] else []
                checks += [(f"Q_{way}", b["Q"])] if b["beyond"] else []
                for key, want in checks:
                    assert abs(float(got[key][i]) - want) <= 1e-12 * max(1.0, abs(want)), (way, key, places[i])
        assert abs(float(t[f"S_{way}"]) - truth[0]["S"]) <= 1e-12 * max(1.0, abs(truth[0]["S"]))
        assert abs(float(got_mx[f"S_{way}"][0]) - truth[0]["S"]) <= 1e-12 * max(1.0, abs(truth[0]["S"]))


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
            "S": rt.least_rope_tension(0.0, 1.0, L, unwind, between=True), "G": rt.tension_at_joints(0.0, 1.0, L, wind)}


@pytest.mark.parametrize("points", [4, pytest.param(10_000, marks=pytest.mark.slow)])   # 10 000: the loops' 7 s
def test_tables_and_places_equal_the_float_loops_of_the_segment_form(points):
    L, alpha, mu = _profile_route(points)
    ends = np.cumsum(L)
    pick = np.unique(np.linspace(0, L.size - 1, min(L.size, 4)).astype(int))
    places = np.concatenate([[0.0], ends[pick], (ends - 0.5 * L)[pick], [ends[-1] + 1.0]])
    t = tb.tables(L, alpha, mu, MU_PL, A_H)
    p = tb.at_places(t, places)
    f, names = _mx(L, alpha, mu, places)
    close = lambda got, want: abs(float(got) - want) <= 1e-12 * max(1.0, abs(want))   # noqa: E731
    sums = {"sum_sin": rt.rope_weight_along_route(1.0, list(L), list(alpha)),
            "sum_mucos": rt.rope_resistance_along_route(1.0, list(L), list(alpha), list(mu)),
            "sum_cos": rt.rope_resistance_along_route(1.0, list(L), list(alpha), [1.0] * L.size),
            "L_u": rt.route_length(list(L))}
    assert all(close(t[k], v) for k, v in sums.items())
    for way, s in WAYS:
        lib = [_library(L, alpha, mu, x, s) for x in places]
        loads = np.array([b["load"] for b in lib])
        got_mx = dict(zip(names, (np.array(v).ravel() for v in f(L, alpha, mu, places, loads))))
        got_np = dict(p, **{f"least_{way}": np.asarray(tb.least_winding_tension(p, way, F_END, Q_L, loads))})
        assert np.max(np.abs(t[f"G_{way}"] - lib[0]["G"]) / np.maximum(1.0, np.abs(lib[0]["G"]))) <= 1e-12
        assert close(t[f"S_{way}"], lib[0]["S"]) and close(got_mx[f"S_{way}"][0], lib[0]["S"])
        for got in (got_np, got_mx):
            for i, b in enumerate(lib):
                for key, want in (("sin", b["sin"]), ("cos", b["cos"]), (f"B_{way}", b["B"]),
                                  (f"least_{way}", b["least"])):
                    assert close(got[key][i], want), (points, way, key, places[i], float(got[key][i]), want)
