"""The least tension along each rope side (docs/physics.md §4) against a brute-force evaluation of the tension
at many points along the route, written in numpy (tests/_route_truth.py): on a route with a dip and on a
gentle slope lowered, in steady motion, in a start and in a stop; then its worst over every place of the load.

The library's F_*_least is the least over the whole side, the drum and the return sheave included; the least
between the ends (``between=True``) with the drum's forces and F_nwl/2 gives the same number.
"""

from __future__ import annotations


import numpy as np
import pytest
from _route_truth import Route, places

import ropemodel as rm
from ropemodel.papers import route as rt

V, T_RAMP = 2.5, 5.0
A = V / T_RAMP           # the linear ramp's acceleration [m/s^2]

#: from the drive: down 8° for 500 m, up 3° for 400 m, down 5° for 300 m: the unwinding rope hauling up is
#: least at the bottom of the dip (x = 500 m), neither at the drum nor at the return sheave
DIP = Route((500.0, 400.0, 300.0), (8.0, -3.0, 5.0), (0.05, 0.05, 0.05), G_m=200e3, q_l=60.0, F_nwl=80e3)
#: a gentle slope beyond a steep one at the drive, lowered: on the 1° segment the winding rope's tension falls
#: toward the drive, and the load's resistance (and a start's inertia) pulls it lower on the load's drive side
GENTLE = Route((300.0, 1000.0), (10.0, 1.0), (0.05, 0.05), G_m=200e3, q_l=60.0, F_nwl=55e3)


def scene(route: Route, **params):
    segments = [{"length": f"{L} m", "inclination": f"{a} deg", "mu_winding": m}
                for L, a, m in zip(route.lengths, route.degrees, route.mus)]
    base = {"G_m": f"{route.G_m} N", "q_l": f"{route.q_l} N/m", "F_nwl": f"{route.F_nwl} N", "mu_pm": route.mu_pm,
            "mu_pl": route.mu_pl, "q_lw": "5.8 mm/kN", "d": "30 mm", "F_min": "700 kN", "D": "1 m", "n_rope": 5,
            "v_pj": f"{V} m/s", "t_ramp": f"{T_RAMP} s"}
    return rm.from_dict({"effects": {"route": "segments", "checks": "design", "dynamics": "trip", "inertia": "rigid",
                                     "rope_elasticity": "rigid"},
                         "route": segments, "parameters": {**base, **params}}, emit=False)


def _places(route):
    return [float(x) for x in (0.0, *route.ends, *(route.ends - 1.0), 0.37 * route.L_u)]


@pytest.mark.parametrize("route, direction", [(DIP, "up"), (DIP, "down"), (GENTLE, "down"), (GENTLE, "up")])
@pytest.mark.parametrize("a", [0.0, A, -A], ids=["steady", "start", "stop"])
def test_least_tension_along_each_side_is_the_brute_force_least(route, direction, a):
    s = 1.0 if direction == "up" else -1.0
    for x_m in _places(route):
        r = rm.run(scene(route, x_m=f"{x_m!r} m", a_h=f"{a!r} m/s^2"))
        assert not hasattr(r, "envelope")                      # one point: the place and the manoeuvre given
        truths = []
        for side, name in (("unwinding", "F_S_least"), ("winding", "F_C_least")):
            truth = route.least(side, x_m, a, s)
            truths.append(truth)
            assert r[f"{name}_{direction}"] == pytest.approx(truth, rel=1e-12, abs=1e-6), (side, x_m)
        F_C, F_S = route.drum(x_m, a, s)                        # and the drum's forces, eq. (12)-(13)
        assert r[f"F_C_{direction}"] == pytest.approx(F_C, rel=1e-12)
        assert r[f"F_S_{direction}"] == pytest.approx(F_S, rel=1e-12)
        assert r[f"route_margin_{direction}"] == pytest.approx(min(truths), rel=1e-12, abs=1e-6)   # F_S_min = 0
        # the least between the ends, with the drum's forces and the return sheave's, covers the whole side
        mus = [m for m in route.mus]
        wind = [rt.rope_gradient(al, m, s, a) for al, m in zip(route.alphas, mus)]
        unwind = [rt.rope_gradient(al, route.mu_pl, -s, a) for al in route.alphas]
        between = min(rt.least_rope_tension(0.5 * route.F_nwl, route.q_l, list(route.lengths), unwind, between=True),
                      rt.least_rope_tension(0.5 * route.F_nwl, route.q_l, list(route.lengths), wind, x_m,
                                            route.pull(x_m, a, s), between=True))
        assert min(between, F_C, F_S, 0.5 * route.F_nwl) == pytest.approx(min(truths), rel=1e-12, abs=1e-6)


