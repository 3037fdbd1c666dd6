"""Dynamic sizing (issue 15): the four manoeuvres, and every check judged by the hybrid simulator."""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np
import pytest

import _route3 as route3
from _dynamic_scene import MANOEUVRES, N_SLIP_DYNAMIC, simulated_failures, write_scene

from optimisation.dynamic.manoeuvres import cases, manoeuvre_scene
from optimisation.dynamic.ramp import shortest_ramp
from optimisation.dynamic.sensitivity import timing_params
from optimisation.dynamic.transient import reads, transient_scene
from optimisation.ipopt import solve_continuous
from optimisation.problem import SizingProblem, load_sizing
from ropemodel.cli import main
from ropemodel.dynamics.smooth import smooth_mode


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory):
    return write_scene(tmp_path_factory.mktemp("dyn"))


@pytest.fixture(scope="module")
def scene(scene_file):
    return load_sizing(scene_file, emit=False)


def test_every_manoeuvre_at_both_ends_and_the_middle(scene):
    """No x_m: each of the four manoeuvres with the load at the drive, in the middle and at the return sheave
    of the (straight) route."""
    got = [(m.dynamics, m.travel, m.x_m) for m in cases(transient_scene(scene))]
    assert got == [(dyn, travel, x) for dyn, travel in MANOEUVRES for x in (0.0, 575.0, 1150.0)]


def test_given_place_is_used_for_all_four(scene):
    ms = cases(transient_scene(scene.with_values({"x_m": 300.0})))
    assert [m.x_m for m in ms] == [300.0] * 4 and all(m.where == "x_m = 300 m (given)" for m in ms)


#: the route of issue 21 without its ramp time: a winch sizing scene with no transient in it
ROUTE = route3.SCENE.replace('t_ramp = "4 s"\n', "")


