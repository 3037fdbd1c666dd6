"""ropemodel.effects.route_arrays: a route as arrays, and the one resolver between them and the names users write
(L_i, alpha_i, mu_wi), against values written out here and the shipped scene's [[route]] tables."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.effects.route_arrays import RouteArrays, beyond, name, parse


@pytest.mark.parametrize("field, text", [("L", "L_{}"), ("alpha", "alpha_{}"), ("mu_w", "mu_w{}")])
def test_names_and_places_translate_both_ways(field, text):
    for i in (1, 2, 9, 10, 99, 10_000):
        assert name(field, i - 1) == text.format(i)
        assert parse(text.format(i)) == (field, i - 1)


@pytest.mark.parametrize("text", ["L_u", "L_ul", "L_0", "L_01", "L1", "alpha1", "mu_w_2", "mu_w0", "L_2x", "x_m",
                                  "", "L_", "mu_pl", "alpha_u"])
def test_other_names_are_not_segments(text):
    assert parse(text) is None


def _values():
    """Three segments, the second without its own μ_w (SI)."""
    return {"L_1": 400.0, "L_2": 650.0, "L_3": 300.0, "alpha_1": 0.3, "alpha_2": -0.1, "alpha_3": 0.05,
            "mu_w1": 0.06, "mu_w3": 0.07, "mu_pl": 0.05, "L_ul": 100.0, "x_m": 500.0}


def test_a_mapping_of_names_gathers_into_arrays():
    r = RouteArrays.from_values(_values())
    assert r.n == 3
    assert r.L.tolist() == [400.0, 650.0, 300.0] and r.alpha.tolist() == [0.3, -0.1, 0.05]
    assert r.mu_w.tolist() == [0.06, 0.05, 0.07] and r.own_mu.tolist() == [True, False, True]
    assert RouteArrays.from_values({"L_u": 1150.0, "alpha_u": 0.28}).n == 0
    with pytest.raises(ValueError):
        r.L[0] = 1.0                                   # read-only


@pytest.mark.parametrize("text, said", [("L_4", "the route has 3 segments, so its values are L_1 … L_3"),
                                        ("mu_w7", "mu_w1 … mu_w3")])
def test_a_name_beyond_the_route_is_refused_with_the_valid_names(text, said):
    assert said in beyond(text, 3)
    assert beyond("L_3", 3) is None and beyond("L_u", 3) is None


def test_the_shipped_scenes_route_tables_read_as_arrays():
    scene = rm.load_scene("route_segments")
    r = RouteArrays.from_values(scene.parameters)
    # ropemodel/data/route_segments.toml: 400 m at 22 deg (mu_winding 0.06), 650 m at 9 deg, 300 m at 3 deg
    assert r.L.tolist() == [400.0, 650.0, 300.0]
    assert np.allclose(r.alpha, [math.radians(22.0), math.radians(9.0), math.radians(3.0)], rtol=1e-15, atol=0)
    assert r.mu_w[0] == 0.06 and r.own_mu.tolist() == [True, False, False]
    assert r.mu_w.tolist()[1:] == [scene.parameters["mu_pl"]] * 2


@pytest.mark.parametrize("argv, said", [
    (["run", "--set", "L_5=3m"], "parameter L_5: the route has 3 segments, so its values are L_1 … L_3"),
    (["run", "--set", "mu_w4=0.1"], "parameter mu_w4: the route has 3 segments, so its values are mu_w1 … mu_w3"),
    (["solve", "--given", "L_4=3m", "--find", "F_nwl"], "given quantity L_4: the route has 3 segments"),
])
def test_a_segment_beyond_the_route_at_the_command_line_names_the_valid_ones(argv, said, capsys):
    from ropemodel.cli import main as cli

    assert cli([argv[0], "route_segments", *argv[1:]]) == 2
    err = capsys.readouterr().err
    assert said in err and "did you mean" not in err and "Traceback" not in err
