"""Each equation of a model as a report shows it, printed from the expression the model computes.

An equation's residual is solved for the quantity it defines with the solver's own linear solve
(:func:`ropemodel.core.compile.linear_solution`), and the SX graph of the solution is printed twice
(:mod:`ropemodel.core.infix`): in Unicode with the quantities' symbols for the page, and as a Python
expression for the calculation sheet.  No formula is typed by hand, so the page cannot show one formula
and compute another.  Three kinds:

``closed``     ``G_ml = G_m sin α_u``: :attr:`Shown.python` evaluates to the value from the inputs.
``implicit``   the explicit form is an iteration (Newton unrolled in SX): the page shows the equation it
               solves, :attr:`Equation.governing <ropemodel.effects.base.Equation>` as ``lhs = rhs``;
               :attr:`Shown.lhs` and :attr:`Shown.rhs` agree at the value (Python, the value under its
               own name), and :attr:`Shown.method` says how it is solved.
``numerical``  an integrator or an error estimate: no closed form; :attr:`Shown.method` names the method
               and :attr:`Shown.tolerance` its relative tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca

from ropemodel.core import infix
from ropemodel.core.compile import linear_solution


@dataclass(frozen=True)
class Shown:
    """An equation as the report and the calculation sheet show it."""

    name: str
    kind: str
    #: Unicode with typeset symbols: ``"G_ml = G_m sin α_u"`` (closed), ``"lhs = rhs"`` (implicit), "" (numerical)
    formula: str
    #: the quantities the equation is computed from (the defined one excluded)
    inputs: tuple[str, ...]
    source: str
    #: closed: a Python expression of the value in SI (``eval(python, {"math": math}, inputs)``)
    python: str | None = None
    #: implicit: the two sides of the governing equation in Python, equal at the value
    lhs: str | None = None
    rhs: str | None = None
    method: str = ""
    tolerance: float | None = None


def symbols(model) -> dict[str, str]:
    """Name → typeset symbol of every quantity of ``model``."""
    return {n: q.typeset for n, q in model.quantities.items()}


def shown(model, eq) -> Shown:
    """How ``eq`` (an equation of ``model``) is shown; :class:`RuntimeError` for one that cannot be shown
    (an iteration without its governing equation or method: a developer's mistake, caught by the tests)."""
    syms = symbols(model)
    lhs_symbol = syms[eq.defines]
    if eq.call is not None:
        return _numerical(eq, eq.call[1])
    if eq.governing is not None:
        return _implicit(eq, syms)
    solution = linear_solution(eq.residual, model.symbols[eq.defines])
    if solution is None:       # nonlinear in what it defines: its residual is the equation to show
        return _implicit(eq, syms, eq.residual, method=eq.method or "Newton's method on the residual (the "
                         "core's rootfinder, absolute tolerance 1e-12)")
    try:
        t = infix.tree(solution)
    except infix.TooLarge:
        return _numerical(eq, _inputs(solution, eq.defines))
    return Shown(eq.defines, "closed", f"{lhs_symbol} = {infix.unicode(t, syms)}", _inputs(solution, eq.defines),
                 eq.source, python=infix.python(t), method=eq.method, tolerance=eq.tolerance)


def _inputs(expr: ca.SX, defines: str) -> tuple[str, ...]:
    return tuple(s.name() for s in ca.symvar(expr) if s.name() != defines)


def _numerical(eq, inputs) -> Shown:
    if not eq.method:
        raise RuntimeError(f"equation of {eq.defines} ({eq.source}) has no closed form to show and names no method")
    return Shown(eq.defines, "numerical", "", tuple(inputs), eq.source, method=eq.method, tolerance=eq.tolerance)


def _implicit(eq, syms, governing=None, method: str = "") -> Shown:
    governing = eq.governing if governing is None else governing
    t = infix.tree(governing)
    left, right = (t[1], t[2]) if t[0] == "-" else (t, ("num", 0.0))
    method = method or eq.method
    if not method:
        raise RuntimeError(f"equation of {eq.defines} ({eq.source}) gives its governing equation but no method")
    formula = f"{infix.unicode(left, syms)} = {infix.unicode(right, syms)}"
    return Shown(eq.defines, "implicit", formula, _inputs(governing, eq.defines), eq.source,
                 lhs=infix.python(left), rhs=infix.python(right), method=method, tolerance=eq.tolerance)
