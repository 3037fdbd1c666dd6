"""Every input has a physical domain: finite ends with their source, checked also where the value is unused.

Truths: the declarations themselves (every input of every variant of every model, and a route's segment
inputs), the closed form of the Euler–Eytelwein ratio at the domains' ends written out in numpy, and
the scene's own refusals.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.core.model import Model
from ropemodel.docs import _roles
from ropemodel.effects import REGISTRY, all_quantities, domains
from ropemodel.effects.winch_route import segment_quantities


def _inputs():
    out = [(m, all_quantities(m)[n]) for m in REGISTRY for n in _roles(m)[0]]
    return out + [("winch", q) for q in segment_quantities(1, True)]


@pytest.mark.parametrize("model, q", _inputs(), ids=lambda x: x if isinstance(x, str) else x.name)
def test_every_input_has_a_finite_domain_with_its_source(model, q):
    assert math.isfinite(q.low) and math.isfinite(q.high) and q.low < q.high, q.range_text()
    assert q.range_source.strip(), f"{model} {q.name}: where the valid range comes from"
    # the range usual for the field lies inside the domain (a usual value is a valid one)
    assert q.warn_low == -math.inf or q.in_range(q.warn_low), (q.name, q.usual_text(), q.range_text())
    assert q.warn_high == math.inf or q.in_range(q.warn_high), (q.name, q.usual_text(), q.range_text())
    if q.default is not None and not q.unlimited:
        assert q.in_range(q.default), (q.name, q.default)


def test_every_model_is_walked():
    assert {m for m, _ in _inputs()} == set(REGISTRY) and len(_inputs()) >= 60


def test_the_traction_at_the_domains_ends_stays_a_double():
    """e^{mu alpha} at the largest friction and wrap (10 over ten turns) is finite and below 1e273."""
    rho = np.exp(np.float64(domains.FRICTION_MAX) * np.float64(domains.WRAP_MAX))
    assert np.isfinite(rho) and rho < 1e273
    # and the domains say so: one more turn at that friction would pass 1e300
    assert np.exp(domains.FRICTION_MAX * (domains.WRAP_MAX + 2 * math.pi)) > 1e300


@pytest.mark.parametrize("name, value", [("n_slip", 0.5), ("alpha_d", "-3 deg"), ("mu_d", -1), ("stroke", "-1 mm"),
                                         ("n_rope", 0), ("t_ramp", "1e308 s"), ("m_t", "1e308 kg")])
def test_an_unused_value_outside_its_domain_is_refused(name, value):
    scene = rm.load_scene("example", emit=False)
    assert name not in scene.built.parameters          # the example does not use it
    with pytest.raises(rm.InputError, match=rf"{name} = .* is outside the valid range.*{name} is not used"):
        scene.with_values({name: value})
    with pytest.raises(rm.InputError, match=rf"{name} = .* is outside the valid range"):
        rm.load_scene("example", values={name: value}, emit=False)


def test_an_unused_value_meets_the_rules_too():
    """x_m is unused on the example's straight route, but the load must still be on it."""
    with pytest.raises(rm.InputError, match=r"x_m = 5000 m is beyond the return sheave at L_u = 1150 m"):
        rm.load_scene("example", values={"x_m": "5000 m"}, emit=False)


def test_an_unused_value_inside_its_domain_is_a_warning():
    scene = rm.load_scene("example", values={"mu_d": 0.3}, emit=False)
    assert "mu_d" in scene.unused and scene.unused_values["mu_d"] == 0.3
    assert any(w.startswith("mu_d is not used") for w in scene.warnings)


def test_segment_domains_reach_every_route():
    """A route's segment inputs are declared per scene (L_1, alpha_1, ...), with the same domains."""
    m = Model("winch", {"route": "segments"}, {"route": (False, True)})
    for i in (1, 2):
        assert m.quantities[f"L_{i}"].range_source == domains.ROUTE_LENGTH["range_source"]
        assert m.quantities[f"alpha_{i}"].high == math.pi / 2
