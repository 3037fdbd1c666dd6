"""CasADi SX expressions printed as infix text: Unicode for a person, Python for a checker.

The equations of the effects are CasADi SX graphs; this module reads a scalar SX graph back as a
tree (:func:`tree`: every operation with :meth:`casadi.SX.op` and its operands with ``dep``), tidies
its signs (``−(a − b)`` is ``b − a``, ``a + (−b)`` is ``a − b``, ``(b − a)/a`` is ``b/a − 1``) and
recognises CasADi's ``if_else`` (``(c ? a : 0) + (!c ? b : 0)``), then prints the same tree twice:

* :func:`python`: an expression that Python evaluates with :mod:`math` (``math.sin(alpha_u)``), in the
  tree's order of operations, so it reproduces the compiled model to rounding;
* :func:`unicode`: the formula as a person reads it, with each quantity's typeset symbol
  (``G_m sin α_u``, ``e^(μ_d α_d)``, ``max(P_drum,up, 0) / η``); ``(a/b)·c`` is shown ``a c / b``.

A tree is a tuple: ``("sym", name)``, ``("num", value)`` or ``(op, *operands)``.  A graph too large
to read as one formula (an unrolled Newton iteration) raises :class:`TooLarge`.

Examples
--------
>>> import casadi as ca
>>> G_m, a = ca.SX.sym("G_m"), ca.SX.sym("alpha_u")
>>> t = tree(-(-(G_m * ca.sin(a))))
>>> python(t), unicode(t, {"alpha_u": "α_u"})
('G_m * math.sin(alpha_u)', 'G_m sin α_u')
>>> unicode(tree(ca.if_else(G_m <= 2, a, 2 * a)), {})
'{alpha_u if G_m ≤ 2; 2 alpha_u otherwise}'
"""

from __future__ import annotations

import keyword
import math

import casadi as ca

#: most operations printed as one formula
MAX_NODES = 2000
#: standard gravity [m/s²] (CGPM 1901), shown as g
G_N = 9.80665

BINARY = {ca.OP_ADD: "+", ca.OP_SUB: "-", ca.OP_MUL: "*", ca.OP_DIV: "/", ca.OP_POW: "pow", ca.OP_CONSTPOW: "pow",
          ca.OP_FMIN: "min", ca.OP_FMAX: "max", ca.OP_ATAN2: "atan2", ca.OP_HYPOT: "hypot",
          ca.OP_COPYSIGN: "copysign", ca.OP_FMOD: "fmod", ca.OP_LT: "<", ca.OP_LE: "<=", ca.OP_EQ: "==",
          ca.OP_NE: "!=", ca.OP_AND: "and", ca.OP_OR: "or", ca.OP_IF_ELSE_ZERO: "ifz"}
UNARY = {ca.OP_NEG: "neg", ca.OP_EXP: "exp", ca.OP_LOG: "log", ca.OP_SQRT: "sqrt", ca.OP_SQ: "sq",
         ca.OP_TWICE: "twice", ca.OP_INV: "inv", ca.OP_SIN: "sin", ca.OP_COS: "cos", ca.OP_TAN: "tan",
         ca.OP_ASIN: "asin", ca.OP_ACOS: "acos", ca.OP_ATAN: "atan", ca.OP_SINH: "sinh", ca.OP_COSH: "cosh",
         ca.OP_TANH: "tanh", ca.OP_ASINH: "asinh", ca.OP_ACOSH: "acosh", ca.OP_ATANH: "atanh",
         ca.OP_FABS: "fabs", ca.OP_FLOOR: "floor", ca.OP_CEIL: "ceil", ca.OP_ERF: "erf", ca.OP_LOG1P: "log1p",
         ca.OP_EXPM1: "expm1", ca.OP_NOT: "not", ca.OP_SIGN: "sign"}


class TooLarge(ValueError):
    """The graph has more than :data:`MAX_NODES` operations: it is no formula a person reads."""


# ------------------------------------------------------------------------------------------ reading


def tree(x: ca.SX) -> tuple:
    """The scalar SX expression ``x`` as a tidied tree (see the module docstring)."""
    budget = [MAX_NODES]
    return _read(ca.SX(x), budget)


def _read(x: ca.SX, budget: list) -> tuple:
    budget[0] -= 1
    if budget[0] < 0:
        raise TooLarge(f"more than {MAX_NODES} operations")
    if x.is_symbolic():
        return ("sym", x.name())
    if x.is_constant():
        return ("num", float(x))
    op = x.op()
    if op in UNARY:
        return make(UNARY[op], _read(x.dep(0), budget))
    if op in BINARY:
        return make(BINARY[op], _read(x.dep(0), budget), _read(x.dep(1), budget))
    raise ValueError(f"CasADi operation {op} has no infix form")