def test_the_dip_is_least_inside_the_route():
    """The case the check exists for: the unwinding rope hauling up is least at the bottom of the dip, 1.7 kN
    below both the drum's F_S and the return sheave's F_nwl/2."""
    r = rm.run(scene(DIP, x_m="100 m", a_h="0 m/s^2"))
    x = np.union1d(np.linspace(0.0, DIP.L_u, 100001), DIP.ends)
    T = DIP.tension(x, "unwinding", 100.0, 0.0, 1.0)
    assert x[np.argmin(T)] == pytest.approx(500.0, abs=0.1)               # the joint at the bottom
    assert r["F_S_least_up"] == pytest.approx(T.min(), rel=1e-9)
    assert T.min() < min(r["F_S_up"], 0.5 * DIP.F_nwl) - 1.7e3
    assert r["route_margin_up"] == pytest.approx(T.min(), rel=1e-9)       # F_S_min = 0
    assert r["sheave_margin"] == pytest.approx(0.5 * DIP.F_nwl, rel=1e-15)


def test_a_lowering_start_on_a_gentle_slope_slackens_the_winding_rope_inside_the_route():
    """Lowering starts with the load on the 1° segment: its pull J = G_m (sin 1° − μ_pm cos 1° − a/g) < 0, the
    rope's tension falls from the load toward the drive along the 1° segment and rises again on the 10° one:
    least at their joint (300 m), 1.3 kN below the drum's F_C."""
    x_m = 1000.0
    r = rm.run(scene(GENTLE, x_m=f"{x_m} m", a_h=f"{A} m/s^2"))
    assert GENTLE.pull(x_m, A, -1.0) < 0
    x = np.union1d(np.linspace(0.0, GENTLE.L_u, 100001), GENTLE.ends)
    T = GENTLE.tension(x, "winding", x_m, A, -1.0)
    assert x[np.argmin(T)] == pytest.approx(300.0, abs=0.1)
    assert r["F_C_least_down"] == pytest.approx(T.min(), rel=1e-12)
    assert r["F_C_least_down"] < r["F_C_down"] - 1.3e3


@pytest.mark.parametrize("route, direction", [(DIP, "up"), (GENTLE, "down")])
def test_the_worst_least_tension_over_every_place_and_manoeuvre(route, direction):
    """Without x_m and a_h: the least tension's worst over the places and the manoeuvres (steady, start, stop)
    equals the brute-force worst over 200 places (and both sides of every joint) and the three accelerations."""
    s = 1.0 if direction == "up" else -1.0
    r = rm.run(scene(route))
    for side, name in (("unwinding", "F_S_least"), ("winding", "F_C_least")):
        truth = min(route.least(side, float(x), a, s, n=2001) for a in (0.0, A, -A) for x in places(route, 200))
        assert r[f"{name}_{direction}"] == pytest.approx(truth, rel=1e-9, abs=1e-5), side
    assert r.where[f"F_C_least_{direction}"]                   # and it says where


def test_sizing_keeps_the_least_tension_everywhere():
    """Sizing the dip route with a grippy drum (no slip to set the pretension) and F_S_min = 1 kN: the least
    tension sets F_nwl.  At the recommended design the brute-force least tension of both sides, at every place
    and manoeuvre, is F_S_min up to the pretension's rounding to 0.1 kN (half of it on each side); 0.2 kN less
    pretension would leave it below."""
    from optimisation.design import size

    sized = rm.from_dict({"effects": {"route": "segments", "rope": "6x36-IWRC", "lining": "rigid"},
                          "route": [{"length": f"{L} m", "inclination": f"{a} deg"}
                                    for L, a in zip(DIP.lengths, DIP.degrees)],
                          "parameters": {"G_m": "200 kN", "mu_pm": 0.05, "mu_pl": 0.05, "rope_grade": "1770 N/mm^2",
                                         "rope_E": "100 kN/mm^2", "mu_d": 0.6, "alpha_d": "720 deg", "n_rope": 5,
                                         "F_S_min": "1 kN", "v_pj": f"{V} m/s", "t_ramp": f"{T_RAMP} s"}},
                         optional=("d", "F_nwl", "stroke", "D"), emit=False)
    design = size(sized, with_sensitivities=False)
    assert design.feasible
    d, F_nwl = design.design["d"], design.design["F_nwl"]

    def least(F):
        route = DIP.with_(q_l=9.80665 * 4090.0 * d * d, F_nwl=F)
        return min(route.least(side, float(x), a, s, n=2001) for side in ("winding", "unwinding")
                   for s in (1.0, -1.0) for a in (0.0, A, -A) for x in places(route, 60))

    assert 1e3 - 1e-6 <= least(F_nwl) <= 1e3 + 50.0
    assert least(F_nwl - 200.0) < 1e3
    assert design.margins["sheave_margin"] >= 0
