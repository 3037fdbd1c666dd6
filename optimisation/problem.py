"""The sizing problem: variables, objective and constraints, from the scene's equations.

Decision variables (SI): the rope diameter ``d`` [m], the tensioner pretension
``F_nwl`` [N] and the installed stroke ``stroke`` [m].  Parameters: every other
parameter of the scene.  Nothing here re-types physics: the compiled scene
Function (``Problem(scene).function``, the same one ``ropemodel run`` evaluates)
is called with the decision variables and the parameters as CasADi MX symbols,
and every margin output (``*_margin*``: rope safety, slip on the drum — from the
lining effect, with the Voigt lining's implicit traction inside —, slack rope,
stroke, drum ratio) becomes a constraint ``margin >= 0`` in both directions.

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

from functools import cached_property

import casadi as ca
import numpy as np

from ropemodel.effects.winch_checks import margin_names
from ropemodel.errors import InputError
from ropemodel.problem import Problem
from ropemodel.scene import Scene

VARIABLES = ("d", "F_nwl", "stroke")
W_F = 1e-3
W_S = 1e-3
#: continuous bounds of d [m] (the catalogue's range is used for discrete designs)
D_BOUNDS = (1e-3, 0.2)

REQUIRED = {"checks": "design", "power": "drive"}


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

    def __init__(self, scene: Scene):
        if scene.model != "winch":
            raise InputError(f"sizing needs model = \"winch\", the scene has model = {scene.model!r}")
        if scene.effects.get("rope") == "given":
            raise InputError("sizing chooses the rope diameter: it needs [effects] rope = \"catalogue\" or a named "
                             "construction such as \"6x36-IWRC\" (the scene has rope = \"given\")")
        for effect, variant in REQUIRED.items():
            if scene.effects.get(effect) != variant:
                raise InputError(f"sizing needs [effects] {effect} = \"{variant}\" "
                                 f"(the scene has {effect} = {scene.effects.get(effect)!r})")
        self.scene = scene
        self.problem = Problem(scene)
        fun = self.problem.function
        self.params = [k for k in self.problem.knowns if k not in VARIABLES]
        self.p0 = np.array([scene.parameters[k] for k in self.params], dtype=float)
        self.constraints = margin_names(self.problem.unknowns)
        if "slip_margin_up" not in self.constraints:
            raise InputError("sizing needs a drum traction check: set [effects] lining = \"rigid\" or \"voigt\"")
        q = scene.built.quantities
        g_m = scene.parameters.get("G_m", 1e5)
        self.F_ref = max(0.1 * abs(g_m), 1e3)
        self.x_scale = np.array([0.01, self.F_ref, 1.0])
        unit_scale = {"1": 1.0, "N": self.F_ref, "m": 1.0}
        self.g_scale = np.array([unit_scale[q[c].unit] for c in self.constraints])
        self.units = {c: q[c].unit for c in self.constraints}

        xs = ca.MX.sym("x", 3)
        p = ca.MX.sym("p", len(self.params))
        x_si = xs * ca.DM(self.x_scale)
        args = {k: p[i] for i, k in enumerate(self.params)}
        args.update({k: x_si[i] for i, k in enumerate(VARIABLES)})
        out = fun.call(args)
        self.xs, self.p = xs, p
        self.g = ca.vertcat(*[out[c] / s for c, s in zip(self.constraints, self.g_scale)])
        # reference mass per metre: the scene's rope at d = 10 mm (fixed number: the weights are constants)
        m_at = ca.Function("m", [xs, p], [out["m_l"]])
        self.m_ref = float(m_at(ca.DM([1.0, 1.0, 1.0]), self.p0))
        self.f_primary = out["m_l"] / self.m_ref
        self.f = self.f_primary + W_F * xs[1] + W_S * xs[2]
        self.output_names = list(self.problem.unknowns)
        self.outputs = ca.Function("outputs", [xs, p], [out[n] for n in self.output_names],
                                   ["x", "p"], self.output_names)

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
        """Scaled starting point: the scene's design."""
        return np.array([self.scene.parameters[k] for k in VARIABLES]) / self.x_scale

    def to_si(self, xs) -> dict[str, float]:
        xs = np.asarray(xs, dtype=float).ravel()
        return {k: float(xs[i] * self.x_scale[i]) for i, k in enumerate(VARIABLES)}

    def p_of(self, values: dict | None = None) -> np.ndarray:
        """Parameter vector with SI ``values`` overriding the scene's."""
        p = self.p0.copy()
        for k, v in (values or {}).items():
            p[self.params.index(k)] = v
        return p

    @cached_property
    def g_function(self) -> ca.Function:
        """Scaled constraints g(x, p)."""
        return ca.Function("g", [self.xs, self.p], [self.g], ["x", "p"], ["g"])

    def margins(self, xs, p=None) -> dict[str, float]:
        """Every margin in its own unit (SI) at scaled ``xs``."""
        g = np.asarray(self.g_function(xs, self.p0 if p is None else p)).ravel()
        return {c: float(v * s) for c, v, s in zip(self.constraints, g, self.g_scale)}

    def evaluate(self, xs, p=None) -> dict[str, float]:
        """Every scene output (SI) at scaled ``xs``."""
        res = self.outputs(x=xs, p=self.p0 if p is None else p)
        return {k: float(v) for k, v in res.items()}
