"""CONTRIBUTING.md shows the S-curve ramp and its test as they are in the package (no drift)."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _blocks(text: str) -> list[str]:
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_contributing_shows_the_module_and_its_test_verbatim():
    blocks = _blocks((ROOT / "CONTRIBUTING.md").read_text())
    assert (ROOT / "ropemodel/effects/transient/ramp_scurve.py").read_text() in blocks
    assert (ROOT / "tests/test_ramp_scurve.py").read_text() in blocks


def test_the_example_variant_is_registered():
    from ropemodel.effects import REGISTRY
    from ropemodel.effects.transient.ramp_scurve import SCurveRamp

    assert REGISTRY["winch"]["ramp"].variants["scurve"] is SCurveRamp
