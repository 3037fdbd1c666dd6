"""The transient (``ropemodel simulate``) on a route of segments: the elastic rope loop built over the segments.

Truths, written out here in numpy and scipy: the route's static forces (docs/physics.md §4: the paper's
eq. (12)-(13) with the sums over the segments and the load's weight and resistance on its own segment),
which a start-up must settle on, with the load inside a segment and on either side of a joint; and the
continuum integral of the loop's elongation at rest, ∫T ds/EA with the tension growing by q_l sin α_i along
each segment and by G_m sin α_j at the load, which the lumped rope must converge to at second order in the
element length.  And the energy balance of the model's own states.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

import ropemodel as rm
from ropemodel.dynamics import simulate, smooth_mode
from ropemodel.errors import InputError

#: the three-segment route of issue 21, from the drive: length [m], inclination [deg], winding rope's mu
SEGMENTS = [(600.0, 12.0, 0.06), (700.0, 20.0, None), (500.0, 6.0, None)]
Q_L, Q_LW, G_M, F_NWL, MU_PM, MU_PL = 50.0, 4.0e-3 / 1e3, 300e3, 60e3, 0.05, 0.05   # N/m, m/N, N, N


def route_scene(x_m, travel="up", numerics=None, **params):
    segments = [{"length": f"{L} m", "inclination": f"{a} deg", **({"mu_winding": mu} if mu else {})}
                for L, a, mu in SEGMENTS]
    values = {"q_l": Q_L, "q_lw": Q_LW, "G_m": G_M, "F_nwl": F_NWL, "mu_pm": MU_PM, "mu_pl": MU_PL, "x_m": x_m,
              "v_pj": 3.0, "t_ramp": 4.0, "t_end": 20.0, "stroke": 50.0, "mu_d": 0.3, "alpha_d": 4 * math.pi,
              "rope_damping": 0.05, **params}
    return rm.from_dict({"effects": {"route": "segments", "dynamics": "start", "travel": travel, "lining": "rigid"},
                         "route": segments, "parameters": values, "numerics": numerics or {}}, bare="si")


def _profile():
    L = np.array([s[0] for s in SEGMENTS])
    a = np.radians([s[1] for s in SEGMENTS])
    mu = np.array([MU_PL if s[2] is None else s[2] for s in SEGMENTS])
    return L, a, mu, np.concatenate([[0.0], np.cumsum(L)])


def static_forces(x, travel):
    """F_C, F_S [N] of the route with the load at x (a load on a joint: the segment nearer the drive)."""
    L, a, mu, ends = _profile()
    s = 1.0 if travel == "up" else -1.0
    j = int(np.searchsorted(ends[1:], x, side="left"))
    weight = Q_L * np.sum(L * np.sin(a))
    F_S = 0.5 * F_NWL + weight - s * MU_PL * Q_L * np.sum(L * np.cos(a))
    F_C = (0.5 * F_NWL + weight + G_M * math.sin(a[j])
           + s * (MU_PM * G_M * math.cos(a[j]) + Q_L * np.sum(mu * L * np.cos(a))))
    return F_C, F_S


#: either side of both joints (the load on the drive-side segment at the joint itself, on the far one 1 mm beyond)
#: and in the middle of the steepest segment
PLACES = [600.0, 600.001, 950.0, 1300.0, 1300.001]


@pytest.mark.parametrize("travel", ["up", "down"])
@pytest.mark.parametrize("x", PLACES)
def test_start_settles_on_the_routes_static_forces(x, travel):
    """A start-up ends at constant speed on the route's F_C and F_S with the load where it is, to 1e-9.
    The rope's damping (0.5 s) makes the oscillation die out within the run; it does not change the steady
    state."""
    sim = simulate(route_scene(x, travel, t_end=120.0, rope_damping=0.5), progress=False)
    s = sim.summary
    assert not s["slip"] and not s["slack"]
    F_C, F_S = static_forces(x, travel)
    assert s["F_C_end"] == pytest.approx(F_C, rel=1e-9)
    assert s["F_S_end"] == pytest.approx(F_S, rel=1e-9)


def elongation_at_rest(x):
    """∫T ds / EA around the loop at rest (no resistance): the unwinding rope from the drive to the return
    sheave, the winding rope from the sheave to the load and from the load to the drive; each starts at
    F_nwl/2 at the sheave and gains q_l sin α per metre towards the drive, the winding rope G_m sin α_j at the
    load.  EA = L_u/q_lw (Krauze et al. eq. (19)-(20))."""
    L, a, _, ends = _profile()
    L_u = ends[-1]
    j = int(np.searchsorted(ends[1:], x, side="left"))

    def rise(s):               # ∫_s^L_u q_l sin α dσ: the rope's weight along the route beyond s
        return Q_L * sum(np.sin(ai) * max(0.0, e1 - max(s, e0)) for ai, e0, e1 in zip(a, ends[:-1], ends[1:]))

    h = F_NWL / 2
    points = list(ends[1:-1])
    unwinding = quad(lambda s: h + rise(s), 0.0, L_u, points=points, epsabs=0, epsrel=1e-13, limit=200)[0]
    beyond = quad(lambda s: h + rise(s), x, L_u, points=[p for p in points if p > x], epsabs=0, epsrel=1e-13)[0]
    nearer = quad(lambda s: h + rise(s) + G_M * math.sin(a[j]), 0.0, x, points=[p for p in points if p < x],
                  epsabs=0, epsrel=1e-13)[0]
    return (unwinding + beyond + nearer) * Q_LW / L_u


@pytest.mark.parametrize("x", [950.0, 1300.001])
def test_rest_take_up_converges_to_the_continuum_integral_on_a_route(x):
    """Take-up at rest = the loop's elongation: the lumped rope over three segments converges to the continuum
    at second order (errors fall at least 3.3 times per halving of the element; measured 4.4 to 6.2)."""
    exact = elongation_at_rest(x)
    errs = []
    for n in (2, 4, 8, 16):
        sim = simulate(route_scene(x, t_end=1.0, t_ramp=1.0, numerics={"segments": n}), progress=False)
        z0 = sim.history["take_up [m]"].iloc[0]
        errs.append(abs(z0 - exact) / exact)
    assert errs[-1] < 1e-3
    for e0, e1 in zip(errs, errs[1:]):
        assert e1 < 0.3 * e0


@pytest.mark.parametrize("travel", ["up", "down"])
def test_energy_balance_on_a_route(travel):
    """Drum work = Δ(kinetic + potential) + dissipated, with the load on the steepest segment."""
    sim = simulate(route_scene(950.0, travel), progress=False)
    assert sim.summary["energy_residual"] < 100 * sim.scene.numerics["sim_rtol"]


def test_a_segments_length_stays_a_number_in_the_smooth_mode():
    """The rope's elements and the load are placed on the segments by their lengths: a length cannot be a
    symbol of the smooth mode (dynamic sizing's sensitivities and sweeps leave it out); an inclination can."""
    sc = route_scene(950.0)
    with pytest.raises(InputError, match="L_2 fixes the structure"):
        smooth_mode(sc, ["L_2"])
    assert smooth_mode(sc, ["alpha_2"]).params == ("alpha_2",)