def _num(t) -> float | None:
    return t[1] if t[0] == "num" else None


def make(op: str, *a) -> tuple:
    """The node ``(op, *a)``, its signs tidied and CasADi's if_else recognised (exact identities only)."""
    if op == "twice":
        return make("*", ("num", 2.0), a[0])
    if op == "inv":
        return make("/", ("num", 1.0), a[0])
    if op == "neg":
        return _neg(a[0])
    if op == "+":
        return _add(*a)
    if op == "-":
        return _sub(*a)
    if op in ("*", "/"):
        return _product(op, *a)
    if op == "if":
        return ("if", a[0], _assume(a[1], a[0], True), _assume(a[2], a[0], False))
    return (op, *a)


def _neg(a):
    if a[0] == "neg":
        return a[1]
    if a[0] == "num":
        return ("num", -a[1])
    if a[0] == "-":
        return make("-", a[2], a[1])
    if a[0] == "/" and a[1][0] == "-":               # −(x − y)/z = (y − x)/z
        return make("/", make("-", a[1][2], a[1][1]), a[2])
    return ("neg", a)


def _add(a, b):
    if b[0] == "neg":
        return make("-", a, b[1])
    if a[0] == "neg":
        return make("-", b, a[1])
    if _num(b) is not None and b[1] < 0:
        return make("-", a, ("num", -b[1]))
    if _num(b) == 0.0:
        return a
    if _num(a) == 0.0:
        return b
    cond = _if_pair(a, b) or _if_pair(b, a)
    if cond is not None:
        return make("if", *cond)
    return ("+", a, b)


def _if_pair(a, b):
    """(c, x, y) when a = (c ? x : 0) and b = (!c ? y : 0): CasADi's if_else(c, x, y)."""
    if a[0] == "ifz" and b[0] == "ifz" and b[1] == ("not", a[1]):
        return a[1], a[2], b[2]
    return None


def _sub(a, b):
    if b[0] == "neg":
        return make("+", a, b[1])
    if _num(b) is not None and b[1] < 0:
        return make("+", a, ("num", -b[1]))
    if _num(b) == 0.0:
        return a
    if _num(a) == 0.0:
        return make("neg", b)
    return ("-", a, b)


def _product(op, a, b):
    if a[0] == "neg" or (_num(a) is not None and a[1] < 0):     # (−a)·b = −(a·b), (−a)/b = −(a/b)
        return make("neg", make(op, _neg(a), b))
    if b[0] == "neg" or (_num(b) is not None and b[1] < 0):
        return make("neg", make(op, a, _neg(b)))
    if op == "*" and _num(a) == 1.0:
        return b
    if _num(b) == 1.0:
        return a
    if op == "/" and a[0] == "-" and a[2] == b:     # (x − b)/b = x/b − 1
        return make("-", make("/", a[1], b), ("num", 1.0))
    return (op, a, b)


def _assume(t, cond, holds: bool):
    """``t`` where ``cond`` is known to hold (or not): CasADi's guards (c ? x : 0) inside a branch resolved."""
    if t[0] == "ifz" and t[1] in (cond, ("not", cond)):
        return _assume(t[2], cond, holds) if (t[1] == cond) == holds else ("num", 0.0)
    if t[0] == "if" and t[1] == cond:
        return _assume(t[2] if holds else t[3], cond, holds)
    if t[0] in ("sym", "num"):
        return t
    return make(t[0], *[_assume(c, cond, holds) for c in t[1:]])


# ------------------------------------------------------------------------------------------ Python

PY_FUNCTIONS = {"exp": "math.exp", "log": "math.log", "sqrt": "math.sqrt", "sin": "math.sin", "cos": "math.cos",
                "tan": "math.tan", "asin": "math.asin", "acos": "math.acos", "atan": "math.atan",
                "sinh": "math.sinh", "cosh": "math.cosh", "tanh": "math.tanh", "asinh": "math.asinh",
                "acosh": "math.acosh", "atanh": "math.atanh", "fabs": "math.fabs", "floor": "math.floor",
                "ceil": "math.ceil", "erf": "math.erf", "log1p": "math.log1p", "expm1": "math.expm1",
                "min": "min", "max": "max", "atan2": "math.atan2", "hypot": "math.hypot",
                "copysign": "math.copysign", "fmod": "math.fmod"}
