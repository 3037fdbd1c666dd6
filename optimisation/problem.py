"""The sizing problem: variables, objective and constraints, from the scene's equations and its machine's
sizing declaration (:attr:`ropemodel.machines.Machine.sizing`).

Decision variables (SI): what the machine declares (a winch: the rope diameter ``d`` [m], the tensioner
pretension and the installed stroke).  Parameters: every other parameter of the scene.  Nothing here
re-types physics: the compiled scene Function (``Problem(scene).function``, the same one ``ropemodel run``
evaluates) is called with the decision variables and the parameters as CasADi MX symbols, and every margin
output the machine checks (``*_margin*``: rope safety, slip, taut ropes everywhere in the loop, ...)
becomes a constraint ``margin >= 0`` (in the form the declaration gives, ``nlp_form``) in both directions,
in every load case the scene leaves open: every place of the load on a route, and with the ramps' inertia
every manoeuvre (steady motion, a start and a stop anywhere, an emergency stop; :mod:`ropemodel.envelope`).

Objective: the declaration's primary output (``PRIMARY``) over its value at x = 1, plus the other variables
(scaled) weighted far below it (``WEIGHTS``): a lexicographic order encoded as a weighted sum with scale
separation (a winch's: least rope mass per metre, then least pretension, then least stroke; why that weighted
sum gives the lexicographic optimum exactly, :mod:`ropemodel.machines.winch.sizing`).
:func:`optimisation.ipopt.solve_continuous` verifies the order on every solve (``lexicographic_ok``).

Scaling: x is solved in the units the declaration gives (``x_scale``), with F_ref its force scale; margins
in N are divided by F_ref, margins in m are taken in m, ratio margins as they are.
"""

from __future__ import annotations

import copy
import math
from collections import ChainMap
from functools import cached_property

import casadi as ca
import numpy as np

from optimisation.nlp_parts import Ends, check_work, depends, nlp_outputs, partly_folded, restricted, vector_model
from ropemodel.envelope import Envelope, LoadCase, envelope, free, load_cases
from ropemodel.envelope.cases import distinct, joint_ends
from ropemodel.envelope.prune import prune
from ropemodel.machines import default
from ropemodel.machines.base import declared_machine, needing
from ropemodel.problem import Problem
from ropemodel.scene import Scene, SceneLike, SceneWarning, as_scene

#: the default machine's design variables, what sizing chooses itself (a scene may leave these out: a start
#: is computed) and the dimensions it may leave out besides (kept for callers of the default machine)
VARIABLES = SIZED = default().sizing.VARIABLES
D_OPTIONAL = default().sizing.D_OPTIONAL


def declaration(scene):
    """The sizing declaration of ``scene``'s machine; :class:`InputError` for a machine that cannot be sized."""
    return needing("sizing", scene, "sizing")


def _label(check: str, case: LoadCase, inputs, params, ends=None) -> str:
    """``slip_margin_up @ segment 2, x_m = 1300 m, start``: the check and the case it is made in (of the case
    inputs it depends on; the check alone where it depends on none; ``ends``: the places' x_m, as
    :meth:`LoadCase.values` takes them)."""
    where = case.label(params, inputs, ends)
    return f"{check} @ {where}" if where else check


def _base(constraint: str) -> str:
    """The check's output name of a constraint (``slip_margin_up @ segment 2`` → ``slip_margin_up``)."""
    return constraint.split(" @ ")[0]


def load_sizing(scene: SceneLike, emit: bool = True) -> Scene:
    """A scene read for sizing (:func:`prepare`): a :class:`~ropemodel.scene.Scene` as it is, or a TOML file or
    built-in scene's name loaded with no starting design needed; the warnings of a scene loaded here
    (``emit=False``: kept in ``scene.warnings`` for the caller to print)."""
    import warnings

    loaded = as_scene(scene, optional=_loadable(scene), emit=False)
    prepared = prepare(loaded)
    if emit and loaded is not scene:
        for note in prepared.warnings:
            warnings.warn(note, SceneWarning, stacklevel=2)
    return prepared


def _loadable(scene) -> tuple[str, ...]:
    """What a scene to be sized may leave out: its machine's design and optional dimensions (a scene not yet
    loaded: the default machine's)."""
    sizing = declaration(scene) if isinstance(scene, Scene) else default().sizing
    return sizing.VARIABLES + sizing.D_OPTIONAL


