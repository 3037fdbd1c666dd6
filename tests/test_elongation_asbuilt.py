"""The stroke as built (``elongation = "asbuilt"``, issue 24 item 2) against an independent integration.

Truth: each rope side's tension written out here in numpy on a fine grid of the three-segment route of
``tests/_route3.py`` (from 0.5 F_nwl at the return sheave, growing by the rope's weight and resistance per
metre toward the drive and, on the winding side, by the load's weight and resistance at x_m), integrated by
the trapezoidal rule on a grid through every joint and x_m (exact for a piecewise-linear profile), divided by
EA = E C d² typed from the catalogue's factor.  The constructional stretch is the rope makers' table typed
here (fibre core 0.25/0.5/0.75 %, steel core 0.125/0.25/0.5 % at safety factors 8/5/3), the reeving 1/n.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

import ropemodel as rm
import _route3

G = 9.80665
SEGMENTS = [(600.0, 12.0), (700.0, 20.0), (500.0, 6.0)]          # (length m, inclination deg), from the drive
E, C_IWRC, W_IWRC = 100e9, 0.460, 0.409 / (100 * 1e-6)          # rope_E; EN 12385-4 6x36-IWRC C, W [kg/m^3]
D, F_NWL, G_M, MU = 0.036, 24.7e3, 300e3, 0.05
POSITIONS = (150.0, 600.0, 950.0, 1450.0, 1800.0)                # x_m [m]; 600 m is a joint (segment 1's)


def scene(x_m=None, **params):
    d = tomllib.loads(_route3.SCENE + _route3.DESIGN)
    d["effects"]["elongation"] = "asbuilt"
    if x_m is not None:
        d["parameters"]["x_m"] = f"{x_m} m"
    d["parameters"].update(params)
    return d


def run(d):
    d["parameters"].pop("t_ramp", None)      # a trip's ramp: not read by a static run
    return rm.run(rm.from_dict(d))


def profile_integrals(x_m, sign, n=20001):
    """(∫T_C dx, ∫T_S dx) [N m] of the direction ``sign`` (+1 up), by the trapezoidal rule in numpy."""
    ends = np.cumsum([s[0] for s in SEGMENTS])
    L_u = ends[-1]
    x = np.unique(np.concatenate([np.linspace(0.0, L_u, n), ends, [0.0, x_m]]))
    mid = 0.5 * (x[1:] + x[:-1])                      # the grid runs through every joint: each mid in one segment
    alpha = np.radians([s[1] for s in SEGMENTS])[np.searchsorted(ends, mid)]
    q_l = G * W_IWRC * D**2
    w_C = q_l * (np.sin(alpha) + sign * MU * np.cos(alpha))                      # N/m, per grid interval
    w_S = q_l * (np.sin(alpha) - sign * MU * np.cos(alpha))
    j = min(np.searchsorted(ends, x_m, side="left"), len(SEGMENTS) - 1)         # on a joint: the drive's side
    a_j = math.radians(SEGMENTS[j][1])
    jump = G_M * (math.sin(a_j) + sign * MU * math.cos(a_j))

    def from_sheave(w):      # T(x) = T(L_u) + ∫_x^{L_u} w ds: exact at the nodes, linear between them
        rise = np.concatenate([[0.0], np.cumsum(w * np.diff(x))])
        return 0.5 * F_NWL + rise[-1] - rise

    # the winding side's step at x_m (x_m a node): the load's force over [0, x_m]
    return np.trapezoid(from_sheave(w_C), x) + jump * x_m, np.trapezoid(from_sheave(w_S), x)


@pytest.mark.parametrize("x_m", POSITIONS)
def test_profile_matches_numpy_integration(x_m):
    r = run(scene(x_m))
    EA = E * C_IWRC * D**2
    assert r["EA"] == pytest.approx(EA, rel=1e-12)
    for way, sign in (("up", 1), ("down", -1)):
        int_C, int_S = profile_integrals(x_m, sign)
        assert r[f"dF_C_{way}"] == pytest.approx(int_C / EA, rel=1e-9)
        assert r[f"dF_S_{way}"] == pytest.approx(int_S / EA, rel=1e-9)
        eps = 0.0025                                   # steel core at n_rope = 5: 0.25 % (table)
        loop = 2 * 1800.0
        assert r[f"dF_{way}"] == pytest.approx((int_C + int_S) / EA + eps * loop, rel=1e-9)


def test_profile_is_below_eq19_bound():
    """Eq. (19)-(20) load the whole side with its drive-end force: an upper bound of the profile's elongation."""
    r = run(scene(1800.0))
    for way in ("up", "down"):
        assert r[f"dF_C_{way}"] < r["q_lw"] * r[f"F_C_{way}"]
        assert r[f"dF_S_{way}"] < r["q_lw"] * r[f"F_S_{way}"]


