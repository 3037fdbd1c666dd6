"""Drum contact stiffness of the transient from the capstan model (drum_contact = "capstan").

Truths: the rigid drum's transient (limit of a stiff contact, D → 0), closed-form natural
frequencies of springs in series with the contact spring (Li et al. eq. (12) typed here from the
paper), the static model (unchanged by the effect), and the continuity of the tight side's
stiffness at the slip zone's saturation (docs/physics.md §5).
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest
from scipy.optimize import curve_fit

import ropemodel as rm
from ropemodel.dynamics import simulate
from ropemodel.effects.transient.capstan import capstan_contact_stiffness

DATA = resources.files("ropemodel.data")
G_N = 9.80665            # standard gravity [m/s²]


def scene(name="winch_start.toml", effects=None, params=None, numerics=None):
    """A built-in dynamic scene with overrides."""
    d = tomllib.loads(DATA.joinpath(name).read_text())
    d["effects"].update(effects or {})
    if (effects or {}).get("rope") == "catalogue":
        for k in ("q_l", "q_lw"):                      # outputs of the catalogue rope
            d["parameters"].pop(k)
    d["parameters"].update(params or {})
    d.setdefault("numerics", {}).update(numerics or {})
    return rm.from_dict(d, bare="si")

CAPSTAN = {"drum_contact": "capstan"}


def _li_eq12(F_tight, F_slack, mu, EA, R):
    """Li et al. eq. (12), K_1 = μEA(F_p + F_T)/(R F_T), with F_p = F_slack, F_T = F_tight − F_slack."""
    return mu * EA * F_tight / (R * (F_tight - F_slack))


def test_contact_stiffness_is_li_eq12_and_continuous_at_saturation():
    mu, EA, R, alpha = 0.25, 2e8, 1.25, 4 * math.pi
    assert capstan_contact_stiffness(2e5, 3e4, mu, EA, R, alpha) == pytest.approx(_li_eq12(2e5, 3e4, mu, EA, R),
                                                                                  rel=1e-14)
    assert capstan_contact_stiffness(3e4, 2e5, mu, EA, R, alpha) == math.inf      # slack side: stick arc
    # at the saturation F_T = F_p(e^{μα} − 1) eq. (12) meets eq. (15) (the tight side is continuous)
    F_p = 3e4
    F_sw = F_p * math.expm1(mu * alpha)
    below = capstan_contact_stiffness(F_p + F_sw * (1 - 1e-12), F_p, mu, EA, R, alpha)
    above = capstan_contact_stiffness(F_p + F_sw * (1 + 1e-12), F_p, mu, EA, R, alpha)
    assert below == pytest.approx(above, rel=1e-9)
    assert above == pytest.approx(mu * EA / (R * (1 - math.exp(-mu * alpha))), rel=1e-14)


def test_single_spring_in_series_with_the_contact_spring():
    """The load at the return sheave (x_m = L_u), one element per span, a fixed tensioner: one mass
    m = G_m/g + q_l L_u/(2g) held by a spring k = EA/L_u to each side of the drum; the winding (tight)
    side's spring is in series with the contact spring K_1 (Li et al. eq. (12) at the static forces):
    ω_d² = (k + k_eff)/m − σ², k_eff = 1/(1/K_1 + 1/k), σ = (c + c_eff)/(2m), c = τk, c_eff = τk_eff.
    A large drum and little friction (D = 50 m, μ_d = 0.1 over ten turns) make K_1 comparable to k."""
    sc = scene(effects={"rope_elasticity": "spring", "tensioner": "fixed", **CAPSTAN},
               params={"x_m": "1150 m", "F_nwl": "150 kN", "t_end": "25 s", "D": "50 m", "mu_d": 0.1,
                       "alpha_d": "3600 deg"},
               numerics={"sim_rtol": 1e-11, "sim_dt": 0.005})
    v, st = sc.parameters, rm.run(sc)
    sim = simulate(sc)
    assert not sim.summary["slip"] and not sim.summary["slack"]
    EA = v["L_u"] / v["q_lw"]
    k, K1 = EA / v["L_u"], _li_eq12(st["F_C_up"], st["F_S_up"], v["mu_d"], EA, v["D"] / 2)
    assert sim.summary["drum_contact"]["K_C"] == pytest.approx(K1, rel=1e-12)
    k_eff = 1 / (1 / K1 + 1 / k)
    m = (v["G_m"] + v["q_l"] * v["L_u"] / 2) / G_N
    sigma = v["rope_damping"] * (k + k_eff) / (2 * m)
    w_d = math.sqrt((k + k_eff) / m - sigma ** 2)
    assert abs(w_d / math.sqrt(2 * k / m - (v["rope_damping"] * k / m) ** 2) - 1) > 0.02   # the contact matters
    h = sim.history
    sel = h["t [s]"] > v["t_ramp"] + 1e-9
    t, y = h.loc[sel, "t [s]"].to_numpy() - v["t_ramp"], h.loc[sel, "v_load [m/s]"].to_numpy()

    def model(t, A, B, w, s):
        return v["v_pj"] + np.exp(-s * t) * (A * np.cos(w * t) + B * np.sin(w * t))

    p, _ = curve_fit(model, t, y, p0=[-0.01, 0.0, w_d * 1.01, sigma], xtol=1e-14, ftol=1e-14)
    assert p[2] == pytest.approx(w_d, rel=1e-6)                       # measured 7e-8
    assert p[3] == pytest.approx(sigma, rel=1e-5)                     # measured 2.1e-6


def test_stiff_contact_gives_the_rigid_drum():
    """K_1 ∝ 1/R: as D → 0 the transient tends to the rigid drum's, the difference falling like D."""
    tight = {"sim_rtol": 1e-11}             # the forces' integration error (~1e-8 relative) below the differences
    rigid = simulate(scene(params={"t_end": "12 s"}, numerics=tight))
    diffs = []
    for D in ("2.5 m", "0.025 m", "0.00025 m"):
        sim = simulate(scene(effects=CAPSTAN, params={"t_end": "12 s", "D": D}, numerics=tight))
        assert sim.summary["drum_contact"]["K_C"] > 0 and sim.summary["drum_contact"]["K_S"] is None
        h = sim.history
        F = np.interp(rigid.history["t [s]"], h["t [s]"], h["F_C [N]"])
        diffs.append(np.max(np.abs(F - rigid.history["F_C [N]"])) / rigid.summary["F_C_max"])
    assert diffs[-1] < 1e-6
    for d0, d1 in zip(diffs, diffs[1:]):
        assert d1 / d0 == pytest.approx(1e-2, rel=0.2)                 # first order in the compliance