def prepare(scene) -> Scene:
    """The scene as sizing needs it (its machine's ``prepare``: design checks on, ...).

    The scene may leave out the design (:data:`SIZED`, the sizing chooses it) and what the declaration's
    ``optional`` allows (a winch: D on a drum without a compliant lining).  Load it with
    ``load(path, optional=SIZED + D_OPTIONAL)`` (what ``ropemodel size`` does) or pass it loaded.
    """
    return declaration(scene).prepare(scene)


def reads(scene: Scene) -> tuple[set[str], dict[str, str]]:
    """What the sizing of the (prepared) ``scene`` is computed from, and what it sets itself (name → how): its
    machine's sizing's ``reads`` (a winch: every check, the rope mass, the drive power, the load cases' places and
    accelerations; the design variables set)."""
    return declaration(scene).reads(scene)


def rope_problem(scene) -> str | None:
    """Why sizing cannot choose ``scene``'s rope (a rope given by its weight, no catalogue to choose from), or
    None."""
    return declaration(scene).rope_problem(scene)


class SizingProblem:
    """The NLP of sizing one scene, as its machine declares it (:func:`declaration`).

    Attributes
    ----------
    scene: the scene (its design, where it gives one, is the start).
    sizing: its machine's sizing declaration; variables: its design variables, in the order of x.
    params: names of the NLP parameters p (every other scene parameter), in order.
    p0: their SI values from the scene.
    constraints: names of the margin outputs, in order (g >= 0 after scaling).
    outputs: a Function (x_SI, p) → every scene output (for reports: N_p, margins).
    """

    #: the NLP is the checks of its load cases alone: its derivatives in x at ``p0`` may be taken of
    #: :attr:`at_scene` (the same NLP, the scene's values folded in), those in p of :meth:`nlp_of`
    STATIC = True

    def __init__(self, scene: Scene, prune_places: bool = True, generate: bool = False, first_range=None):
        scene = prepare(scene)
        self.scene = scene
        self.machine = declared_machine(scene)
        self.sizing = sizing = self.machine.sizing
        self.variables = sizing.VARIABLES
        #: a dimension left out: its check becomes a result (a winch without D: the least drum D_ratio_min * d)
        held, freed = sizing.frees(scene)
        self.least_drum = bool(freed)
        #: every place of the load and every manoeuvre the scene leaves open (:func:`ropemodel.envelope.load_cases`),
        #: their inputs (x_m, a_h) set by each case
        self.all_cases, self.free = load_cases(scene), free(scene)
        #: the places that can govern (:func:`ropemodel.envelope.prune.prune`, for every rope and pretension;
        #: ``prune_places=False`` for a sweep varying the route or the load): where :meth:`envelope` evaluates a
        #: design and, unless the constraints are generated (``generate``: the NLP holds the cases each check is
        #: least in at the start, more added as the designs found are checked at every candidate,
        #: :mod:`optimisation.generation`), where the NLP makes the checks.  With ``first_range`` (low, high) of
        #: the first design variable: only for designs with it in that range (the declaration's
        #: ``place_weights``; :meth:`covers`)
        self.first_range = first_range if hasattr(sizing, "place_weights") else None
        weights = sizing.place_weights(scene, self.first_range) if self.first_range else (0.0, math.inf)
        self.candidates = (prune(self.all_cases, scene.parameters, scene.built, weights) if prune_places
                           else self.all_cases)
        if not generate:
            check_work(scene, self.candidates, len(self.all_cases))    # before the model is compiled
        self.problem = Problem(scene, held, freed) if freed else Problem(scene)
        fun = self.problem.function
        derived, held_out = scene.built.derived, {*self.variables, *self.problem.given, *self.free}
        self.params = [k for k in self.problem.knowns if k not in held_out and k not in derived]
        self.case_inputs = [*self.free, *(k for k in self.problem.knowns if k in derived)]   # + a long route's numbers
        self._route_numbers = self.problem.case_numbers(self.candidates, derived and joint_ends(scene.parameters))
        self.p0 = np.array([scene.parameters[k] for k in self.params], dtype=float)
        self.F_ref = sizing.force_scale(scene)
        self.x_scale = sizing.x_scale(self.F_ref)
        self.xs, self.p = ca.MX.sym("x", len(self.variables)), ca.MX.sym("p", len(self.params))
        self._args = self.known_values(self.p, self.xs * ca.DM(self.x_scale))
        self.checks = self.machine.checks(self.problem.unknowns)
        #: the model the NLP's cases call, (x, p, c) -> its checks and outputs (:func:`~.nlp_parts.vector_model`)
        self.nlp_model = vector_model(fun, self.variables, self.params, self.case_inputs, self.problem.given,
                                      nlp_outputs(fun.name_out(), self.checks, sizing, self._args))
        unit_scale = {"1": 1.0, "N": self.F_ref, "m": 1.0}
        q = scene.built.quantities
        #: each check's scale in the NLP (g = its NLP form over this)
        self.check_scale = {c: unit_scale[sizing.unit(c, q[c].unit)] for c in self.checks}
        #: the case inputs each check depends on (a check the same in every case is made once)
        self.depends = depends(self.nlp_model, self.checks, self.free, self.case_inputs, derived)
        self.cases = self.candidates
        if generate:
            from optimisation.generation import first_cases

            self.cases = first_cases(self)
        self._build_nlp()

    def covers(self, xs) -> bool:
        """Whether the :attr:`candidates` hold every worst case of the design at scaled ``xs``: its first variable in
        :attr:`first_range` (or no range)."""
        if self.first_range is None:
            return True
        first = float(np.asarray(xs, dtype=float).ravel()[0] * self.x_scale[0])
        return self.first_range[0] <= first <= self.first_range[1]

    def known_values(self, p, x_si) -> dict:
        """Every known of the model by name: the parameters from ``p``, the design ``x_si`` (SI), a check held at 0
        where its dimension is a result."""
        args = dict(zip(self.params, ca.vertsplit(p) if self.params else []))     # one node, not one per parameter
        args.update({k: x_si[i] for i, k in enumerate(self.variables)})
        args.update({k: 0.0 for k in self.problem.given})
        return args

    def with_cases(self, more) -> SizingProblem:
        """This problem with the NLP also making its checks at the candidates ``more`` (indices into
        :attr:`candidates`; the model is not compiled again)."""
        out = copy.copy(self)
        known = set(self.cases)
        out.cases = self.cases + [self.candidates[i] for i in sorted(set(more)) if self.candidates[i] not in known]
        out._build_nlp()
        return out

    def _build_nlp(self) -> None:
        """The NLP of :attr:`cases`: its constraints, their units and scales, the objective; what was derived
        from a previous NLP (folded NLP, Jacobians, solvers) is dropped."""
        for k in ("at_scene", "folded_primary", "g_function", "margin_function", "_jac_kept", "_jac_g", "_grad_f0",
                  "_jac_folded"):
            self.__dict__.pop(k, None)
        sizing, xs, p = self.sizing, self.xs, self.p
        self.constraints, self._g, self._margin_exprs, out, self._made = self.make_constraints(
            self.nlp_model, self._args, p)
        self.units = {c: sizing.unit(c, self.scene.built.quantities[_base(c)].unit) for c in self.constraints}
        self.g_scale = np.array([self.check_scale[_base(c)] for c in self.constraints])
        self.g = ca.vertcat(*self._g) / ca.DM(self.g_scale)
        # reference of the primary objective: its value at x = 1 in scaled units (fixed number: the weights are
        # constants; a winch: the rope mass per metre at d = 10 mm)
        m_at = ca.Function("m", [xs, p], [out[sizing.PRIMARY]])
        self.m_ref = float(m_at(ca.DM.ones(len(self.variables)), self.p0))
        self.f_primary = out[sizing.PRIMARY] / self.m_ref
        self.f = self._objective(self.f_primary)
        self.output_names = list(self.problem.unknowns)
        self._first_case = self.cases[0]      # where :attr:`outputs` puts the load

    @cached_property
    def outputs(self) -> ca.Function:
        """Every scene output as a Function (x scaled, p), with the load in the first case."""
        args, params = self._args, self.scene.parameters
        every = self.problem.function.call({**args, **self.case_values(self._first_case, ChainMap(args, params))})
        return ca.Function("outputs", [self.xs, self.p], [every[n] for n in self.output_names],
                           ["x", "p"], self.output_names)

    def make_constraints(self, model, args, p, only=None, t=None) -> tuple[list, list, list, dict, list]:
        """Every check in every case it can differ in (a check that depends only on the manoeuvre once per
        manoeuvre, one that depends on neither once), or the (check, case index) pairs ``only``: their labels, the
        constraints g, the margins, the outputs at the first case and the pairs made.  The cases' places and
        accelerations follow the NLP's parameters ``p`` (a segment's length moves x_m).  ``model``: the NLP's model
        (:func:`~optimisation.nlp_parts.vector_model`, or one of some checks alone), or a Function (c) → a Function
        (x[, t]) → its outputs, each case and the scene's values folded in (``t``: a parameter left free,
        :func:`optimisation.infeasibility.freeing`); ``args``: each known's value (the design in SI among them)."""
        values = ChainMap(args, self.scene.parameters)
        ends = self._ends(values, p) if self.scene.route else None
        x_si = ca.vertcat(*[args[k] for k in self.variables])

        def at_case(i: int) -> dict:
            case = self.case_values(self.cases[i], values, ends)   # an input a case leaves alone: 0 (CasADi's)
            c = ca.vertcat(*[case.get(k, 0.0) for k in self.case_inputs])
            if not isinstance(model, ca.Function):
                folded = model(c)
                return folded.call({k: {"x": x_si, "t": t}[k] for k in folded.name_in()})
            given = {"x": x_si, "p": p, "c": c}
            return model.call({k: given[k] for k in model.name_in()})

        labelled = ends if ends is None else [float(e) for e in joint_ends(self.scene.parameters)]
        made = only if only is not None else [(c, i) for c in self.checks
                                              for i in distinct(self.cases, self.depends[c])]
        at: dict[int, dict] = {}
        labels, g, exprs = [], [], []
        for c, i in made:
            if i not in at:
                at[i] = at_case(i)
            labels.append(_label(c, self.cases[i], self.depends[c], self.scene.parameters, labelled))
            g.append(self.sizing.nlp_form(c, at[i], args))
            exprs.append(at[i][c])
        first = at[min(at)] if at else at_case(0)     # the objective: the same in every case
        return labels, g, exprs, first, made

    def case_values(self, case: LoadCase, values, ends=None) -> dict:
        """The inputs ``case`` sets and a long route's numbers there (:mod:`ropemodel.papers.route_numbers`)."""
        return {**case.values(values, ends), **self._route_numbers.get(case, {})}

    def nlp_of(self, taken, kept=None, p_kept=None) -> tuple:
        """(f, g_S) of the NLP (parametric) with the constraints S = ``taken`` (indices into :attr:`constraints`)
        alone, from a model of their checks alone: a route's least tensions, which the other checks need, are
        then left out of the derivatives in the parameters (:mod:`optimisation.sensitivity`).  ``kept`` (indices
        into :attr:`params`): only those stay parameters (``p_kept``), the others folded in at ``p0``."""
        made = [self._made[i] for i in taken]
        checks = list(dict.fromkeys(c for c, _ in made))
        model = restricted(self.nlp_model, nlp_outputs(self.nlp_model.name_out(), checks, self.sizing, self._args))
        p, args = self.p, self._args
        if kept is not None:
            model, p = partly_folded(model, self.p0, kept), p_kept
            args = {**self._at_p0(), **{self.params[i]: p_kept[j] for j, i in enumerate(kept)}}
        _, g, _, out, _ = self.make_constraints(model, args, p, only=made)
        g_s = ca.vertcat(*g) / ca.DM(self.g_scale[list(taken)]) if taken else ca.MX(0, 1)
        return self._objective(out[self.sizing.PRIMARY] / self.m_ref), g_s

    def _at_p0(self) -> dict:
        """Every known at the scene's parameters ``p0`` (floats), the design a symbol."""
        args = self.known_values(ca.DM(self.p0), self.xs * ca.DM(self.x_scale))
        return {k: float(v) if isinstance(v, ca.DM) else v for k, v in args.items()}

    def _ends(self, values, p):
        """The places' x_m (:func:`ropemodel.envelope.cases.joint_ends`): numbers where ``values`` are, else each
        a sum of the NLP's parameters ``p`` (one operation per place, not a chain through every segment)."""
        ends = joint_ends(self.scene.parameters)
        if all(isinstance(values[f"L_{i}"], float) for i in range(1, len(ends))):
            return joint_ends(values)
        where = {k: i for i, k in enumerate(self.params)}
        lengths = [where[f"L_{i}"] for i in range(1, len(ends))]
        return Ends(p, lengths)

    @cached_property
    def at_scene(self) -> dict:
        """The NLP (:meth:`nlp`) at the scene's parameters ``p0``, folded into its expressions, each case's place and
        acceleration too (a route's sums and minima are numbers; the NLP's ``p`` is still there, unused): what
        IPOPT solves when ``p`` is ``p0``, its derivatives no longer carrying every segment's parameters."""
        if not self.nlp_model.is_a("SXFunction"):
            return self.nlp()
        model = self.folded_model()
        x = ca.SX.sym("x", self.nlp_model.size1_in("x"))

        def case(c) -> ca.Function:
            return ca.Function("nlp_case", [x], model.call([x, ca.DM(ca.evalf(c))]), ["x"], model.name_out())

        _, g, _, out, _ = self.make_constraints(case, self._at_p0(), self.p)
        self.__dict__["folded_primary"] = out[self.sizing.PRIMARY] / self.m_ref
        return self.nlp(f=self._objective(self.__dict__["folded_primary"]), g=ca.vertcat(*g) / ca.DM(self.g_scale))

    def folded_model(self) -> ca.Function:
        """The NLP's model (:func:`~optimisation.nlp_parts.vector_model`) at the scene's parameters ``p0`` (SX,
        folded): a Function (x SI, c)."""
        if "_folded" not in self.__dict__:
            x, c = (ca.SX.sym(k, self.nlp_model.size1_in(k)) for k in ("x", "c"))
            self.__dict__["_folded"] = ca.Function("nlp_model_p0", [x, c],
                                                   self.nlp_model.call([x, ca.DM(self.p0), c]), ["x", "c"],
                                                   self.nlp_model.name_out())
        return self.__dict__["_folded"]

    def _objective(self, primary):
        """The primary objective (scaled), then the other variables in order, far below it."""
        f = primary
        for i, w in enumerate(self.sizing.WEIGHTS):
            f = f + w * self.xs[1 + i]
        return f

    def envelope(self, xs, p=None) -> Envelope:
        """Every output of the scene at scaled ``xs`` in every case, each at its worst
        (:func:`ropemodel.envelope.envelope`): the margins, forces and power at a design.  At the scene's
        parameters the cases are the :attr:`candidates` (every worst is among them), else every case."""
        at_p0 = p is None or np.array_equal(np.asarray(p, dtype=float), self.p0)
        params = dict(zip(self.params, self.p0 if p is None else np.asarray(p, dtype=float)))
        env = envelope(self.problem, self.candidates if at_p0 else self.all_cases, {**params, **self.to_si(xs)})
        env.spanned = self.all_cases
        return env

    # ------------------------------------------------------------------ helpers
    def nlp(self, f=None, g=None, x=None) -> dict:
        """The NLP dict for ``ca.nlpsol`` (scaled x, parameters p)."""
        return {"x": self.xs if x is None else x, "p": self.p, "f": self.f if f is None else f,
                "g": self.g if g is None else g}

    def bounds(self, d_range=None) -> tuple[np.ndarray, np.ndarray]:
        """Scaled bounds of x: the declaration's, the first (catalogue) variable in ``d_range`` where given."""
        lo, hi = self.sizing.bounds(d_range)
        return lo / self.x_scale, hi / self.x_scale

    def x0(self) -> np.ndarray:
        """Scaled starting point: the scene's design where it gives one, else :meth:`start`."""
        start, v = self.start(), self.scene.parameters
        given = {k: v[k] for k in self.variables
                 if k in v and self.scene.origin.get(k) != "default" and math.isfinite(v[k])}
        return np.array([given.get(k, start[k]) for k in self.variables]) / self.x_scale

    def start(self) -> dict[str, float]:
        """A start computed from the scene (SI, the declaration's).  Only a start: IPOPT moves on from it."""
        return self.sizing.start(self.scene.parameters)

    def to_si(self, xs) -> dict[str, float]:
        xs = np.asarray(xs, dtype=float).ravel()
        return {k: float(xs[i] * self.x_scale[i]) for i, k in enumerate(self.variables)}

    def p_of(self, values: dict | None = None) -> np.ndarray:
        """Parameter vector with SI ``values`` overriding the scene's."""
        p = self.p0.copy()
        values = dict(values or {})
        values.update(self.scene.rule_values({**self.scene.parameters, **values}, values))   # rules follow L_u
        for k, v in values.items():
            p[self.params.index(k)] = v
        return p

    @cached_property
    def g_function(self) -> ca.Function:
        """Scaled constraints g(x, p)."""
        return ca.Function("g", [self.xs, self.p], [self.g], ["x", "p"], ["g"])

    @cached_property
    def margin_function(self) -> ca.Function:
        """Every constraint's margin (the check's own definition and unit, SI) as a Function (x, p)."""
        return ca.Function("margins", [self.xs, self.p], [ca.vertcat(*self._margin_exprs)])

    def margins(self, xs, p=None) -> dict[str, float]:
        """Every margin (the checks' own definition and unit, SI) at scaled ``xs``, for every state."""
        values = np.asarray(self.margin_function(xs, self.p0 if p is None else p)).ravel()
        return dict(zip(self.constraints, map(float, values)))

    def evaluate(self, xs, p=None) -> dict[str, float]:
        """Every scene output (SI) at scaled ``xs``."""
        return {k: float(v) for k, v in self.outputs(x=xs, p=self.p0 if p is None else p).items()}
