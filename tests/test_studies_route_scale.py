"""The route-scale study (studies/route_scale.py): its numbers against numpy, and what the README says of it."""

from __future__ import annotations

import pytest
from _studies import load_study

from optimisation.problem import SizingProblem, load_sizing
from ropemodel import budget


def test_sizing_checks_seven_of_a_hundred_places(tmp_path):
    """The 100-point profile of the study: 300 cases (100 places x steady, start, stop), 21 of them kept
    (CHANGELOG, studies/README.md)."""
    study = load_study("route_scale")
    x, h = study.profile(100)
    (tmp_path / "profile.csv").write_text("distance [m],height [m]\n"
                                          + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, h)))
    (tmp_path / "scene.toml").write_text(study.SIZE)
    with budget.lifted():       # 100 places x 99 segments: above the route-sizing budget
        problem = SizingProblem(load_sizing(str(tmp_path / "scene.toml"), emit=False))
    assert len(problem.all_cases) == 300
    assert len(problem.cases) == 21
    assert len({c.joint for c in problem.cases}) == 7


@pytest.mark.slow      # about 12 s: nine commands in fresh processes (it was minutes before constraint generation)
def test_route_scale_study(tmp_path):
    table = load_study("route_scale").main(tmp_path, fast=True)
    assert (tmp_path / "route_scale.png").stat().st_size > 0
    run = table[table["command"] == "run"].set_index("points")
    # the worst F_C_up over every place and manoeuvre is numpy's, at every size
    for n, row in run.iterrows():
        assert row["F_C_up"] == pytest.approx(row["F_C_up_numpy"], rel=1e-12), n
    assert set(table["command"]) == {"run", "trip", "size"}
    assert (table["peak_MB"] < 1024.0).all()
    # what studies/README.md says of the cost: each command more than a thousand times the numpy peer
    assert (table["vs_numpy"] > 1e3).all()
