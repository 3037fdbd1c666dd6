"""pint Quantities are read through their magnitude and unit text (ropemodel itself never imports pint)."""

import math

import pytest

import ropemodel as rm

pint = pytest.importorskip("pint")
ureg = pint.UnitRegistry()


@pytest.mark.parametrize("name, value, si", [
    ("G_m", ureg.Quantity(467, "kN"), 467e3),
    ("alpha_u", ureg.Quantity(16, "degree"), math.radians(16)),
    ("q_lw", ureg.Quantity(5.8, "mm/kN"), 5.8e-6),
    ("q_l", ureg.Quantity(80, "N/m"), 80.0),
    ("L_u", ureg.Quantity(1.15, "km"), 1150.0),
])
def test_a_pint_quantity_is_taken_in_its_unit(name, value, si):
    scene = rm.load_scene().with_values({name: value})
    assert scene.parameters[name] == pytest.approx(si, rel=1e-15)


def test_a_pint_quantity_of_the_wrong_dimension_is_refused():
    with pytest.raises(rm.InputError, match="G_m"):
        rm.load_scene().with_values({"G_m": ureg.Quantity(467, "m")})
