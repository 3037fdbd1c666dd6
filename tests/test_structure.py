"""Structure checks: every effect combination is well-posed; DM analysis against brute force."""

import itertools

import casadi as ca
import numpy as np
import pytest

import ropemodel as rm
from ropemodel.core import Model, analyse, compile_solver
from ropemodel.core.structure import incidence
from ropemodel.effects import REGISTRY, Equation, Submodel, Symbols, define_effect, register
from ropemodel.quantity import Quantity


def _builds_equations(cls) -> bool:
    return bool(cls().equations(Symbols()))


def _inert(effects) -> list[str]:
    """Effects none of whose variants builds an algebraic equation (e.g. the transient-only ones)."""
    return [e for e, spec in effects.items() if not any(_builds_equations(c) for c in spec.variants.values())]


def _combinations():
    """Every combination of the variants that can change the equation system; inert effects at default."""
    for model, effects in sorted(REGISTRY.items()):
        if model.startswith("_test"):
            continue
        names = sorted(set(effects) - set(_inert(effects)))
        for variants in itertools.product(*(sorted(effects[e].variants) for e in names)):
            yield model, dict(zip(names, variants))


def test_inert_effects_leave_the_equations_alone():
    """What justifies leaving inert effects out of the product: switching them changes no equation."""
    for model, effects in REGISTRY.items():
        for e in _inert(effects):
            ref = [(q.defines, q.source) for q in Model(model).equations]
            for v in effects[e].variants:
                assert [(q.defines, q.source) for q in Model(model, {e: v}).equations] == ref


def _pairs(model, effects) -> set:
    items = sorted(effects.items())
    return {(model, a) for a in items} | {(model, a, b) for a, b in itertools.combinations(items, 2)}


def _pairwise(combinations) -> set[int]:
    """Indices of a covering sample: every variant, and every pair of variants of two effects, is in at
    least one chosen combination (greedy: the combination that covers the most uncovered pairs first).
    An ill-posed system comes from how two effects' equations meet; the default suite checks these 60 or
    so, ``-m slow`` all 3,000."""
    covers = [_pairs(model, effects) for model, effects in combinations]
    uncovered = set().union(*covers)
    chosen: set[int] = set()
    while uncovered:
        best = max(range(len(covers)), key=lambda i: len(covers[i] & uncovered))
        chosen.add(best)
        uncovered -= covers[best]
    return chosen


def _structure_cases():
    combinations = list(_combinations())
    sample = _pairwise(combinations)
    for i, (model, effects) in enumerate(combinations):
        yield pytest.param(model, effects, id=f"{model}-" + ",".join(f"{k}={v}" for k, v in effects.items()),
                           marks=[] if i in sample else [pytest.mark.slow])


def test_the_default_sample_covers_every_pair_of_variants():
    """The sample is a covering array: checked by brute force over all pairs, not by the greedy's own count."""
    combinations = list(_combinations())
    sample = [combinations[i] for i in _pairwise(combinations)]
    assert len(sample) < len(combinations) / 20
    for model, effects in combinations:
        for a, b in itertools.combinations(sorted(effects.items()), 2):
            assert any(m == model and e[a[0]] == a[1] and e[b[0]] == b[1] for m, e in sample), (model, a, b)


@pytest.mark.parametrize("model, effects", list(_structure_cases()))
def test_every_effect_combination_is_well_posed(model, effects):
    m = Model(model, effects)
    s = analyse(m, m.outputs, m.parameters)
    assert sorted(u for b in s.blocks for u in b.unknowns) == sorted(m.outputs)
    # an independent check: CasADi's structural rank of the full incidence equals the count
    A = incidence(m, m.outputs)
    assert A.shape[0] == A.shape[1] == len(m.outputs)
    rows = [i for i, js in enumerate(A.rows) for _ in js]
    cols = [j for js in A.rows for j in js]
    assert ca.sprank(ca.Sparsity.triplet(*A.shape, rows, cols)) == len(m.outputs)


def test_elongation_off_builds_no_elongation_equation(fig9):
    on = Model("winch", {"elongation": "krauze2025"})
    off = Model("winch", {"elongation": "none"})
    assert {"dF_up", "dF_nwl", "dF_C_down"} <= set(on.outputs)
    assert not [o for o in off.outputs if o.startswith("dF")]
    assert "q_lw" not in off.parameters
    # eq. (19)-(21), (23) per direction + eq. (22) + the rope's EA = L_u/q_lw
    assert len(on.equations) - len(off.equations) == 10


def test_power_only_when_asked():
    assert not [o for o in Model("winch").outputs if o.startswith("N_p")]
    assert {"N_p_up", "N_p_down"} <= set(Model("winch", {"power": "drive"}).outputs)


