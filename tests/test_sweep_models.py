"""Sweeps of every built-in scene (winch, sheave, capstan, ...) equal single solves point by point."""

from importlib import resources

import numpy as np
import pytest

import ropemodel as rm

SCENES = sorted(p.name for p in resources.files("ropemodel.data").iterdir() if p.name.endswith(".toml")
                and p.name != "ropes.toml")


def _swept_parameter(scene):
    """The first nonzero parameter that can move ±5 % and stay valid."""
    q = scene.built.quantities
    for name, value in scene.parameters.items():
        if value == 0.0:
            continue
        values = [value * f for f in (0.95, 1.0, 1.05)]
        if not all(q[name].in_range(v) for v in values):
            continue
        try:
            for v in values:
                scene.with_values({name: v})
        except rm.InputError:
            continue
        return name, values
    raise AssertionError("no parameter to sweep")


@pytest.mark.parametrize("name", SCENES)
def test_sweep_equals_single_solves(name):
    scene = rm.load_scene(str(resources.files("ropemodel.data").joinpath(name)))
    par, values = _swept_parameter(scene)
    frame = rm.sweep(scene, {par: values}, si=True, progress=False)
    problem = rm.Problem(scene)
    for i, v in enumerate(values):
        single = problem.solve({par: v})
        for j, out in enumerate(problem.unknowns):
            got = frame.iloc[i, 1 + j]
            assert got == pytest.approx(single[out], rel=1e-10, abs=1e-12), (name, par, v, out)
    assert np.isfinite(frame.to_numpy(dtype=float)).all()