def test_a_static_route_scene_is_asked_only_for_its_ramp_then_accepted(tmp_path, capsys):
    """A winch sizing scene on a route of segments, no transient in it: ``size --dynamic`` asks for the one
    thing it cannot default, the ramp time (exit 2, one line, nothing on stdout).  Given it, the transient is
    built: the manoeuvres with the load at the ends and the middle of every segment (a joint from both
    sides), and each default stated — t_end from the rope loop's slowest period."""
    path = tmp_path / "route.toml"
    path.write_text(ROUTE)
    assert main(["size", str(path), "--dynamic"]) == 2
    out = capsys.readouterr()
    assert out.out == "" and "Traceback" not in out.err
    lines = [ln for ln in out.err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "t_ramp" in lines[0] and "dynamic sizing" in lines[0]
    sc = transient_scene(load_sizing(path, emit=False).with_values({"t_ramp": "4 s"}))
    places = [0.0, 300.0, 600.0, 600.001, 950.0, 1300.0, 1300.001, 1550.0, 1800.0]
    assert [m.x_m for m in cases(sc)] == pytest.approx([x for _ in MANOEUVRES for x in places], abs=1e-9)
    assert {"t_end", "m_t", "rope_damping", "v_eps", "x_m"} <= set(sc.defaults)
    assert "T_1" in sc.defaults["t_end"] and sc.parameters["t_end"] > sc.parameters["t_ramp"]
    assert sc.effects["rope_elasticity"] == "segments" and sc.effects["tensioner"] == "constant_force"
    names, sets = reads(sc)        # what a --set reaches: the transient's own parameters too
    assert {"t_ramp", "t_end", "rope_damping", "m_t", "G_m", "alpha_2"} <= names and "x_m" in sets


@pytest.mark.parametrize("name, asked", [
    ("winch_sizing_fig9", ["t_ramp"]),
    ("winch_sizing_voigt", ["t_ramp"]),
    # both at once, not one after the other: the rope (with what a rope construction would still need) and the ramp
    ("winch_sizing_paper_rope", ['rope = "given"', "rope_grade", "rope_E", "q_l", "t_ramp"]),
])
def test_shipped_sizing_scenes_are_asked_for_everything_at_once(name, asked, capsys):
    """Each shipped winch sizing scene has no ramp: ``size --dynamic`` names every missing item in one error
    (exit 2, one line each, nothing on stdout), before any computation."""
    assert main(["size", name, "--dynamic"]) == 2
    out = capsys.readouterr()
    assert out.out == "" and "Traceback" not in out.err
    problems = [ln for ln in out.err.splitlines() if ln.strip() and not re.match(r"error: \d+ problems:$", ln)]
    assert len(problems) == len(asked)
    for line, word in zip(problems, asked):
        assert word in line


def test_static_optimum_slips_or_overloads_in_a_start(scene):
    """The static optimum (every static check met) fails in the simulated upward start from the return sheave:
    the reason for dynamic sizing."""
    static = SizingProblem(scene)
    sol = solve_continuous(static)
    assert sol.feasible
    failures = simulated_failures(scene, static.to_si(sol.xs), manoeuvres=[("start", "up")], where=[1150.0])
    assert any(f.startswith(("slip", "rope safety")) for f in failures), failures


# ---------------------------------------------------------------------------------------- the shortest ramp
@pytest.mark.slow
@pytest.mark.exhaustive     # minutes: not in CI (CONTRIBUTING, "Test tiers")
def test_shortest_ramp_holds_and_a_slightly_shorter_one_fails(scene):
    """The shortest t_ramp for a given design, checked by the simulator on both sides: at the answer every
    check holds through the four manoeuvres, the slip reserve n_slip_dynamic among them; 1 % shorter, some
    check fails."""
    design = {"d": 0.048, "F_nwl": 65e3, "stroke": 3.8}
    answer = shortest_ramp(scene.with_values(design))
    t = answer.t_ramp
    assert 0.5 < t < scene.parameters["t_end"]
    assert simulated_failures(scene, design, {"t_ramp": t}, slip_factor=N_SLIP_DYNAMIC) == []
    assert simulated_failures(scene, design, {"t_ramp": 0.99 * t}, slip_factor=N_SLIP_DYNAMIC) != []


# ---------------------------------------------------------------------------------------- the command line
def test_cli_bad_input_exits_2(scene_file, capsys):
    assert main(["size", str(scene_file), "--find", "t_ramp"]) == 2          # --find needs --dynamic
    assert main(["size", str(scene_file), "--dynamic", "--find", "mu_d"]) == 2
    assert main(["size", str(scene_file), "--dynamic", "--find", "t_ramp"]) == 2  # no design given
    err = capsys.readouterr().err
    assert "Traceback" not in err and "needs --dynamic" in err and "must give d, F_nwl, stroke" in err


def test_cli_no_design_exits_1(scene_file, capsys):
    """n_rope so high that no catalogue rope carries even the static forces: exit 1, the check named in words."""
    assert main(["size", str(scene_file), "--dynamic", "--set", "n_rope=60"]) == 1
    out = capsys.readouterr()
    assert "Traceback" not in out.err and "rope force F_C <= F_min/n_rope" in out.out and "safety_margin" not in out.out
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


def test_an_inextensible_rope_states_only_the_defaults_it_reads(tmp_path):
    """The route with an inextensible rope: no element to damp (rope_damping is no default used), no oscillation
    (t_end is the ramp and half a ramp more: 6 s for the 4 s ramp)."""
    path = tmp_path / "rigid.toml"
    path.write_text(route3.SCENE.replace('power = "drive"\n', 'power = "drive"\nrope_elasticity = "rigid"\n'))
    sc = transient_scene(load_sizing(path, emit=False))
    assert "rope_damping" not in sc.defaults and {"x_m", "v_eps", "t_end"} <= set(sc.defaults)
    assert sc.parameters["t_end"] == pytest.approx(6.0, rel=1e-12)


def test_no_catalogue_size_says_the_drum_check_fails_at_the_next_size():
    """winch_sizing_voigt with a 4 s ramp: its continuous dynamic optimum, 52.96 mm, is under the drum's limit
    D / D_ratio_min = 1.6 m / 30 = 53.3 mm, so the next catalogue size, 54 mm, breaks D / d >= 30 whatever
    the pretension and stroke: the answer says so, and what alone would help (D >= 30 * 54 mm = 1.62 m)."""
    from types import SimpleNamespace

    from optimisation.dynamic.design import DynamicDesign, why_no_size

    scene = load_sizing("winch_sizing_voigt", emit=False)
    D, ratio = scene.parameters["D"], scene.parameters["D_ratio_min"]
    assert D / ratio == pytest.approx(0.05333, abs=1e-5) and D / 0.054 < ratio
    design = DynamicDesign(scene, False, message="no catalogue diameter")
    why_no_size(SimpleNamespace(scene=scene), 0.05296, design)
    assert "the next size up, 54 mm, already fails the static checks" in design.message
    assert "drum_margin" in design.message and f"D >= {ratio * 54:g} mm" in design.message


@pytest.mark.parametrize("ramp", ["linear", "scurve"])
def test_the_ramps_timing_is_read_from_where_its_phases_meet(tmp_path, ramp):
    """The parameters that get no sensitivity of the dynamic optimum (they move the instant a peak sits at) are
    those the phases' ends depend on: t_ramp for a linear ramp; for an S-curve also jerk_max and v_pj, through
    its jerk phases' ends t_ramp s_j and t_ramp (1 - s_j), s_j (1 - s_j) = v_pj/(J t_ramp^2) (written out here:
    the phase bounds at the scene's numbers are those)."""
    extra = ("jerk_max",) if ramp == "scurve" else ()
    path = write_scene(tmp_path, 'jerk_max = "1 m/s^3"' if extra else "")
    path.write_text(path.read_text().replace('rope_elasticity = "segments"',
                                             f'ramp = "{ramp}"\nrope_elasticity = "segments"'))
    sc = transient_scene(load_sizing(path, emit=False))
    design = {"d": 0.03, "F_nwl": 2e5, "stroke": 3.0}
    names = ("d", "F_nwl", "stroke", "t_ramp", "v_pj", "G_m", "mu_d", *extra)
    paths = []
    for m in cases(sc)[::3][:2]:       # an upward start and an upward stop
        sm = smooth_mode(manoeuvre_scene(sc, m, design, ("d", "F_nwl", "stroke")), names)
        paths.append(SimpleNamespace(sm=sm, names=names))
        t0, t1 = (np.asarray(b, float).ravel() for b in sm.bounds(sm.p0))
        T = 4.0
        if ramp == "scurve":
            sj = (1 - np.sqrt(1 - 4 * 2.5 / (1.0 * T**2))) / 2
            assert t1[:3] == pytest.approx([T * sj, T * (1 - sj), T], rel=1e-12)
        else:
            assert t1[0] == pytest.approx(T, rel=1e-12)
        assert t1[-1] == pytest.approx(12.0) and t0[0] == 0.0
    expected = {"t_ramp", "jerk_max", "v_pj"} if ramp == "scurve" else {"t_ramp"}
    assert timing_params(SimpleNamespace(all_paths=paths)) == expected


# ---------------------------------------------------------------------- the continuous optimum's record


@pytest.mark.slow
def test_the_nlps_own_record_of_a_design_is_the_simulators(scene):
    """The continuous optimum is reported through the NLP's own integration (``integrated``), not simulated:
    in every case the hybrid simulator runs smoothly through (no event), each check's least margin there agrees
    with the simulator's to half the NLP's back-off — what the NLP leaves for the difference between its
    integrator and the simulator's (optimisation.dynamic.refine) — at a design near the optimum (the static
    design with the transient's own factors, the sizing's start)."""
    from optimisation.design import solve_best
    from optimisation.dynamic.problem import BACKOFF, DynamicSizingProblem
    from optimisation.dynamic.start import factored_start
    from optimisation.dynamic.verify import integrated, verify

    problem = DynamicSizingProblem(scene)
    xs = factored_start(problem, solve_best(SizingProblem(problem.scene)).xs)
    ours, simulated = integrated(problem, xs, 1e-3), verify(problem, xs)
    smooth = [i for i, v in enumerate(simulated) if all(f.split()[0] in v.least for f in v.failures)]  # no event
    assert len(smooth) >= len(simulated) // 2, [v.failures for v in simulated]
    for i in smooth:
        assert ours[i].scaled.keys() == simulated[i].scaled.keys()
        for check, value in simulated[i].scaled.items():
            assert ours[i].scaled[check] == pytest.approx(value, abs=0.5 * BACKOFF), (simulated[i].where, check)
