"""Dynamic sizing (issue 15): the four manoeuvres, and every check judged by the hybrid simulator."""

from __future__ import annotations

import pytest

from _dynamic_scene import simulated_failures, write_scene

from optimisation.dynamic.manoeuvres import manoeuvres
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.ramp import shortest_ramp
from optimisation.dynamic.verify import verify
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, load_sizing
from ropemodel.cli import main
from ropemodel.errors import InputError


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory):
    return write_scene(tmp_path_factory.mktemp("dyn"))


@pytest.fixture(scope="module")
def scene(scene_file):
    return load_sizing(scene_file, emit=False)


def test_natural_places_of_the_manoeuvres(scene):
    """No x_m: an upward trip starts at the return sheave (x_m = L_u) and stops at the drive (x_m = 0), a
    downward trip the other way round."""
    got = {(m.dynamics, m.travel): m.x_m for m in manoeuvres(scene)}
    assert got == {("start", "up"): 1150.0, ("stop", "up"): 0.0, ("start", "down"): 0.0, ("stop", "down"): 1150.0}
    assert all("trip" in m.source for m in manoeuvres(scene))


def test_given_place_is_used_for_all_four(scene):
    ms = manoeuvres(scene.with_values({"x_m": 300.0}))
    assert [m.x_m for m in ms] == [300.0] * 4 and all(m.source == "given" for m in ms)


def test_a_scene_without_transient_is_refused(tmp_path):
    text = write_scene(tmp_path).read_text().replace('dynamics = "start"\n', "")
    (tmp_path / "static.toml").write_text(text)
    with pytest.raises(InputError, match="transient"):
        DynamicSizingProblem(load_sizing(tmp_path / "static.toml", emit=False))


def test_static_optimum_slips_or_overloads_in_a_start(scene):
    """The static optimum (every static check met) fails in the simulated upward start: the reason for
    dynamic sizing.  The simulator names the failure."""
    static = SizingProblem(scene)
    sol = solve_continuous(static)
    assert sol.feasible
    problem = DynamicSizingProblem(scene)
    verdicts = verify(problem, sol.xs)
    up_start = verdicts[0]
    assert up_start.manoeuvre == "upward start" and not up_start.ok
    assert any(f.startswith(("slip", "safety")) for f in up_start.failures)


# ---------------------------------------------------------------------------------------- the shortest ramp
@pytest.mark.slow
def test_shortest_ramp_holds_and_a_slightly_shorter_one_fails(scene):
    """The shortest t_ramp for a given design, checked by the simulator on both sides: at the answer every
    check holds through the four manoeuvres; 1 % shorter, some check fails."""
    design = {"d": 0.048, "F_nwl": 65e3, "stroke": 3.8}
    answer = shortest_ramp(scene.with_values(design))
    t = answer.t_ramp
    assert 0.5 < t < scene.parameters["t_end"]
    assert simulated_failures(scene, design, {"t_ramp": t}) == []
    assert simulated_failures(scene, design, {"t_ramp": 0.99 * t}) != []


# ---------------------------------------------------------------------------------------- the command line
def test_cli_bad_input_exits_2(scene_file, capsys):
    assert main(["size", str(scene_file), "--find", "t_ramp"]) == 2          # --find needs --dynamic
    assert main(["size", str(scene_file), "--dynamic", "--find", "mu_d"]) == 2
    assert main(["size", str(scene_file), "--dynamic", "--find", "t_ramp"]) == 2  # no design given
    err = capsys.readouterr().err
    assert "Traceback" not in err and "needs --dynamic" in err and "must give d, F_nwl, stroke" in err


def test_cli_no_design_exits_1(scene_file, capsys):
    """n_rope so high that no catalogue rope carries even the static forces: exit 1, the check named."""
    assert main(["size", str(scene_file), "--dynamic", "--set", "n_rope=60"]) == 1
    out = capsys.readouterr()
    assert "Traceback" not in out.err and "safety" in out.out
    assert main(["size", str(scene_file), "--dynamic", "--find", "t_ramp", "--json",
                 "--set", "d=40mm", "--set", "F_nwl=40kN", "--set", "stroke=2m"]) == 1
    out = capsys.readouterr()
    assert "Traceback" not in out.err and "no ramp up to t_end" in out.err


def test_sweep_refuses_structural_parameters(tmp_path, capsys):
    """t_end fixes the manoeuvres' grids: a dynamic sizing sweep cannot vary it (exit 2, the valid names)."""
    scene_file = write_scene(tmp_path, 'd = "48 mm"\nF_nwl = "60 kN"\nstroke = "3.8 m"')
    out = tmp_path / "s.csv"
    assert main(["sweep", str(scene_file), "--sizing", "--dynamic", "--vary", "t_end=10s:14s:2", "-o", str(out)]) == 2
    assert main(["sweep", str(scene_file), "--dynamic", "--vary", "G_m=440kN:480kN:2", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "cannot vary t_end" in err and "acts only with --sizing" in err and "Traceback" not in err
