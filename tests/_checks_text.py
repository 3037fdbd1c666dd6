"""Reading the checks table of ``size --dynamic``'s text (tests/test_dynamic_output.py, the slow end-to-end
tests of dynamic sizing)."""

from __future__ import annotations

import re

from optimisation.dynamic.manoeuvres import WORDS
from ropemodel.machines.winch.manoeuvres import ORDER

#: every internal name a text output must not show: any ``..._margin...``, an indexed constraint, a peak's key
#: (F_S_min is also the scene's least tension, a parameter the user writes: the limit of the taut checks)
INTERNAL = re.compile(r"[a-z]+_margin|\w+\[\d+\]|F_C_max|take_up_max|dynamic_factor")
MANOEUVRES = [f"{WORDS[travel]} {dynamics}" for dynamics, travel in ORDER]


def groups(text: str) -> dict[str, list[str]]:
    """Title line → its rows (indented lines) in the checks table."""
    table = text[text.index("\nchecks, "):text.index("\nfactors: ")]
    out: dict[str, list[str]] = {}
    title = ""
    for line in table.splitlines()[3:]:
        if line.startswith("  "):
            out[title].append(line)
        elif line:
            title = line
            out[title] = []
    return out
