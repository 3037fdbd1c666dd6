"""The dynamic sizing study in --fast mode (the Fig. 9 route, a 4 s ramp): the findings the README quotes."""

from __future__ import annotations

import pytest
from _studies import load_study

pytestmark = [pytest.mark.slow, pytest.mark.exhaustive]     # minutes each: not in CI (CONTRIBUTING, "Test tiers")


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    out = tmp_path_factory.mktemp("dynamic_sizing")
    df = load_study("dynamic_sizing").main(out, fast=True)
    assert (out / "dynamic_sizing.csv").exists() and (out / "dynamic_sizing.png").exists()
    return df.set_index("method")


def test_static_sizing_misses_and_fails_in_the_upward_start(table):
    s = table.loc["static"]
    assert s["d vs dynamic [%]"] == pytest.approx(-19, abs=0.5)
    assert s["F_nwl vs dynamic [%]"] == pytest.approx(-29, abs=0.5)
    assert not s["ok"] and "upward start" in s["failures"]


def test_a_flat_factor_1_1_still_misses_and_fails(table):
    s = table.loc["static x 1.1"]
    assert s["d vs dynamic [%]"] == pytest.approx(-14, abs=0.5)
    assert s["F_nwl vs dynamic [%]"] == pytest.approx(-20, abs=0.5)
    assert not s["ok"]


def test_the_transients_own_factor_holds_but_wastes(table):
    s = table.loc["static x k"]
    assert s["k"] == pytest.approx(1.48, abs=0.005)
    assert s["ok"]
    assert s["d vs dynamic [%]"] == pytest.approx(6, abs=0.5)
    assert s["F_nwl vs dynamic [%]"] == pytest.approx(21, abs=0.5)


def test_dynamic_design_holds_and_costs_hundreds_of_static_solves(table):
    d = table.loc["dynamic"]
    assert d["ok"]
    assert d["time ratio"] > 100      # measured 390-700 on this machine (same run)
