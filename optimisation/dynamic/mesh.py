"""The rope's spatial discretisation under error control: how many elements per span dynamic sizing
integrates, and each check's back-off from the estimate of its discretisation error.

The transient's rope is lumped: each span cut into n = ``[numerics] segments`` Kelvin–Voigt elements
(docs/physics.md §6).  A check's least value through a manoeuvre, g(n), tends to the continuous rope's g*
as n grows, g(n) ≈ g* + C n^(−p).  Measured on the test scene of ``tests/_dynamic_scene.py`` (d 48 mm,
F_nwl 60 kN): from 4 to 8, 16 and 32 elements the slip function of the upward start moved by 226, 157 and
91 N (observed order 0.5 to 0.8), and the unwinding rope's force at the drum by 423 N at each doubling
from 8 elements (order 1: the first element's tension stands for the tangent point's force, half an
element's weight and resistance away).  Not the n^(−2) of a smooth solution, so the order is estimated
from three meshes, never assumed.

:func:`richardson`: from g(n), g(2n), g(4n), p = log2(|g(n) − g(2n)| / |g(2n) − g(4n)|) clipped to
[:data:`P_MIN`, :data:`P_MAX`] (:data:`P_MIN` where the differences change sign or do not shrink: not yet
in the asymptotic range), and the error of g(n) is E(n) = |g(n) − g(2n)| / (1 − 2^(−p)), the geometric
sum of the changes still to come (Richardson extrapolation with the observed order; Roache,
*Verification and Validation in Computational Science and Engineering*, 1998, ch. 5).

:func:`control`: at a design, every case (each manoeuvre with the load at each candidate place) on every mesh
from the scene's ``segments`` up to n (cheap: no finer than the sizing's own), and, from n = the scene's
``segments`` doubling, E(n) of each check in each case *within reach* of its limit (:func:`within_reach`: its
least margin at n within :data:`~optimisation.dynamic.screen.SCREEN_TOL` of its limit, 5 % of the load's
weight or 0.5 m of take-up, where it can govern; or within :data:`REACH` times its largest change from a coarser
mesh, where an error or a coarser mesh could take it below its limit although it does not govern) — only those
cases are integrated on 2n, and on 4n only where the coarser meshes do not show the asymptotic range
(:func:`from_coarser`: E(n) from n/4, n/2, n and 2n, the order of the finer triple not below the coarser one's by
more than :data:`P_DROP`, taken at the lower of the two) or where their estimate of a force check is above the
tolerance; the first n at which every such force check's E(n) is within the scene's ``mesh_tol`` [N] is the
mesh.  :func:`backoffs`: each check's back-off *in each case* is :data:`MARGIN` times
what its margin at n must keep (:attr:`CaseError.need`), plus the integration's
:data:`~optimisation.dynamic.problem.BACKOFF`: the larger of the part of its E(n) on the unsafe side
(:func:`unsafe_part`: all of it where the margins fall as the mesh is refined or show no steady trend, none
where they rise steadily; the stroke checks', in m, too: no tolerance of their own) and the most a coarser mesh
from the scene's judged it worse (a rising margin: the scene's own mesh, which ``simulate`` runs, and twice it
judge the design more harshly than n).  :func:`converge`: the NLP solved again on that mesh with those
back-offs, until the estimate at its optimum is within the back-offs it was solved with; the catalogue design
too (d fixed, :mod:`optimisation.dynamic.design`).  A design that keeps g(n) ≥ its need keeps g ≥ 0 in the
limit n → ∞, at every finer mesh while g(n) converges monotonically, and on every mesh from the scene's to n.

Measured on the three-segment route of issue 21 (8 elements a span; the mesh chosen, 32): the slip margin of
the downward start with the load at 1550 m, the catalogue design's active check, went −948, −314, +11, +176 N
at 8, 16, 32, 64 elements (rising: E(32) on the unsafe side 0; orders 0.96 and 0.98 from 8-16-32 and 16-32-64,
the asymptotic range: its 128 elements, a third of the sizing's time when every estimate integrated them, are
not needed).  Backed off only by its unsafe part, the design
held at 32 elements and in the limit but not with 16, twice the scene's: the coarser meshes' judgement is
now part of each case's back-off.  Per case, because one check's error differs by orders of magnitude between
places (the same check at the return sheave: 39 N).  On the test scene: the slip margins rise as the mesh is
refined, the rope safety's falls.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from optimisation.dynamic.problem import BACKOFF, DynamicSizingProblem
from optimisation.dynamic.refine import solve_refined
from optimisation.dynamic.screen import SCREEN_TOL, all_margins, check_scale, least_margins
from ropemodel.errors import SolveError

#: the least and largest order of convergence Richardson's estimate takes (the measured orders were 0.5 to 2.2)
P_MIN, P_MAX = 0.5, 2.0
#: the back-off of a check is this many times its estimated error (the error moves with the design between
#: the estimate and the optimum it sets the back-offs of)
MARGIN = 1.2
#: a check in a case is estimated (its finer meshes integrated) where its least margin at n is within this many
#: times the largest change from a coarser mesh to n: with changes still to come no larger than that one, no
#: estimate :func:`control` can make backs it off by more (Richardson's at the least order gives E at most
#: 1/(1 − 2^(−P_MIN)) = 3.41 times the next change, times :data:`MARGIN`), nor does a coarser mesh judge it below
#: its limit.  Where it is further off, no error this control could find reaches its limit
REACH = MARGIN / (1.0 - 2.0 ** -P_MIN)
#: the order of convergence may fall this much from one triple of meshes to the next, finer, one for the error to
#: be estimated from the coarser meshes (:func:`from_coarser`): an order still falling that fast past n makes
#: E(n) at most a few per cent larger than the estimate (at p = 1, 1/(1 − 2^−0.9) against 1/(1 − 2^−1): 7 %),
#: within :data:`MARGIN`
P_DROP = 0.1
#: the finest mesh :func:`control` compares with (elements per span; ``[numerics] segments`` allows 400)
SEGMENTS_MAX = 256
#: re-solves of :func:`converge`
ROUNDS = 3


def richardson(g_n: float, g_2n: float, g_4n: float) -> tuple[float, float]:
    """(E(n), p): the estimated error |g(n) − g*| of ``g_n`` and the observed order of convergence, from a
    quantity on three meshes each twice as fine (see the module).

    Examples
    --------
    g(h) = 1 + 3 h² at h = 1/4, 1/8, 1/16: the error of g(1/4) is 3/16, the order 2.

    >>> E, p = richardson(1 + 3 / 16, 1 + 3 / 64, 1 + 3 / 256)
    >>> round(E, 12), round(p, 12)
    (0.1875, 2.0)
    """
    d1, d2 = g_n - g_2n, g_2n - g_4n
    if d1 == 0.0:
        return abs(d2) / (1.0 - 2.0 ** -P_MIN), P_MIN
    p = math.log2(abs(d1) / abs(d2)) if d2 != 0.0 and d1 * d2 > 0.0 else P_MIN
    p = min(max(p, P_MIN), P_MAX)
    return abs(d1) / (1.0 - 2.0 ** -p), p


def segments_of(scene) -> int:
    return int(scene.numerics["segments"])


def with_segments(scene, n: int):
    """``scene`` with ``n`` elements per span (kept when its manoeuvres' scenes are read again)."""
    raw = {k: dict(v) if isinstance(v, dict) else v for k, v in scene.raw.items()}
    raw["numerics"] = {**raw.get("numerics", {}), "segments": n}
    return dataclasses.replace(scene, raw=raw, numerics={**scene.numerics, "segments": n})


def margins_at(problem, xs, n: int, p=None, which=None) -> dict[int, dict[str, float]]:
    """Every check's least margin (SI, before back-offs) in every case (``which``: these, indices) at scaled
    design ``xs`` with ``n`` elements per span (the NLP's integrator, no sensitivities; the smooth modes of
    another mesh built at the start design, once: :meth:`DynamicSizingProblem.start_path`)."""
    scale = {name: check_scale(problem, c) for name, c in problem.machine.manoeuvres.CHECK.items()}
    if n == segments_of(problem.scene):
        margins = all_margins(problem, xs, p, which)
    else:
        scene = with_segments(problem.scene, n)
        p = problem.p0 if p is None else p
        a = {k: float(v) for k, v in problem.values(np.asarray(xs, float) * problem.x_scale, p).items()}
        indices = range(len(problem.cases)) if which is None else which
        margins = {i: least_margins(problem, problem.start_path(i, scene), xs, p, a) for i in indices}
    return {i: {c: v * scale[c] for c, v in m.items()} for i, m in margins.items()}


@dataclass
class MeshEstimate:
    """What :func:`control` found: the ``segments`` chosen, the tolerance ``tol`` [N], the meshes compared
    (``meshes``: from the scene's to 4 ``segments``), each estimated case's checks (``cases``: a
    :class:`CaseError` per (case tag, check)), per check the largest over the cases of its error ``errors``, of
    its unsafe part ``unsafe``, of how much worse a coarser mesh judged it ``coarse`` (unit in ``units``: N or
    m) and the observed order ``orders`` at the largest error, and per mesh tried (``levels``) the largest
    force error."""

    segments: int
    tol: float
    cases: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)
    levels: list = field(default_factory=list)
    meshes: list = field(default_factory=list)

    def _largest(self, what: str) -> dict[str, float]:
        out: dict[str, float] = {}
        for (_, check), e in self.cases.items():
            out[check] = max(out.get(check, 0.0), getattr(e, what))
        return out

    @property
    def errors(self) -> dict[str, float]:
        return self._largest("error")

    @property
    def unsafe(self) -> dict[str, float]:
        return self._largest("unsafe")

    @property
    def coarse(self) -> dict[str, float]:
        return self._largest("coarse")

    @property
    def orders(self) -> dict[str, float]:
        worst: dict[str, CaseError] = {}
        for (_, check), e in self.cases.items():
            if check not in worst or e.error > worst[check].error:
                worst[check] = e
        return {c: e.order for c, e in worst.items()}

    def to_dict(self) -> dict:
        return {"segments": self.segments, "tolerance": self.tol, "errors": self.errors, "unsafe": self.unsafe,
                "coarse": self.coarse, "orders": self.orders, "units": dict(self.units), "levels": self.levels,
                "meshes": self.meshes,
                "cases": [{"case": tag, "check": c, **dataclasses.asdict(e)} for (tag, c), e in self.cases.items()]}


