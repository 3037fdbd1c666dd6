"""Structural analysis of a choice of unknowns (Dulmage–Mendelsohn).

Given the equations of a :class:`~ropemodel.core.model.Model` and a set of
unknowns, the incidence pattern (which unknown appears in which equation, the
sparsity of the Jacobian) decides whether the problem is well-posed before any
number is computed:

* a maximum matching of equations to unknowns (augmenting paths, Kuhn's algorithm)
  shows the *under-determined* unknowns (reachable by alternating paths from an
  unmatched unknown: no equation pins them) and the *over-determined* equations
  (reachable from an unmatched equation: more equations than their unknowns);
* when the matching is perfect, CasADi's ``Sparsity.btf`` gives the fine
  block-triangular form: the irreducible blocks, each solved in turn.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import casadi as ca

from ropemodel.errors import IllPosedError


@dataclass(frozen=True)
class Block:
    """An irreducible block: equations (indices into the model) solved together for ``unknowns``."""

    equations: tuple[int, ...]
    unknowns: tuple[str, ...]


@dataclass(frozen=True)
class Structure:
    """A well-posed choice of unknowns, with its blocks in solving order."""

    unknowns: tuple[str, ...]
    knowns: tuple[str, ...]
    blocks: tuple[Block, ...]


@dataclass(frozen=True)
class Incidence:
    """Which unknown appears in which equation (the sparsity of ∂residual/∂unknowns), both ways."""

    rows: tuple[tuple[int, ...], ...]   # equation → unknowns
    cols: tuple[tuple[int, ...], ...]   # unknown → equations

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.rows), len(self.cols)


def incidence(model, unknowns) -> Incidence:
    """Equations × unknowns incidence (the sparsity of ∂residual/∂unknowns)."""
    res = ca.vertcat(*[model.structural(i) for i in range(len(model.equations))])
    x = ca.vertcat(*[model.symbols[u] for u in unknowns])
    J = ca.jacobian_sparsity(res, x)   # the pattern only: the Jacobian itself grows as the square of a long route
    rows, cols = J.get_triplet()
    by_row: list[list[int]] = [[] for _ in range(J.size1())]
    by_col: list[list[int]] = [[] for _ in range(J.size2())]
    for i, j in zip(rows, cols):
        by_row[i].append(j)
        by_col[j].append(i)
    return Incidence(tuple(map(tuple, by_row)), tuple(map(tuple, by_col)))


def matching(A: Incidence) -> tuple[list[int], list[int]]:
    """A maximum matching: (unknown matched to each equation, equation matched to each unknown), -1 if none.

    Kuhn's augmenting-path algorithm, O(V·E): the systems here have at most a few hundred equations.
    """
    row_match, col_match = [-1] * len(A.rows), [-1] * len(A.cols)

    def augment(i, seen):
        for j in A.rows[i]:
            if j in seen:
                continue
            seen.add(j)
            if col_match[j] < 0 or augment(col_match[j], seen):
                row_match[i], col_match[j] = j, i
                return True
        return False

    for i in range(len(A.rows)):
        augment(i, set())
    return row_match, col_match


def _alternating_reach(start, neighbours, partner):
    """Nodes reachable from ``start`` along edge → matched-edge alternating paths."""
    seen_a, seen_b = set(start), set()
    queue = deque(start)
    while queue:
        a = queue.popleft()
        for b in neighbours(a):
            if b in seen_b:
                continue
            seen_b.add(b)
            nxt = partner(b)
            if nxt >= 0 and nxt not in seen_a:
                seen_a.add(nxt)
                queue.append(nxt)
    return seen_a, seen_b


def analyse(model, unknowns, knowns) -> Structure:
    """Check that ``unknowns`` are determined by the model's equations; return the blocks.

    Raises :class:`~ropemodel.errors.IllPosedError` naming the under- and
    over-determined variables otherwise.
    """
    unknowns, knowns = list(unknowns), list(knowns)
    A = incidence(model, unknowns)
    n_eq, n_x = A.shape
    row_match, col_match = matching(A)   # eq -> unknown, unknown -> eq: one matching, both ways
    free_x = [j for j in range(n_x) if col_match[j] < 0]
    free_eq = [i for i in range(n_eq) if row_match[i] < 0]
    if free_x or free_eq:
        # under-determined: unknowns reachable from unmatched unknowns (x -> eq -> its matched x)
        under, _ = _alternating_reach(free_x, lambda j: A.cols[j], lambda i: row_match[i])
        # over-determined: equations reachable from unmatched equations (eq -> x -> its matched eq)
        over_eq, over_x = _alternating_reach(free_eq, lambda i: A.rows[i], lambda j: col_match[j])
        raise IllPosedError(_message(model, unknowns, knowns, n_eq, n_x, under, over_eq, over_x))
    return Structure(tuple(unknowns), tuple(knowns), tuple(_blocks(model, unknowns, A, row_match)))


def _blocks(model, unknowns, A, row_match):
    """Fine BTF blocks (CasADi) ordered so that each block only needs earlier ones."""
    n = A.shape[0]
    # permute columns so the matching lies on the diagonal, then take CasADi's BTF
    perm = list(row_match)                       # diagonal position i holds unknown perm[i]
    where = {j: k for k, j in enumerate(perm)}
    tri = [(i, where[j]) for i in range(n) for j in A.rows[i]]
    S = ca.Sparsity.triplet(n, n, [t[0] for t in tri], [t[1] for t in tri])
    nb, rowperm, colperm, rowblock, colblock, _, _ = S.btf()
    raw = []
    for k in range(nb):
        eqs = tuple(rowperm[rowblock[k]:rowblock[k + 1]])
        cols = tuple(int(perm[c]) for c in colperm[colblock[k]:colblock[k + 1]])
        raw.append((eqs, cols))
    owner = {c: k for k, (_, cols) in enumerate(raw) for c in cols}
    deps = []
    for eqs, cols in raw:
        needed = {owner[int(j)] for i in eqs for j in A.rows[i]}
        deps.append(needed - {owner[cols[0]]})
    order, done = [], set()
    while len(order) < nb:  # topological order; the BTF guarantees there is no cycle
        for k in range(nb):
            if k not in done and deps[k] <= done:
                done.add(k)
                order.append(k)
    return [Block(tuple(int(i) for i in raw[k][0]), tuple(unknowns[c] for c in raw[k][1])) for k in order]


def _message(model, unknowns, knowns, n_eq, n_x, under, over_eq, over_x):
    parts = [f"ill-posed: {n_eq} equations for {n_x} unknowns"]
    if under:
        names = sorted(unknowns[j] for j in under)
        found = [n for n in names if n in model.parameters]
        shown = found or names
        more = (f" (and {len(names) - len(found)} quantities computed from them)"
                if found and len(names) > len(found) else "")
        parts.append(f"under-determined (no equation pins them): {', '.join(shown)}{more}"
                     " — give another --given value or --find fewer")
    if over_eq:
        eqs = sorted(model.equations[i].defines for i in over_eq)
        givens = sorted(k for k in knowns if k in model.defined_by and k in eqs)
        upstream = sorted(_upstream_knowns(model, [model.equations[i] for i in over_eq], set(knowns)))
        if givens:
            text = f"over-determined: {', '.join(givens)} given, but every input it depends on is known too"
        else:
            text = f"over-determined: the equations for {', '.join(eqs)} have no unknown left to satisfy"
        if upstream:
            text += f" — free one of {', '.join(upstream)} with --find"
        parts.append(text)
    return "; ".join(parts)


def _upstream_knowns(model, equations, knowns):
    """Known quantities the given equations depend on, directly or through defined ones."""
    out, seen = set(), set()
    stack = list(equations)
    while stack:
        eq = stack.pop()
        for name in eq.names():
            if name in seen:
                continue
            seen.add(name)
            if name in knowns and name in model.parameters:
                out.add(name)
            elif name in model.defined_by and model.equation_of(name) is not eq:
                stack.append(model.equation_of(name))
    return out
