"""Dynamic sizing of the three-segment route of issue 21 with an inextensible rope (``rope_elasticity = "rigid"``,
as the shipped ``route_segments`` has it), from a scene with no transient in it (slow: one sizing ~1 CPU-min).

Truth, written out here in numpy: Newton's second law for an inextensible rope loop on the route.  The route's
static forces (docs/physics.md §4: the paper's eq. (12)-(13) summed over the segments, the load's weight and
resistance on its own segment) with the catalogue rope's weight q_l = W d² g (EN 12385-4); in a linear ramp of
acceleration a = v_pj / t_ramp every mass moves with the drum, so the drive side carries the load and the winding
rope, F_C = F_C,static + (G_m + q_l L)/g · a, and the slack side loses F_S = F_S,static − q_l L/g · a; at rest
the simulator's regularised friction vanishes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import _route3 as route3

from optimisation.dynamic import size_dynamic
from optimisation.problem import load_sizing
from ropemodel.papers import en12385

pytestmark = [pytest.mark.slow, pytest.mark.exhaustive]     # minutes each: not in CI (CONTRIBUTING, "Test tiers")

G_N = 9.80665                                           # standard gravity [m/s²]
#: the route from the drive: length [m], inclination [deg] (no segment gives its own friction: mu_pl on each)
SEGMENTS = [(600.0, 12.0), (700.0, 20.0), (500.0, 6.0)]
G_M, V, T_RAMP, MU_PM, MU_PL, W = 300e3, 3.0, 4.0, 0.05, 0.05, en12385.construction("6x36-IWRC").W


@pytest.fixture(scope="module")
def design(tmp_path_factory):
    path = tmp_path_factory.mktemp("rigid") / "route3_rigid.toml"
    path.write_text(route3.SCENE.replace('power = "drive"\n', 'power = "drive"\nrope_elasticity = "rigid"\n'),
                    encoding="utf-8")
    return size_dynamic(load_sizing(path, emit=False))


def static_forces(x, d, F_nwl, s=1.0):
    """F_C, F_S [N] with the load at x [m] (a load on a joint: the segment nearer the drive), rope d [m],
    pretension F_nwl [N]: in steady upward motion (s = 1), or at rest (s = 0: the simulator's regularised
    friction, tanh(v / v_eps), vanishes there)."""
    L, a = np.array([seg[0] for seg in SEGMENTS]), np.radians([seg[1] for seg in SEGMENTS])
    q_l = W * d**2 * G_N
    j = int(np.searchsorted(np.cumsum(L), x, side="left"))
    weight = q_l * np.sum(L * np.sin(a))
    F_S = 0.5 * F_nwl + weight - s * MU_PL * q_l * np.sum(L * np.cos(a))
    F_C = 0.5 * F_nwl + weight + G_M * math.sin(a[j]) + s * (MU_PM * G_M * math.cos(a[j]) + MU_PL * q_l * np.sum(
        L * np.cos(a)))
    return F_C, F_S


def test_a_catalogue_design_is_found_and_verified(design):
    assert design.feasible
    assert design.design["d"] in en12385.diameters() and design.design["d"] >= design.continuous["d"]
    assert design.continuous["d"] >= design.static["d"]
    assert design.transient["rope_elasticity"][0] == "rigid"
    assert all(m["ok"] for m in design.manoeuvres)


def test_upward_start_and_stop_peaks_are_newtons_law_at_every_place(design):
    """Every one of the nine places of the load: the upward start's peak F_C and least F_S are the steady
    forces plus and minus the moving masses times v_pj / t_ramp.  A stop decelerates from t = 0 (an inextensible
    rope unloads the drive side at once) and ends at rest: its peak F_C and least F_S are those of the ramp or
    of rest, whichever is worse."""
    d, F_nwl = design.design["d"], design.design["F_nwl"]
    L = sum(seg[0] for seg in SEGMENTS)
    q_l, a = W * d**2 * G_N, V / T_RAMP
    m_C, m_S = (G_M + q_l * L) / G_N, q_l * L / G_N          # the drive side: load and winding rope
    by = {m["manoeuvre"]: m["positions"] for m in design.manoeuvres}
    assert len(by["upward start"]) == len(by["upward stop"]) == 9
    for start, stop in zip(by["upward start"], by["upward stop"]):
        F_C, F_S = static_forces(start["x_m"], d, F_nwl)
        rest_C, rest_S = static_forces(start["x_m"], d, F_nwl, s=0.0)
        assert start["peaks"]["F_C_max"] == pytest.approx(F_C + m_C * a, rel=1e-9)
        assert start["peaks"]["F_S_min"] == pytest.approx(F_S - m_S * a, rel=1e-9)
        assert stop["peaks"]["F_C_max"] == pytest.approx(max(F_C - m_C * a, rest_C), rel=1e-9)
        assert stop["peaks"]["F_S_min"] == pytest.approx(min(F_S + m_S * a, rest_S), rel=1e-9)


def test_the_rope_is_safe_in_every_upward_start(design):
    """Rope safety F_min = K d² R_r (EN 12385-4) against n_rope times Newton's peak of the upward start, with the
    load at every place of the route (the steepest segment's places govern), holds at the design."""
    d, F_nwl = design.design["d"], design.design["F_nwl"]
    L = sum(seg[0] for seg in SEGMENTS)
    a = V / T_RAMP
    places = [0.0, 300.0, 600.0, 600.001, 950.0, 1300.0, 1300.001, 1550.0, 1800.0]
    peaks = [static_forces(x, d, F_nwl)[0] + (G_M + W * d**2 * G_N * L) / G_N * a for x in places]
    F_min = en12385.minimum_breaking_force(en12385.construction("6x36-IWRC").K, d, 1770e6)
    assert 5 * max(peaks) <= F_min
    assert int(np.argmax(peaks)) == places.index(600.001)
