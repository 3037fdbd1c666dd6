"""The sizing problem: variables, objective and constraints, from the scene's equations.

Decision variables (SI): the rope diameter ``d`` [m], the tensioner pretension
``F_nwl`` [N] and the installed stroke ``stroke`` [m].  Parameters: every other
parameter of the scene.  Nothing here re-types physics: the compiled scene
Function (``Problem(scene).function``, the same one ``ropemodel run`` evaluates)
is called with the decision variables and the parameters as CasADi MX symbols,
and every margin output (``*_margin*``: rope safety, slip on the drum — from the
lining effect, with the Voigt lining's implicit traction inside —, taut ropes
everywhere in the loop, stroke, drum ratio) becomes a constraint ``margin >= 0`` in
both directions, in every load case the scene leaves open: every place of the load
on a route, and with the ramps' inertia every manoeuvre (steady motion, a start
and a stop anywhere, an emergency stop; :mod:`ropemodel.envelope`).

Objective — the lexicographic order "least rope mass per metre, then least
pretension, then least stroke" encoded as a weighted sum with scale separation::

    J = m_l / m_ref  +  w_F · F_nwl / F_ref  +  w_s · stroke / s_ref,   w_F = w_s = 1e-3

Why a weighted sum gives the lexicographic optimum exactly (not approximately):

1. ``stroke`` appears only in its own constraints ``stroke >= ΔF_d``, so for any
   w_s > 0 the optimum has stroke = max_d ΔF_d(d, F_nwl): the third objective
   is met exactly at every (d, F_nwl).
2. In (d, F_nwl) the least-mass design is a vertex: the least F_nwl for traction
   and slack rises (or falls slowly) with d, the most F_nwl the safety check
   allows rises fast with d; the least feasible d is where they meet (or a bound
   of d).  A vertex stays optimal for every objective whose gradient lies in the
   cone of the active constraint normals; the primary gradient ∂m_l/∂d lies
   strictly inside it, and the secondary terms tilt the gradient by w_F·F_ref⁻¹·
   ∂F_lo/∂d and w_s·∂ΔF/∂d relative to ∂(m_l/m_ref)/∂d.  For haulage ropes these
   ratios are <= ~1 (∂F_lo/∂d ≈ −4 L_u sin α_u g W d; ∂ΔF/∂d ≈ −2ΔF/d with ΔF of
   order 1 m), so weights of 1e-3 leave a margin of ~1000 before the order
   could flip.  At the vertex the optimum is then fixed by the active
   constraints alone: the weights change the multipliers, not the design.
   The tests check this against an independent one-dimensional search, and
   :func:`optimisation.ipopt.solve_continuous` verifies it on every solve (the
   multipliers of the primary objective alone stay >= 0, see ``lexicographic_ok``).
3. When d sits at a bound, F_nwl is pushed to its least feasible value by w_F > 0,
   again exactly (a bound, active constraints).

Scaling: x is solved in units of (10 mm, F_ref, 1 m) with F_ref = 0.1·G_m; margins
in N are divided by F_ref, margins in m are taken in m, ratio margins as they are.
"""

from __future__ import annotations

import math
from collections import ChainMap
from functools import cached_property
from typing import Any

import casadi as ca
import numpy as np

from ropemodel.effects.sizing import declared
from ropemodel.core.evaluate import reordered
from ropemodel.effects.winch_checks import margin_names
from ropemodel.envelope import RAMPS, Envelope, LoadCase, envelope, free, load_cases
from ropemodel.envelope.cases import depends_on, distinct, joint_ends
from ropemodel.envelope.prune import prune
from ropemodel.envelope.cases import reads as case_reads
from ropemodel.errors import InputError, Problems
from ropemodel.problem import Problem
from ropemodel.scene import Scene, SceneLike, SceneWarning, as_scene

VARIABLES = ("d", "F_nwl", "stroke")
W_F = 1e-3
W_S = 1e-3
#: continuous bounds of d [m] (the catalogue's range is used for discrete designs)
D_BOUNDS = (1e-3, 0.2)

#: what sizing chooses itself: a scene may leave these out (a start is computed)
SIZED = ("d", "F_nwl", "stroke")
#: linings whose traction does not need the drum diameter: D is optional, and without it the drum
#: check becomes a result, the least drum diameter D_ratio_min * d
D_OPTIONAL_LININGS = ("none", "rigid")
D_OPTIONAL = ("D",)