_PY_BIN = {"+": (" + ", 5), "-": (" - ", 5), "*": (" * ", 6), "/": (" / ", 6), "<": (" < ", 4),
           "<=": (" <= ", 4), "==": (" == ", 4), "!=": (" != ", 4), "and": (" and ", 2), "or": (" or ", 1)}


def identifier(name: str) -> str:
    """The Python name of a quantity: its own, with ``_`` appended to a keyword (``lambda_``)."""
    return f"{name}_" if keyword.iskeyword(name) else name


def python(t) -> str:
    """A Python expression of the tree, for ``eval(text, {"math": math}, inputs)`` (inputs by :func:`identifier`)."""
    return _py(t)[0]


def _py(t) -> tuple[str, int]:
    """(text, precedence): 9 an atom or a call, 8 a power, 7 a unary minus, 6 a product, 5 a sum, ≤ 4 logic."""
    op = t[0]
    if op == "sym":
        return identifier(t[1]), 9
    if op == "num":
        if t[1] != t[1] or abs(t[1]) == math.inf:          # nan, ±inf: math's names
            return ("math.nan" if t[1] != t[1] else ("math.inf" if t[1] > 0 else "(-math.inf)")), 9
        return (repr(t[1]), 9) if t[1] >= 0 else (f"({t[1]!r})", 9)
    if op in _PY_BIN:
        sep, p = _PY_BIN[op]
        left, right = _py(t[1]), _py(t[2])
        return f"{_wrap(left, p)}{sep}{_wrap(right, p + 1)}", p     # left to right, as CasADi evaluates
    if op == "neg":
        return f"-{_wrap(_py(t[1]), 7)}", 7
    if op == "pow":     # math.pow: a real power or a domain error, never a complex number
        return f"math.pow({_py(t[1])[0]}, {_py(t[2])[0]})", 9
    if op == "sq":
        return f"{_wrap(_py(t[1]), 9)} ** 2", 8
    if op == "not":
        return f"not {_wrap(_py(t[1]), 3)}", 3
    if op == "sign":
        x = _py(t[1])[0]
        return f"(({x}) > 0) - (({x}) < 0)", 5
    if op == "ifz":
        return f"({_py(t[2])[0]} if {_py(t[1])[0]} else 0.0)", 9
    if op == "if":
        return f"({_py(t[2])[0]} if {_py(t[1])[0]} else {_py(t[3])[0]})", 9
    return f"{PY_FUNCTIONS[op]}({', '.join(_py(c)[0] for c in t[1:])})", 9


def _wrap(part: tuple[str, int], least: int) -> str:
    text, p = part
    return text if p >= least else f"({text})"


# ------------------------------------------------------------------------------------------ Unicode

_UNI_BIN = {"+": (" + ", 5), "-": (" − ", 5), "<": (" < ", 4), "<=": (" ≤ ", 4), "==": (" = ", 4),
            "!=": (" ≠ ", 4), "and": (" and ", 2), "or": (" or ", 1)}
_NOT = {"<": "≥", "<=": ">", "==": "≠", "!=": "="}
_FUNCTIONS = {"sin", "cos", "tan", "sinh", "cosh", "tanh", "asin", "acos", "atan", "asinh", "acosh", "atanh",
              "erf", "floor", "ceil"}
_SUPERSCRIPT = {2.0: "²", 3.0: "³"}


def unicode(t, symbols: dict[str, str]) -> str:
    """The tree as a person reads it; ``symbols`` maps a quantity's name to its typeset symbol."""
    return _uni(t, symbols)[0]


def number(v: float) -> str:
    """A constant as a formula shows it: ``2``, ``0.5``, ``g`` (9.80665), ``1×10^(-30)``."""
    if v == G_N:
        return "g"
    if v < 0:
        return f"−{number(-v)}"
    if not math.isfinite(v):
        return "∞" if v > 0 else "NaN"
    if v == int(v) and v < 1e6:
        return str(int(v))
    text = f"{v:.10g}"
    if "e" in text:
        mantissa, exp = text.split("e")
        power = f"10^({int(exp)})".replace("-", "−")
        return power if mantissa == "1" else f"{mantissa}×{power}"
    return text


