"""The pieces of dynamic sizing's mesh control and dynamic slip factor that are cheap to check (the sizing
itself under refinement: tests/_mesh_checks.py, run by the slow tests/test_dynamic_sizing_design.py and
tests/test_dynamic_sizing_route.py).

Truths: a quantity with a known error C h^p written out here (the Richardson estimate must give the error
exactly when the three meshes are in the asymptotic range), and Euler–Eytelwein's slip reserve
(ρ F_slack − n F_tight)/ρ written out in numpy against the check built from the simulator's switching
functions.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from optimisation.dynamic import mesh
from optimisation.dynamic.manoeuvres import sides
from optimisation.dynamic.mesh import P_MAX, P_MIN, richardson, unsafe_part
from ropemodel.effects.transient.contact import N_SLIP_DYNAMIC
from ropemodel.effects.transient.rope import MESH_TOL
from ropemodel.machines.winch import manoeuvres as winch
from ropemodel.machines.winch.manoeuvres import CHECK


@pytest.mark.parametrize("p", [0.6, 1.0, 2.0])
@pytest.mark.parametrize("C", [-250.0, 4e3])
def test_richardson_gives_a_power_laws_error_and_order(p, C):
    """g(n) = g* + C n^-p at n = 4, 8, 16: E(4) = |g(4) − g*| and the order p, to rounding."""
    g_star = 1234.5

    def g(n):
        return g_star + C * n ** -p

    E, order = richardson(g(4), g(8), g(16))
    assert E == pytest.approx(abs(g(4) - g_star), rel=1e-9)
    assert order == pytest.approx(p, rel=1e-9)


def test_richardson_outside_the_asymptotic_range_is_conservative():
    """Changes that grow or change sign: the least order, 0.5, so E = 1/(1 − 2^-0.5) = 3.41 times the first
    change, more than any change seen so far."""
    for g in [(0.0, 10.0, 30.0), (0.0, 10.0, 5.0)]:
        E, order = richardson(*g)
        assert order == P_MIN
        assert E == pytest.approx(10.0 / (1 - 2 ** -0.5)) and E >= max(abs(g[0] - g[1]), abs(g[0] - g[2]))


def test_richardson_order_is_clipped_at_two():
    """g* + C n^-3 (faster than the estimate believes): the order taken is 2, and E over-estimates the error."""
    E, order = richardson(*(5.0 + 64.0 * n ** -3.0 for n in (4, 8, 16)))
    assert order == P_MAX == 2.0 and P_MIN == 0.5
    assert E == pytest.approx((1.0 - 1.0 / 8.0) / (1.0 - 2.0 ** -2.0)) and E > 1.0


def test_only_a_margin_that_falls_with_refinement_needs_a_back_off():
    """A margin that rises steadily as the mesh is refined (the coarse mesh on the safe side) needs none; one that
    falls needs all of its error; one with no steady trend needs all of it too."""
    rising = [10.0 - 8.0 * n ** -1.0 for n in (4, 8, 16)]
    falling = [10.0 + 8.0 * n ** -1.0 for n in (4, 8, 16)]
    assert unsafe_part(*rising) == 0.0
    assert unsafe_part(*falling) == pytest.approx(2.0)       # g(4) − g* = 8/4
    assert unsafe_part(0.0, -1.0, 0.5) == richardson(0.0, -1.0, 0.5)[0] > 0.0


def test_transient_slip_check_uses_the_dynamic_factor():
    """The slip checks through a manoeuvre are (ρ F_S − n F_C)/ρ and (ρ F_C − n F_S)/ρ with n = n_slip_dynamic,
    from the switching functions F_S − F_C/ρ and F_C − F_S/ρ."""
    rng = np.random.default_rng(1)
    F_C, F_S, rho = rng.uniform(1e4, 3e5, 50), rng.uniform(1e4, 3e5, 50), rng.uniform(1.2, 6.0, 50)
    o = {"F_C": F_C, "F_S": F_S, "slip_fwd": F_S - F_C / rho, "slip_back": F_C - F_S / rho}
    for n in (1.0, 1.1, 1.5):
        a = {"n_slip_dynamic": n}
        assert np.allclose(CHECK["slip_margin_fwd"].nlp(o, a), (rho * F_S - n * F_C) / rho, rtol=0, atol=1e-8)
        assert np.allclose(CHECK["slip_margin_back"].nlp(o, a), (rho * F_C - n * F_S) / rho, rtol=0, atol=1e-8)
        # the limit the output shows beside the force it judges is n F_C/rho (n F_S/rho), not the bare F_C/rho
        for i in (0, 17, 49):
            fwd, back = sides(winch, "slip_margin_fwd", o, a, i), sides(winch, "slip_margin_back", o, a, i)
            assert fwd["value"] == pytest.approx(F_S[i]) and fwd["limit"] == pytest.approx(n * F_C[i] / rho[i])
            assert back["value"] == pytest.approx(F_C[i]) and back["limit"] == pytest.approx(n * F_S[i] / rho[i])


def test_defaults_say_where_they_come_from():
    """The dynamic slip factor's default is stated as engineering judgement (no named practice found); the mesh
    tolerance is a force with a unit."""
    assert N_SLIP_DYNAMIC.default == 1.1 and "engineering judgement" in N_SLIP_DYNAMIC.range_source
    assert "engineering judgement" in N_SLIP_DYNAMIC.default_note
    assert MESH_TOL.unit == "N" and MESH_TOL.default == 1000.0 and MESH_TOL.range_source


def _power_law(g_star: float, C: float, p: float, meshes) -> dict:
    """One case's one check, g(m) = g* + C m^-p on each mesh m."""
    return {m: {0: {"slip_margin_back": g_star + C * m ** -p}} for m in meshes}


