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
    """Each point equals ``rm.run`` at it: one solve, or on a scene that leaves the load's place or the manoeuvre
    open each output's worst over the cases (reduced by numpy there, inside the swept Function here), and the
    place and acceleration of its governing case (the ``@x_m``, ``@a_h`` columns)."""
    scene = rm.load_scene(str(resources.files("ropemodel.data").joinpath(name)))
    par, values = _swept_parameter(scene)
    frame = rm.sweep(scene, {par: values}, si=True, progress=False)
    for i, v in enumerate(values):
        single = rm.run(scene.with_values({par: v}))
        env = getattr(single, "envelope", None)
        for col in frame.columns[1:]:
            out, _, inp = col.split(" [")[0].partition("@")
            got = frame.loc[i, col]
            if inp and out in env.constant:       # the same in every case (the least at the return sheave): any
                assert got in {c.values(env.params)[inp] for c in env.cases}, (name, col)
                continue
            if inp:
                want = env.worst(out).case.values(env.params)[inp]
            else:
                want = single[out]
            assert got == pytest.approx(want, rel=1e-10, abs=1e-12), (name, par, v, col)
        assert {c.split(" [")[0] for c in frame.columns[1:] if "@" not in c} == set(single.outputs)
    assert np.isfinite(frame.to_numpy(dtype=float)).all()
