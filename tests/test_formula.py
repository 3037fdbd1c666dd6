"""The safe formula evaluator (ropemodel.formula): arithmetic only, one parse for every use.

Truths: the same formulas typed here as Python (float and numpy), and Python's own evaluation of the
expression the formula prints; refusals for everything that is not arithmetic.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ropemodel.errors import InputError
from ropemodel.formula import MAX_CHARS, Formula, FormulaError

CASES = [  # text, the same in Python, variables
    ("7.0 - 0.0005 * L", lambda L, T: 7.0 - 0.0005 * L),
    ("max(7.5 - 0.001 * L, 6.0)", lambda L, T: max(7.5 - 0.001 * L, 6.0)),
    ("min(L, T, 3) / 2", lambda L, T: min(L, T, 3) / 2),
    ("-L ** 2 + (L - T) / (T + 1)", lambda L, T: -L ** 2 + (L - T) / (T + 1)),
    ("(-L) ** 2 - L / (L * T)", lambda L, T: (-L) ** 2 - L / (L * T)),
    ("2 ** -T * L - (L - (T - 1))", lambda L, T: 2 ** -T * L - (L - (T - 1))),
    ("1/3", lambda L, T: 1 / 3),
    ("+L - -T", lambda L, T: +L - -T),
]


@pytest.mark.parametrize("text, truth", CASES)
def test_value_for_floats_arrays_casadi_and_python(text, truth):
    f = Formula.parse(text, ["L", "T"])
    for L, T in ((1000.0, 2.0), (3.5, 0.25), (7.0, 9.0)):
        want = truth(L, T)
        assert f(L=L, T=T) == pytest.approx(want, rel=1e-14)
        got = eval(f.python(), {"__builtins__": {"min": min, "max": max}, "math": math}, {"L": L, "T": T})
        assert got == pytest.approx(want, rel=1e-12)
        sL, sT = ca.SX.sym("L"), ca.SX.sym("T")
        assert float(ca.Function("f", [sL, sT], [f(L=sL, T=sT)])(L, T)) == pytest.approx(want, rel=1e-12)
    Ls, Ts = np.array([1000.0, 3.5, 7.0]), np.array([2.0, 0.25, 9.0])
    want = np.array([truth(a, b) for a, b in zip(Ls, Ts)])
    np.testing.assert_allclose(f(L=Ls, T=Ts), want, rtol=1e-12)


@settings(max_examples=60, deadline=None)
@given(st.floats(1e-3, 1e4), st.floats(1e-3, 1e2))
def test_python_expression_with_a_substitution_is_the_formula_in_other_units(L_m, T):
    """A formula in feet, given a length in metres: ``python({"L": "L / 0.3048"})`` is the formula at L/0.3048."""
    f = Formula.parse("7.0 - 0.0005 * L + min(L, T) ** 2 / (1 + T)", ["L", "T"])
    expr = f.python({"L": "L / 0.3048"})
    got = eval(expr, {"__builtins__": {"min": min, "max": max}}, {"L": L_m, "T": T})
    assert got == pytest.approx(f(L=L_m / 0.3048, T=T), rel=1e-12)


def test_unicode_is_what_a_person_reads():
    assert Formula.parse("7.0 - 0.0005 * L").unicode() == "7.0 − 0.0005·L"
    assert Formula.parse("max(7.5 - 0.001*L, 6.0)").unicode() == "max(7.5 − 0.001·L, 6.0)"
    assert Formula.parse("a - (b - c)").unicode() == "a − (b − c)"
    assert Formula.parse("a / (b * c)").unicode() == "a/(b·c)"
    assert Formula.parse("L**2").unicode() == "L²"
    assert Formula.parse("(a + b) ** x").unicode() == "(a + b)^x"
    assert Formula.parse("0.0005 * L").unicode({"L": "T"}) == "0.0005·T"
    assert Formula.parse("7.0").unicode() == "7.0"       # the digits as the source wrote them


@pytest.mark.parametrize("text, why", [
    ("__import__('os').system('ls')", "a call of something other than min or max"),
    ("open('x').read()", "a call of something other than min or max"),
    ("L.real", "attribute access"),
    ("L[0]", "indexing"),
    ("L < 4000", "a comparison"),
    ("L if L else 1", "a conditional"),
    ("L and 1", "and/or"),
    ("lambda: 1", "a lambda"),
    ("[L]", "a list"),
    ("L % 2", "the operator Mod"),
    ("L // 2", "the operator FloorDiv"),
    ("~L", "the operator Invert"),
    ("not L", "the operator Not"),
    ("True", "True is not a number"),
    ("'7'", "'7' is not a number"),
    ("1j", "1j is not a number"),
    ("_L", "no name may start with _"),
    ("X * 2", "unknown variable X"),
    ("min(L)", "two or more plain arguments"),
    ("max(*L)", "two or more plain arguments"),
    ("min(L, key=1)", "two or more plain arguments"),
    ("min + 1", "min is a function"),
    ("(x := 2)", "an assignment"),
    ("f'{L}'", "an f-string"),
    ("L +", "not a formula"),
    ("", "not a formula"),
])
def test_anything_but_arithmetic_is_refused(text, why):
    with pytest.raises(FormulaError, match=why.replace("(", r"\(").replace(")", r"\)")) as info:
        Formula.parse(text, ["L"])
    assert isinstance(info.value, InputError)      # a scene error, listed with the others


def test_limits_and_values_without_a_finite_result():
    with pytest.raises(FormulaError, match="longer than"):
        Formula.parse("L + " * (MAX_CHARS // 4 + 1) + "1")
    with pytest.raises(FormulaError, match="more than"):
        Formula.parse("+".join(["L"] * 150))
    with pytest.raises(FormulaError, match="no finite value"):
        Formula.parse("1 / (L - 2)")(L=2.0)
    with pytest.raises(FormulaError, match="no finite value"):
        Formula.parse("10.0 ** L")(L=400.0)           # an overflow, not a silent inf
    with pytest.raises(FormulaError, match="no finite value"):
        Formula.parse("L ** 0.5")(L=-4.0)             # a complex number is not a value
    with pytest.raises(FormulaError, match="no finite value"):
        Formula.parse("1 / L")(L=np.array([1.0, 0.0]))
    with pytest.raises(FormulaError, match="needs T"):
        Formula.parse("L + T")(L=1.0)
    with pytest.raises(FormulaError, match="no finite value"):   # numbers are floats: 9.0 ** 387420489.0
        Formula.parse("9 ** 9 ** 9 * 0 + L")(L=1.0)            # overflows at once, no huge integer is built