def test_contact_is_built_only_when_asked_and_leaves_static_results_alone():
    from ropemodel.core.model import Model

    base, cap = scene(), scene(effects=CAPSTAN, params={"D": "2.5 m"})
    assert "D" not in base.parameters and cap.parameters["D"] == 2.5
    static = Model("winch", {**cap.effects, "dynamics": "none"})
    assert [str(e.residual) for e in cap.built.equations] == [str(e.residual) for e in static.equations]
    r_base, r_cap = rm.run(base), rm.run(cap)
    for k in ("F_C_up", "F_C_down", "F_S_up", "F_S_down", "dF_up"):
        assert r_cap[k] == r_base[k]
    default = simulate(scene(params={"t_end": "6 s"}))
    rigid = simulate(scene(effects={"drum_contact": "rigid"}, params={"t_end": "6 s"}))
    np.testing.assert_array_equal(default.history["F_C [N]"], rigid.history["F_C [N]"])
    assert default.summary["drum_contact"] is None


@pytest.mark.parametrize("change,match", [
    (dict(effects=CAPSTAN), "D"),                                             # the diameter is required
    (dict(effects={**CAPSTAN, "rope_elasticity": "rigid"}, params={"D": "2.5 m"}), "elastic rope"),
])
def test_contact_bad_input(change, match):
    with pytest.raises(rm.InputError, match=match):
        simulate(scene(**change))


def test_capstan_example_scene_reports_the_contact(capsys):
    from ropemodel.cli import main

    assert main(["simulate", "winch_start_capstan", "--set", "t_end=6s"]) == 0
    out = capsys.readouterr().out
    assert "drum contact (capstan" in out and "C side" in out
    sc = rm.load_scene(str(DATA.joinpath("winch_start_capstan.toml")))
    st, v = rm.run(sc), sc.parameters
    K = simulate(sc.with_values({"t_end": "6 s"})).summary["drum_contact"]["K_C"]
    EA = v["L_u"] / v["q_lw"]
    assert K == pytest.approx(_li_eq12(st["F_C_up"], st["F_S_up"], v["mu_d"], EA, v["D"] / 2), rel=1e-12)
    assert K / (EA / v["x_m"]) == pytest.approx(260, rel=0.02)        # the README's "about 260 times"


def test_catalogue_rope_gives_the_contact_its_EA():
    """rope = "catalogue": q_lw = L_u/(E C d²) is an output of the static model, so the contact's EA is
    the catalogue's E·A_m = E·C·d² (EN 12385-4 factors here; the 6 m stroke holds the softer rope)."""
    sc = scene("winch_start_capstan.toml", effects={"rope": "catalogue"},
               params={"d": "42 mm", "rope_grade": "1770 N/mm^2", "rope_E": "100 kN/mm^2", "rope_K": 0.356,
                       "rope_W": 4090, "rope_C": 0.46, "stroke": "6 m", "t_end": "6 s"})
    v, st = sc.parameters, rm.run(sc)
    EA = v["rope_E"] * v["rope_C"] * v["d"] ** 2
    K = simulate(sc).summary["drum_contact"]["K_C"]
    assert K == pytest.approx(_li_eq12(st["F_C_up"], st["F_S_up"], v["mu_d"], EA, v["D"] / 2), rel=1e-12)