#: ratio checks written as force differences in the NLP (same sign as the margin while the rope is taut, which
#: the taut/slack checks ensure; no pole where F_C crosses 0, so IPOPT never meets an infinite margin)
RATIO_FORMS = ("safety_margin", "slip_margin")


def _nlp_form(name: str, out: dict, args: dict):
    """The constraint g >= 0 of check ``name`` in the NLP: rope safety F_min − n_rope·F_C [N], no slip
    F_S − n_slip·F_C/traction [N] (the tension the unwinding rope needs; divided by the traction e^{μα} > 0,
    not multiplied: a drum of much friction has a traction of 10^20 and more, whose product scaled the
    constraint out of IPOPT's reach); every other margin as it is."""
    way = name.rsplit("_", 1)[1]
    if name.startswith("safety_margin"):
        return out["F_min"] - args["n_rope"] * out[f"F_C_{way}"]
    if name.startswith("slip_margin"):
        return out[f"F_S_{way}"] - args["n_slip"] * out[f"F_C_{way}"] / out[f"traction_{way}"]
    return out[name]


def _nlp_function(fun: ca.Function, unknowns) -> ca.Function:
    """``fun`` with only the outputs the NLP reads (the checks, what :func:`_nlp_form` writes them from, the rope
    mass): a route's model has an output per segment, and every derivative of the NLP would carry them."""
    reads = {"m_l", "F_min", *margin_names(unknowns)}
    reads |= {f"{f}_{d}" for f in ("F_C", "F_S", "traction") for d in ("up", "down")}
    wanted = [u for u in unknowns if u in reads]
    return reordered(fun, fun.name_in(), wanted)


def _vector_model(fun: ca.Function, params, free, given) -> ca.Function:
    """``fun`` (one scalar input per known) as a Function of three vectors: the design ``x`` (SI, in the order of
    :data:`VARIABLES`), the NLP's parameters ``p`` (``params``) and the case inputs ``c`` (``free``); the
    ``given`` outputs 0.  Each case of the NLP is one call of it, not a node per parameter (a route has
    thousands), and its derivatives are those of one SX Function."""
    sym: Any = ca.SX.sym if fun.is_a("SXFunction") else ca.MX.sym
    x, p, c = sym("x", len(VARIABLES)), sym("p", len(params)), sym("c", len(free))
    env = {**{k: p[i] for i, k in enumerate(params)}, **{k: c[i] for i, k in enumerate(free)},
           **{k: x[i] for i, k in enumerate(VARIABLES)}, **{k: 0.0 for k in given}}
    out = fun.call({k: env[k] for k in fun.name_in() if k in env})
    return ca.Function("nlp_model", [x, p, c], [out[k] for k in fun.name_out()], ["x", "p", "c"],
                       list(fun.name_out()))


def _label(check: str, case: LoadCase, inputs, params) -> str:
    """``slip_margin_up @ segment 2, x_m = 1300 m, start``: the check and the case it is made in (of the case
    inputs it depends on; the check alone where it depends on none)."""
    where = case.label(params, inputs)
    return f"{check} @ {where}" if where else check


def _base(constraint: str) -> str:
    """The check's output name of a constraint (``slip_margin_up @ segment 2`` → ``slip_margin_up``)."""
    return constraint.split(" @ ")[0]


def load_sizing(scene: SceneLike, emit: bool = True) -> Scene:
    """A scene read for sizing (:func:`prepare`): a :class:`~ropemodel.scene.Scene` as it is, or a TOML file or
    built-in scene's name loaded with no starting design needed; the warnings of a scene loaded here
    (``emit=False``: kept in ``scene.warnings`` for the caller to print)."""
    import warnings

    loaded = as_scene(scene, optional=SIZED + D_OPTIONAL, emit=False)
    prepared = prepare(loaded)
    if emit and loaded is not scene:
        for note in prepared.warnings:
            warnings.warn(note, SceneWarning, stacklevel=2)
    return prepared


