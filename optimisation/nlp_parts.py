"""The parts the sizing NLP is built of (:class:`optimisation.problem.SizingProblem`): the scene's model as a
Function of three vectors (design, parameters, case inputs) with only the outputs the checks read, which case
inputs each check depends on, and the places' x_m as sums of the NLP's parameters."""

from __future__ import annotations

from typing import Any

import casadi as ca

from ropemodel.core.evaluate import reordered


class _Reads(dict):
    """Outputs as symbols, each made when first read: its keys are what a declaration's ``nlp_form`` writes a
    check from."""

    def __missing__(self, key):
        self[key] = ca.MX.sym(key)
        return self[key]


def nlp_outputs(names, checks, sizing, args) -> list[str]:
    """The outputs among ``names`` the NLP reads (each check in its ``nlp_form``, the primary objective), in
    their order."""
    out = _Reads()
    for c in checks:
        sizing.nlp_form(c, out, args)
    wanted = {sizing.PRIMARY, *checks, *out}
    return [k for k in names if k in wanted]


def restricted(model: ca.Function, outputs) -> ca.Function:
    """``model`` (:func:`vector_model`) with only ``outputs``: the same expressions, called on its three vectors
    (not built again from the scene's model of one input per known: a route's has 20 000)."""
    sym: Any = ca.SX.sym if model.is_a("SXFunction") else ca.MX.sym
    args = {k: sym(k, model.size1_in(k)) for k in model.name_in()}
    out = model.call(args)
    return ca.Function(model.name(), [args[k] for k in model.name_in()], [out[k] for k in outputs],
                       list(model.name_in()), list(outputs))


def partly_folded(model: ca.Function, p0, kept) -> ca.Function:
    """The SX ``model`` (x, p, c) with its parameters other than ``kept`` (indices into p) fixed at ``p0``: a
    Function (x, p_kept, c) in which CasADi has done the arithmetic on the fixed values once (a long route's sums
    and minima are numbers, so its derivatives in the kept parameters no longer pass through every segment)."""
    x, c = (ca.SX.sym(k, model.size1_in(k)) for k in ("x", "c"))
    pk = ca.SX.sym("p", len(kept))
    p = ca.SX(ca.DM(p0))
    for j, i in enumerate(kept):
        p[i] = pk[j]
    return ca.Function(model.name(), [x, pk, c], model.call([x, p, c]), ["x", "p", "c"], model.name_out())


def vector_model(fun: ca.Function, variables, params, free, given, outputs=None) -> ca.Function:
    """``fun`` (one scalar input per known) as a Function of three vectors: the design ``x`` (SI, in the order of
    ``variables``), the NLP's parameters ``p`` (``params``) and the case inputs ``c`` (``free``); the ``given``
    outputs 0; only ``outputs`` (default all; the NLP's: :func:`nlp_outputs`, a route's model has an output per
    segment, and every derivative of the NLP would carry them).  Each case of the NLP is one call of it, not a node
    per parameter (a route has thousands), and its derivatives are those of one SX Function."""
    if outputs is not None and not fun.is_a("SXFunction"):   # an MX call node evaluates every output of its Function
        fun = reordered(fun, fun.name_in(), outputs)
    sym: Any = ca.SX.sym if fun.is_a("SXFunction") else ca.MX.sym
    x, p, c = sym("x", len(variables)), sym("p", len(params)), sym("c", len(free))
    env = {**dict(zip(params, ca.vertsplit(p) if params else [])), **{k: c[i] for i, k in enumerate(free)},
           **{k: x[i] for i, k in enumerate(variables)}, **{k: 0.0 for k in given}}
    out = fun.call({k: env[k] for k in fun.name_in() if k in env})
    names = list(fun.name_out()) if outputs is None else list(outputs)
    return ca.Function("nlp_model", [x, p, c], [out[k] for k in names], ["x", "p", "c"], names)


class Ends:
    """x_m of joint k, L_1 + … + L_k, as one sum of the NLP's parameters (their indices ``lengths``), made when
    asked: summed in order, as the model's own cumulative sums of the segments are."""

    def __init__(self, p, lengths):
        self.p, self.lengths = p, lengths

    def __getitem__(self, k: int):
        return ca.sum1(self.p[self.lengths[:k]]) if k else 0.0


def depends(model: ca.Function, checks, free, inputs=None, follows=None) -> dict[str, tuple[str, ...]]:
    """Check → the case inputs of ``free`` it depends on (as :func:`ropemodel.envelope.cases.depends_on`), from the
    structure of :func:`vector_model`: one sparsity sweep per check through its case input vector ``c`` (of
    ``inputs``, default ``free``; one of them in ``follows``, a long route's number, counts as the case inputs it
    follows)."""
    inputs = list(free if inputs is None else inputs)
    follows = follows or {}
    out = {}
    for check in checks:
        pattern = model.sparsity_jac("c", check) if inputs else None
        used = {k for j, k in enumerate(inputs) if pattern is not None and pattern.has_nz(0, j)}
        out[check] = tuple(k for k in free if k in used or any(k in follows.get(n, ()) for n in used))
    return out


def check_work(scene, where: list, spanned: int) -> None:
    """The NLP's size on a route, every check at every load case it is built at (the places that can govern, of
    ``spanned`` cases) through every segment, against its budget."""
    from ropemodel import budget

    segments = len(scene.route)
    if segments:       # counted so on a route held as route numbers too: size --dynamic's transient goes through each
        kept = "" if len(where) == spanned else f" (the cases that can govern of {spanned})"
        budget.check("route sizing", len(where) * segments,
                     f"sizing on a route of {segments} segments checks every check at {len(where)} load cases{kept}, "
                     f"each through the {segments} segments: an NLP of {len(where)} x {segments}",
                     "join neighbouring segments of nearly the same inclination")
