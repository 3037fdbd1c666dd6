"""What the dynamic sizing's re-solves read of its NLP, against the full computations they replaced (kept here as the
truth): the Jacobian's rows of the blocks holding the active checks (:meth:`DynamicSizingProblem.jacobian_rows`)
equal the rows of the whole Jacobian, and their checks (:meth:`~DynamicSizingProblem.g_rows`) those of the whole
g; the smooth mode built with the rope's quantities kept across the drive's phases equals the one built publishing
them anew, bit for bit; the active sets the warm re-solve tries (:func:`optimisation.dynamic.warm._orders`) move a
check's row to the case that violates it."""

from __future__ import annotations

import numpy as np
import pytest

from _dynamic_scene import write_scene

from optimisation.dynamic import warm
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.ipopt import _jac_functions, jacobian_at
from optimisation.problem import load_sizing
from ropemodel.effects.transient import rope


@pytest.fixture(scope="module")
def problem(tmp_path_factory):
    scene = load_sizing(write_scene(tmp_path_factory.mktemp("rows")), emit=False)
    return DynamicSizingProblem(scene, selected=[0, 3])


def test_the_rows_of_the_blocks_asked_equal_the_whole_jacobians(problem):
    xs, p = problem.x0(), problem.p0
    g_full, J_full = (np.asarray(a, float) for a in _jac_functions(problem)[0](xs, p))
    n_static = problem.g_static.numel()
    last = len(problem.constraints) - 1                 # in the last case's block
    g, J = problem.jacobian_rows(xs, p, [0, last])
    assert np.array_equal(g, g_full.ravel())
    first_case = n_static + problem._blocks[1].numel()
    assert np.isnan(J[n_static:first_case]).all()       # the first case's block: not asked, not computed
    for rows in (slice(0, n_static), slice(first_case, None)):
        np.testing.assert_allclose(J[rows], J_full[rows], rtol=1e-12, atol=1e-12 * np.abs(J_full).max())
    g_some = problem.g_rows(xs, p, [last])                # a Newton step's residual: the same integrations
    assert np.isnan(g_some[:first_case]).all() and np.array_equal(g_some[first_case:], g_full.ravel()[first_case:])
    # the kept evaluation completes itself when a row it lacks is asked
    jacobian_at(problem, xs, p, [last])
    _, J_all = jacobian_at(problem, xs, p, [0, n_static])
    assert not np.isnan(J_all[[0, n_static, last]]).any()


def test_the_smooth_mode_with_the_rope_kept_equals_the_one_published_anew(problem, monkeypatch):
    path = problem.all_paths[0]
    kept = path.sm
    monkeypatch.setattr(rope, "_same", lambda a, b: False)      # every publish builds the rope's quantities again
    anew = problem._path(problem.cases[0], problem.to_si(problem.x0())).sm
    rng = np.random.default_rng(1)
    pp = problem.pp0(path)
    x0 = np.asarray(kept.x0(pp), float).ravel()
    assert np.array_equal(x0, np.asarray(anew.x0(pp), float).ravel())
    for a, b in zip(kept.pieces, anew.pieces):
        x = x0 * (1 + 0.01 * rng.standard_normal(x0.size))
        assert np.array_equal(np.asarray(a.f(x, 1.3, pp)), np.asarray(b.f(x, 1.3, pp)))
        assert a.out.name_out() == b.out.name_out()
        for u, v in zip(a.out(x, 1.3, pp), b.out(x, 1.3, pp)):
            assert np.array_equal(np.asarray(u), np.asarray(v))


class _Named:
    def __init__(self, constraints):
        self.constraints = constraints


def test_a_check_violated_in_another_case_takes_its_rows_place():
    new = _Named(["stroke_margin_up @ segment 2",
                  "safety_margin @ upward start, x_m = 600 m, t = 1.7 s",
                  "slip_margin_back @ downward start, x_m = 1550 m, t = 2.6 s",
                  "safety_margin @ upward start, x_m = 950 m, t = 2 s",
                  "safety_margin @ upward start, x_m = 950 m, t = 2.1 s",
                  "slip_margin_fwd @ upward start, x_m = 950 m, t = 2.1 s"])
    g0 = np.array([0.0, 1e-9, 0.0, -2e-3, -3e-3, -1e-3])
    tried = list(warm._orders(new, [0, 1, 2], 3, g0, "carried"))
    assert tried[0] == ((0, 1, 2), "carried")
    # the same check's worst row in the case that violates it, in place of its old row; slip_margin_fwd has none
    assert tried[1:] == [([0, 4, 2], None)]
    assert list(warm._orders(new, [0, 1, 2], 2, g0, None)) == [(r, None) for r in ((0, 1), (0, 2), (1, 2))]
