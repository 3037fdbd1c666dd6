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

:func:`control`: at a design, from n = the scene's ``segments``, doubling: E(n) of every check in every
case where it can govern (its least margin within :data:`~optimisation.dynamic.screen.SCREEN_TOL` of its
limit: 5 % of the load's weight, 0.5 m of take-up); the first n at which every force check's E(n) is
within the scene's ``mesh_tol`` [N] is the mesh.  :func:`backoffs`: each check's back-off in the NLP is
:data:`MARGIN` times the part of its largest E(n) on the unsafe side (:func:`unsafe_part`: all of it where
the margins fall as the mesh is refined or show no steady trend, none where they rise steadily; the stroke
checks', in m, too: no tolerance of their own) plus the integration's
:data:`~optimisation.dynamic.problem.BACKOFF`.  :func:`converge`: the NLP solved again on
that mesh with those back-offs, until the estimate at its optimum is within the back-offs it was solved
with.  A design that keeps g(n) ≥ its unsafe part of E(n) keeps g ≥ 0 in the limit n → ∞, and at every
finer mesh while g(n) converges monotonically.  Measured on the test scene: the slip margins rise as the mesh
is refined (the coarse mesh is on the safe side), the rope safety's falls.
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
    """What :func:`control` found: the ``segments`` chosen, the tolerance ``tol`` [N], each check's estimated
    error ``errors`` (its unit in ``units``: N or m), how much of it is on the unsafe side ``unsafe`` (the
    margin at n above the converged one: what the back-off must cover) and observed ``orders`` there, and per
    mesh tried (``levels``) the largest force error."""

    segments: int
    tol: float
    errors: dict = field(default_factory=dict)
    unsafe: dict = field(default_factory=dict)
    orders: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)
    levels: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"segments": self.segments, "tolerance": self.tol, "errors": self.errors, "unsafe": self.unsafe,
                "orders": self.orders, "units": self.units, "levels": self.levels}


def unsafe_part(g_n: float, g_2n: float, g_4n: float) -> float:
    """How far the margin ``g_n`` may lie above the converged one (≥ 0): E(n) where the margins fall as the
    mesh is refined (the coarse mesh flatters the design) or do not yet fall or rise steadily (no trend to
    trust), 0 where they rise steadily (the coarse mesh is on the safe side)."""
    d1, d2 = g_n - g_2n, g_2n - g_4n
    rising = d1 < 0.0 and d2 < 0.0
    return 0.0 if rising else richardson(g_n, g_2n, g_4n)[0]


def estimate(g: dict, n: int) -> tuple[dict, dict, dict]:
    """Each check's E(n) (SI), its unsafe part (:func:`unsafe_part`) and observed order, the largest over the
    cases where it can govern (its least margin within :data:`~optimisation.dynamic.screen.SCREEN_TOL` of its
    limit, as the screening judges it: a check further from its limit than any error estimated here cannot
    govern), from ``g`` (mesh → case → check → least margin)."""
    errors: dict[str, float] = {}
    unsafe: dict[str, float] = {}
    orders: dict[str, float] = {}
    first = g[n]
    for i, margins in first.items():
        for check, value in margins.items():
            if value > SCREEN_TOL * _scale(check, g):
                continue
            three = (value, g[2 * n][i][check], g[4 * n][i][check])
            e, p = richardson(*three)
            if e >= errors.get(check, -1.0):
                errors[check], orders[check] = e, p
            unsafe[check] = max(unsafe.get(check, 0.0), unsafe_part(*three))
    return errors, unsafe, orders


def _scale(check: str, g: dict) -> float:
    return g["F_ref"] if g["units"][check] == "N" else 1.0


def control(problem, xs, p=None, say=None) -> MeshEstimate | None:
    """The mesh and each check's estimated error at scaled design ``xs`` (see the module); None when the
    transient's rope has no elements to refine (``mesh_tol`` not a parameter: a rigid rope, one spring)."""
    if "mesh_tol" not in problem.scene.parameters:
        return None
    tol = problem.scene.parameters["mesh_tol"]
    n = segments_of(problem.scene)
    units = {c: check.unit for c, check in problem.machine.manoeuvres.CHECK.items()}
    g: dict = {"F_ref": problem.F_ref, "units": units}
    levels = []
    while True:
        _measure(problem, xs, p, g, n, range(len(problem.cases)), say)
        near = [i for i, margins in g[n].items() if any(v <= SCREEN_TOL * _scale(c, g) for c, v in margins.items())]
        for m in (2 * n, 4 * n):        # the finer meshes in the cases where a check can govern (all estimate reads)
            _measure(problem, xs, p, g, m, near, say)
        errors, unsafe, orders = estimate(g, n)
        force = max((e for c, e in errors.items() if units[c] == "N"), default=0.0)
        levels.append({"segments": n, "largest_force_error": force})
        if force <= tol:
            return MeshEstimate(n, tol, errors, unsafe, orders, {c: units[c] for c in errors}, levels)
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


def backoffs(problem, found: MeshEstimate) -> dict[str, float]:
    """Check name → its back-off in the NLP (scaled): :data:`MARGIN` times the unsafe part of its E(n), plus
    :data:`BACKOFF`."""
    check = problem.machine.manoeuvres.CHECK
    return {c: BACKOFF + MARGIN * e / check_scale(problem, check[c]) for c, e in found.unsafe.items()}


def converge(problem, sol, record=None, say=None):
    """The continuous optimum ``sol`` of ``problem`` solved again on the mesh :func:`control` chooses, with
    the back-offs of :func:`backoffs`, until the estimate at the optimum is within the back-offs it was
    solved with: (problem, solution, :class:`MeshEstimate` or None).  Each re-solve first tries Newton on the
    previous optimum's active set (:func:`~optimisation.dynamic.warm.on_active_set`: kept only at a KKT point of
    the new problem), then IPOPT from it.  A solution that is not feasible is returned as it is (no design on
    the finer mesh)."""
    for _ in range(ROUNDS):
        found = control(problem, sol.xs, say=say)
        if found is None:
            return problem, sol, None
        wanted = backoffs(problem, found)
        if found.segments == segments_of(problem.scene) and all(
                BACKOFF + (b - BACKOFF) / MARGIN <= problem.backoff(c) * (1 + 1e-9) for c, b in wanted.items()):
            return problem, sol, found
        if say is not None:
            say(f"dynamic optimum on {found.segments} elements per span, checks backed off by their error")
        scene, old = with_segments(problem.scene, found.segments), problem
        problem = DynamicSizingProblem(scene, selected=problem.selected, backoffs=wanted,
                                       shared_paths=problem.shared_paths)
        problem, sol = solve_refined(problem, sol.xs, record=record, warm=(old, sol))
        if not sol.feasible:
            return problem, sol, found
    raise SolveError(f"the mesh's error estimates at the optimum kept exceeding the back-offs it was solved with "
                     f"after {ROUNDS} re-solves; report it")
