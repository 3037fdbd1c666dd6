"""The smooth mode sampled at numbers into numpy (:meth:`optimisation.dynamic.shooting.Path.samples`, through
:func:`~optimisation.dynamic.shooting.evaluate`) equals the same integration and outputs called through CasADi's
DM (the code path it replaced, kept here as the truth), bit for bit."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from _dynamic_scene import write_scene

from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.shooting import OPTS, evaluate
from optimisation.problem import load_sizing


def dm_samples(path, pp, grid):
    """The DM code path: each phase's integrator called with DM, its outputs mapped over the samples, converted."""
    q = np.asarray(pp, float)[path.moving]
    t0s, t1s = path._bounds(q)
    x = path._x0(q)
    times, cols, states = [], {}, []
    for k, (piece, tau) in enumerate(zip(path.sm.pieces, grid)):
        tau = np.asarray(tau, float)
        integ = ca.integrator(f"I_{k}", "cvodes", path._dae[k], 0.0, list(tau[1:]), OPTS)
        X = ca.horzcat(x, integ(x0=x, p=ca.vertcat(q, t0s[k], t1s[k]))["xf"])
        t = t0s[k] + (t1s[k] - t0s[k]) * ca.DM(tau).T
        out = piece.out.map(len(tau))(X, t, pp)
        for i, key in enumerate(piece.out.name_out()):
            cols.setdefault(key, []).append(out[i])
        times.append(t)
        states.append(X)
        x = X[:, -1]
    return (np.asarray(ca.horzcat(*times)).ravel(), {k: np.asarray(ca.horzcat(*v)) for k, v in cols.items()},
            np.asarray(ca.horzcat(*states)))


@pytest.fixture(scope="module")
def problem(tmp_path_factory):
    scene = load_sizing(write_scene(tmp_path_factory.mktemp("samples")), emit=False)
    return DynamicSizingProblem(scene, selected=[0])


def test_samples_at_numbers_equal_the_dm_path(problem):
    for path in problem.all_paths[::5]:
        pp = problem.pp0(path)
        grid = path.uniform_grid(pp, 0.1)
        t, o, X = path.samples(pp, grid)
        t_ref, o_ref, X_ref = dm_samples(path, pp, grid)
        assert np.array_equal(t, t_ref) and np.array_equal(X, X_ref)
        assert o.keys() == o_ref.keys()
        for k in o:
            assert o[k].shape == o_ref[k].shape and np.array_equal(o[k], o_ref[k]), k


def test_evaluate_equals_a_call_with_a_sparse_output_and_an_input_left_out():
    x, y = ca.SX.sym("x", 2, 3), ca.SX.sym("y")
    f = ca.Function("f", [x, y], [x * 2 + y, ca.sparsify(ca.vertcat(x[0, 0], 0, x[1, 2])), ca.SX(0, 4)],
                    ["x", "y"], ["a", "b", "c"])
    xv = np.arange(6.0).reshape(2, 3)
    out = evaluate(f, {"x": xv})
    ref = f.call({"x": ca.DM(xv)})
    for k in "abc":
        assert out[k].shape == ref[k].shape and np.array_equal(out[k], np.asarray(ref[k])), k
