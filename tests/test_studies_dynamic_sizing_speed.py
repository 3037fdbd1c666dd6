"""The dynamic sizing speed study, ratios measured in the same run (CPU seconds of one process).

What it shows, and what is asserted:

* the issue's design goal (issue 23, item 3: a dynamic design within 10x one simulation of the four manoeuvres,
  the peer, measured in the same run) on the shipped scene, as the median of three rounds, each round's ratio
  its two contenders measured back to back (a shared machine's load moves both).  Measured against the
  simulator on sparse LU: 6.95x median of three rounds on a loaded 2-core machine (docs/machines/winch.md,
  "Speed"; 7.5x against the simulator on QR).  The returned (catalogue) design is verified by the simulator in
  every case within reach of a limit and at each manoeuvre's least place (on the shipped scene 5 of 12 cases), the
  others by the NLP's integration;
  and on the three-segment route, one round (``--route``): 7.18x, the median of three runs against the simulator
  on sparse LU (83.9 CPU-s against 11.7; the others 7.07x and 7.36x; a loaded 2-core machine, the peer's own time
  8.7-12.0 CPU-s in that session's runs); run at the same time as the previous code, 7.45x (89.1 CPU-s against
  12.0) against its 14.68x (148.9 against 10.1), the same design (16.3x-16.9x a session before; 8.3x against
  the simulator on QR, 18.0x before that).  The shipped scene at the same code: 6.21x (22.0 CPU-s against 3.22,
  median of three rounds).  After the merge with the least tension over the whole side, on a less loaded machine
  (a faster peer, 8.3-9.2 CPU-s): 8.43x, the median of three (8.33x, 8.96x).  The "no design" goal (30x) is met
  and asserted by ``tests/test_dynamic_no_design_speed.py`` (median of three rounds);
* the re-solves of the dynamic NLP by Newton on the previous optimum's active set
  (:mod:`optimisation.dynamic.warm`) make dynamic sizing cheaper than the same sizing with every re-solve by
  IPOPT (its peer, measured in the same run), and both return the same catalogue design.  Reason: from the
  previous optimum IPOPT re-enters the central path (16-19 iterations, each integrating the transients with
  their sensitivities); Newton on the active set takes two Jacobians (chord steps between);
* each scene gets the answer it has (a design, or none), and every contender costs something (a ratio of
  nothing is no ratio).

All exhaustive (CONTRIBUTING, test tiers): the shipped scene alone (``fast``) is three rounds of two dynamic
sizings, about 5 CPU minutes; the route alone about 2; the full study (the route once more, with its IPOPT
re-solves' sizing, and the "no design" answer) more than 15."""

from __future__ import annotations

import pytest
from _studies import load_study

#: three rounds of two dynamic sizings of the shipped scene: minutes (CONTRIBUTING, test tiers)
pytestmark = [pytest.mark.slow, pytest.mark.exhaustive]


@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    return load_study("dynamic_sizing_speed").main(tmp_path_factory.mktemp("speed"), fast=True, rounds=3)


def test_a_design_costs_at_most_ten_simulations_of_the_four_manoeuvres(shipped):
    study = load_study("dynamic_sizing_speed")
    row = shipped.iloc[0]
    assert row["rounds"] == 3 and row["answer"] == "design"
    assert row["ratio to peer"] <= study.GOAL_DESIGN == 10.0 and row["meets goal"]


def test_the_routes_design_costs_at_most_ten_simulations_of_the_four_manoeuvres(tmp_path):
    """The three-segment route (``--route``: one round, without the IPOPT re-solves' sizing), its ratio that of the
    dynamic design and the peer measured back to back in this process."""
    study = load_study("dynamic_sizing_speed")
    row = study.main(tmp_path, route=True).iloc[0]
    assert row["rounds"] == 1 and row["answer"] == "design" and row["segments"] == 32
    assert row["ratio to peer"] <= study.GOAL_DESIGN == 10.0 and row["meets goal"]


def test_the_shipped_scene_gets_its_design_both_ways(shipped):
    row = shipped.iloc[0]
    assert row["answer"] == "design" and row["same design"]
    assert row["peer [CPU s]"] > 0 and row["static [CPU s]"] > 0 and row["ratio to static"] > 1


def test_warm_resolves_are_cheaper_than_ipopt_resolves(shipped):
    assert shipped["ratio to IPOPT re-solves"].iloc[0] < 1.0


def test_each_scene_gets_its_answer(tmp_path):
    table = load_study("dynamic_sizing_speed").main(tmp_path, fast=False, rounds=1)
    assert list(table["answer"]) == ["design", "design", "no design"]
    designs = table[table["answer"] == "design"]
    assert designs["same design"].all() and (designs["ratio to IPOPT re-solves"] < 1.0).all()
    assert (table["peer [CPU s]"] > 0).all() and (table["ratio to static"] > 1).all()