def prepare(scene) -> Scene:
    """The scene as sizing needs it: design checks on; drive power on when ``v_pj`` is given.

    The scene may leave out d, F_nwl and stroke (:data:`SIZED`, the sizing chooses them) and, for a
    drum without a compliant lining, D (:data:`D_OPTIONAL_LININGS`).  Load it with
    ``load(path, optional=SIZED + ("D",))`` (what ``ropemodel size`` does) or pass it loaded.
    """
    declaration = declared(scene.model)          # a model that declares its sizing (not the winch)
    if declaration is not None:
        return declaration.prepare(scene)
    if scene.model != "winch":
        raise InputError(f"sizing needs model = \"winch\", the scene has model = {scene.model!r}")
    effects = {"checks": "design"}
    if scene.effects.get("power") == "none" and ("v_pj" in scene.unused or "v_pj" in scene.parameters):
        effects["power"] = "drive"
    if "t_ramp" in scene.unused or scene.effects.get("dynamics") == "trip":   # size through a trip's ramps
        effects.update(RAMPS, power="drive")
    optional = SIZED + (D_OPTIONAL if scene.effects.get("lining", "none") in D_OPTIONAL_LININGS else ())
    if scene.effects.get("rope") == "given":
        _refuse_given_rope(scene, effects, optional)
    if all(scene.effects.get(k) == v for k, v in effects.items()) and not (set(scene.absent) - set(optional)):
        return scene
    return scene.with_effects(effects, optional=optional)


def _refuse_given_rope(scene, effects: dict, optional) -> None:
    """:class:`InputError`: sizing chooses d, so it needs a rope construction; with it, every other problem
    the scene would still have (e.g. a missing rope_grade or n_rope), at once."""
    from ropemodel.effects import effects_of

    named = [v for v in effects_of("winch")["rope"].variants if v not in ("given", "catalogue")]
    usual = "6x36-IWRC" if "6x36-IWRC" in named else named[0]     # the README's sizing scene's
    found = Problems()
    found.add(f"sizing chooses the rope diameter d, so it needs a rope construction, not the rope given as q_l and "
              f"q_lw (rope = \"given\"): set [effects] rope = \"{usual}\" or another of {', '.join(named)}, or "
              f"\"catalogue\" with rope_K, rope_W and rope_C")
    with found.collect():
        scene.with_effects({**effects, "rope": usual}, optional=optional)
    found.raise_if_any()


def _check_work(scene, where: list, spanned: int) -> None:
    """The NLP's size on a route, every check at every load case it is built at (the places that can govern, of
    ``spanned`` cases) through every segment, against its budget."""
    from ropemodel import budget

    segments = len(scene.route)
    if segments:
        kept = "" if len(where) == spanned else f" (the cases that can govern of {spanned})"
        budget.check("route sizing", len(where) * segments,
                     f"sizing on a route of {segments} segments checks every check at {len(where)} load cases{kept}, "
                     f"each through the {segments} segments: an NLP of {len(where)} x {segments}",
                     "join neighbouring segments of nearly the same inclination")


def reads(scene: Scene) -> tuple[set[str], dict[str, str]]:
    """What the sizing of the (prepared) ``scene`` is computed from (every check, the rope mass, the drive
    power, the load cases' places and accelerations: :func:`ropemodel.envelope.reads`), and what it sets itself
    (name → how): the design variables."""
    declaration = declared(scene.model)
    if declaration is not None:
        return declaration.reads(scene)
    chosen = {k: "the sizing chooses it (a value given only starts the search)" for k in VARIABLES}
    return scene.built.inputs_of() | case_reads(scene), chosen


def rope_problem(scene) -> str | None:
    """Why sizing cannot choose ``scene``'s rope (a rope given by its weight, no catalogue to choose from), or
    None."""
    if scene.effects.get("rope") == "given":
        return ("sizing chooses the rope diameter: it needs [effects] rope = \"catalogue\" or a named construction "
                "such as \"6x36-IWRC\" (the scene has rope = \"given\")")
    return None


