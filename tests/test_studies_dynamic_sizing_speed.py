"""The dynamic sizing speed study (full: the shipped scene, the three-segment route, a "no design" answer),
ratios to one simulation of the four manoeuvres by the hybrid simulator, measured in the same run.  Truth:
each answer is the one the scene has (a design, or none), and the issue's goals — a design within 10x the
simulation, "no design" with its remedies within 30x — are asserted; a goal not yet met is a strict xfail
with the ratio measured, so it turns red the day it is met and the docs must then say so."""

from __future__ import annotations

import pytest
from _studies import load_study

pytestmark = pytest.mark.slow

#: measured in this branch (CPU seconds of one process, the peer at rtol 1e-10): see docs/machines/winch.md
NOT_MET = {"design": "measured 14-16x (the shipped scene; verification alone is 6 simulations of the four "
                     "manoeuvres: two designs x 12 cases)",
           "no design": "measured above 30x: the starts' IPOPT runs to its iteration limit before the least-violation "
                        "problem, the scan and the remedies decide"}


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    return load_study("dynamic_sizing_speed").main(tmp_path_factory.mktemp("speed"), fast=False)


def test_each_scene_gets_its_answer(table):
    assert list(table["answer"]) == ["design", "design", "no design"]
    assert (table["peer [CPU s]"] > 0).all() and (table["ratio to static"] > 1).all()


@pytest.mark.xfail(strict=True, reason=NOT_MET["design"])
def test_a_dynamic_design_within_10x_one_simulation(table):
    assert (table.loc[table["answer"] == "design", "ratio to peer"] <= 10.0).all()


@pytest.mark.xfail(strict=True, reason=NOT_MET["no design"])
def test_no_design_with_remedies_within_30x_one_simulation(table):
    assert (table.loc[table["answer"] == "no design", "ratio to peer"] <= 30.0).all()
