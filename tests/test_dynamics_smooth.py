"""The symbolic smooth mode (``ropemodel.dynamics.smooth_mode``) for dynamic sizing.

Truths: the numeric mode that ``simulate`` integrates (built from the scene's numbers, not from
symbols), and central finite differences of that numeric mode rebuilt at perturbed scene values for
the Jacobians with respect to the parameters (the rope diameter of a catalogue rope, through q_l, EA
and the static forces; the pretension; the stroke; the ramp time).
"""

from __future__ import annotations

import tomllib
from importlib import resources

import casadi as ca
import numpy as np
import pytest

import ropemodel as rm
from ropemodel.dynamics.assemble import build
from ropemodel.dynamics.smooth import smooth_mode

DATA = resources.files("ropemodel.data")
PARAMS = ("d", "F_nwl", "stroke", "t_ramp")


def catalogue_scene(name="winch_start.toml", params=None, **effects):
    """The Fig. 9 start-up with a catalogue rope of d = 42 mm (q_l and q_lw follow from d)."""
    d = tomllib.loads(DATA.joinpath(name).read_text())
    d["effects"].update({"rope": "catalogue", **effects})
    for k in ("q_l", "q_lw"):
        d["parameters"].pop(k)
    d["parameters"].update({"d": "42 mm", "rope_grade": "1770 N/mm^2", "rope_E": "100 kN/mm^2", "rope_K": 0.356,
                            "rope_W": 4090, "rope_C": 0.46, "stroke": "6 m", "t_end": "20 s", **(params or {})})
    return rm.from_dict(d, bare="si")


def _states(system, x0, n=3, seed=1):
    rng = np.random.default_rng(seed)
    return [x0 + rng.normal(scale=1e-2, size=x0.size) * (1 + np.abs(x0)) for _ in range(n)]


@pytest.fixture(scope="module")
def case():
    sc = catalogue_scene()
    return sc, smooth_mode(sc, PARAMS), build(sc)


def test_smooth_mode_is_the_numeric_mode_at_the_scene_numbers(case):
    sc, sm, num = case
    x0, mode = num.initial()
    assert mode == num.smooth_mode()
    np.testing.assert_allclose(np.array(sm.x0(sm.p0)).ravel(), x0, rtol=1e-12, atol=1e-12)
    assert sm.phase_ends == pytest.approx((sc.parameters["t_ramp"], sc.parameters["t_end"]), rel=1e-15)
    for t, k in ((0.7, 0), (4.2, 0), (9.0, 1)):
        fns = num.functions(k, mode)
        for x in _states(num, x0):
            xdot = np.array(fns.rhs(x, t)).ravel()
            np.testing.assert_allclose(np.array(sm.f(x, t, sm.p0)).ravel(), xdot, rtol=1e-12,
                                       atol=1e-12 * np.max(np.abs(xdot)))
            cols = num.values(k, mode, x, t)
            out = sm.out(x=x, t=t, p=sm.p0)
            for name, label in (("F_C", "F_C [N]"), ("F_S", "F_S [N]"), ("take_up", "take_up [m]"),
                                ("T_min", "T_min [N]")):
                assert float(out[name]) == pytest.approx(cols[label], rel=1e-12, abs=1e-9)
            g = dict(zip(fns.g_names, np.array(fns.g(x, t)).ravel() * [s.scale for s in fns.switches]))
            assert float(out["slip_fwd"]) == pytest.approx(g["slip_fwd"], rel=1e-12, abs=1e-6)


