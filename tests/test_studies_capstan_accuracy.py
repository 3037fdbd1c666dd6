"""The capstan accuracy study runs in --fast mode and its claims hold."""

from __future__ import annotations

import numpy as np
from _studies import load_study


def test_capstan_accuracy_fast(tmp_path):
    """README claim: the default rotation meets rtol 1e-7 against the event-located reference; no plain scipy
    configuration of the fast run is as accurate (they step blindly over the jumps of K)."""
    mod = load_study("capstan_accuracy")
    df = mod.main(tmp_path, fast=True)
    assert (tmp_path / "capstan_accuracy.png").exists()
    assert df.iloc[0]["max rel. error"] <= 1e-7
    scipy = df[df["method"].str.startswith("scipy")]
    assert np.all(scipy["max rel. error"] > df.iloc[0]["max rel. error"])
