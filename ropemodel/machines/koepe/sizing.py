"""Sizing a Koepe hoist (``ropemodel size`` on ``model = "koepe"``): the declaration the generic driver consumes.

Design variables: the head ropes' diameter ``d_head`` (a catalogue size, next size up), the tail ropes' mass per
metre ``q_tail`` and the wheel's diameter ``D``, for each number of head ropes ``n_head`` enumerated over 1 to
10 (multi-rope friction hoists hang 1 to 10; one continuous NLP per number, the lightest feasible kept, the
fewer ropes on a tie).  Objective: the suspended rope mass, both sides, at any position of the wind
(docs/physics.md §7: each side's head rope is H_head + y, the two add up to 2 H_head + H; the tail ropes to
H + 2 h_loop)::

    M_rope = n_head q_head (2 H_head + H) + n_tail q_tail (H + 2 h_loop)      [kg]

then the least wheel (weight 1e-3 per metre of D against the mass in units of the starting design's: the
wheel is fixed by D/d or D_min, which the mass does not feel).

The head ropes' mass and strength follow their diameter: for a catalogue construction (``head_ropes =
"6x36-IWRC"`` ...) q_head = W d², F_min_head = K d² R_r (EN 12385-4, :mod:`ropemodel.papers.en12385`); for head
ropes given (``head_ropes = "given"``) the same construction in the other sizes, q_head and F_min_head scaled by
(d/d_head)² from the scene's rope (W = q_head/d_head², K R_r = F_min_head/d_head²: EN 12385-4's forms with the
given rope's constants).  A tail rope of another mass per metre is the same construction in another size: its
breaking force scales with q_tail (its breaking length F_min_tail/(g q_tail) is the construction's), so the tail
ropes' safety does not depend on q_tail.

Checks, each smooth and made in every state it can govern in (:mod:`ropemodel.effects.koepe_states`), one
constraint per state and side: head and tail rope safety, D/d and the least wheel, the ratings, the static
anti-slip factor (σ >= σ_min multiplied out, both sides: :func:`ropemodel.papers.koepe.anti_slip_margin`) and,
with ``brake = "window"`` (switched on by sizing), the braking window of each direction: every end state's slip
limit at least ``a_brake_min``, at least every end state's deceleration without brake, and ``a_brake_max`` at
least both.  The lining's slip limits and traction are the scene's lining's own (rigid or Voigt).
"""

from __future__ import annotations

import math

from ropemodel.effects import koepe_states as st
from ropemodel.effects.koepe import MODEL
from ropemodel.effects.koepe_brake import DIRECTIONS
from ropemodel.machines.sizing import Check, Declaration, Transient, Variable
from ropemodel.papers import en12385 as ropes
from ropemodel.papers import koepe as kp
from ropemodel.papers import koepe_slip as ks
from ropemodel.papers.route import G_N

#: the numbers of head ropes enumerated (multi-rope friction hoists hang 1 to 10: koepe.N_HEAD's usual range)
COUNTS = tuple(range(1, 11))
#: weight of the least wheel against the rope mass (scaled): far below it, so the mass decides first
W_D = 1e-3
#: what the design variables are, in words (the output's meaning column)
VARIABLES = (Variable("d_head", 0.01, 0.0, 0.5), Variable("q_tail", 1.0, 0.0, 1e3, (0.1, 0.01)),
             Variable("D", 1.0, 1e-3, 100.0, (0.1, 0.01)))


def _submodel(scene, effect: str):
    """The scene's submodel of ``effect``."""
    return dict(zip(scene.built.effects, scene.built.submodels))[effect]


def _strength(scene, v, d):
    """(q_head [kg/m], F_min_head [N]) of a head rope of diameter ``d`` [m] (module docstring)."""
    variant = scene.effects.get("head_ropes", "given")
    construction = ropes.constructions().get(variant)
    if construction is not None:
        return (ropes.rope_mass_per_metre(construction.W, d),
                ropes.minimum_breaking_force(construction.K, d, v["rope_grade"]))
    d0 = scene.parameters["d_head"]
    return v["q_head"] * (d / d0) ** 2, v["F_min_head"] * (d / d0) ** 2


