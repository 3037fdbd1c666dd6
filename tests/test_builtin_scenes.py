"""Every scene shipped in the package loads by name and runs to finite SI numbers."""

import json
import math

import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.scene import builtin_scenes


def test_example_is_fig9():
    assert rm.load_scene().name == rm.load_scene("example").name == rm.load_scene("krauze2025_fig9").name


@pytest.mark.parametrize("name", builtin_scenes())
def test_builtin_scene_runs(name, capsys):
    assert main(["run", name, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out and all(math.isfinite(v) for v in out.values() if isinstance(v, float))


def test_misspelt_builtin_name_suggests(capsys):
    assert main(["run", "capstan_li_experimnt"]) == 2
    assert "did you mean 'capstan_li_experiment'" in capsys.readouterr().err
