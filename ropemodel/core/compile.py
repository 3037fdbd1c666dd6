"""Compile a well-posed structure into one CasADi Function: knowns → unknowns.

Each block of the block-triangular form is solved in turn, in terms of the
knowns and of the blocks before it:

* **explicit** blocks — the residuals are linear in the block's unknowns (every
  definition ``y - f(x) = 0`` of the forward problem, and inverse questions such
  as "G_m from F_C" that stay linear): solved symbolically, ``x = -J⁻¹ r(0)``,
  so the forward model is a closed-form expression with no iteration at all.
  A call equation (``y = fun(args)``, see :meth:`Equation.from_call`) solved
  for ``y`` is explicit too: ``fun`` is simply called.
* **implicit** blocks — nonlinear in their unknowns (the Voigt lining's implicit
  tension, an inverse solve through a sine or through an integrator): CasADi's
  ``rootfinder`` (Newton) from the quantities' guesses.  Strictly positive
  unknowns are solved for their logarithm, which keeps Newton inside the domain
  and makes the lining's ``ln s + c s = μα`` convex and monotone.

When no block is implicit and no call equation is used, the Function is expanded
to SX (fastest for sweeps); otherwise common subexpressions of the MX graph are merged
(``ca.cse``), so call equations that are outputs of one Function (e.g. a quantity and
its error estimate, each wrapped ``always_inline``) evaluate that Function once.  The rootfinder is
differentiable (implicit function theorem), so sensitivities of inverse solves come out of the same Function.
"""

from __future__ import annotations

import math

import casadi as ca

from ropemodel.core.structure import Structure

#: one scalar input per known: a route of thousands of segments has thousands, and CasADi would warn of them on
#: stderr (a solver log) for the Function and every map of it
MANY_INPUTS = {"max_io": 0}
#: Newton's options; a failure is reported by the caller in the user's terms, never as a solver log
NEWTON_OPTIONS = {"abstol": 1e-12, "abstolStep": 1e-14, "max_iter": 100, "error_on_fail": False,
                  "show_eval_warnings": False}


def compile_solver(model, structure: Structure, guesses: dict[str, float] | None = None,
                   name: str = "solve") -> ca.Function:
    """Function with one named scalar input per known and one named output per unknown."""
    explicit = _explicit_solver(model, structure, name)
    if explicit is not None:
        return explicit
    guesses = dict(guesses or {})
    value: dict[str, ca.MX] = {k: ca.MX.sym(k) for k in structure.knowns}
    expandable = True
    for b, block in enumerate(structure.blocks):
        eqs = [model.equations[i] for i in block.equations]
        deps = sorted({n for eq in eqs for n in eq.names()} - set(block.unknowns))
        p_val = ca.vertcat(*[value[d] for d in deps]) if deps else ca.MX(0, 1)
        if any(eq.call is not None for eq in eqs):
            expandable = False
            if len(eqs) == 1 and eqs[0].defines == block.unknowns[0]:
                fun, args = eqs[0].call
                out = fun(*[value[a] for a in args])
            else:
                out = _newton(model, block, _mx_residual(eqs, block.unknowns, deps), deps, guesses, b)(p_val)
        else:
            res = ca.vertcat(*[eq.residual for eq in eqs])
            x = ca.vertcat(*[model.symbols[u] for u in block.unknowns])
            p = ca.vertcat(*[model.symbols[d] for d in deps]) if deps else ca.SX(0, 1)
            sol = linear_solution(res, x)
            if sol is not None:
                out = ca.Function(f"block{b}", [p], [sol])(p_val)
            else:
                expandable = False
                out = _newton(model, block, ca.Function(f"res{b}", [x, p], [res]), deps, guesses, b)(p_val)
        for k, u in enumerate(block.unknowns):
            value[u] = out[k]
    outputs = [value[u] for u in structure.unknowns]
    if not expandable:
        # identical calls (two call equations slicing one integrator, inlined) are evaluated once
        outputs = ca.cse(outputs)
    fun = ca.Function(name, [value[k] for k in structure.knowns], outputs,
                      list(structure.knowns), list(structure.unknowns), MANY_INPUTS)
    return fun.expand(name, MANY_INPUTS) if expandable else fun


def _explicit_solver(model, structure: Structure, name: str) -> ca.Function | None:
    """The SX Function of a structure whose every block is explicit and without a call equation, or None.

    Each block's solution is written in the model's symbols (:func:`linear_solution`), then the unknowns are
    substituted block after block (``substitute_inplace``): one pass over the expression graph, where a Function
    per block costs a graph of its own (a route of thousands of segments has thousands of blocks)."""
    unknowns, solutions = [], []
    for block in structure.blocks:
        eqs = [model.equations[i] for i in block.equations]
        if any(eq.call is not None for eq in eqs):
            return None
        x = ca.vertcat(*[model.symbols[u] for u in block.unknowns]) if len(block.unknowns) > 1 else \
            model.symbols[block.unknowns[0]]
        sol = _definition(eqs[0].residual, x, block.unknowns[0]) if len(eqs) == 1 else None
        sol = linear_solution(ca.vertcat(*[eq.residual for eq in eqs]), x) if sol is None else sol
        if sol is None:
            return None
        unknowns += [model.symbols[u] for u in block.unknowns]
        solutions += [sol[k] for k in range(len(block.unknowns))]
    resolved, _ = ca.substitute_inplace(unknowns, solutions, [], False)    # each in terms of the knowns only
    by_name = {u: resolved[k] for k, u in enumerate(u for b in structure.blocks for u in b.unknowns)}
    return ca.Function(name, [model.symbols[k] for k in structure.knowns], [by_name[u] for u in structure.unknowns],
                       list(structure.knowns), list(structure.unknowns), MANY_INPUTS)


