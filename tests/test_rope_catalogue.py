"""Rope catalogue (effect rope = "catalogue", ropemodel.papers.en12385) against published tables and Hooke's law."""

import math

import numpy as np
import pytest

from ropemodel.papers import en12385 as ropes
from ropemodel.errors import InputError
from ropemodel.problem import run
from ropemodel.scene import from_dict, load

# API Spec 9A Table C.1 (class 6x7 fibre core), nominal length mass [kg/100 m] and minimum
# breaking force [kN] for grades 1770 and 1960; class factors W = 0.345, K = 0.332 (EN 12385-4).
API_9A_6X7_FC = [  # d [mm], mass [kg/100 m], F_min 1770 [kN], F_min 1960 [kN]
    (8, 22.1, 37.6, 41.6),
    (10, 34.5, 58.8, 65.1),
    (16, 88.3, 150, 167),
    (24, 199, 338, 375),
    (32, 353, 602, 666),
    (40, 552, 940, 1040),
]


def _half_last_digit(x):
    """Half a unit in the third significant figure of x (the table's rounding), plus float noise."""
    return 0.5 * 10 ** (math.floor(math.log10(x)) - 2) + 1e-9


@pytest.mark.parametrize("d_mm, mass, f1770, f1960", API_9A_6X7_FC)
def test_catalogue_relations_reproduce_published_table(d_mm, mass, f1770, f1960):
    d = d_mm * 1e-3
    W = 0.345 * ropes.W_CATALOGUE_UNIT
    # the table prints 3 significant figures: agreement to half a unit in the last place
    assert abs(ropes.rope_mass_per_metre(W, d) * 100 - mass) <= _half_last_digit(mass)
    for grade, table in ((1770e6, f1770), (1960e6, f1960)):
        F = ropes.minimum_breaking_force(0.332, d, grade) / 1e3
        assert abs(F - table) <= _half_last_digit(table)


def test_shipped_constructions_have_sources_and_sane_factors():
    table = ropes.constructions()
    assert set(table) == {"6x19-FC", "6x19-IWRC", "6x36-FC", "6x36-IWRC", "8x36-FC", "8x36-IWRC"}
    for c in table.values():
        assert "EN 12385-4" in c.source
        # the metallic area can not exceed the circle; the breaking factor K = C * spinning-loss < C
        assert 0 < c.K < c.C < math.pi / 4
        # the rope weighs at least its steel (density 7850 kg/m^3 over the metallic area)
        assert c.W / c.C > 7850
    # steel core ropes are heavier and stronger than fibre core ropes of the same class
    for cls in ("6x19", "6x36", "8x36"):
        assert table[f"{cls}-IWRC"].W > table[f"{cls}-FC"].W
        assert table[f"{cls}-IWRC"].K > table[f"{cls}-FC"].K
    assert ropes.grades() == [1570e6, 1770e6, 1960e6, 2160e6]
    ds = ropes.diameters()
    assert ds == sorted(ds) and ds[0] == pytest.approx(0.008) and 0.042 in [round(x, 3) for x in ds]


def _scene(**extra_effects):
    base = load()
    params = {k: v for k, v in base.parameters.items() if k not in ("q_l", "q_lw")}
    params.update({"d": 0.042, "rope_grade": "1770 N/mm^2", "rope_E": "100 kN/mm^2"})
    data = {"scene": {"name": "catalogue"}, "effects": {"power": "drive", "rope": "6x36-IWRC", **extra_effects},
            "parameters": params}
    return from_dict(data, bare="si")


def test_catalogue_rope_feeds_the_forces_and_elongation():
    res = run(_scene())
    d = 0.042
    q_l = 9.80665 * 4090.0 * d**2           # 0.409 kg/(100 m mm^2)
    A = 0.460 * d**2
    assert res["q_l"] == pytest.approx(q_l, rel=1e-12)
    assert res["m_l"] == pytest.approx(4090.0 * d**2, rel=1e-12)
    assert res["A_m"] == pytest.approx(A, rel=1e-12)
    assert res["F_min"] == pytest.approx(0.356 * d**2 * 1770e6, rel=1e-12)
    # Hooke's law over the route length: the winding rope stretches F L / (E A)
    assert res["dF_C_up"] == pytest.approx(res["F_C_up"] * 1150.0 / (100e9 * A), rel=1e-12)
    # eq. (13) by hand with the catalogue weight per metre
    a = math.radians(16)
    G_m = 467e3
    F_C_up = 0.5 * 20e3 + (G_m + q_l * 1150) * math.sin(a) + 0.05 * G_m * math.cos(a) + 0.05 * q_l * 1150 * math.cos(a)
    assert res["F_C_up"] == pytest.approx(F_C_up, rel=1e-12)


def test_named_construction_equals_explicit_factors():
    named = run(_scene())
    s = _scene()
    data = {"scene": {"name": "factors"}, "effects": {**s.effects, "rope": "catalogue"},
            "parameters": {**s.parameters, "rope_K": 0.356, "rope_W": "0.409 kg/(100 m*mm^2)", "rope_C": 0.46}}
    explicit = run(from_dict(data, bare="si"))
    for k in ("q_l", "q_lw", "F_min", "F_C_up", "dF_up"):
        assert explicit[k] == pytest.approx(named[k], rel=1e-14)


def test_rope_W_catalogue_unit_parses_to_si():
    s = _scene()
    data = {"scene": {"name": "factors"}, "effects": {**s.effects, "rope": "catalogue"},
            "parameters": {**s.parameters, "rope_K": 0.356, "rope_W": "0.409 kg/(100 m*mm^2)", "rope_C": 0.46}}
    assert from_dict(data, bare="si").parameters["rope_W"] == pytest.approx(4090.0)


def test_unknown_construction_is_named_with_a_suggestion():
    base = _scene()
    data = {"scene": {"name": "x"}, "effects": {**base.effects, "rope": "6x36-IWCR"},
            "parameters": dict(base.parameters)}
    with pytest.raises(InputError, match="did you mean '6x36-IWRC'"):
        from_dict(data, bare="si")


def test_catalogue_functions_accept_arrays_and_casadi():
    import casadi as ca

    d = np.array([0.01, 0.02])
    assert np.allclose(ropes.metallic_area(0.46, d), 0.46 * d**2)
    x = ca.SX.sym("d")
    f = ca.Function("f", [x], [ropes.unit_elongation(1000.0, 1e11, 0.46, x)])
    assert float(f(0.02)) == pytest.approx(1000.0 / (1e11 * 0.46 * 4e-4))