@dataclass(frozen=True)
class CaseError:
    """One check in one case at the chosen mesh n: its least ``margin`` there (SI, before back-offs), its
    Richardson ``error`` E(n) and observed ``order``, the ``unsafe`` part of E(n) (:func:`unsafe_part`), and
    ``coarse``: how much lower the least margin was on a coarser mesh from the scene's (≥ 0; the design must
    keep the check there too, :attr:`need`)."""

    margin: float
    error: float
    order: float
    unsafe: float
    coarse: float

    @property
    def need(self) -> float:
        """What the margin at n must keep (≥ 0): its unsafe part of E(n) (the limit n → ∞, and every finer mesh
        while the margins converge monotonically) or the most a coarser mesh judges it worse, the larger."""
        return max(self.unsafe, self.coarse)


def unsafe_part(g_n: float, g_2n: float, g_4n: float) -> float:
    """How far the margin ``g_n`` may lie above the converged one (≥ 0): E(n) where the margins fall as the
    mesh is refined (the coarse mesh flatters the design) or do not yet fall or rise steadily (no trend to
    trust), 0 where they rise steadily (the coarse mesh is on the safe side)."""
    d1, d2 = g_n - g_2n, g_2n - g_4n
    rising = d1 < 0.0 and d2 < 0.0
    return 0.0 if rising else richardson(g_n, g_2n, g_4n)[0]


