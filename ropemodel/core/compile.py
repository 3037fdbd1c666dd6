"""Compile a well-posed structure into one CasADi Function: knowns → unknowns.

Each block of the block-triangular form is solved in turn, in terms of the
knowns and of the blocks before it:

* **explicit** blocks — the residuals are linear in the block's unknowns (every
  definition ``y - f(x) = 0`` of the forward problem, and inverse questions such
  as "G_m from F_C" that stay linear): solved symbolically, ``x = -J⁻¹ r(0)``,
  so the forward model is a closed-form expression with no iteration at all;
* **implicit** blocks — nonlinear in their unknowns (the Voigt lining's implicit
  tension, an inverse solve through a sine): CasADi's ``rootfinder`` (Newton)
  from the quantities' guesses.  Strictly positive unknowns are solved for their
  logarithm, which keeps Newton inside the domain and makes the lining's
  ``ln s + c s = μα`` convex and monotone.

When no block is implicit the Function is expanded to SX (fast for sweeps).
The rootfinder is differentiable (implicit function theorem), so sensitivities
of inverse solves come out of the same Function.
"""

from __future__ import annotations

import math

import casadi as ca

from ropemodel.core.structure import Structure

NEWTON_OPTIONS = {"abstol": 1e-12, "abstolStep": 1e-14, "max_iter": 100, "error_on_fail": False}


def compile_solver(model, structure: Structure, guesses: dict[str, float] | None = None,
                   name: str = "solve") -> ca.Function:
    """Function with one named scalar input per known and one named output per unknown."""
    guesses = dict(guesses or {})
    value: dict[str, ca.MX] = {k: ca.MX.sym(k) for k in structure.knowns}
    implicit = False
    for b, block in enumerate(structure.blocks):
        res = ca.vertcat(*[model.equations[i].residual for i in block.equations])
        x = ca.vertcat(*[model.symbols[u] for u in block.unknowns])
        dep_syms = [s for s in ca.symvar(res) if s.name() not in block.unknowns]
        dep_vals = [value[s.name()] for s in dep_syms]
        p = ca.vertcat(*dep_syms) if dep_syms else ca.SX(0, 1)
        J = ca.jacobian(res, x)
        if not ca.depends_on(J, x):
            r0 = ca.substitute(res, x, ca.DM.zeros(x.shape))
            sol = -r0 / J if x.numel() == 1 else ca.solve(J, -r0)
            f = ca.Function(f"block{b}", [p], [sol])
        else:
            implicit = True
            f = _newton_block(model, block, res, x, p, guesses, b)
        out = f(ca.vertcat(*dep_vals) if dep_vals else ca.MX(0, 1))
        for k, u in enumerate(block.unknowns):
            value[u] = out[k]
    fun = ca.Function(name, [value[k] for k in structure.knowns], [value[u] for u in structure.unknowns],
                      list(structure.knowns), list(structure.unknowns))
    return fun if implicit else fun.expand()


def _newton_block(model, block, res, x, p, guesses, b):
    """Newton on the block, in log variables for strictly positive unknowns."""
    z = ca.SX.sym("z", x.numel())
    x_of_z, z0 = [], []
    for k, u in enumerate(block.unknowns):
        q = model.quantities[u]
        g = guesses.get(u, q.guess)
        if q.positive:
            x_of_z.append(ca.exp(z[k]))
            z0.append(math.log(g) if g > 0 else 0.0)
        else:
            x_of_z.append(z[k])
            z0.append(g)
    x_of_z = ca.vertcat(*x_of_z)
    scale = ca.DM([max(1.0, abs(guesses.get(u, model.quantities[u].guess))) for u in block.unknowns])
    g_res = ca.substitute(res, x, x_of_z) / scale
    rf = ca.rootfinder(f"newton{b}", "newton", ca.Function(f"res{b}", [z, p], [g_res]), NEWTON_OPTIONS)
    p_mx = ca.MX.sym("p", p.shape)
    x_fun = ca.Function(f"x_of_z{b}", [z], [x_of_z])
    return ca.Function(f"block{b}", [p_mx], [x_fun(rf(ca.DM(z0), p_mx))])
