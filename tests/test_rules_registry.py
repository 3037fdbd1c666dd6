"""The rule-set files: every mistake of a data file named at once, and every shipped set unambiguous for each
machine it is written for (each choice picks at most one rule per factor)."""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import pytest

from ropemodel.effects.rulebinding import RULE_BINDINGS
from ropemodel.errors import InputError, Problems
from ropemodel.rules import apply, rule_sets
from ropemodel.rules.ruleset import read
from ropemodel.rules.vocabulary import MACHINES, STATUSES

GOOD_RULE = {"id": "r", "governs": "rope_safety", "formula": "5", "clause": "§ 1", "status": "confirmed",
             "evidence": "Read: \"5\""}
GOOD = {"title": "t", "authority": "a", "source": "s", "url": "u", "machines": ["winch"], "rules": [GOOD_RULE]}


def test_a_good_set_reads():
    rs = read("good", GOOD)
    assert rs.rules[0].value({}) == 5.0 and rs.status == "confirmed"


def test_every_mistake_of_a_data_file_at_once():
    bad = {**GOOD, "titel": "x", "machines": ["winch", "crane"], "rules": [
        {**GOOD_RULE, "id": "a", "governs": "rope_safty", "status": "probably"},
        {**GOOD_RULE, "id": "b", "where": {"rope": "steel", "colour": "red"}, "unit": "kN"},
        {**{k: v for k, v in GOOD_RULE.items() if k != "formula"}, "id": "c",
         "pieces": [{"formula": "7 - L", "below": 10}, {"formula": "os.system(1)"}],
         "variables": {"L": {"length": "suspended", "unit": "yd"}}},
        {**GOOD_RULE, "id": "d", "formula": None, "pieces": [{"formula": "1", "below": 5}, {"formula": "2",
                                                                                          "below": 3}]},
        {**GOOD_RULE, "id": "a", "evidence": ""},
    ]}
    with pytest.raises(InputError) as info:
        read("bad", bad)
    text = "\n".join(info.value.problems)
    for expected in ("unknown key 'titel'", "unknown machine 'crane'", "governs = 'rope_safty' is unknown",
                     "did you mean 'rope_safety'", "status = 'probably'", "where.rope = 'steel'",
                     "where.colour: unknown key", "unit 'kN' is not a unit of rope_safety",
                     "variables.L = { length", "c: piece 2: formula \"os.system(1)\": a call of something other",
                     "give either formula", "give evidence as text"):
        assert expected in text, expected
    assert "in rule set bad" in str(info.value)


def test_pieces_must_rise_and_only_the_last_is_open():
    rule = {**GOOD_RULE, "formula": None, "variables": {"L": {"length": "suspended", "unit": "m"}}}
    rule.pop("formula")
    for pieces in ([{"formula": "1", "below": 5}, {"formula": "2", "below": 3}, {"formula": "3"}],
                   [{"formula": "1"}, {"formula": "2"}],
                   [{"formula": "1", "below": 5}, {"formula": "2", "below": 9}]):
        with pytest.raises(InputError, match="every piece but the last ends with below"):
            read("p", {**GOOD, "rules": [{**rule, "pieces": pieces}]})
    rs = read("p", {**GOOD, "rules": [{**rule, "pieces": [{"formula": "1", "below": 5, "from": 2},
                                                          {"formula": "2"}]}]})
    r = rs.rules[0]
    assert r.value({"suspended": 2.0}) == 1.0 and r.value({"suspended": 5.0}) == 2.0
    with pytest.raises(InputError, match="has no value for L = 1 m: it covers L >= 2 m"):
        r.value({"suspended": 1.0})


def _combinations(rs):
    keys = list(rs.choices)
    for values in itertools.product(*(list(rs.choices[k]) for k in keys)):
        yield dict(zip(keys, values))


@pytest.mark.parametrize("name", list(rule_sets()))
def test_every_choice_picks_at_most_one_rule_per_factor(name):
    rs = rule_sets()[name]
    assert rs.machines and all(m in MACHINES for m in rs.machines)
    assert all(r.status in STATUSES and r.evidence and r.clause for r in rs.rules)
    for model, binds in RULE_BINDINGS.items():
        if binds.machine not in rs.machines:
            continue
        fake = SimpleNamespace(name=model, parameters=[b.parameter for b in binds.bindings])
        for choices in _combinations(rs):
            found = Problems()
            governed, pending = apply._select(rs, binds, choices, fake, found)   # RuntimeError if two match
            assert not pending
            assert not found, (choices, found.items)
            for _, (_, rule) in governed.items():
                assert all(v.length in binds.lengths for v in rule.variables)


def test_a_wrong_set_on_the_command_line_is_one_readable_error(tmp_path, capsys):
    from ropemodel.cli import main

    scene = tmp_path / "s.toml"
    scene.write_text('[scene]\nname = "x"\n[rules]\nset = "au-swa-2011"\ncarried = "persons"\n')
    assert main(["run", str(scene)]) == 2
    err = capsys.readouterr().err
    assert "is written for drum-hoist, koepe" in err and "Traceback" not in err