def _uni(t, s) -> tuple[str, int]:
    op = t[0]
    if op == "sym":
        return s.get(t[1], t[1]), 9
    if op == "num":
        return number(t[1]), 9
    if op in ("+", "-") and _ends_in_expm1(t[2]):    # a − b (e^x − 1) shown as a + b (1 − e^x)
        return _uni(("+" if op == "-" else "-", t[1], _one_minus(t[2])), s)
    if op in _UNI_BIN:
        sep, p = _UNI_BIN[op]
        # + and − read alike either way round: only a difference on the right needs its brackets
        return f"{_wrap(_uni(t[1], s), p)}{sep}{_wrap(_uni(t[2], s), p + (op == '-'))}", p
    if op == "*":
        return _times(t, s)
    if op == "/":
        return f"{_wrap(_uni(t[1], s), 6)} / {_wrap(_uni(t[2], s), 7)}", 6
    if op == "neg":
        if _ends_in_expm1(t[1]):
            return _uni(_one_minus(t[1]), s)
        return f"−{_wrap(_uni(t[1], s), 6)}", 7
    if op == "1-exp":
        return f"1 − e^({_uni(t[1], s)[0]})", 5
    if op in ("pow", "sq"):
        return _power(t, s)
    return _call(t, s)


def _ends_in_expm1(t) -> bool:
    return t[0] == "expm1" or (t[0] == "*" and _ends_in_expm1(t[2]))


def _one_minus(t):
    """−t for a t that ends in (e^x − 1): the same product ending in (1 − e^x)."""
    return ("1-exp", t[1]) if t[0] == "expm1" else ("*", t[1], _one_minus(t[2]))


def _times(t, s) -> tuple[str, int]:
    a, b = t[1], t[2]
    if a[0] == "/":                                  # (x/y)·b shown as x b / y
        return _uni(("/", ("*", a[1], b), a[2]), s)
    if b[0] == "/" and a[0] != "num":                # a·(x/y) shown as a x / y
        return _uni(("/", ("*", a, b[1]), b[2]), s)
    if b[0] == "num" and a[0] != "num":              # a·2 shown as 2 a
        return _times(("*", b, a), s)
    left, right = _wrap(_uni(a, s), 6), _wrap(_uni(b, s), 6)
    dot = b[0] == "num" or right.startswith("−")
    return f"{left}{'·' if dot else ' '}{right}", 6


def _power(t, s) -> tuple[str, int]:
    base = _wrap(_uni(t[1], s), 9)
    exponent = 2.0 if t[0] == "sq" else _num(t[2])
    if exponent in _SUPERSCRIPT:
        return f"{base}{_SUPERSCRIPT[exponent]}", 8
    return f"{base}^({_uni(t[2], s)[0]})", 8


def _call(t, s) -> tuple[str, int]:
    op, args = t[0], [_uni(c, s) for c in t[1:]]
    if op == "exp":
        return f"e^({args[0][0]})", 8
    if op == "expm1":
        return f"e^({args[0][0]}) − 1", 5
    if op == "log1p" and t[1][0] == "neg":
        return f"ln(1 − {_wrap(_uni(t[1][1], s), 6)})", 9
    if op in ("log", "log1p"):
        inner = args[0] if op == "log" else (f"1 + {args[0][0]}", 5)
        return (f"ln {inner[0]}", 7) if inner[1] == 9 and op == "log" else (f"ln({inner[0]})", 9)
    if op in _FUNCTIONS:
        return (f"{op} {args[0][0]}", 7) if args[0][1] == 9 and t[1][0] == "sym" else (f"{op}({args[0][0]})", 9)
    if op == "sqrt":
        return f"√{_wrap(args[0], 9)}", 9
    if op == "fabs":
        return f"|{args[0][0]}|", 9
    if op == "not":
        inner = t[1]
        if inner[0] in _NOT:
            return f"{_uni(inner[1], s)[0]} {_NOT[inner[0]]} {_uni(inner[2], s)[0]}", 4
        return f"not {_wrap(args[0], 3)}", 3
    if op in ("ifz", "if"):
        return "{" + "; ".join(f"{v} if {c}" if c else f"{v} otherwise" for v, c in _cases(t, s)) + "}", 9
    return f"{op}({', '.join(a[0] for a in args)})", 9


def _cases(t, s) -> list[tuple[str, str]]:
    """(value, condition) of a chain of if_else, the last with condition "" (otherwise); a branch that is
    itself a choice is put last, so that the chain reads as one list of cases."""
    out = []
    while t[0] in ("if", "ifz"):
        cond, then, other = t[1], t[2], t[3] if t[0] == "if" else ("num", 0.0)
        if then[0] in ("if", "ifz") and other[0] not in ("if", "ifz"):
            cond, then, other = _negate(cond), other, then
        out.append((_uni(then, s)[0], _uni(cond, s)[0]))
        t = other
    return out + [(_uni(t, s)[0], "")]


def _negate(cond):
    return cond[1] if cond[0] == "not" else ("not", cond)
