"""What sizing chooses for a winch, what it minimises and how it keeps every check (Krauze et al. 2025).

Decision variables (SI): the rope diameter ``d`` [m], the tensioner pretension ``F_nwl`` [N] and the installed
stroke ``stroke`` [m].  The generic driver (:class:`optimisation.problem.SizingProblem`) reads this declaration.

Objective — the lexicographic order "least rope mass per metre, then least pretension, then least stroke"
encoded as a weighted sum with scale separation::

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

Scaling: x is solved in units of (10 mm, F_ref, 1 m) with F_ref = 0.1·G_m; margins in N are divided by F_ref,
margins in m are taken in m, ratio margins as they are.
"""

from __future__ import annotations

import math

import numpy as np

from ropemodel.envelope import RAMPS
from ropemodel.envelope.cases import reads as case_reads
from ropemodel.errors import Problems

#: the design variables, in the order of x
VARIABLES = ("d", "F_nwl", "stroke")
#: the output minimised first, and the weights of the other variables (scaled) far below it
PRIMARY = "m_l"
WEIGHTS = (1e-3, 1e-3)
#: continuous bounds of d [m] (the catalogue's range is used for discrete designs)
D_BOUNDS = (1e-3, 0.2)
#: linings whose traction does not need the drum diameter: D is optional, and without it the drum
#: check becomes a result, the least drum diameter D_ratio_min * d
D_OPTIONAL_LININGS = ("none", "rigid")
D_OPTIONAL = ("D",)
#: ratio checks written as force differences in the NLP (same sign as the margin while the rope is taut, which
#: the taut/slack checks ensure; no pole where F_C crosses 0, so IPOPT never meets an infinite margin)
RATIO_FORMS = ("safety_margin", "slip_margin")
#: steps the recommended F_nwl [N] and stroke [m] are rounded up to, coarsest first
ROUNDING = ((100.0, 1e-3), (10.0, 1e-4), (1.0, 1e-5))
#: the units a sweep shows the design in
UNITS = {"d": "mm", "F_nwl": "kN", "stroke": "mm"}
#: the warning of a design where the secondary weights outweighed the rope mass (:func:`optimisation.size`)
NOT_LEXICOGRAPHIC = ("; warning: the rope mass alone is not optimal at this design (the pretension or stroke "
                     "weight outweighed it): check the lexicographic order")
#: what sizing chooses, in words (``ropemodel size``'s status line)
CHOOSES = "rope, pretension and stroke"
#: what sizing does, in words (the report's sizing section, and its rounding)
INTRO = ("The lightest catalogue rope, then the least pretension, then the least stroke, with every design check\n"
         "met in both directions of travel")
#: what the rope's elongation variant sets (``ropemodel size``'s line on it)
ELONGATION = "stroke from elongation"
#: what a scene the report sizes is (a Jinja2 template of ``scene``)
SCENE_TEXT = 'a winch with a catalogue rope (rope = "{{ scene.effects.rope }}")'
ROUNDED = "Rounded up to practical steps (F_nwl to 0.1 kN, the stroke to 1 mm where the checks allow)"


def optional(scene) -> tuple[str, ...]:
    """What a scene may leave out for sizing: the design, and D on a drum whose lining does not need it."""
    return VARIABLES + (D_OPTIONAL if scene.effects.get("lining", "none") in D_OPTIONAL_LININGS else ())


def prepare(scene):
    """The scene as sizing needs it: design checks on; drive power on when ``v_pj`` is given; the ramps'
    inertia when the scene gives a ramp time or makes a trip."""
    effects = {"checks": "design"}
    if scene.effects.get("power") == "none" and ("v_pj" in scene.unused or "v_pj" in scene.parameters):
        effects["power"] = "drive"
    if "t_ramp" in scene.unused or scene.effects.get("dynamics") == "trip":   # size through a trip's ramps
        effects.update(RAMPS, power="drive")
    wanted = optional(scene)
    if scene.effects.get("rope") == "given":
        _refuse_given_rope(scene, effects, wanted)
    if all(scene.effects.get(k) == v for k, v in effects.items()) and not (set(scene.absent) - set(wanted)):
        return scene
    return scene.with_effects(effects, optional=wanted)


def _refuse_given_rope(scene, effects: dict, wanted) -> None:
    """:class:`InputError`: sizing chooses d, so it needs a rope construction; with it, every other problem
    the scene would still have (e.g. a missing rope_grade or n_rope), at once."""
    from ropemodel.effects import effects_of

    named = [v for v in effects_of(scene.model)["rope"].variants if v not in ("given", "catalogue")]
    usual = "6x36-IWRC" if "6x36-IWRC" in named else named[0]     # the README's sizing scene's
    found = Problems()
    found.add(f"sizing chooses the rope diameter d, so it needs a rope construction, not the rope given as q_l and "
              f"q_lw (rope = \"given\"): set [effects] rope = \"{usual}\" or another of {', '.join(named)}, or "
              f"\"catalogue\" with rope_K, rope_W and rope_C")
    with found.collect():
        scene.with_effects({**effects, "rope": usual}, optional=wanted)
    found.raise_if_any()