def test_reeving_divides_the_take_up():
    one, two = run(scene(950.0)), run(scene(950.0, n_falls=2))
    for way in ("up", "down"):
        assert two[f"dF_{way}"] == pytest.approx(one[f"dF_{way}"] / 2, rel=1e-13)


@pytest.mark.parametrize(("construction", "n_rope", "eps"), [
    ("6x36-IWRC", 5, 0.0025), ("6x36-IWRC", 8, 0.00125), ("6x36-IWRC", 3, 0.005), ("6x36-FC", 5, 0.005),
    ("6x36-FC", 10, 0.0025),                                             # beyond the table: 'lightly loaded'
    ("6x36-IWRC", 4, 0.0025 + 0.0025 * (1 / 4 - 1 / 5) / (1 / 3 - 1 / 5)),   # linear in 1/n between rows
])
def test_constructional_stretch_adds_its_closed_form(construction, n_rope, eps):
    d = scene(950.0, n_rope=n_rope, n_falls=2)
    d["effects"]["rope"] = construction
    new, run_in = run(d), run({**d, "parameters": {**d["parameters"], "c_stretch": 0.0}})
    assert new["eps_c"] == pytest.approx(eps, rel=1e-12)
    for way in ("up", "down"):
        assert new[f"dF_{way}"] - run_in[f"dF_{way}"] == pytest.approx(eps * 2 * 1800.0 / 2, rel=1e-9)


def test_temperature_adds_thermal_expansion():
    cold, warm = run(scene(950.0)), run(scene(950.0, dT_rope="20 K"))
    assert warm["dF_up"] - cold["dF_up"] == pytest.approx(12.5e-6 * 20 * 3600.0, rel=1e-9)


def test_pretension_alone_is_eq22():
    r = run(scene(950.0))
    assert r["dF_nwl"] == pytest.approx(F_NWL * 1800.0 / (E * C_IWRC * D**2), rel=1e-12)


def test_sizing_takes_the_stroke_as_built():
    """IPOPT sizes with the variant: the stroke it recommends is the closed form's at the design it chose
    (Fig. 9 route, straight: ∫T_C = T_0 L + w_C L²/2 + J L, ∫T_S = T_0 L + w_S L²/2; a movable return sheave)."""
    from importlib import resources

    from optimisation.design import size

    d = tomllib.loads(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml").read_text())
    d["effects"]["elongation"] = "asbuilt"
    d["parameters"]["n_falls"] = 2
    design = size(rm.from_dict(d))
    assert design.feasible and any(a.split(" @ ")[0] == "stroke_margin_up" for a in design.active)   # load at L
    dd, F = design.design["d"], design.design["F_nwl"]
    q, EA, L, a = G * W_IWRC * dd**2, E * C_IWRC * dd**2, 1150.0, math.radians(16.0)
    w_C, w_S = q * (math.sin(a) + MU * math.cos(a)), q * (math.sin(a) - MU * math.cos(a))
    J = 467e3 * (math.sin(a) + MU * math.cos(a))
    eps = 0.0025 + 0.0025 * (1 / 4.5 - 1 / 5) / (1 / 3 - 1 / 5)          # steel core at n_rope = 4.5
    stroke = ((F * L + (w_C + w_S) * L**2 / 2 + J * L) / EA + eps * 2 * L) / 2
    assert 0.0 <= design.design["stroke"] - stroke < 1e-3                # rounded up to the next mm