def _static(scene, v) -> list[Check]:
    """Rope safety, the ratings and the anti-slip factor in each static state, one constraint per side."""
    out, lining = [], _submodel(scene, "lining")
    finite = {k: math.isfinite(scene.parameters.get(k, math.inf)) for k in ("T_rated", "dT_rated")}
    for s in [st.sides(v, _tail(scene, v), state) for state in st.STATIC]:
        name = s.state.name
        for side, T, other in (("the loaded side", s.T_L, s.T_E), ("the other side", s.T_E, s.T_L)):
            where = f"{name}, {side}"
            out.append(Check("head_safety_margin", where, v["n_head"] * v["F_min_head"] - v["n_safety_head"] * T, "N"))
            if finite["T_rated"]:
                out.append(Check("pull_margin", where, v["T_rated"] - T, "N"))
            if finite["dT_rated"]:
                out.append(Check("difference_margin", f"{name}, {side} high", v["dT_rated"] - (T - other), "N"))
            out.append(Check("antislip_margin", f"{name}, {side} high",
                             kp.anti_slip_margin(T, other, lining.limit(v, other), v["sigma_static_min"]), "N"))
    return out


def _tail(scene, v):
    """(n_tail, q_tail, h_loop) of the scene's tail ropes."""
    return _submodel(scene, "tail_ropes").terms(v)


def _brake(scene, v) -> list[Check]:
    """The braking window of each direction, one constraint per end state and bound."""
    lining, brake, out = _submodel(scene, "lining"), _submodel(scene, "brake"), []
    a_max = math.isfinite(scene.parameters.get("a_brake_max", math.inf))
    for d, (sign, text) in DIRECTIONS.items():
        free = brake.coasting(v, sign)
        for s in (st.sides(v, _tail(scene, v), state) for state in st.DYNAMIC):
            M_L, M_E = st.masses(v, s)
            sides = ks.manoeuvre_sides(s.T_L, s.T_E, M_L, M_E, v["F_r"])[f"{d}_decel"]
            slip = lining.slip(v, *sides) * (1.0 - v[f"brake_allowance_{d}"])     # what the elastic ropes leave
            where = f"{text}: the slip limit {st.describe(s, compartment=True)}"
            out.append(Check(f"brake_margin_{d}", f"{where} against a_brake_min", slip - v["a_brake_min"], "m/s^2"))
            out += [Check(f"brake_margin_{d}", f"{where} against the deceleration without brake ({c.state.name})",
                          slip - x, "m/s^2") for c, x in free]
        if a_max:
            out += [Check(f"brake_margin_{d}", f"{text}: a_brake_max against the deceleration without brake "
                          f"({c.state.name})", v["a_brake_max"] - x, "m/s^2") for c, x in free]
    return out