def test_blocks_ordered_and_explicit(fig9):
    m = fig9.built
    s = analyse(m, m.outputs, m.parameters)
    solved = set(m.parameters)
    for b in s.blocks:  # each block needs only knowns and earlier blocks
        for i in b.equations:
            assert set(m.equations[i].names()) - set(b.unknowns) <= solved
        solved |= set(b.unknowns)
    assert all(len(b.unknowns) == 1 for b in s.blocks)  # the forward winch model is fully explicit


def test_random_structures_against_sprank():
    """Well-posedness verdicts agree with CasADi's structural rank on random patterns."""
    rng = np.random.default_rng(1)
    for _ in range(200):
        n = rng.integers(2, 7)
        P = rng.random((n, n)) < 0.35

        class Fake:
            pass

        x = [ca.SX.sym(f"x{j}") for j in range(n)]
        eqs = [sum((x[j] for j in range(n) if P[i, j]), ca.SX(0)) for i in range(n)]
        fake = Fake()
        fake.equations = [Equation(f"e{i}", e, "") for i, e in enumerate(eqs)]
        fake.structural = lambda i, fake=fake: fake.equations[i].residual
        fake.symbols = {f"x{j}": x[j] for j in range(n)}
        fake.parameters, fake.defined_by = [], {}
        rank = ca.sprank(ca.jacobian(ca.vertcat(*eqs), ca.vertcat(*x)).sparsity())
        if rank == n:
            analyse(fake, [f"x{j}" for j in range(n)], [])
        else:
            with pytest.raises(rm.IllPosedError):
                analyse(fake, [f"x{j}" for j in range(n)], [])


@pytest.fixture()
def toy_model():
    """A throw-away model with a call equation y = f(a, b) through a CasADi integrator."""
    name = "_test_toy"
    define_effect(name, "main", "on", "toy")

    y0, k = ca.MX.sym("y0"), ca.MX.sym("k")
    y = ca.MX.sym("y")
    integ = ca.integrator("decay", "cvodes", {"x": y, "p": k, "ode": -k * y}, 0.0, 1.0,
                          {"abstol": 1e-12, "reltol": 1e-12})
    fun = ca.Function("y_end", [y0, k], [integ(x0=y0, p=k)["xf"]])

    @register(name, "main", "on")
    class Toy(Submodel):
        quantities = (Quantity("a", "1", "initial value", positive=True, low=0, guess=1.0),
                      Quantity("k", "1", "rate", guess=0.5),
                      Quantity("y", "1", "value at t = 1"),
                      Quantity("z", "1", "twice y"))

        def equations(self, v):
            return [Equation.from_call("y", fun, ("a", "k"), "y = a exp(-k)", "a CasADi Function"),
                    Equation("z", v["z"] - 2 * v["y"], "z = 2 y")]

    yield name
    del REGISTRY[name]


def test_call_equation_forward_and_inverse(toy_model):
    m = Model(toy_model)
    fwd = compile_solver(m, analyse(m, ["y", "z"], ["a", "k"]))
    out = fwd(a=2.0, k=0.3)
    assert float(out["y"]) == pytest.approx(2 * np.exp(-0.3), rel=1e-9)   # closed form of the ODE
    assert float(out["z"]) == pytest.approx(4 * np.exp(-0.3), rel=1e-9)
    # inverse through the integrator: k from z
    inv = compile_solver(m, analyse(m, ["y", "k"], ["a", "z"]))
    assert float(inv(a=2.0, z=1.0)["k"]) == pytest.approx(np.log(4.0), rel=1e-8)
    # sensitivities through the integrator: dz/dk = -2 a exp(-k)
    a, k = ca.MX.sym("a"), ca.MX.sym("k")
    dz = ca.Function("dz", [a, k], [ca.jacobian(fwd(a=a, k=k)["z"], k)])
    assert float(dz(2.0, 0.3)) == pytest.approx(-4 * np.exp(-0.3), rel=1e-7)


def test_matching_is_maximum_against_scipy():
    """Our augmenting-path matching has the size of scipy's maximum bipartite matching (independent code)."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import maximum_bipartite_matching

    from ropemodel.core.structure import Incidence, matching

    rng = np.random.default_rng(7)
    for _ in range(300):
        n, m = rng.integers(1, 60, size=2)
        P = rng.random((n, m)) < rng.uniform(0.02, 0.3)
        rows = tuple(tuple(int(j) for j in np.flatnonzero(P[i])) for i in range(n))
        cols = tuple(tuple(int(i) for i in np.flatnonzero(P[:, j])) for j in range(m))
        row_match, col_match = matching(Incidence(rows, cols))
        size = sum(j >= 0 for j in row_match)
        assert size == sum(i >= 0 for i in col_match)
        assert all(col_match[j] == i for i, j in enumerate(row_match) if j >= 0)
        assert all(P[i, j] for i, j in enumerate(row_match) if j >= 0)
        ref = maximum_bipartite_matching(sp.csr_matrix(P.astype(float)), perm_type="column")
        assert size == int((ref >= 0).sum())
