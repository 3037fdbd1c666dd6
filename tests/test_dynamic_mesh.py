"""The pieces of dynamic sizing's mesh control and dynamic slip factor that are cheap to check (the sizing
itself under refinement: tests/_mesh_checks.py, run by the slow tests/test_dynamic_sizing_design.py and
tests/test_dynamic_sizing_route.py).

Truths: a quantity with a known error C h^p written out here (the Richardson estimate must give the error
exactly when the three meshes are in the asymptotic range), and Euler–Eytelwein's slip reserve
(ρ F_slack − n F_tight)/ρ written out in numpy against the check built from the simulator's switching
functions.
"""

from __future__ import annotations

import numpy as np
import pytest

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
