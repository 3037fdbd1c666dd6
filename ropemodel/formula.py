"""Formulas written as text (in data files), read safely: one parsed source, five uses.

A rule set's factor is a formula in the suspended length, ``"7.0 - 0.0005 * L"``, stored in a data file.
Such text is never given to ``eval``: :meth:`Formula.parse` reads it with Python's :mod:`ast` and accepts
only arithmetic — numbers, named variables, ``+ - * / **``, unary ``-``/``+`` and ``min(...)``/``max(...)``
— and refuses anything else (attribute access, calls of other functions, subscripts, comparisons,
lambdas, names not declared), naming what it found.  The parsed formula then gives, from the same tree:

* its value for floats, numpy arrays or CasADi expressions alike (:meth:`Formula.__call__`);
* the formula as a person reads it, in Unicode (:meth:`Formula.unicode`: ``7.0 − 0.0005·L``);
* a Python expression that Python (with ``min``/``max`` and :mod:`math`) evaluates, with each variable
  optionally replaced by an expression of another (:meth:`Formula.python`: ``7.0 - 0.0005 * (L / 0.3048)``
  for a length given in metres to a formula written in feet).

Numbers keep the digits the source wrote (``7.0`` stays ``7.0``); they are computed as floats, so an
integer power cannot grow without bound.  A value that is not finite (a division by zero, an overflow)
is an error, never a number.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ropemodel import _math
from ropemodel.errors import InputError

#: longest formula text accepted, and most nodes in its tree (a formula is a line, not a program)
MAX_CHARS = 400
MAX_NODES = 200
FUNCTIONS = {"min": _math.fmin, "max": _math.fmax}
_OPS = {ast.Add: ("+", " + ", 1), ast.Sub: ("-", " − ", 1), ast.Mult: ("*", "·", 2), ast.Div: ("/", "/", 2),
        ast.Pow: ("**", "^", 4)}
_UNARY = {ast.USub: ("-", "−"), ast.UAdd: ("+", "+")}
_SUPERSCRIPT = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
_WHAT = {ast.Attribute: "attribute access", ast.Subscript: "indexing", ast.Compare: "a comparison",
         ast.BoolOp: "and/or", ast.IfExp: "a conditional", ast.Lambda: "a lambda", ast.Call: "a call",
         ast.List: "a list", ast.Tuple: "a tuple", ast.Dict: "a dict", ast.Set: "a set",
         ast.JoinedStr: "an f-string", ast.Starred: "unpacking", ast.NamedExpr: "an assignment"}
ALLOWED = "numbers, named variables, + - * / ** and min(...)/max(...)"


class FormulaError(InputError):
    """A formula that is not plain arithmetic, or that has no finite value where it is evaluated."""


@dataclass(frozen=True, eq=False)
class Formula:
    """A parsed arithmetic formula (see the module docstring).  Build it with :meth:`parse`.

    Examples
    --------
    >>> f = Formula.parse("7.0 - 0.0005 * L", variables=["L"])
    >>> f(L=3000.0)
    5.5
    >>> f.unicode()
    '7.0 − 0.0005·L'
    >>> f.python({"L": "L / 0.3048"})
    '7.0 - 0.0005 * (L / 0.3048)'
    >>> try:
    ...     Formula.parse("__import__('os').system('ls')")
    ... except FormulaError as exc:
    ...     print(str(exc).split(";")[0])
    formula "__import__('os').system('ls')": a call of something other than min or max is not arithmetic
    """

    text: str
    tree: ast.expr = field(repr=False)
    variables: tuple[str, ...] = ()

    @classmethod
    def parse(cls, text: str, variables: Sequence[str] | None = None) -> Formula:
        """Read ``text``; ``variables``: the names it may use (None: any name that is not a function's)."""
        if not isinstance(text, str):
            raise FormulaError(f"a formula is text, got {text!r}")
        where = f"formula {text!r}" if '"' in text else f'formula "{text}"'
        if len(text) > MAX_CHARS:
            raise FormulaError(f"{where[:60]}...: longer than {MAX_CHARS} characters")
        try:
            tree = ast.parse(text.strip(), mode="eval").body
        except SyntaxError as exc:
            raise FormulaError(f"{where}: not a formula ({exc.msg}); a formula may use {ALLOWED}") from None
        nodes = list(ast.walk(tree))
        if len(nodes) > MAX_NODES:
            raise FormulaError(f"{where}: more than {MAX_NODES} terms")
        names: list[str] = []
        for node in nodes:
            problem = _problem(node, variables)
            if problem:
                raise FormulaError(f"{where}: {problem}")
            if isinstance(node, ast.Name) and node.id not in FUNCTIONS and node.id not in names:
                names.append(node.id)
        for node in nodes:   # a function name used as a value (``min + 1``)
            if isinstance(node, ast.Name) and node.id in FUNCTIONS and not _called(node, nodes):
                raise FormulaError(f"{where}: {node.id} is a function: call it, {node.id}(a, b)")
        return cls(text.strip(), tree, tuple(names))

    def __call__(self, **values):
        """The value for ``values`` (variable → float, numpy array or CasADi expression)."""
        missing = [v for v in self.variables if v not in values]
        if missing:
            raise FormulaError(f'formula "{self.text}" needs {", ".join(missing)}')
        try:
            with np.errstate(all="ignore"):
                out = _value(self.tree, self.text, values)
        except (ZeroDivisionError, OverflowError):
            out = math.nan
        if _symbolic(out):
            return out
        if isinstance(out, complex) or not np.all(np.isfinite(out)):
            raise FormulaError(f'formula "{self.text}" has no finite value at '
                               + ", ".join(f"{k} = {values[k]!r}" for k in self.variables))
        return float(out) if np.ndim(out) == 0 else out

    def unicode(self, names: Mapping[str, str] | None = None) -> str:
        """The formula as a person reads it (``−``, ``·``, superscript powers); ``names`` rename variables."""
        return _show(self.tree, self.text, dict(names or {}), unicode=True)

    def python(self, names: Mapping[str, str] | None = None) -> str:
        """A Python expression of the formula; ``names`` maps a variable to the expression it stands for."""
        return _show(self.tree, self.text, dict(names or {}), unicode=False)


def _called(name: ast.Name, nodes) -> bool:
    return any(isinstance(n, ast.Call) and n.func is name for n in nodes)


def _problem(node, variables) -> str | None:
    """Why ``node`` is not allowed in a formula, or None."""
    if isinstance(node, (ast.BinOp, ast.UnaryOp, ast.Load)) or type(node) in _OPS or type(node) in _UNARY:
        if isinstance(node, ast.BinOp) and type(node.op) not in _OPS:
            return f"the operator {type(node.op).__name__} is not allowed; a formula may use {ALLOWED}"
        if isinstance(node, ast.UnaryOp) and type(node.op) not in _UNARY:
            return f"the operator {type(node.op).__name__} is not allowed; a formula may use {ALLOWED}"
        return None
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            return f"{node.value!r} is not a number; a formula may use {ALLOWED}"
        return None
    if isinstance(node, ast.Name):
        if node.id.startswith("_"):
            return f"the name {node.id} is not allowed (no name may start with _)"
        if node.id not in FUNCTIONS and variables is not None and node.id not in variables:
            known = ", ".join(variables) or "none"
            return f"unknown variable {node.id} (variables: {known})"
        return None
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            return f"a call of something other than min or max is not arithmetic; a formula may use {ALLOWED}"
        if node.keywords or len(node.args) < 2 or any(isinstance(a, ast.Starred) for a in node.args):
            return f"{node.func.id}(...) takes two or more plain arguments"
        return None
    what = _WHAT.get(type(node), type(node).__name__)
    return f"{what} is not arithmetic; a formula may use {ALLOWED}"


def _symbolic(x) -> bool:
    return isinstance(x, (_math.ca.SX, _math.ca.MX, _math.ca.DM))


def _value(node, text: str, values: Mapping):
    if isinstance(node, ast.Constant):
        return float(node.value)  # type: ignore[arg-type]  # parse accepts int and float constants only
    if isinstance(node, ast.Name):
        return values[node.id]
    if isinstance(node, ast.UnaryOp):
        x = _value(node.operand, text, values)
        return -x if isinstance(node.op, ast.USub) else x
    if isinstance(node, ast.Call):
        args = [_value(a, text, values) for a in node.args]
        fun = FUNCTIONS[node.func.id]  # type: ignore[attr-defined]  # parse accepts min/max by name only
        out = args[0]
        for a in args[1:]:
            out = fun(out, a)
        return out
    a, b = _value(node.left, text, values), _value(node.right, text, values)
    op = type(node.op)
    if op is ast.Add:
        return a + b
    if op is ast.Sub:
        return a - b
    if op is ast.Mult:
        return a * b
    if op is ast.Div:
        return a / b
    return a ** b


def _precedence(node) -> int:
    if isinstance(node, ast.BinOp):
        return _OPS[type(node.op)][2]
    if isinstance(node, ast.UnaryOp):
        return 3
    return 5


def _show(node, text: str, names: dict, unicode: bool) -> str:
    if isinstance(node, ast.Constant):
        return ast.get_source_segment(text, node) or repr(node.value)
    if isinstance(node, ast.Name):
        if node.id in names:
            sub = names[node.id]
            return sub if unicode or sub.isidentifier() else f"({sub})"
        return node.id
    if isinstance(node, ast.Call):
        name = node.func.id  # type: ignore[attr-defined]
        return f"{name}({', '.join(_show(a, text, names, unicode) for a in node.args)})"
    if isinstance(node, ast.UnaryOp):
        inner = _wrap(node.operand, 3, text, names, unicode, strict=True)
        return _UNARY[type(node.op)][1 if unicode else 0] + inner
    py, uni, prec = _OPS[type(node.op)]
    power = isinstance(node.op, ast.Pow)
    left = _wrap(node.left, prec, text, names, unicode, strict=power)
    right = _wrap(node.right, prec, text, names, unicode,
                  strict=isinstance(node.op, (ast.Sub, ast.Div)) and not power)
    if power and unicode and isinstance(node.right, ast.Constant) and isinstance(node.right.value, int) \
            and 0 <= node.right.value <= 9:
        return left + str(node.right.value).translate(_SUPERSCRIPT)
    return f"{left}{uni}{right}" if unicode else f"{left} {py} {right}"


def _wrap(node, prec: int, text: str, names: dict, unicode: bool, strict: bool) -> str:
    """``node`` shown, in parentheses where the operator around it binds tighter."""
    inner = _show(node, text, names, unicode)
    p = _precedence(node)
    return f"({inner})" if p < prec or (strict and p == prec) else inner


__all__ = ["Formula", "FormulaError", "FUNCTIONS"]
