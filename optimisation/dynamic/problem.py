"""The dynamic sizing NLP: the static sizing problem plus every check through the four manoeuvres.

Same decision variables (d, F_nwl, stroke, scaled as in :class:`optimisation.problem.SizingProblem`),
same lexicographic objective (least rope mass, then pretension, then stroke), same parameters p and
every static check; added: the checks of :data:`~ropemodel.machines.winch.manoeuvres.CHECKS` at every
point of each case's time grid, each case's transient integrated inside the NLP
(:mod:`optimisation.dynamic.shooting`).  The cases integrated are those that govern a check
(:mod:`optimisation.dynamic.screen`), out of every manoeuvre with the load at every candidate
position.  A constraint is named ``"<check> @ <manoeuvre>, x_m = <place> m, t = <time> s"``.  The
class is a :class:`SizingProblem` (the same attributes: ``g``, ``constraints``, ``units``,
``g_scale``, ``margins()``), so the static package's
IPOPT solve with its active-set polish, catalogue rounding, infeasibility diagnosis and
sensitivities apply to it unchanged.
"""

from __future__ import annotations

from functools import cached_property

import casadi as ca
import numpy as np

from optimisation.dynamic.manoeuvres import cases, manoeuvre_scene
from optimisation.dynamic.screen import governing
from optimisation.dynamic.shooting import Path
from optimisation.dynamic.transient import transient_scene
from optimisation.problem import SizingProblem
from ropemodel.dynamics.assemble import chosen, structural

#: largest step [s] of the first time grid (refinement adds the exact local minima of the checks)
DT_GRID = 0.1
#: back-off of every check through a manoeuvre in the NLP for the time integration, in scaled units (F_ref =
#: 0.1 G_m for forces, 1 m for the stroke): the NLP asks g >= BACKOFF plus the check's discretisation error
#: (``backoffs``, :mod:`optimisation.dynamic.mesh`).  Two integrations at rtol 1e-10 (the NLP's and the hybrid
#: simulator's) of the Fig. 9 manoeuvres agree to 0.2 N (4e-6 F_ref); the back-off (4.7 N on ~250 kN, 0.1 mm
#: of stroke) keeps a design the NLP puts on a check on the safe side of it in the simulator too
BACKOFF = 1e-4
#: IPOPT's first barrier parameter: the start (:func:`optimisation.dynamic.start.factored_start`) is near the
#: optimum; IPOPT's default 0.1 first pushes the stroke (objective weight 1e-3) ~1e4 m up and takes ~20
#: iterations to come back (measured on the Fig. 9 scene: 39 iterations against 15)
MU_INIT = 1e-5
#: IPOPT's iteration limit on the dynamic NLP (each iteration integrates its cases with sensitivities,
#: ~0.4 s on the test scene): measured 13-18 iterations to an optimum, 183 to "Infeasible_Problem_Detected"
#: (the test scene with a 2 s ramp); a start that reaches the limit hands over to the next start and then to
#: the least-violation problem (:mod:`optimisation.dynamic.diagnose`)
MAX_ITER = 250
#: consecutive iterations at IPOPT's acceptable level (``acceptable_tol`` 1e-8, the NLP error with the
#: complementarity) that end a solve of the dynamic NLP (IPOPT's default 15): its checks through the integrators have
#: a noise floor near 1e-9, so IPOPT reaches the acceptable level but not its ``tol`` of 1e-10, and spent the
#: iterations after it at the floor until a line search failed; the polish (Newton on the active set,
#: :mod:`optimisation.ipopt`) then takes the vertex exactly.  Measured on the three-segment route's first solve: 21
#: iterations ending 1.2e-8 outside a check (not polished), 10.8 CPU-s; with 2, 17 iterations, 7.8 CPU-s, polished,
#: the same active set
ACCEPTABLE_ITER = 2
#: parameters that stay numbers in the transient: its duration (the grid) and where the load is
FIXED = ("t_end",)