def _definition(res: ca.SX, x: ca.SX, name: str) -> ca.SX | None:
    """``f`` of a definition ``res = x − f`` with ``f`` free of ``x`` (the model's symbol ``name``: one symbol per
    name), else None: what :func:`linear_solution` gives, −(0 − f)/1, which CasADi simplifies to ``f`` itself,
    without its Jacobian and substitution (a route of thousands of segments defines thousands of coefficients,
    each a symbol: told apart from ``x`` by name)."""
    if not (res.is_scalar() and res.is_op(ca.OP_SUB)):
        return None
    y, f = res.dep(0), res.dep(1)
    if not (y.is_symbolic() and y.name() == name):
        return None
    free = f.name() != name if f.is_symbolic() else not ca.depends_on(f, x)
    return f if free else None


def linear_solution(res: ca.SX, x: ca.SX) -> ca.SX | None:
    """The solution of ``res(x) = 0`` for ``x`` when ``res`` is linear in ``x`` (``x = −J⁻¹ r(0)``), else None.

    Every explicit block of the compiled model is solved by it, and reports print an equation from it
    (:mod:`ropemodel.core.formulas`): the formula shown is the expression computed.
    """
    J = ca.jacobian(res, x)
    if ca.depends_on(J, x):
        return None
    r0 = ca.substitute(res, x, ca.DM.zeros(x.shape))
    return -r0 / J if x.numel() == 1 else ca.solve(J, -r0)


def _mx_residual(eqs, unknowns, deps) -> ca.Function:
    """Residual Function (x, p) → r in MX for a block with call equations."""
    x = ca.MX.sym("x", len(unknowns))
    p = ca.MX.sym("p", len(deps))
    env = {u: x[k] for k, u in enumerate(unknowns)}
    env.update({d: p[j] for j, d in enumerate(deps)})
    rows = []
    for eq in eqs:
        if eq.call is not None:
            fun, args = eq.call
            rows.append(env[eq.defines] - fun(*[env[a] for a in args]))
        else:
            syms = ca.symvar(eq.residual)
            f = ca.Function("r", syms, [eq.residual])
            rows.append(f(*[env[s.name()] for s in syms]))
    return ca.Function("res", [x, p], [ca.vertcat(*rows)])


def _newton(model, block, res: ca.Function, deps, guesses, b) -> ca.Function:
    """Newton on ``res(x, p) = 0`` for the block, in log variables for strictly positive unknowns.

    Each residual row is divided by max(1, |guess|) of the block's unknown of the same
    index.  This scaling is crude: the stopping test (``abstol`` on the scaled residual)
    can accept too early when an equation's natural size is far above its unknown's
    guess.  Writing such an equation multiplied out, so that it stays linear in the
    unknowns it is solved for, avoids the Newton block altogether.  A scaling by each
    row's own size at the start was tried and rejected: CasADi's line search measures
    progress with the same residual norm, and with it the voigt least-pretension solves
    stalled.  With the line search off as well, those solves converged, but the
    Thirion pressure inverse and the "no pretension prevents slip" refusal then
    failed their tests.  What
    guards every inverse solve is :meth:`ropemodel.problem.Problem.solve`'s
    round-trip check: the forward model must reproduce each given value.
    """
    n = len(block.unknowns)
    z = ca.MX.sym("z", n)
    p = ca.MX.sym("p", len(deps))
    x_parts, z0, scale = [], [], []
    for k, u in enumerate(block.unknowns):
        q = model.quantities[u]
        g = guesses.get(u, q.guess)
        scale.append(max(1.0, abs(g)))
        if q.positive:
            x_parts.append(ca.exp(z[k]))
            z0.append(math.log(g) if g > 0 else 0.0)
        else:
            x_parts.append(z[k])
            z0.append(g)
    x_of_z = ca.vertcat(*x_parts)
    g_res = ca.Function(f"res{b}", [z, p], [res(x_of_z, p) / ca.DM(scale)])
    rf = ca.rootfinder(f"newton{b}", "newton", g_res, NEWTON_OPTIONS)
    x_fun = ca.Function(f"x_of_z{b}", [z], [x_of_z])
    return ca.Function(f"block{b}", [p], [x_fun(rf(ca.DM(z0), p))])


_CACHE: dict[tuple, object] = {}
CACHE_SIZE = 64


def _cached(key, make):
    if key not in _CACHE:
        if len(_CACHE) >= CACHE_SIZE:  # oldest first out
            del _CACHE[next(iter(_CACHE))]
        _CACHE[key] = make()
    return _CACHE[key]


def structure_of(model, unknowns, knowns) -> Structure:
    """:func:`~ropemodel.core.structure.analyse`, once per model structure and choice of unknowns."""
    from ropemodel.core.structure import analyse

    return _cached(("structure", model.key, tuple(unknowns), tuple(knowns)), lambda: analyse(model, unknowns, knowns))


def solver_of(model, structure: Structure, guesses: dict[str, float] | None = None) -> ca.Function:
    """:func:`compile_solver`, once per model structure, choice of unknowns and Newton guesses."""
    g = tuple(sorted((guesses or {}).items()))
    return _cached(("solver", model.key, structure, g), lambda: compile_solver(model, structure, dict(g)))


def forward_of(model) -> ca.Function:
    """The forward Function of ``model``: every output from the parameters (compiled once)."""
    return solver_of(model, structure_of(model, model.outputs, model.arguments))