@pytest.mark.parametrize("C", [-2e4, 2e4])       # rising (the coarse meshes pessimistic) and falling margins
def test_a_margin_kept_at_its_need_holds_on_every_mesh_from_the_scenes_and_in_the_limit(C):
    """g(m) = g* + C/m from the scene's 8 elements a span, estimated at 32: a design whose margin at 32 is exactly
    its need (the unsafe part of E(32) or the most a coarser mesh judges it worse) keeps g >= 0 at 8, 16, 32, every
    finer mesh and in the limit; and the need is not more than that requires (one of them is 0 to rounding)."""
    shape = _power_law(0.0, C, 1.0, (8, 16, 32, 64, 128))
    need = mesh.estimate(shape, 32, {0: ["slip_margin_back"]}, ["case"])[("case", "slip_margin_back")].need
    g_star = need - shape[32][0]["slip_margin_back"]        # the limit of the margins kept at exactly the need
    held = {m: g_star + C / m for m in (8, 16, 32, 64, 128, 1024)}
    assert min(*held.values(), g_star) >= -1e-9 * abs(C)
    assert min(*held.values(), g_star) == pytest.approx(0.0, abs=1e-9 * abs(C))


def test_cases_within_reach_of_their_limit_are_estimated():
    """A case is estimated where its margin at n is within the screening's limit or within REACH times its
    largest change from a coarser mesh: 30 kN with a 9 kN change is (30 < 4.1 x 9), 30 kN with 5 kN is not, 1 kN
    with no change is (under the 15 kN screening limit)."""
    assert mesh.REACH == pytest.approx(mesh.MARGIN / (1 - 2 ** -0.5))
    g = {16: {0: {"c": 39e3}, 1: {"c": 35e3}, 2: {"c": 1e3}}, 32: {0: {"c": 30e3}, 1: {"c": 30e3}, 2: {"c": 1e3}}}
    assert mesh.within_reach(g, 32, {"c": 15e3}) == {0: ["c"], 2: ["c"]}


def test_each_case_is_backed_off_by_its_own_need():
    """The back-off of a check in a case: BACKOFF + MARGIN x its need / the check's scale, per case (two places of
    one check with different errors keep different back-offs)."""
    problem = SimpleNamespace(F_ref=3e4, machine=SimpleNamespace(manoeuvres=SimpleNamespace(CHECK=CHECK)))
    found = mesh.MeshEstimate(32, 1e3, {("a", "slip_margin_back"): mesh.CaseError(11.0, 330.0, 1.0, 0.0, 959.0),
                                        ("b", "slip_margin_back"): mesh.CaseError(321.0, 39.0, 1.6, 39.0, 35.0)})
    assert mesh.backoffs(problem, found) == {"a": {"slip_margin_back": pytest.approx(1e-4 + 1.2 * 959.0 / 3e4)},
                                             "b": {"slip_margin_back": pytest.approx(1e-4 + 1.2 * 39.0 / 3e4)}}
    assert found.errors == {"slip_margin_back": 330.0} and found.coarse == {"slip_margin_back": 959.0}


@pytest.mark.parametrize("p", [0.7, 1.0, 1.6])
@pytest.mark.parametrize("C", [-2e4, 3e3])
def test_the_error_from_the_coarser_meshes_is_a_power_laws_error(p, C):
    """g(m) = g* + C m^-p on 8, 16, 32, 64: the error of g(32) from the coarser meshes (no 128) is |g(32) − g*|
    exactly, at order p; the unsafe part is 0 where the margins rise (C < 0), all of it where they fall."""
    g = _power_law(1e3, C, p, (8, 16, 32, 64))
    e, order, unsafe = mesh.from_coarser(g, 32, 0, "slip_margin_back")
    assert e == pytest.approx(abs(C) * 32 ** -p, rel=1e-9) and order == pytest.approx(p, rel=1e-9)
    assert unsafe == (0.0 if C < 0 else e)
    found = mesh.estimate(g, 32, {0: ["slip_margin_back"]}, ["case"])[("case", "slip_margin_back")]
    assert found.error == pytest.approx(e, rel=1e-12) and found.order == pytest.approx(p, rel=1e-9)


def test_the_coarser_meshes_must_show_the_asymptotic_range():
    """No estimate from the coarser meshes (the finer mesh, 4n, is integrated instead) where the changes change
    sign, where the order falls by more than P_DROP from one triple to the next, finer one, or where it is below
    P_MIN; an order that rises is taken at the coarser triple's, the lower (a larger error)."""
    def shape(values):
        return {m: {0: {"c": v}} for m, v in zip((8, 16, 32, 64), values)}

    assert mesh.from_coarser(shape([0.0, 8.0, 12.0, 11.0]), 32, 0, "c") is None       # changes change sign
    assert mesh.from_coarser(shape([0.0, 8.0, 10.0, 10.9]), 32, 0, "c") is None       # order 2 then 1.15
    assert mesh.from_coarser(shape([0.0, 4.0, 7.0, 9.5]), 32, 0, "c") is None         # order 0.26 below P_MIN
    rising_order = shape([0.0, 8.0, 12.0, 13.0])                                       # orders 1 then 2
    e, order, _ = mesh.from_coarser(rising_order, 32, 0, "c")
    assert order == pytest.approx(1.0) and e == pytest.approx(1.0 / (1.0 - 0.5))
    assert mesh.from_coarser(rising_order, 16, 0, "c") is None                       # no mesh 4 to compare
    assert mesh.needs_finer(rising_order, 32, {0: ["c"]}, 1e3, {"c": "N"}) == {}
    assert mesh.needs_finer(rising_order, 32, {0: ["c"]}, 1.0, {"c": "N"}) == {0: ["c"]}   # above the tolerance
