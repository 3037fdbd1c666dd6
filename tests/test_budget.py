"""Work budgets: a job's size counted before it starts, refused above its budget, run with --no-limit.

Truths: the counts written out here from their definitions (history rows t_end/sim_dt + 1, Sobol
evaluations N(D + 2), route sizing load cases built x segments), and the documentation's table of budgets.
"""

from __future__ import annotations

import re

import pytest

from _docs_text import section
from _fuzz_classes import route_scene
from ropemodel import budget
from ropemodel.cli import main
from ropemodel.envelope import load_cases
from ropemodel.envelope.prune import prune
from ropemodel.errors import InputError


def _error(capsys) -> str:
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if not line.startswith("warning: ")]
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    return lines[0]


def test_a_long_transient_is_refused_with_its_rows(capsys):
    assert main(["simulate", "winch_start", "--set", "t_end=1e6s"]) == 2
    err = _error(capsys)
    rows = 1e6 / 0.02 + 1                              # winch_start's [numerics] sim_dt = 0.02 s
    assert f"{rows:,.0f} history rows" in err and "budget of 1,000,000" in err and "--no-limit" in err


def test_no_limit_runs_it_and_does_not_outlive_its_command(monkeypatch, capsys):
    """With a budget of 100 rows the 60 s start-up (3001 rows at 0.02 s) is refused, runs with --no-limit, and
    is refused again by the next command without it (the flag is the command's, not the process's)."""
    monkeypatch.setitem(budget.BUDGETS, "history", budget.Budget(100, "history rows", "test"))
    assert main(["simulate", "winch_start"]) == 2
    assert "3,001 history rows" in _error(capsys)
    assert main(["simulate", "winch_start", "--no-limit"]) == 0
    assert main(["--no-limit", "simulate", "winch_start"]) == 0
    capsys.readouterr()
    assert main(["simulate", "winch_start"]) == 2


def test_a_large_sobol_study_is_refused_with_its_evaluations(capsys):
    n, d = 2**20, 2
    assert main(["sensitivity", "example", "--sobol", "G_m=400kN:467kN", "--sobol", "alpha_u=10deg:20deg",
                 "--samples", str(n)]) == 2
    assert f"{n * (d + 2):,} evaluations" in _error(capsys)


@pytest.mark.parametrize("n, refused", [(49, False), (50, True)])
def test_sizing_at_every_place_is_counted_by_its_segments(n, refused, tmp_path):
    """n segments, every place checked (a sizing sweep, which may move the governing place): the load at each of
    the n + 1 places that bound them (the drive, the joints, the return sheave), each through the n segments:
    (n + 1) n segment evaluations; 49 segments (2450) are within the budget's 2500, 50 (2550) are not."""
    from optimisation.problem import SizingProblem, load_sizing

    scene = tmp_path / "route.toml"
    scene.write_text(route_scene(n, "1 m"))
    if not refused:   # the NLP is built (not solved): at the budget it is not refused
        assert len(SizingProblem(load_sizing(scene, emit=False), prune_places=False).cases) == n + 1
        return
    with pytest.raises(InputError, match=f"{(n + 1) * n:,} segment evaluations"):
        SizingProblem(load_sizing(scene, emit=False), prune_places=False)


def test_size_builds_few_cases_and_the_whole_nlp_is_counted(tmp_path, capsys):
    """``size`` makes its checks at the cases where each can be least and adds those a design leaves below zero
    (optimisation.generation; every design checked at every place that can govern): 1000 segments are sized
    (the NLP holds a few cases, not counted against the budget).  The NLP of every place that can govern
    (``sensitivity --sizing``, ``size --dynamic``'s start) is refused with the count of its cases (at least the
    route's two ends, far fewer than its 1001 places) times the segments."""
    import json

    from optimisation.problem import SizingProblem, load_sizing, prepare

    n = 1000
    scene = tmp_path / "route.toml"
    scene.write_text(route_scene(n, "1 m"))
    assert main(["size", str(scene), "--json"]) == 0
    cases = json.loads(capsys.readouterr().out)["load_cases"]
    assert cases["in_nlp"] <= cases["candidates"] < cases["cases"] == n + 1     # steady motion: one case a place
    sized = prepare(load_sizing(scene, emit=False))
    kept = len(prune(load_cases(sized), sized.parameters, sized.built))
    assert kept == cases["candidates"] and 2 <= kept < n + 1 and kept * n > budget.BUDGETS["route sizing"].limit
    with pytest.raises(InputError, match=f"{kept * n:,} segment evaluations"):
        SizingProblem(sized)