class DynamicSizingProblem(SizingProblem):
    """The dynamic sizing NLP of ``scene`` (a winch sizing scene; its transient is made by
    :func:`~optimisation.dynamic.transient.transient_scene`).

    ``cases``: every manoeuvre with the load at every candidate position; ``all_paths``: their smooth
    modes (:class:`~optimisation.dynamic.shooting.Path`); ``selected``: the indices of the cases the NLP
    integrates (default: those governing a check at the start design, :func:`~optimisation.dynamic.screen.governing`),
    ``paths`` theirs and ``grids`` their time grids (default a uniform grid of step :data:`DT_GRID`).
    ``paths`` given: the smooth modes of a previous problem of the same scene, re-used.  ``backoffs``: case tag
    (:attr:`~optimisation.dynamic.manoeuvres.Manoeuvre.tag`) → check name → its back-off in that case in the NLP
    (scaled; default :data:`BACKOFF`), from the mesh's error estimate in that case
    (:func:`optimisation.dynamic.mesh.backoffs`).  ``shared_paths``: the cases' smooth modes built at the start
    design (:meth:`start_path`), shared by the problems one sizing makes of the same scene (its grids, cases,
    meshes), so that none is built twice.
    """

    def __init__(self, scene, grids=None, paths=None, selected=None, backoffs=None, shared_paths=None):
        super().__init__(transient_scene(scene))
        self.backoffs = {tag: dict(by) for tag, by in (backoffs or {}).items()}
        self.shared_paths = {} if shared_paths is None else shared_paths
        self.static_constraints = list(self.constraints)
        self.g_static = self.g
        self.cases = cases(self.scene)
        self.tags = [case.tag for case in cases(self.scene)]
        if paths is None:
            paths = [self.start_path(i) for i in range(len(self.cases))]
        self.all_paths = paths
        self.selected = tuple(governing(self, self.x0()) if selected is None else selected)
        self.paths = [paths[i] for i in self.selected]
        self.grids = grids or [path.uniform_grid(self.pp0(path), DT_GRID) for path in self.paths]
        self._add_paths()

    def start_path(self, i: int, scene=None) -> Path:
        """The smooth mode of case ``i`` built at the start design (the scene's), for ``scene`` (default this
        problem's; another mesh of it: its ``segments``), built once per mesh and shared through ``shared_paths``."""
        scene = self.scene if scene is None else scene
        key = (scene.numerics.get("segments"), i)
        if key not in self.shared_paths:
            self.shared_paths[key] = self._path(self.cases[i], self.to_si(self.x0()), scene)
        return self.shared_paths[key]

    def _path(self, manoeuvre, design, scene=None) -> Path:
        optional = self.variables + self.sizing.D_OPTIONAL
        sc = manoeuvre_scene(scene or self.scene, manoeuvre, design, optional)
        fixed = structural(chosen(sc))
        shared = [k for k in self.params if k in sc.parameters and k not in fixed and k not in FIXED]
        return Path(manoeuvre, sc, self.variables + tuple(shared))

    def pp_of(self, path, x_si, p):
        """The smooth mode's parameter vector of ``path`` from the design (SI) and the NLP's p."""
        idx = [self.params.index(k) for k in path.names[len(self.variables):]]
        return ca.vertcat(x_si, *[p[i] for i in idx])

    def pp0(self, path, xs=None, p=None) -> np.ndarray:
        """Numbers of :meth:`pp_of` at scaled ``xs`` (default the start) and ``p`` (default the scene's)."""
        xs = self.x0() if xs is None else np.asarray(xs, float)
        p = self.p0 if p is None else np.asarray(p, float)
        return np.asarray(ca.evalf(self.pp_of(path, ca.DM(xs * self.x_scale), ca.DM(p)))).ravel()

    @cached_property
    def _static_at(self) -> ca.Function:
        x_m = ca.MX.sym("x_m")
        args = {k: self.p[i] for i, k in enumerate(self.params)}
        args.update({k: self.xs[i] * self.x_scale[i] for i, k in enumerate(self.variables)})
        args.update({k: 0.0 for k in self.problem.given})
        out = self.problem.function.call({**args, "x_m": x_m})
        names = [f"{f}_{w}" for f in ("F_C", "F_S") for w in ("up", "down")]
        return ca.Function("static_at", [self.xs, self.p, x_m], [out[n] for n in names], ["x", "p", "x_m"], names)

    def static_at(self, xs, p, x_m: float) -> dict[str, float]:
        """The static forces F_C and F_S of both directions [N] at scaled ``xs`` with the load at ``x_m`` [m]."""
        return {k: float(v) for k, v in self._static_at(x=xs, p=p, x_m=x_m).items()}

    def values(self, x_si, p) -> dict:
        """What the checks through the manoeuvres read besides the transient (the machine's ``values``)."""
        return self.machine.manoeuvres.values(self, x_si, p)

    def _add_paths(self) -> None:
        x_si = self.xs * ca.DM(self.x_scale)
        a = self.values(x_si, self.p)
        g: list = []
        scale: list = []
        names, margins, offsets = [], [], []
        unit_scale = {"N": self.F_ref, "m": 1.0}
        self._blocks = [self.g_static]
        for j, (path, grid) in enumerate(zip(self.paths, self.grids)):
            first = len(g), len(scale)
            _, o, _ = path.samples(self.pp_of(path, x_si, self.p), grid, f"m{j}")
            times = np.concatenate(path.times(self.pp0(path), grid))
            for check in path.checks:
                rows = o[check.needs].shape[0]
                g.append(ca.vec(check.nlp(o, a)))
                margins.append(ca.vec(check.margin(o, a)))
                for t in times:
                    for e in range(rows):
                        tag = f"[{e}]" if check.needs == "T" else ""
                        names.append(f"{check.name}{tag} @ {path.manoeuvre.tag}, t = {t:.6g} s")
                scale += [unit_scale[check.unit]] * (rows * len(times))
                offsets += [self.backoff(check.name, self.selected[j])] * (rows * len(times))
                self.units.update({n: check.unit for n in names[len(names) - rows * len(times):]})
            self._blocks.append(ca.vertcat(*g[first[0]:]) / ca.DM(scale[first[1]:]) - ca.DM(offsets[first[1]:]))
        self.dynamic_constraints = names
        self.constraints = self.static_constraints + names
        self.g = ca.vertcat(self.g, ca.vertcat(*g) / ca.DM(scale) - ca.DM(offsets))
        self.g_scale = np.concatenate([self.g_scale, scale])
        self._margin_exprs = self._margin_exprs + margins

    def jacobian_rows(self, xs, p, rows) -> tuple[np.ndarray, np.ndarray]:
        """(g, ∂g/∂x) at scaled ``xs`` and ``p`` with only the blocks of g holding ``rows`` differentiated (the static
        checks, or one case's checks through its manoeuvre: their transient integrated with its sensitivities),
        the other rows of ∂g/∂x NaN; g whole, integrated without sensitivities.  The warm re-solves' Newton steps
        and KKT tests, the active set, the polish and the lexicographic test read the active rows alone: measured
        on the three-segment route at 32 elements a span, two of the six cases hold them."""
        g = np.asarray(self.g_function(xs, p), float).ravel()
        J = np.full((len(g), self.xs.numel()), np.nan)
        for b, lo, hi in self._holding(rows):
            J[lo:hi] = np.asarray(self._block_function(b, True)(xs, p), float)
        return g, J

    def g_rows(self, xs, p, rows) -> np.ndarray:
        """g at scaled ``xs`` and ``p`` in the blocks holding ``rows`` (the same numbers as :attr:`g_function`'s: the
        same integrations), the other rows NaN: what a Newton step on ``rows`` reads (the warm re-solves')."""
        g = np.full(self.g.numel(), np.nan)
        for b, lo, hi in self._holding(rows):
            g[lo:hi] = np.asarray(self._block_function(b, False)(xs, p), float).ravel()
        return g

    def _holding(self, rows):
        """(block, its first row, the row after its last) of each block of g holding one of ``rows``."""
        lo = 0
        for b, block in enumerate(self._blocks):
            hi = lo + block.numel()
            if any(lo <= r < hi for r in rows):
                yield b, lo, hi
            lo = hi

    def _block_function(self, b: int, jacobian: bool) -> ca.Function:
        """(x, p) → block ``b`` of g, or (``jacobian``) its ∂/∂x; built once per block."""
        made = self.__dict__.setdefault("_block_functions", {})
        if (b, jacobian) not in made:
            block = self._blocks[b]
            made[b, jacobian] = ca.Function(f"block_{b}", [self.xs, self.p],
                                            [ca.jacobian(block, self.xs) if jacobian else block])
        return made[b, jacobian]

    def backoff(self, check: str, case: int) -> float:
        """The back-off of ``check`` (a name of the machine's ``CHECKS``) in case ``case`` (index into
        ``cases``) in the NLP, scaled."""
        return self.backoffs.get(self.tags[case], {}).get(check, BACKOFF)

    def largest_backoff(self, default: float = BACKOFF) -> float:
        """The largest back-off of any check in any case (scaled; ``default`` where none is set)."""
        return max((b for by in self.backoffs.values() for b in by.values()), default=default)

    #: the checks through the manoeuvres are not static: derivatives of :meth:`nlp`, not of its static forms
    STATIC = False

    @cached_property
    def at_scene(self) -> dict:
        """The NLP IPOPT solves at the scene's parameters: this problem's own (:meth:`nlp`), the checks through
        the manoeuvres included.  The static problem's folds ``p0`` into its static checks alone, over its load
        cases (``cases`` here are the manoeuvres): on this problem it raised AttributeError, which the solver's
        ``hasattr`` took for "no fold", and had it built it would have dropped every dynamic check."""
        return self.nlp()

    @cached_property
    def ipopt_options(self) -> dict:
        """IPOPT settings of this NLP (:func:`optimisation.ipopt.solver` adds them): the first barrier parameter
        :data:`MU_INIT`, the acceptable stop :data:`ACCEPTABLE_ITER`, and the Hessian of the Lagrangian of the
        objective and the static checks only (exact, closed form).  The transient's own second derivatives are left
        out: through the integrator they cost 20-80 Jacobians each (forward-over-adjoint 19 s, forward-over-forward
        5.4 s against 0.28 s for the Jacobian, measured on the Fig. 9 scene), and at the usual optimum, a vertex of
        three active checks, the Newton step is fixed by the active constraints' Jacobian alone, so IPOPT converges
        as fast without them (measured: 15 iterations).  The optimum satisfies the KKT conditions with the exact
        first derivatives."""
        lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", self.g.numel())
        n = self.g_static.numel()
        lagrangian = lam_f * self.f + ca.dot(lam_g[:n], self.g_static)
        hess = ca.Function("hess_lag", [self.xs, self.p, lam_f, lam_g], [ca.triu(ca.hessian(lagrangian, self.xs)[0])],
                           ["x", "p", "lam_f", "lam_g"], ["hess"])
        return {"hess_lag": hess, "ipopt.mu_init": MU_INIT, "ipopt.max_iter": MAX_ITER,
                "ipopt.acceptable_iter": ACCEPTABLE_ITER}

    def relinearised(self, xs, p=None) -> DynamicSizingProblem | None:
        """This problem with its manoeuvres' smooth modes built again at the design ``xs`` (scaled) and the
        parameters ``p``, when a choice they made from the numbers of the design they were built at differs
        there (the branch of Li's law the capstan drum contact takes, eq. (12) or (15), is chosen from the
        steady forces); None when both give the same transient at ``xs``.

        A solve ends on a design far from the one its transients were built at (the start); with another
        branch there, the NLP's transient is not the simulator's (measured: the test scene with the capstan
        contact, 11 N of slip margin apart at the optimum, whose simulation slips)."""
        p = self.p0 if p is None else np.asarray(p, float)
        changed = {k: float(p[i]) for i, k in enumerate(self.params) if p[i] != self.p0[i]}
        scene = self.scene.with_values(changed) if changed else self.scene
        paths = list(self.all_paths)        # the cases it integrates built again; the others screened as they are
        for i in self.selected:
            paths[i] = self._path(self.cases[i], self.to_si(xs), scene)
        for i in self.selected:
            old, new = self.all_paths[i], paths[i]
            if not _same_transient(self.pp0(old, xs, p), old, self.pp0(new, xs, p), new, self.F_ref):
                return DynamicSizingProblem(self.scene, None, paths, self.selected, self.backoffs, self.shared_paths)
        return None

    def refined(self, grids) -> DynamicSizingProblem:
        """The same problem on other grids (the cases' smooth modes re-used)."""
        return DynamicSizingProblem(self.scene, grids, self.all_paths, self.selected, self.backoffs, self.shared_paths)

    def with_cases(self, selected) -> DynamicSizingProblem:
        """The same problem integrating the cases ``selected`` (indices); a case it already integrates keeps its
        grid."""
        selected = sorted(set(selected))
        kept = dict(zip(self.selected, self.grids))
        grids = [kept.get(i) or self.all_paths[i].uniform_grid(self.pp0(self.all_paths[i]), DT_GRID) for i in selected]
        return DynamicSizingProblem(self.scene, grids, self.all_paths, selected, self.backoffs, self.shared_paths)

    def screened(self, xs, p=None) -> DynamicSizingProblem:
        """The same problem integrating the cases that govern a check at scaled design ``xs``."""
        return self.with_cases(governing(self, xs, p))


#: step [s] on which two builds of a manoeuvre's smooth mode are compared (:meth:`DynamicSizingProblem.relinearised`)
DT_SAME = 0.05


def _same_transient(pp_a, a: Path, pp_b, b: Path, force: float) -> bool:
    """Whether two builds of one manoeuvre's smooth mode give the same transient (to 1e-9 of ``force`` [N] and
    1e-9 m) at their parameter vectors."""
    grid_a, grid_b = a.uniform_grid(pp_a, DT_SAME), b.uniform_grid(pp_b, DT_SAME)
    if [len(g) for g in grid_a] != [len(g) for g in grid_b]:
        return False
    _, oa, _ = a.samples(pp_a, grid_a)
    _, ob, _ = b.samples(pp_b, grid_b)
    tol = {"take_up": 1e-9}
    return oa.keys() == ob.keys() and all(
        np.allclose(np.asarray(oa[k], float), np.asarray(ob[k], float), rtol=0.0, atol=tol.get(k, 1e-9 * force))
        for k in oa)
