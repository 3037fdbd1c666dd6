"""The batched active-set Newton (optimisation.activeset) against closed forms on small NLPs.

Projection of p onto the half-plane x0 + x1 <= 1 with x1 >= 0:

    min (x0 - p0)² + (x1 - p1)²   s.t.   g = 1 - x0 - x1 >= 0,   x1 >= 0

* p0 + p1 > 1 and p1 - p0 > -1: the optimum is on the edge, x = p - (s/2)(1, 1), s = p0 + p1 - 1, with
  CasADi's multiplier λ = -s (one active constraint: the KKT rows with the Hessian are needed);
* p1 - p0 < -1 (and p0 + p1 > 1): the corner (1, 0) (a vertex: the edge and the bound x1 >= 0);
* p0 + p1 < 1, p1 > 0: the interior, x = p.
"""

import casadi as ca
import numpy as np
import pytest

from optimisation.activeset import BatchNLP, Mode

RNG = np.random.default_rng(7)


def projection():
    x, p = ca.MX.sym("x", 2), ca.MX.sym("p", 2)
    f = ca.sumsqr(x - p)
    g = 1 - x[0] - x[1]
    return BatchNLP(x, p, f, g, [-np.inf, 0.0], [np.inf, np.inf], [0, 1], [0.0, 0.0])


def mode(constraints=(), bounds=(), x=(0.5, 0.5)):
    return Mode(tuple(constraints), tuple(bounds), np.array(x, dtype=float), np.zeros(1), np.zeros(2))


def test_edge_points_are_accepted_with_the_closed_form_and_its_multiplier():
    nlp = projection()
    s = RNG.uniform(0.1, 2.0, 200)
    t = RNG.uniform(-0.9, 0.9, 200) * (1 + s)           # p1 - p0 in (-(1+s), 1+s): the edge
    P = np.column_stack([(1 + s - t) / 2, (1 + s + t) / 2])
    P = P[P[:, 1] - P[:, 0] > -1 + 1e-3]
    res = nlp.solve(mode([0]), P)
    assert res.ok.all()
    s = P.sum(axis=1) - 1
    np.testing.assert_allclose(res.x, P - s[:, None] / 2, atol=1e-14)
    np.testing.assert_allclose(res.lam_g[:, 0], -s, atol=1e-13)


def test_wrong_active_sets_are_rejected():
    nlp = projection()
    inside = np.array([[0.2, 0.3], [0.4, 0.1]])          # interior: the edge's multiplier has the wrong sign
    assert not nlp.solve(mode([0]), inside).ok.any()
    corner = np.array([[3.0, 0.5], [2.0, -0.5]])          # beyond the corner: the edge point has x1 < 0
    assert not nlp.solve(mode([0]), corner).ok.any()
    assert not nlp.solve(mode(), corner).ok.any()          # unconstrained: infeasible
    edge = np.array([[1.0, 1.0]])                          # the corner's bound multiplier has the wrong sign
    assert not nlp.solve(mode([0], [(1, "lower")], x=(1.0, 0.0)), edge).ok.any()


def test_vertex_and_interior_points():
    nlp = projection()
    corner = np.column_stack([RNG.uniform(2.5, 5.0, 50), RNG.uniform(-2.0, 0.5, 50)])
    corner = corner[corner[:, 1] - corner[:, 0] < -1 - 1e-3]
    res = nlp.solve(mode([0], [(1, "lower")], x=(0.9, 0.0)), corner)
    assert res.ok.all()
    np.testing.assert_allclose(res.x, np.tile([1.0, 0.0], (len(corner), 1)), atol=1e-15)
    # multipliers from 2(x - p) + λ(-1, -1) + ν(0, 1) = 0 at x = (1, 0)
    lam = 2 * (1 - corner[:, 0])
    np.testing.assert_allclose(res.lam_g[:, 0], lam, atol=1e-12)
    np.testing.assert_allclose(res.lam_x[:, 1], lam + 2 * corner[:, 1], atol=1e-12)
    inside = np.column_stack([RNG.uniform(0.01, 0.45, 50), RNG.uniform(0.01, 0.45, 50)])
    res = nlp.solve(mode(), inside)
    assert res.ok.all()
    np.testing.assert_allclose(res.x, inside, atol=1e-14)


def test_a_stationary_maximum_along_the_active_constraint_is_rejected():
    """min x0·x1 s.t. x0 + x1 >= 1: (½, ½) is a KKT point with λ = -½ (the right sign), but along the edge
    x0·(1 - x0) has its maximum there; the reduced Hessian (-2) says so."""
    x, p = ca.MX.sym("x", 2), ca.MX.sym("p", 1)
    nlp = BatchNLP(x, p, x[0] * x[1] + 0 * p, x[0] + x[1] - 1, [-10, -10], [10, 10], [0], [0.0])
    res = nlp.solve(mode([0], x=(0.4, 0.6)), np.zeros((1, 1)))
    np.testing.assert_allclose(res.x[0], [0.5, 0.5], atol=1e-14)
    assert res.lam_g[0, 0] == pytest.approx(-0.5, abs=1e-14)
    assert not res.ok[0]
