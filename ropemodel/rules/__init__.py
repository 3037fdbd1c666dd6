"""Rules as data, with provenance: the rule sets an authority applies (rope safety as a formula in the
suspended length, D/d, slip, least tension, dynamic allowance, ...), each rule with its clause, source
and status.

* :mod:`ropemodel.rules.vocabulary` — what a rule may govern, the machines, the statuses;
* :mod:`ropemodel.rules.ruleset` — a rule set read from its data file (``ropemodel/data/rules/*.toml``);
* :mod:`ropemodel.rules.registry` — the shipped rule sets;
* :mod:`ropemodel.rules.apply` — a set applied to a scene (``[rules]``), the values it gives;
* :mod:`ropemodel.rules.describe` — what each factor rests on, in words and in JSON.
"""

from __future__ import annotations

from ropemodel.rules.registry import get, names, rule_sets
from ropemodel.rules.ruleset import Piece, Rule, RuleSet, Variable

__all__ = ["Piece", "Rule", "RuleSet", "Variable", "get", "names", "rule_sets"]