class KoepeSizing(Declaration):
    """The Koepe hoist's sizing (module docstring)."""

    model = MODEL
    variables = VARIABLES
    integer = "n_head"
    allowances = tuple(f"brake_allowance_{d}" for d in DIRECTIONS)
    objective_text = ("the suspended rope mass n_head q_head (2 H_head + H) + n_tail q_tail (H + 2 h_loop), "
                      "then the least wheel")
    CHOOSES = "head ropes, tail ropes and wheel"
    remedies = {
        "head_safety_margin": (("m_payload", "max"), ("n_safety_head", "max")),
        "tail_safety_margin": (("F_min_tail", "min"), ("n_safety_tail", "max")),
        "pull_margin": (("T_rated", "min"), ("m_payload", "max")),
        "difference_margin": (("dT_rated", "min"), ("m_payload", "max")),
        "antislip_margin": (("mu", "min"), ("alpha", "min"), ("m_conveyance", "min"), ("m_payload", "max")),
        "brake_margin_hoist": (("a_brake_min", "max"), ("mu", "min"), ("alpha", "min"), ("m_conveyance", "min")),
        "brake_margin_lower": (("a_brake_min", "max"), ("mu", "min"), ("alpha", "min"), ("m_conveyance", "min")),
        "wheel_size_margin": (("D_min", "max"),),
    }

    def prepare(self, scene):
        effects = {"checks": "design", "brake": "window"}
        if all(scene.effects.get(k) == x for k, x in effects.items()):
            return scene
        return scene.with_effects(effects)

    def counts(self, scene):
        return COUNTS

    def catalogue(self, scene):
        return ropes.diameters()

    def bounds(self, scene):
        out = super().bounds(scene)
        if scene.effects.get("tail_ropes") == "none":
            out[1] = (0.0, 0.0)       # no tail ropes: nothing to choose
        return out

    def unit_scales(self, scene):
        """Forces in tenths of a conveyance's weight."""
        return {**super().unit_scales(scene), "N": 0.1 * G_N * scene.parameters["m_conveyance"]}

    def start(self, scene, count):
        v = scene.parameters
        d0 = v.get("d_head", 0.04) * math.sqrt(v.get("n_head", count) / count)
        tails = v.get("n_tail", 1.0)
        q_tail = v.get("q_tail", count * 4000.0 * d0**2 / tails) if scene.effects.get("tail_ropes") != "none" else 0.0
        return {"d_head": d0, "q_tail": q_tail, "D": max(v.get("D_ratio_min", 80.0) * d0, v.get("D_min", 0.0))}

    def completed(self, scene, v):
        q_head, F_min_head = _strength(scene, v, v["d_head"])
        out = {**v, "q_head": q_head, "F_min_head": F_min_head}
        if scene.effects.get("tail_ropes") != "none":
            out["F_min_tail"] = v["F_min_tail"] * v["q_tail"] / scene.parameters["q_tail"]
        return out

    def objective(self, scene, v):
        n_tail, q_tail, h_loop = _tail(scene, v)
        mass = v["n_head"] * v["q_head"] * (2.0 * v["H_head"] + v["H"]) + n_tail * q_tail * (v["H"] + 2.0 * h_loop)
        return mass, W_D * v["D"]

    def checks(self, scene, v):
        out = _static(scene, v)
        if scene.effects.get("tail_ropes") != "none":
            F_tail = G_N * v["q_tail"] * (v["H"] + v["h_loop"])
            out.append(Check("tail_safety_margin", "a tail rope hanging from a conveyance at its upper position",
                             v["F_min_tail"] - v["n_safety_tail"] * F_tail, "N"))
        out += [Check("wheel_margin", "D/d", v["D"] - v["D_ratio_min"] * v["d_head"], "m"),
                Check("wheel_size_margin", "the least wheel", v["D"] - v["D_min"], "m")]
        return out + _brake(scene, v)

    def at_design(self, scene, design):
        values = {**scene.parameters, **design}
        done = self.completed(scene, values)
        keys = ("q_head", "F_min_head") if scene.effects.get("head_ropes", "given") == "given" else ()
        keys += ("F_min_tail",) if "F_min_tail" in done and scene.effects.get("tail_ropes") != "none" else ()
        out = {**design, **{k: float(done[k]) for k in keys}}
        if "EA_head" in scene.parameters and "d_head" in scene.parameters:    # the same construction: EA ∝ d²
            out["EA_head"] = scene.parameters["EA_head"] * (design["d_head"] / scene.parameters["d_head"]) ** 2
        return out

    def transients(self, scene, values, result):
        """With a braking transient in the scene (``dynamics = "braking"``): that stop (its brake, its direction)
        from where the scene starts it and from the middle of the wind; its allowance is its direction's."""
        if scene.effects.get("dynamics") != "braking":
            return []
        travel = scene.effects.get("travel", "hoist")
        text = DIRECTIONS[travel][1]
        return [Transient(f"brake_allowance_{travel}", {}, {**values, **extra},
                          f"{text}, the scene's brake, from {where}")
                for extra, where in (({}, "the scene's start"),
                                     ({"y_start": 0.5 * scene.parameters["H"]}, "the middle of the wind"))]

    def holds(self, summary):
        return not summary["slip"]

    def reads(self, scene):
        chosen = {x.name: "the sizing chooses it (a value given only starts the search)" for x in VARIABLES}
        chosen["n_head"] = f"the sizing enumerates it over {COUNTS[0]} to {COUNTS[-1]}"
        return scene.built.inputs_of(), chosen