def test_lifted_restores():
    assert not budget._LIFTED
    with budget.lifted():
        assert budget._LIFTED
    assert not budget._LIFTED


def test_readme_states_every_budget():
    """The documentation's table (the scene reference, "Writing a scene") gives each budget (and only those)."""
    text = section("Writing a scene")
    block = text[text.index("**Work budgets.**"):]
    block = block[:block.index("\n\n", block.index("| job |"))]
    shown = re.findall(r"\| (10\^\d+|2\^\d+|\d+) \|", block)
    values = [eval(v.replace("^", "**")) for v in shown]   # noqa: S307 - the README's own numbers
    assert sorted(values) == sorted(b.limit for b in budget.BUDGETS.values())


def _long_route(n: int) -> str:
    """route_segments (Fig. 9 load) on ``n`` segments of 2 m at 5-11 deg."""
    from _fuzz import builtin

    text = builtin("route_segments")
    head, params = text[:text.index("[[route]]")], text[text.index("[parameters]"):]
    segments = "".join(f'[[route]]\nlength = "2 m"\ninclination = "{5 + i % 7} deg"\n' for i in range(n))
    return head + segments + params


def test_an_inverse_solve_on_a_long_route_is_refused_with_its_count(tmp_path, capsys, monkeypatch):
    """``solve --find`` on a route of segments (the segment form: held as route numbers from more than
    VECTOR_ABOVE segments, raised here) answers at every load case through the whole route: load cases x segments
    counted, refused above the budget with the count and the fix (pin the place); pinned by ``--at x_m=``, it
    is one root-find and runs."""
    from ropemodel import load_scene
    from ropemodel.effects import winch_route_vector
    from ropemodel.envelope.cases import with_ramps

    monkeypatch.setattr(winch_route_vector, "VECTOR_ABOVE", 10**6)

    n = 400
    scene = tmp_path / "route.toml"
    scene.write_text(_long_route(n))
    cases = len(load_cases(with_ramps(load_scene(scene)), pinned=["G_m"]))
    assert cases * n > budget.BUDGETS["route solve"].limit
    argv = ["solve", str(scene), "--find", "G_m", "--given", "F_C_up=100kN"]
    assert main(argv) == 2
    err = _error(capsys)
    assert f"{cases * n:,} evaluations" in err and f"through the {n} segments" in err
    assert "--at x_m=" in err and "--no-limit" in err
    assert main([*argv, "--at", "x_m=400m", "--json"]) == 0
    capsys.readouterr()


def test_an_inverse_solve_on_a_route_held_as_route_numbers_is_counted_case_by_case(tmp_path, capsys):
    """Held as route numbers (more than VECTOR_ABOVE segments), each case is a few numbers, but each case's answer
    may be checked at every case: load cases x load cases counted (measured: 9 million at 999 segments, 36 CPU-s;
    quadratic in the places, so a 10 000-point profile would take about an hour), refused above the budget with
    the count and the fix; pinned by ``--at x_m=``, one root-find, it runs."""
    from ropemodel import load_scene
    from ropemodel.envelope.cases import with_ramps

    n = 200
    scene = tmp_path / "route.toml"
    scene.write_text(_long_route(n))
    assert load_scene(scene).built.derived                   # held as route numbers
    cases = len(load_cases(with_ramps(load_scene(scene)), pinned=["G_m"]))
    assert cases * cases > budget.BUDGETS["route solve"].limit
    argv = ["solve", str(scene), "--find", "G_m", "--given", "F_C_up=100kN"]
    assert main(argv) == 2
    err = _error(capsys)
    assert f"{cases * cases:,} evaluations" in err and "each answer checked at every case" in err
    assert "--at x_m=" in err and "--no-limit" in err
    assert main([*argv, "--at", "x_m=300m", "--json"]) == 0
    capsys.readouterr()


def test_an_inverse_solve_on_a_short_route_is_not_counted_against_it(capsys):
    """The shipped three-segment route: far under the budget, answered."""
    assert main(["solve", "route_segments", "--find", "G_m", "--given", "F_C_up=100kN", "--json"]) == 0
    capsys.readouterr()
