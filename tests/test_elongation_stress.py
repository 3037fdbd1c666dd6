"""The stroke as built with a stress-dependent rope modulus (``elongation = "asbuilt_stress"``).

Truth: the strain ε(σ) = ∫_0^σ ds/E_t(s), E_t(s) = E (1 − (1 − r_0) e^{−s/σ_E}), integrated by scipy's quad,
and each side's ∫ε(T(x)/A_m) dx by quad on each piece of the three-segment route, the tension T(x) written
out here (0.5 F_nwl at the return sheave, the rope's weight and resistance per metre, the load's step at x_m).
"""

from __future__ import annotations

import math
import tomllib

import _route3
import pytest
from scipy.integrate import quad

import ropemodel as rm
from ropemodel.papers.ropestretch import rope_strain

G = 9.80665
SEGMENTS = [(600.0, 12.0), (700.0, 20.0), (500.0, 6.0)]
E, C, W = 100e9, 0.460, 0.409 / (100 * 1e-6)
D, F_NWL, G_M, MU = 0.036, 24.7e3, 300e3, 0.05
R0, SIGMA_E = 0.5, 100e6


def compliance_strain(sigma):
    return quad(lambda s: 1.0 / (E * (1.0 - (1.0 - R0) * math.exp(-s / SIGMA_E))), 0.0, sigma,
                epsabs=0.0, epsrel=1e-13)[0]


def run(x_m, **params):
    d = tomllib.loads(_route3.SCENE + _route3.DESIGN)
    d["effects"]["elongation"] = "asbuilt_stress"
    d["parameters"].pop("t_ramp")
    d["parameters"].update({"x_m": f"{x_m} m", "r_E0": R0, "sigma_E": f"{SIGMA_E / 1e6} N/mm^2", **params})
    return rm.run(rm.from_dict(d))


def side(x_m, sign, winding):
    """∫ε(T(x)/A_m) dx [m] of one side by quad, T(x) written out piece by piece."""
    q, A = G * W * D**2, C * D**2
    ends = [sum(s[0] for s in SEGMENTS[: i + 1]) for i in range(len(SEGMENTS))]
    j = next(i for i, end in enumerate(ends) if x_m <= end)
    a_j = math.radians(SEGMENTS[j][1])
    jump = G_M * (math.sin(a_j) + sign * MU * math.cos(a_j)) if winding else 0.0
    mu = sign * MU if winding else -sign * MU

    def w(i):
        a = math.radians(SEGMENTS[i][1])
        return q * (math.sin(a) + mu * math.cos(a))

    def T(x):
        i = next(k for k, end in enumerate(ends) if x <= end)
        rest = sum(w(k) * SEGMENTS[k][0] for k in range(i + 1, len(SEGMENTS)))
        return 0.5 * F_NWL + rest + w(i) * (ends[i] - x) + jump * (x < x_m)

    cuts = sorted({0.0, *ends, x_m})
    # the strain's closed form checked against quad below; quad of it along the side here
    return sum(quad(lambda x: rope_strain_numpy(T(x) / A), a, b, epsabs=0.0, epsrel=1e-12, limit=200)[0]
               for a, b in zip(cuts[:-1], cuts[1:]) if b > a)


def rope_strain_numpy(sigma):
    """ε(σ) in closed form, typed here: [σ + σ_E ln((1 − (1 − r_0) e^{−σ/σ_E})/r_0)]/E."""
    return (sigma + SIGMA_E * math.log((1.0 - (1.0 - R0) * math.exp(-sigma / SIGMA_E)) / R0)) / E


@pytest.mark.parametrize("sigma", [1e6, 5e7, 1e8, 3e8, 8e8])
def test_strain_is_the_integral_of_the_compliance(sigma):
    assert rope_strain_numpy(sigma) == pytest.approx(compliance_strain(sigma), rel=1e-11)
    assert rope_strain(sigma, E, R0, SIGMA_E) == pytest.approx(compliance_strain(sigma), rel=1e-11)


@pytest.mark.parametrize("x_m", [150.0, 600.0, 950.0, 1450.0, 1800.0])
def test_profile_strain_matches_quad(x_m):
    r = run(x_m)
    for way, sign in (("up", 1), ("down", -1)):
        assert r[f"dF_C_{way}"] == pytest.approx(side(x_m, sign, True), rel=1e-9)
        assert r[f"dF_S_{way}"] == pytest.approx(side(x_m, sign, False), rel=1e-9)


def test_a_constant_modulus_is_asbuilt():
    stiff = run(950.0, r_E0=1.0)
    d = tomllib.loads(_route3.SCENE + _route3.DESIGN)
    d["effects"]["elongation"] = "asbuilt"
    d["parameters"].pop("t_ramp")
    d["parameters"]["x_m"] = "950 m"
    hooke = rm.run(rm.from_dict(d))
    for name in ("dF_C_up", "dF_S_down", "dF_up", "dF_down", "dF_nwl"):
        assert stiff[name] == pytest.approx(hooke[name], rel=1e-12)


def test_a_softer_rope_at_low_stress_needs_more_stroke():
    assert run(950.0)["dF_up"] > run(950.0, r_E0=1.0)["dF_up"]