def reads(scene) -> tuple[set[str], dict[str, str]]:
    """What the sizing of the (prepared) ``scene`` is computed from (every check, the rope mass, the drive
    power, the load cases' places and accelerations: :func:`ropemodel.envelope.reads`), and what it sets itself
    (name → how): the design variables."""
    chosen = {k: "the sizing chooses it (a value given only starts the search)" for k in VARIABLES}
    return scene.built.inputs_of() | case_reads(scene), chosen


def rope_problem(scene) -> str | None:
    """Why sizing cannot choose ``scene``'s rope (a rope given by its weight, no catalogue to choose from), or
    None."""
    if scene.effects.get("rope") == "given":
        return ("sizing chooses the rope diameter: it needs [effects] rope = \"catalogue\" or a named construction "
                "such as \"6x36-IWRC\" (the scene has rope = \"given\")")
    return None


def reported(scene) -> bool:
    """Whether the report sizes ``scene``: a scene whose rope sizing can choose (a catalogue rope)."""
    return rope_problem(scene) is None


def frees(scene) -> tuple[dict[str, float], list[str]]:
    """Checks that become results when the scene leaves a dimension out: no drum diameter, the drum check
    is held at zero and D is solved for (the least drum, D_ratio_min·d)."""
    return ({"drum_margin": 0.0}, ["D"]) if "D" in scene.absent else ({}, [])


def force_scale(scene) -> float:
    """F_ref [N]: a tenth of the load's weight (at least 1 kN), the unit of F_nwl and of force margins."""
    return max(0.1 * abs(scene.parameters.get("G_m", 1e5)), 1e3)


def catalogue_range() -> tuple[float, float]:
    """The smallest and the largest catalogue diameter [m] (EN 12385-4 sizes, ropemodel/data/ropes.toml)."""
    from ropemodel.papers import en12385 as ropes

    sizes = ropes.diameters()
    return sizes[0], sizes[-1]


def place_weights(scene, first_range=None) -> tuple[float, float]:
    """The rope weights q_l [N/m] a design with d in ``first_range`` [m] has (default: every d > 0): the range
    the places that can govern are found for (:func:`ropemodel.envelope.prune.prune`).  q_l = g W d² (EN 12385-4)
    grows with d; W is the construction's (or the scene's ``rope_W`` with ``rope = "catalogue"``)."""
    from ropemodel.papers import en12385 as ropes

    if first_range is None:
        return 0.0, math.inf
    W = scene.parameters.get("rope_W")
    if W is None:
        W = ropes.construction(scene.effects["rope"]).W
    return ropes.rope_weight_per_metre(W, first_range[0]), ropes.rope_weight_per_metre(W, first_range[1])


def x_scale(F_ref: float) -> np.ndarray:
    """SI per unit of scaled x: 10 mm, F_ref, 1 m."""
    return np.array([0.01, F_ref, 1.0])


def bounds(first_range=None) -> tuple[np.ndarray, np.ndarray]:
    """SI bounds of x: d in ``first_range`` (default :data:`D_BOUNDS`), F_nwl >= 0, stroke >= 0."""
    lo, hi = first_range or D_BOUNDS
    return np.array([lo, 0.0, 0.0]), np.array([hi, np.inf, np.inf])


def start(v) -> dict[str, float]:
    """A start computed from the scene's values ``v`` (SI): d for the rope safety against the load's pull alone,
    F_nwl twice the least slack-side tension, a 1 m stroke.  Only a start: IPOPT moves on from it."""
    pull = v.get("G_m", 1e5) * (abs(math.sin(v.get("alpha_u", 0.3))) + v.get("mu_pm", 0.05))
    K = v.get("rope_K", 0.356)
    d = math.sqrt(v.get("n_rope", 5.0) * max(pull, 1e3) / (K * v.get("rope_grade", 1770e6)))
    return {"d": min(max(d, D_BOUNDS[0] * 10), D_BOUNDS[1] / 2), "F_nwl": max(2.0 * v.get("F_S_min", 0.0), 1e4),
            "stroke": 1.0}


def nlp_form(name: str, out: dict, args: dict):
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


def unit(check: str, declared: str) -> str:
    """The unit of check ``check``'s constraint: N for the ratio checks written as forces, else its own."""
    return "N" if check.startswith(RATIO_FORMS) else declared


def rounded_up(problem, xs) -> np.ndarray:
    """The design rounded up to practical steps (F_nwl to 0.1 kN, then the least stroke at that F_nwl to
    1 mm; finer steps if needed) so that every check still holds exactly at the rounded, printed values;
    else the design unrounded.

    Rounding F_nwl up is the safe side of the slip and slack checks; the stroke is the least one for
    the rounded F_nwl (stroke margin = stroke - dF, eq. 23), rounded up.  A coarser step is refused
    when it breaks another check (e.g. the rope safety falls as F_nwl rises).
    """
    x = np.maximum(np.asarray(xs, dtype=float), 0.0)
    d, F_nwl, stroke = problem.to_si(x).values()
    for step_F, step_s in ROUNDING:
        F = math.ceil(F_nwl / step_F - 1e-9) * step_F
        margins = problem.margins(np.array([d, F, stroke]) / problem.x_scale)
        need = stroke - min(v for k, v in margins.items() if k.startswith("stroke_margin"))
        trial = np.array([d, F, math.ceil(need / step_s - 1e-9) * step_s]) / problem.x_scale
        if min(problem.margins(trial).values()) >= 0.0:
            return trial
    return x