def within_reach(g: dict, n: int, limits: dict[str, float]) -> dict[int, list[str]]:
    """Case → its checks whose error can reach their limit, from ``g`` (mesh → case → check → least margin,
    every case on ``n`` and every coarser mesh): those whose least margin at n is within ``limits`` (check →
    the screening's :data:`~optimisation.dynamic.screen.SCREEN_TOL` in its unit: it can govern) or within
    :data:`REACH` times the largest change from a coarser mesh to n (an error or a coarser mesh's judgement
    that large could take it below its limit)."""
    out: dict[int, list[str]] = {}
    for i, margins in g[n].items():
        for check, value in margins.items():
            change = max((abs(value - g[m][i][check]) for m in g if m < n), default=0.0)
            if value <= max(limits[check], REACH * change):
                out.setdefault(i, []).append(check)
    return out


def from_coarser(g: dict, n: int, i: int, check: str) -> tuple[float, float, float] | None:
    """(E(n), p, unsafe part) of ``check`` in case ``i`` from the meshes n/4, n/2, n and 2n of ``g`` (no 4n), or
    None when they do not show the asymptotic range.  They show it when the three changes have one sign and the
    order of the finer triple, p(n/2, n, 2n), is at least :data:`P_MIN` and not below the coarser triple's,
    p(n/4, n/2, n), by more than :data:`P_DROP`; then E(n) = |g(n) − g(2n)| / (1 − 2^(−p)) with p the lower of
    the two (clipped at :data:`P_MAX`) — the same change as Richardson's from n, 2n, 4n (:func:`richardson`), at
    an order that is, with the order rising as the mesh is refined (the usual approach to the asymptotic range),
    less than the finest triple would show, so a larger error.  The unsafe part is 0 where the margins rise
    steadily (all three changes), else E(n)."""
    meshes = (n // 4, n // 2, n, 2 * n)
    if n % 4 or any(i not in g.get(m, {}) or check not in g[m][i] for m in meshes):
        return None
    v = [g[m][i][check] for m in meshes]
    d = [v[k] - v[k + 1] for k in range(3)]
    if not (all(x > 0.0 for x in d) or all(x < 0.0 for x in d)):
        return None
    p_coarse, p_fine = math.log2(d[0] / d[1]), math.log2(d[1] / d[2])
    if p_fine < P_MIN or p_fine < p_coarse - P_DROP:
        return None
    p = min(p_coarse, p_fine, P_MAX)
    e = abs(d[2]) / (1.0 - 2.0 ** -p)
    return e, p, (0.0 if d[2] < 0.0 else e)


def estimate(g: dict, n: int, near: dict[int, list[str]], tags: list[str]) -> dict:
    """(case tag, check) → :class:`CaseError` at ``n`` for each case's checks in ``near``, from ``g`` (mesh →
    case → check → least margin, SI: ``near``'s cases on n and 2n, every case on the coarser meshes): from n, 2n
    and 4n (:func:`richardson`, :func:`unsafe_part`) where ``g`` has the case on 4n, else from the coarser meshes
    (:func:`from_coarser`)."""
    out = {}
    for i, checks in near.items():
        for check in checks:
            g_n = g[n][i][check]
            if i in g.get(4 * n, {}):
                three = (g_n, g[2 * n][i][check], g[4 * n][i][check])
                e, p = richardson(*three)
                unsafe = unsafe_part(*three)
            else:
                found = from_coarser(g, n, i, check)
                if found is None:
                    raise ValueError(f"case {tags[i]}: {check} needs {4 * n} elements per span to be estimated")
                e, p, unsafe = found
            coarse = max((g_n - g[m][i][check] for m in g if m < n), default=0.0)
            out[(tags[i], check)] = CaseError(g_n, e, p, unsafe, max(coarse, 0.0))
    return out


def needs_finer(g: dict, n: int, near: dict[int, list[str]], tol: float, units: dict[str, str]) -> dict:
    """The cases of ``near`` (case → checks) to integrate on 4n: those where some check's margins on the coarser
    meshes do not show the asymptotic range (:func:`from_coarser`), or where a force check's estimate from them
    is above ``tol`` [N] (the sharper order of the finest triple may bring it within: the mesh is not refined on
    the coarser estimate alone)."""
    out = {}
    for i, checks in near.items():
        for check in checks:
            found = from_coarser(g, n, i, check)
            if found is None or (units[check] == "N" and found[0] > tol):
                out[i] = checks
                break
    return out


def control(problem, xs, p=None, say=None, coarsest: int | None = None) -> MeshEstimate | None:
    """The mesh and each check's estimated error in each case within reach at scaled design ``xs`` (see the
    module), comparing with every mesh from ``coarsest`` elements per span (default the problem's) up; None
    when the transient's rope has no elements to refine (``mesh_tol`` not a parameter: a rigid rope, one
    spring)."""
    if "mesh_tol" not in problem.scene.parameters:
        return None
    tol = problem.scene.parameters["mesh_tol"]
    n = segments_of(problem.scene)
    check = problem.machine.manoeuvres.CHECK
    units = {c: check[c].unit for c in check}
    limits = {c: SCREEN_TOL * check_scale(problem, check[c]) for c in check}
    tags = [case.tag for case in problem.cases]
    every = range(len(problem.cases))
    g: dict[int, dict] = {}
    m = coarsest or n
    while m < n:                    # the coarser meshes from the scene's, every case: their judgement counts too
        _measure(problem, xs, p, g, m, every, say)
        m *= 2
    levels = []
    while True:
        _measure(problem, xs, p, g, n, every, say)
        near = within_reach(g, n, limits)
        _measure(problem, xs, p, g, 2 * n, near, say)   # the finer meshes only in the cases within reach
        _measure(problem, xs, p, g, 4 * n, needs_finer(g, n, near, tol, units), say)
        found = estimate(g, n, near, tags)
        force = max((e.error for (_, c), e in found.items() if units[c] == "N"), default=0.0)
        levels.append({"segments": n, "largest_force_error": force})
        if force <= tol:
            return MeshEstimate(n, tol, found, {c: units[c] for _, c in found}, levels, sorted(g))
        if 8 * n > SEGMENTS_MAX:
            raise SolveError(f"the rope's discretisation error is {force:.4g} N at {n} elements per span "
                             f"(Richardson's estimate from {n}, {2 * n} and {4 * n}), above mesh_tol = {tol:.4g} N; "
                             f"no finer mesh is tried (it would compare with {8 * n} > {SEGMENTS_MAX}): raise mesh_tol")
        n *= 2


def _measure(problem, xs, p, g: dict, m: int, cases, say) -> None:
    """``g[m]`` (case → check → least margin with ``m`` elements per span) filled in for ``cases``."""
    missing = [i for i in cases if i not in g.setdefault(m, {})]
    if missing:
        if say is not None:
            say(f"mesh: {m} elements per span")
        g[m].update(margins_at(problem, xs, m, p, missing))


def backoffs(problem, found: MeshEstimate) -> dict[str, dict[str, float]]:
    """Case tag → check → its back-off in the NLP (scaled): :data:`MARGIN` times what the margin must keep
    (:attr:`CaseError.need`), plus :data:`BACKOFF`."""
    check = problem.machine.manoeuvres.CHECK
    out: dict[str, dict[str, float]] = {}
    for (tag, c), e in found.cases.items():
        out.setdefault(tag, {})[c] = BACKOFF + MARGIN * e.need / check_scale(problem, check[c])
    return out


def _solved_with(problem, wanted: dict) -> bool:
    """Whether every need in ``wanted`` (:func:`backoffs`, less its :data:`MARGIN`) is within the back-off
    ``problem`` was solved with."""
    return all(BACKOFF + (b - BACKOFF) / MARGIN <= problem.backoffs.get(tag, {}).get(c, BACKOFF) * (1 + 1e-9)
               for tag, by in wanted.items() for c, b in by.items())


def converge(problem, sol, record=None, say=None, fix_d: float | None = None, coarsest: int | None = None):
    """The optimum ``sol`` of ``problem`` (``fix_d``: with d fixed, the catalogue's) solved again on the mesh
    :func:`control` chooses (comparing from ``coarsest`` elements per span, default the problem's), with the
    back-offs of :func:`backoffs`, until the estimate at its optimum is within the back-offs it was solved with:
    (problem, solution, :class:`MeshEstimate` or None).  Each re-solve first tries Newton on the previous
    optimum's active set (:func:`~optimisation.dynamic.warm.on_active_set`: kept only at a KKT point of the new
    problem), then IPOPT from it.  A solution that is not feasible is returned as it is (no design on the finer
    mesh)."""
    coarsest = coarsest or segments_of(problem.scene)
    for _ in range(ROUNDS):
        found = control(problem, sol.xs, say=say, coarsest=coarsest)
        if found is None:
            return problem, sol, None
        wanted = backoffs(problem, found)
        if found.segments == segments_of(problem.scene) and _solved_with(problem, wanted):
            return problem, sol, found
        if say is not None:
            say(f"dynamic optimum on {found.segments} elements per span, checks backed off by their error")
        scene, old = with_segments(problem.scene, found.segments), problem
        problem = DynamicSizingProblem(scene, selected=problem.selected, backoffs=wanted,
                                       shared_paths=problem.shared_paths)
        problem, sol = solve_refined(problem, sol.xs, fix_d=fix_d, record=record, warm=(old, sol))
        if not sol.feasible:
            return problem, sol, found
    raise SolveError(f"the mesh's error estimates at the optimum kept exceeding the back-offs it was solved with "
                     f"after {ROUNDS} re-solves; report it")