class SizingProblem:
    """The NLP of winch sizing for one scene (model ``winch``).

    Attributes
    ----------
    scene: the scene (its d, F_nwl, stroke are the starting design).
    params: names of the NLP parameters p (every other scene parameter), in order.
    p0: their SI values from the scene.
    constraints: names of the margin outputs, in order (g >= 0 after scaling).
    outputs: a Function (x_SI[3], p) → every scene output (for reports: N_p, margins).
    """

    def __init__(self, scene: Scene, prune_places: bool = True):
        scene = prepare(scene)
        self.scene = scene
        #: no drum diameter given: the drum check becomes a result, D = D_ratio_min * d (the least drum)
        self.least_drum = "D" in scene.absent
        #: every place of the load and every manoeuvre the scene leaves open (:func:`ropemodel.envelope.load_cases`),
        #: their inputs (x_m, a_h) set by each case: where :meth:`envelope` evaluates a design
        self.all_cases, self.free = load_cases(scene), free(scene)
        #: where the NLP makes the checks: the places that can govern (:func:`ropemodel.envelope.prune.prune`,
        #: for every rope and pretension; ``prune_places=False`` for a sweep varying the route or the load)
        self.cases = prune(self.all_cases, scene.parameters, scene.built) if prune_places else self.all_cases
        _check_work(scene, self.cases, len(self.all_cases))    # before the model is compiled
        self.problem = Problem(scene, {"drum_margin": 0.0}, ["D"]) if self.least_drum else Problem(scene)
        fun = self.problem.function
        self.params = [k for k in self.problem.knowns
                       if k not in VARIABLES and k not in self.problem.given and k not in self.free]
        self.p0 = np.array([scene.parameters[k] for k in self.params], dtype=float)
        g_m = scene.parameters.get("G_m", 1e5)
        self.F_ref = max(0.1 * abs(g_m), 1e3)
        self.x_scale = np.array([0.01, self.F_ref, 1.0])

        xs = ca.MX.sym("x", 3)
        p = ca.MX.sym("p", len(self.params))
        x_si = xs * ca.DM(self.x_scale)
        args = {k: p[i] for i, k in enumerate(self.params)}
        args.update({k: x_si[i] for i, k in enumerate(VARIABLES)})
        args.update({k: 0.0 for k in self.problem.given})   # drum_margin = 0 when D is a result
        self.xs, self.p = xs, p
        self._nlp_model = _vector_model(_nlp_function(fun, self.problem.unknowns), self.params, self.free,
                                        self.problem.given)
        self.constraints, self._g, self._margin_exprs, out = self._constraints(self._nlp_model, fun, args, p)
        unit_scale = {"1": 1.0, "N": self.F_ref, "m": 1.0}
        q = scene.built.quantities
        self.units = {c: ("N" if c.startswith(RATIO_FORMS) else q[_base(c)].unit) for c in self.constraints}
        self.g_scale = np.array([unit_scale[self.units[c]] for c in self.constraints])
        self.g = ca.vertcat(*self._g) / ca.DM(self.g_scale)
        # reference mass per metre: the scene's rope at d = 10 mm (fixed number: the weights are constants)
        m_at = ca.Function("m", [xs, p], [out["m_l"]])
        self.m_ref = float(m_at(ca.DM([1.0, 1.0, 1.0]), self.p0))
        self.f_primary = out["m_l"] / self.m_ref
        self.f = self.f_primary + W_F * xs[1] + W_S * xs[2]
        self.output_names = list(self.problem.unknowns)
        every = fun.call({**args, **self.cases[0].values(ChainMap(args, scene.parameters))})
        self.outputs = ca.Function("outputs", [xs, p], [every[n] for n in self.output_names],
                                   ["x", "p"], self.output_names)

    def _constraints(self, model: ca.Function, fun: ca.Function, args, p) -> tuple[list, list, list, dict]:
        """Every check in every case it can differ in (a check that depends only on the manoeuvre once per
        manoeuvre, one that depends on neither once): their labels, the constraints g and the margins.
        The cases' places and accelerations follow the NLP's parameters ``p`` (a segment's length moves x_m).
        ``model``: :func:`_vector_model`; ``fun``: the same with one input per known; ``args``: each known's
        value.  Returns (labels, g, margins, the outputs at the first case)."""
        values = ChainMap(args, self.scene.parameters)
        ends = joint_ends(values) if self.scene.route else None
        x_si = self.xs * ca.DM(self.x_scale)

        def at_case(i: int) -> dict:
            case = self.cases[i].values(values, ends)     # an input a case leaves alone: 0, as CasADi's default
            given = {"x": x_si, "p": p, "c": ca.vertcat(*[case.get(k, 0.0) for k in self.free])}
            return model.call({k: given[k] for k in model.name_in()})

        margins = margin_names(self.problem.unknowns)
        depends = depends_on(fun, margins)
        at: dict[int, dict] = {}
        labels, g, exprs = [], [], []
        for c in margins:
            for i in distinct(self.cases, depends[c]):
                if i not in at:
                    at[i] = at_case(i)
                labels.append(_label(c, self.cases[i], depends[c], self.scene.parameters))
                g.append(_nlp_form(c, at[i], args))
                exprs.append(at[i][c])
        return labels, g, exprs, (at[0] if 0 in at else at_case(0))

    @cached_property
    def at_scene(self) -> dict:
        """The NLP (:meth:`nlp`) at the scene's parameters ``p0``, folded into its expressions (a route's sums are
        numbers; the NLP's ``p`` is still there, unused): what IPOPT solves when ``p`` is ``p0``, its derivatives no
        longer carrying every segment's parameters."""
        if not self._nlp_model.is_a("SXFunction"):
            return self.nlp()
        x, c = (ca.SX.sym(k, self._nlp_model.size1_in(k)) for k in ("x", "c"))
        model = ca.Function("nlp_model_p0", [x, c], self._nlp_model.call([x, ca.DM(self.p0), c]),
                            ["x", "c"], self._nlp_model.name_out())
        x_si = self.xs * ca.DM(self.x_scale)
        args = {**dict(zip(self.params, self.p0.tolist())), **{k: x_si[i] for i, k in enumerate(VARIABLES)},
                **{k: 0.0 for k in self.problem.given}}
        _, g, _, out = self._constraints(model, self.problem.function, args, self.p)
        f = out["m_l"] / self.m_ref + W_F * self.xs[1] + W_S * self.xs[2]
        return self.nlp(f=f, g=ca.vertcat(*g) / ca.DM(self.g_scale))

    def envelope(self, xs, p=None) -> Envelope:
        """Every output of the scene at scaled ``xs`` in every case, each at its worst
        (:func:`ropemodel.envelope.envelope`): the margins, forces and power at a design."""
        params = dict(zip(self.params, self.p0 if p is None else np.asarray(p, dtype=float)))
        return envelope(self.problem, self.all_cases, {**params, **self.to_si(xs)})

    # ------------------------------------------------------------------ helpers
    def nlp(self, f=None, g=None, x=None) -> dict:
        """The NLP dict for ``ca.nlpsol`` (scaled x, parameters p)."""
        return {"x": self.xs if x is None else x, "p": self.p, "f": self.f if f is None else f,
                "g": self.g if g is None else g}

    def bounds(self, d_range=None) -> tuple[np.ndarray, np.ndarray]:
        """Scaled bounds of x: d in ``d_range`` (default :data:`D_BOUNDS`), F_nwl >= 0, stroke >= 0."""
        lo, hi = d_range or D_BOUNDS
        lbx = np.array([lo, 0.0, 0.0]) / self.x_scale
        ubx = np.array([hi, np.inf, np.inf]) / self.x_scale
        return lbx, ubx

    def x0(self) -> np.ndarray:
        """Scaled starting point: the scene's design where it gives one, else :meth:`start`."""
        start, v = self.start(), self.scene.parameters
        given = {k: v[k] for k in VARIABLES if k in v and self.scene.origin.get(k) != "default" and math.isfinite(v[k])}
        return np.array([given.get(k, start[k]) for k in VARIABLES]) / self.x_scale

    def start(self) -> dict[str, float]:
        """A start computed from the scene (SI): d for the rope safety against the load's pull alone,
        F_nwl twice the least slack-side tension, a 1 m stroke.  Only a start: IPOPT moves on from it."""
        v = self.scene.parameters
        pull = v.get("G_m", 1e5) * (abs(math.sin(v.get("alpha_u", 0.3))) + v.get("mu_pm", 0.05))
        K = v.get("rope_K", 0.356)
        d = math.sqrt(v.get("n_rope", 5.0) * max(pull, 1e3) / (K * v.get("rope_grade", 1770e6)))
        return {"d": min(max(d, D_BOUNDS[0] * 10), D_BOUNDS[1] / 2), "F_nwl": max(2.0 * v.get("F_S_min", 0.0), 1e4),
                "stroke": 1.0}

    def to_si(self, xs) -> dict[str, float]:
        xs = np.asarray(xs, dtype=float).ravel()
        return {k: float(xs[i] * self.x_scale[i]) for i, k in enumerate(VARIABLES)}

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
        res = self.outputs(x=xs, p=self.p0 if p is None else p)
        return {k: float(v) for k, v in res.items()}
