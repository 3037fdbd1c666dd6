"""The rule sets shipped with ropemodel: one TOML file each in ``ropemodel/data/rules/`` (package data).

A new rule set is a new file there (and a test comparing each of its formulas with the text it cites,
see CONTRIBUTING "Adding a rule set"); nothing else needs editing.
"""

from __future__ import annotations

import tomllib
from functools import lru_cache
from importlib import resources

from ropemodel.errors import InputError, suggest
from ropemodel.rules.ruleset import RuleSet, read

PACKAGE = "ropemodel.data"
FOLDER = "rules"


@lru_cache(maxsize=1)
def rule_sets() -> dict[str, RuleSet]:
    """Every shipped rule set, by name (the file's stem), sorted by name."""
    folder = resources.files(PACKAGE).joinpath(FOLDER)
    out = {}
    for f in sorted(folder.iterdir(), key=lambda f: f.name):
        if f.name.endswith(".toml"):
            name = f.name[:-5]
            try:
                data = tomllib.loads(f.read_text(encoding="utf-8"))
            except tomllib.TOMLDecodeError as exc:
                raise InputError(f"rule set {name} ({FOLDER}/{f.name}): invalid TOML: {exc}") from None
            out[name] = read(name, data)
    return out


def names() -> list[str]:
    """Names of the shipped rule sets."""
    return list(rule_sets())


def get(name: str) -> RuleSet:
    """The rule set ``name``; :class:`InputError` naming the valid ones otherwise."""
    sets = rule_sets()
    if not isinstance(name, str) or name not in sets:
        raise InputError(f"unknown rule set {name!r}; rule sets: {', '.join(sets)}{suggest(str(name), sets)}")
    return sets[name]
