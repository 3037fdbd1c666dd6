"""Every example in a docstring runs and prints what it shows (the numbers are the papers')."""

import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MODULES = sorted(
    ".".join(p.relative_to(ROOT).with_suffix("").parts)
    for package in ("ropemodel", "optimisation")
    for p in (ROOT / package).rglob("*.py")
    if ">>> " in p.read_text(encoding="utf-8")
)


def test_examples_are_found():
    assert {"ropemodel.papers.krauze2025", "ropemodel.papers.hajduk1992", "ropemodel.papers.li_capstan",
            "ropemodel.papers.en12385", "ropemodel.papers.friction"} <= set(MODULES)


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0
