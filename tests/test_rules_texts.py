"""Every rule of every shipped rule set against the text it cites, written out here independently of the
data files, at two lengths each (and beyond a limit where the text has one).

The truth of each rule is the cited formula typed from the text (the quotation is beside it), in the
text's own unit; the data file's formula is evaluated at the same length given in metres.  A rule
without a test here fails ``test_every_rule_has_its_text`` (CONTRIBUTING, "Adding a rule set").
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from ropemodel.rules import rule_sets

FT = 0.3048      # m per international foot


def _const(c):
    return lambda length: c


# (set, rule id) → (truth: length in the text's unit → value, unit of that length, two lengths [+ beyond])
TEXTS = {
    # 30 CFR § 57.19021(a), as W. Va. Code R. § 36-1-35.3.1.a reads: "For rope lengths less than 3,000 feet:
    # Minimum Value = Static Load x (7.0-0.001L)"; 4.0 at 3,000 ft or more (to verify)
    ("us-30cfr-57", "winding-drum-rope"): (lambda L: 7.0 - 0.001 * L if L < 3000 else 4.0, "ft", (1000, 2500, 3500)),
    # § 57.19021(b): "For rope lengths less than 4,000 feet: Minimum Value = Static Load x (7.0-0.0005L)"; 5.0 beyond
    ("us-30cfr-57", "friction-drum-rope"): (lambda L: 7.0 - 0.0005 * L if L < 4000 else 5.0, "ft", (1000, 3000, 5000)),
    # § 57.19021(c): "Tail ropes (balance ropes). Minimum Value = Weight of Rope x 7.0" (to verify)
    ("us-30cfr-57", "tail-rope"): (_const(7.0), "ft", (1000, 3000)),
    # § 57.19019: "Minimum value = Static Load × 5.0"
    ("us-30cfr-57", "guide-rope"): (_const(5.0), "ft", (1000, 3000)),
    # § 57.19025(a): "develops at least 80 percent of the nominal strength of the rope"
    ("us-30cfr-57", "load-end-attachment"): (_const(0.80), "ft", (1000, 3000)),
    # BPVS § 48 (issue 24): "9.5 − 0.001 T for persons, 7.2 − 0.0005 T for goods", T in m
    ("at-bpvs", "head-rope-persons"): (lambda T: 9.5 - 0.001 * T, "m", (500, 1500)),
    ("at-bpvs", "head-rope-material"): (lambda T: 7.2 - 0.0005 * T, "m", (500, 1500)),
    # § 21(1): "wenigstens das 50fache des Seildurchmessers, mindestens aber 1,2 m"; § 27(5): "µ von wenigstens 0,25"
    ("at-bpvs", "rope-carrier-ratio"): (_const(50.0), "m", (500, 1500)),
    ("at-bpvs", "rope-carrier-diameter"): (_const(1.2), "m", (500, 1500)),
    ("at-bpvs", "lining-friction"): (_const(0.25), "m", (500, 1500)),
    # SWA draft §1.3 (issue 24): "7.5 − 0.001 L (at least 6.0) for people, 5.5 − 0.0003 L for material", L in m
    ("au-swa-2011", "winding-rope-persons"): (lambda L: max(7.5 - 0.001 * L, 6.0), "m", (1000, 2000)),
    ("au-swa-2011", "winding-rope-material"): (lambda L: 5.5 - 0.0003 * L, "m", (1000, 2000)),
    # 煤矿安全规程 (secondary): connectors of endless-rope haulage ≥ 6; new hoisting ropes 9 (persons), 6.5 (material)
    ("cn-coal-2016", "endless-rope-connectors"): (_const(6.0), "m", (500, 1500)),
    ("cn-coal-2016", "hoisting-rope-persons"): (_const(9.0), "m", (500, 1500)),
    ("cn-coal-2016", "hoisting-rope-material"): (_const(6.5), "m", (500, 1500)),
    # DGUV 54, DA zu § 18 Abs. 1: "nicht kleiner als 3,0"; DA zu § 19 Abs. 1 Nr. 1: "des 20fachen Seildurchmessers"
    ("de-dguv-54", "hand-pulled-winch-rope"): (_const(3.0), "m", (500, 1500)),
    ("de-dguv-54", "v-groove-traction-sheave"): (_const(20.0), "m", (500, 1500)),
    # TAS Nr. 3.1.3: "Zuschlag von 10 v. H."; "im anderen Trum 1/3 der Seilbruchkraft"
    ("de-tas-2005", "dynamic-allowance"): (_const(0.10), "m", (500, 1500)),
    ("de-tas-2005", "friction-drum-design-load"): (_const(1 / 3), "m", (500, 1500)),
    # Krauze et al. (2025), introduction: "D ≥ 30d"
    ("paper-krauze2025", "drum-ratio"): (_const(30.0), "m", (500, 1500)),
}
# ISO 4308-1 Zp, running ropes (as read in the secondary sources): M1 3.15 ... M8 9.00
for _g, _zp in zip(("M1", "M2", "M3", "M4", "M5", "M6", "M7", "M8"), (3.15, 3.35, 3.55, 4.0, 4.5, 5.6, 7.1, 9.0)):
    TEXTS[("iso-4308-1", f"running-rope-{_g}")] = (_const(_zp), "m", (100, 1000))


def _rules():
    return [(s.name, r) for s in rule_sets().values() for r in s.rules]


def test_every_rule_has_its_text():
    ids = {(name, r.id) for name, r in _rules()}
    assert ids == set(TEXTS), \
        f"rules without a text test: {sorted(ids - set(TEXTS))}; stale: {sorted(set(TEXTS) - ids)}"


@pytest.mark.parametrize("name, rule", _rules(), ids=lambda x: x if isinstance(x, str) else x.id)
def test_rule_matches_its_text(name, rule):
    truth, unit, lengths = TEXTS[(name, rule.id)]
    metre = FT if unit == "ft" else 1.0
    for v in rule.variables:
        assert v.unit == unit, f"{rule.id}: the text writes the length in {unit}"
    si_per_unit = rule.factor
    for L in lengths:
        got = rule.value({"suspended": L * metre})
        assert got == pytest.approx(truth(L) * si_per_unit, rel=1e-12), (rule.id, L)


@pytest.mark.parametrize("name, rule", _rules(), ids=lambda x: x if isinstance(x, str) else x.id)
def test_rule_python_and_casadi_agree_with_its_value(name, rule):
    """The Python expression (SI length L [m]) and the CasADi expression give the value the rule gives."""
    _, unit, lengths = TEXTS[(name, rule.id)]
    metre = FT if unit == "ft" else 1.0
    expr = rule.python({"suspended": "L"})
    L = ca.SX.sym("L")
    f = ca.Function("f", [L], [rule.value({"suspended": L})])
    arr = rule.value({"suspended": np.array([x * metre for x in lengths])})
    for i, x in enumerate(lengths):
        want = rule.value({"suspended": x * metre})
        assert eval(expr, {"__builtins__": {"min": min, "max": max}, "math": math}, {"L": x * metre}) == \
            pytest.approx(want, rel=1e-12)
        assert float(f(x * metre)) == pytest.approx(want, rel=1e-12)
        assert np.broadcast_to(arr, (len(lengths),))[i] == pytest.approx(want, rel=1e-12)


def test_30cfr_friction_drum_at_its_limit_and_in_metres():
    """Hand values: 1000 ft → 6.5, 3000 ft → 5.5, 4000 ft (the limit, second row) → 5.0; 1150 m = 3772.97 ft
    → 7.0 − 0.0005·3772.97 = 5.1135."""
    rule = next(r for r in rule_sets()["us-30cfr-57"].rules if r.id == "friction-drum-rope")
    assert rule.value({"suspended": 1000 * FT}) == pytest.approx(6.5, rel=1e-12)
    assert rule.value({"suspended": 3000 * FT}) == pytest.approx(5.5, rel=1e-12)
    assert rule.value({"suspended": 4000 * FT}) == 5.0
    assert rule.value({"suspended": 1150.0}) == pytest.approx(7.0 - 0.0005 * 1150 / 0.3048, rel=1e-12)
    assert rule.unicode() == "7.0 − 0.0005·L for L < 4000 ft; 5.0 for L ≥ 4000 ft"


def test_statuses_are_never_better_than_what_was_read():
    """A confirmed rule quotes what was read; the sets known only from the issue or a summary are to verify."""
    for name, r in _rules():
        if r.status == "confirmed":
            assert "Read" in r.evidence and ("\"" in r.evidence or "“" in r.evidence), (name, r.id)
    for name in ("au-swa-2011", "iso-4308-1", "cn-coal-2016"):
        assert {r.status for r in rule_sets()[name].rules} == {"to verify"}, name
    bpvs = {r.id: r.status for r in rule_sets()["at-bpvs"].rules}
    assert bpvs["head-rope-persons"] == bpvs["head-rope-material"] == "to verify"
    cfr = {r.id: r.status for r in rule_sets()["us-30cfr-57"].rules}
    assert cfr["winding-drum-rope"] == cfr["friction-drum-rope"] == cfr["tail-rope"] == "to verify"