def test_smooth_mode_jacobian_matches_finite_differences_of_rebuilt_scenes(case):
    """d/dp of f(x, t, p) and of x0(p), exact (CasADi), against central differences of the numeric mode
    built from the scene with one parameter moved by ±1e-5 of its value (they agree to 1.1e-9 of the largest
    entry of each column; the differences carry (1e-5)² truncation and rounding)."""
    sc, sm, num = case
    p = ca.SX.sym("p", len(sm.params))
    x = ca.SX.sym("x", sm.layout.nx)
    t = ca.SX.sym("t")
    J_f = ca.Function("J_f", [x, t, p], [ca.jacobian(sm.f(x, t, p), p)])
    J_x0 = ca.Function("J_x0", [p], [ca.jacobian(sm.x0(p), p)])
    x0, mode = num.initial()
    cases = [(x, tt, k) for x in _states(num, x0, n=2) for tt, k in ((2.0, 0), (8.0, 1))]
    for i, name in enumerate(sm.params):
        h = 1e-5 * sm.p0[i]
        plus, minus = (build(sc.with_values({name: sm.p0[i] + s * h})) for s in (1, -1))
        fd_x0 = (plus.initial()[0] - minus.initial()[0]) / (2 * h)
        exact = np.array(J_x0(sm.p0))[:, i]
        np.testing.assert_allclose(exact, fd_x0, rtol=1e-8, atol=1e-8 * np.max(np.abs(fd_x0)) + 1e-12)
        for xx, tt, k in cases:
            fd = (np.array(plus.functions(k, mode).rhs(xx, tt)).ravel()
                  - np.array(minus.functions(k, mode).rhs(xx, tt)).ravel()) / (2 * h)
            exact = np.array(J_f(xx, tt, sm.p0))[:, i]
            np.testing.assert_allclose(exact, fd, rtol=1e-8, atol=1e-8 * np.max(np.abs(fd)) + 1e-12)


@pytest.mark.parametrize("params,match", [
    (["x_m"], "structure"),
    (["L_u", "d"], "structure"),
    (["G_mx"], "not a parameter"),
])
def test_smooth_mode_bad_parameters(case, params, match):
    with pytest.raises(rm.InputError, match=match):
        smooth_mode(case[0], params)


def test_voigt_lining_smooth_mode_is_the_numeric_mode():
    """A Voigt-lined drum: the slip function uses Hajduk's ratio of the slack-side force (symbolic in F_nwl)."""
    sc = catalogue_scene(params={"Q": "2e-6 1/N", "lambda": "0.05 s", "D": "2.5 m"}, lining="voigt")
    sm, num = smooth_mode(sc, ["F_nwl", "d"]), build(sc)
    x0, mode = num.initial()
    for t, k in ((1.0, 0), (6.0, 1)):
        fns = num.functions(k, mode)
        for x in _states(num, x0, n=2):
            g = dict(zip(fns.g_names, np.array(fns.g(x, t)).ravel() * [s.scale for s in fns.switches]))
            out = sm.out(x=x, t=t, p=sm.p0)
            assert float(out["slip_fwd"]) == pytest.approx(g["slip_fwd"], rel=1e-12, abs=1e-6)
            assert float(out["slip_back"]) == pytest.approx(g["slip_back"], rel=1e-12, abs=1e-6)


def test_inextensible_rope_smooth_mode_is_the_numeric_mode():
    """An inextensible rope: one node, the tensioner's carriage fixed (its only mode); with d, F_nwl, stroke and
    t_ramp as symbols the start and the right-hand side are the numeric mode's (before: the symbolic start failed
    on the one-node state, and the smooth mode let the carriage run free)."""
    sc = catalogue_scene(rope_elasticity="rigid")
    sm, num = smooth_mode(sc, PARAMS), build(sc)
    x0, mode = num.initial()
    assert mode == num.smooth_mode() and dict(mode.items)["tensioner"] == "fixed"
    np.testing.assert_allclose(np.array(sm.x0(sm.p0)).ravel(), x0, rtol=1e-12, atol=1e-12)
    for t, k in ((0.7, 0), (9.0, 1)):
        fns = num.functions(k, mode)
        for x in _states(num, x0):
            xdot = np.array(fns.rhs(x, t)).ravel()
            np.testing.assert_allclose(np.array(sm.f(x, t, sm.p0)).ravel(), xdot, rtol=1e-12,
                                       atol=1e-12 * np.max(np.abs(xdot)))
