"""The capstan accuracy study runs in --fast mode and its claims hold; the README's claims on the full run."""

from __future__ import annotations

import pytest
from _studies import load_study


def _check(mod, df, tmp_path):
    """The README's claims that hold on any sample: the default rotation meets rtol 1e-7 against the
    event-located reference, its estimate delta_error stays between the true error and rtol (also at the
    study's other rtol); and the default is at least 100x faster per point than the peer measured in the same
    run: the cheapest scipy solve_ivp configuration (plain numpy right side) as accurate on the same drives or,
    where none is, the most accurate of them (the cheapest within a factor 2 of the best scipy error).
    Measured 5000-6000x compiled to C and about 750x on CasADi's virtual machine (no C compiler)."""
    assert (tmp_path / "capstan_accuracy.png").exists()
    s = mod.summary(df).iloc[0]
    assert s["ropemodel max rel. error"] <= 1e-7 and s["ropemodel max estimate"] <= 1e-7, s
    assert s["ropemodel max error / estimate"] <= 1.0 and s["ropemodel max error / rtol"] <= 1.0, s
    assert s["peer time / ropemodel time"] >= 100.0, s
    return s


def test_capstan_accuracy_fast(tmp_path):
    """Fast mode: 200 drives, the scipy peers on the first 20.  Those 20 happen to avoid the jumps of K that
    scipy steps over blindly, so with scipy 1.17 Radau at rtol 1e-12 is as accurate as the default there (and
    is the peer); the claim that none is as accurate belongs to the full run (the slow test below)."""
    mod = load_study("capstan_accuracy")
    _check(mod, mod.main(tmp_path, fast=True), tmp_path)


@pytest.mark.slow
def test_capstan_accuracy_full_meets_the_readme(tmp_path):
    """The README's claims on the full run (2000 drives, the scipy peers on the first 100): on those 100 the
    default's error stays below 1e-9 and every scipy configuration's exceeds 1e-7 (the best, Radau at rtol
    1e-13, stalls at 1.6e-7), so none is as accurate; and the speed claim of the fast test."""
    mod = load_study("capstan_accuracy")
    s = _check(mod, mod.main(tmp_path, fast=False), tmp_path)
    assert s["ropemodel max rel. error, scipy drives"] <= 1e-9, s
    assert s["most accurate scipy max rel. error"] > 1e-7, s
    assert s["scipy configurations as accurate"] == 0, s
