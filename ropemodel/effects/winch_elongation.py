"""The rope's elongation as built (``[effects] elongation = "asbuilt"``): docs/physics.md §8.

Where ``krauze2025`` (eq. (19)-(23)) loads each whole rope side with its force at the drive and lets the
return sheave take up the loop's whole elongation, ``asbuilt`` integrates Hooke's law along each side with
its tension profile (the load at ``x_m``, the route's segments, the resistances and inertia of the
direction of travel), divides the loop's change of length by the tensioner's falls ``n_falls``, and adds
the constructional stretch of a new rope and the rope's temperature change since its installation:

    ΔF_C,w = ∫T_C,w dx / EA,  ΔF_S,w = ∫T_S,w dx / EA,  EA = L_u/q_lw
    ΔF_w = (ΔF_C,w + ΔF_S,w + ε_c·2L_u + α_T·ΔT·2L_u) / n_falls,   ε_c = c_stretch·ε(n_rope, core)

(:mod:`ropemodel.papers.ropestretch`).  The stroke is the take-up from the rope spliced unstressed at its
installation temperature; eq. (23) adds ΔF_nwl = q_lw F_nwl once more to ΔF_C + ΔF_S, which already carry
0.5 F_nwl each, so it counts the pretension twice (conservative).  Here ΔF_nwl is reported, not added.
"""

from __future__ import annotations

from typing import ClassVar

from ropemodel._math import cos, sin
from ropemodel.effects import domains as dom
from ropemodel.effects.base import REGISTRY, Equation, Submodel, register
from ropemodel.effects.transient.travel import X_M
from ropemodel.effects.winch import DF, DF_NWL, DF_SIDES, DIRECTIONS, EA, MODEL, Q, Q_LW, usual
from ropemodel.effects.winch_checks import N_ROPE
from ropemodel.effects.winch_rope import RopeCatalogue
from ropemodel.papers import ropestretch as rs

#: where the equations come from
SRC = "as built, docs/physics.md §8 (not in Krauze et al. 2025)"
#: the rope cores the constructional-stretch table has a steel column for (others: the fibre column)
STEEL_CORES = ("IWRC", "WSC")

#: the rope's metallic area (an output of a catalogue rope; a parameter with a rope given by q_l, q_lw)
A_M = next(q for q in RopeCatalogue.quantities if q.name == "A_m")

QUANTITIES = (
    Q("n_falls", "1", "falls of the tensioner's reeving: it moves 1/n_falls of the rope it takes up",
      **dom.domain(1.0, 100.0, "at least 1 (the loop itself); tensioners reeve 1 to 8 falls"),
      guess=1.0, default=1.0, symbol="n_falls",
      default_note="not given: the tensioner takes up the loop's whole elongation (Krauze et al. 2025, eq. (23)); "
                   "a movable return sheave carrying both rope sides: 2"),
    Q("c_stretch", "1", "share of the table's constructional stretch still to come (1 new rope, 0 run in)",
      **dom.domain(0.0, 1.0, "physics: a share of the table's stretch, none to all of it"), guess=1.0, default=1.0,
      default_note="not given: a new rope, not pre-stretched (the whole constructional stretch to come)"),
    Q("alpha_T", "1/K", "linear thermal expansion coefficient of the rope", "1/K", guess=12.5e-6,
      **dom.domain(0.0, 1e-3, "0 to 1e-3 /K, fifty times steel's (12e-6 /K) and beyond any polymer's (about 2e-4 /K)"),
      default=rs.ALPHA_STEEL_ROPE, symbol="α_T", default_note=rs.ALPHA_SOURCE,
      **usual(10e-6, 14e-6, "carbon steel 11-13e-6 /K")),
    Q("dT_rope", "K", "rope temperature above its installation temperature (< 0: colder)", "K", guess=0.0,
      default=0.0, symbol="ΔT_rope",
      **dom.domain(-100.0, 100.0, "±100 K: beyond the range of mine air (about -40 to +50 °C) around an installation"),
      default_note="not given: the rope at its installation temperature"),
    Q("eps_c", "1", "constructional (permanent) stretch of the rope still to come", "%", symbol="ε_c",
      equation=f"the rope makers' table by core and safety factor: {rs.STRETCH_SOURCE}"),
    Q("dF_c", "m", "constructional stretch of the loop, eps_c 2 L_u", "mm", symbol="ΔF_c", equation=SRC),
    Q("dF_T", "m", "thermal elongation of the loop, alpha_T dT_rope 2 L_u", "mm", symbol="ΔF_T", equation=SRC),
)


@register(MODEL, "elongation", "asbuilt")
class ElongationAsBuilt(Submodel):
    """The stroke as built: each side's tension profile integrated, the reeving, constructional stretch and
    temperature (docs/physics.md §8, :mod:`ropemodel.papers.ropestretch`)."""

    description = ("elongation of each rope side from its tension profile along the route, the tensioner's "
                   "falls, constructional stretch and temperature")
    #: the winding side's tension integral holds the load's pull times x_m (side_tension_integral): a worst
    #: elongation may be at a place the pruned list leaves out
    place_through_pull = False
    #: integrates each side segment by segment: a long route keeps its segments in the model for it
    reads_route_profile = True
    citations: ClassVar[tuple[str, ...]] = ("krauze2025", "rope_extension")
    assumptions = (
        "Hooke's law along each rope side with its tension profile (load position x_m; not given: the load at "
        "the return sheave, where the winding side stretches most); the rope on the drum and sheaves is left out.",
        "The stroke is the take-up from the rope spliced unstressed at its installation temperature; eq. (23)'s "
        "second count of the pretension's elongation (ΔF_nwl) is not added.",
        "Constructional stretch from the rope makers' table (fibre core 0.25-0.75 %, steel core 0.125-0.5 % by "
        "safety factor 8-3) read at the required safety factor n_rope (the rope's own is higher: less stretch); "
        "a rope whose core is not a steel core (IWRC) is read from the fibre-core column.",
        "The same modulus at every tension (EA = L_u/q_lw).",
    )
    missing = ("The rope maker's constructional stretch and a measured modulus of the installed rope: the table's "
               "values are approximate (\"cannot be accurately determined by calculation\").",)
    quantities = (Q_LW, EA, X_M, N_ROPE, *QUANTITIES, DF_NWL, *DF_SIDES, *DF)
    #: how each side's elongation is computed where no closed form shows it, and its relative tolerance
    elastic_method: ClassVar[str] = ""
    elastic_tolerance: ClassVar[float | None] = None

    def _fibre_core(self) -> bool:
        rope = REGISTRY[MODEL]["rope"].variants.get(self.effects.get("rope", ""))
        construction = getattr(rope, "construction", None)
        return getattr(construction, "core", "") not in STEEL_CORES

    def _sides(self, v, sign):
        """The tension profiles of the direction ``sign`` (+1 up, −1 down): T_0 at the return sheave, the
        pieces' lengths, the winding and unwinding rope's rise per metre w_C, w_S [N/m] and the load's step J."""
        spec = REGISTRY[MODEL]
        route = spec["route"].variants[self.effects.get("route", spec["route"].default)](self.options, self.effects)
        inertia = spec["inertia"].variants[self.effects.get("inertia", spec["inertia"].default)](self.options,
                                                                                                 self.effects)
        lengths, alphas, mus = route.profile(v)
        a_rope = inertia.rope_force_per_metre(v)
        q, T_0 = v["q_l"], 0.5 * v["F_nwl"]
        w_C = [q * (sin(a) + sign * mu * cos(a)) + sign * a_rope for a, mu in zip(alphas, mus)]
        w_S = [q * (sin(a) - sign * v["mu_pl"] * cos(a)) - sign * a_rope for a in alphas]
        d = "up" if sign > 0 else "down"
        rise_C = sum(w * length for w, length in zip(w_C, lengths))
        J = v[f"F_C_{d}"] - T_0 - rise_C           # the load's share of F_C (eq. (13)): its step at x_m
        return T_0, lengths, w_C, w_S, J

    def elastic(self, v, sign):
        """(ΔF_C, ΔF_S) [m]: Hooke's law integrated along each side."""
        T_0, lengths, w_C, w_S, J = self._sides(v, sign)
        return (rs.elastic_elongation(rs.side_tension_integral(T_0, w_C, lengths, J, v["x_m"]), v["EA"]),
                rs.elastic_elongation(rs.side_tension_integral(T_0, w_S, lengths, 0.0, v["x_m"]), v["EA"]))

    def pretension(self, v):
        """The loop's elastic elongation under the pretension alone [m]."""
        return v["F_nwl"] * v["L_u"] / v["EA"]

    def equations(self, v):
        loop = 2.0 * v["L_u"]
        eqs = [
            Equation("EA", v["EA"] - v["L_u"] / v["q_lw"], "Hooke's law over the route: EA = L_u/q_lw"),
            Equation("dF_nwl", v["dF_nwl"] - self.pretension(v),
                     f"{SRC}: the loop under 0.5 F_nwl per side (= eq. (22)), reported, not added"),
            Equation("eps_c", v["eps_c"] - v["c_stretch"] * rs.constructional_stretch(v["n_rope"],
                                                                                      self._fibre_core()),
                     "constructional stretch: the rope makers' table by core and safety factor (rope_extension)"),
            Equation("dF_c", v["dF_c"] - v["eps_c"] * loop, SRC),
            Equation("dF_T", v["dF_T"] - rs.thermal_elongation(v["alpha_T"], v["dT_rope"], loop), SRC),
        ]
        for d, sign in DIRECTIONS.items():
            elastic_C, elastic_S = self.elastic(v, sign)
            loop_change = v[f"dF_CS_{d}"] + v["dF_c"] + v["dF_T"]
            eqs += [
                Equation(f"dF_C_{d}", v[f"dF_C_{d}"] - elastic_C, f"{SRC}, eq. (19) along the profile",
                         method=self.elastic_method, tolerance=self.elastic_tolerance),
                Equation(f"dF_S_{d}", v[f"dF_S_{d}"] - elastic_S, f"{SRC}, eq. (20) along the profile",
                         method=self.elastic_method, tolerance=self.elastic_tolerance),
                Equation(f"dF_CS_{d}", v[f"dF_CS_{d}"] - (v[f"dF_C_{d}"] + v[f"dF_S_{d}"]), "eq. (21)"),
                Equation(f"dF_{d}", v[f"dF_{d}"] - rs.take_up(loop_change, v["n_falls"]),
                         f"{SRC}: the tensioner's take-up through its falls"),
            ]
        return eqs


MODULUS = (
    Q("r_E0", "1", "rope modulus at zero tension relative to its modulus under load, E_0/E",
      **dom.domain(0.0, 1.0, "physics: a fraction of the modulus under load, above 0", low_open=True),
      guess=0.6, symbol="r_E0", **usual(0.3, 1.0, "stranded ropes stiffen as they bed in (Feyrer "
                                                                 "2015, §1.3); take it from the maker's curve")),
    Q("sigma_E", "Pa", "rope tensile stress over which the modulus rises toward E (1 - 1/e of the way)", "N/mm^2",
      **dom.domain(0.0, 1e10, "above 0, up to 10 GPa: beyond the strongest drawn steel wire (about 3 GPa)",
                   low_open=True), guess=1e8, symbol="σ_E", **usual(1e7, 5e8, "a fraction of the working stress "
                                                                         "(judgement); the maker's curve")),
)


@register(MODEL, "elongation", "asbuilt_stress")
class ElongationStressModulus(ElongationAsBuilt):
    """The stroke as built with a rope modulus that rises with the rope tensile stress σ = T/A_m:
    E_t(σ) = E (1 − (1 − r_E0) e^{−σ/σ_E}), E = EA/A_m, each side's strain ε(T(x)/A_m) integrated along it by
    Gauss–Legendre (:func:`ropemodel.papers.ropestretch.rope_strain`, ``side_strain_integral``).  Smooth for
    IPOPT; r_E0 = 1 is ``asbuilt``."""

    description = ("as built (tension profile, falls, constructional stretch, temperature) with a rope modulus "
                   "rising with the rope tensile stress")
    citations = ("krauze2025", "rope_extension", "feyrer2015")
    assumptions = (*ElongationAsBuilt.assumptions[:-1],
                   "The rope's tangent modulus rises from r_E0 E at zero stress toward E = EA/A_m over a stress "
                   "σ_E (an exponential form with the behaviour Feyrer describes, not his own fit).")
    quantities = (*ElongationAsBuilt.quantities, A_M, *MODULUS)
    elastic_method = "8-point Gauss-Legendre on each piece of the side (the segments, split at x_m)"
    elastic_tolerance = 1e-9          # against scipy's adaptive quadrature, tests/test_elongation_stress.py

    def _strain(self, v):
        E = v["EA"] / v["A_m"]
        return lambda T: rs.rope_strain(T / v["A_m"], E, v["r_E0"], v["sigma_E"])

    def elastic(self, v, sign):
        T_0, lengths, w_C, w_S, J = self._sides(v, sign)
        strain = self._strain(v)
        return (rs.side_strain_integral(T_0, w_C, lengths, J, v["x_m"], strain),
                rs.side_strain_integral(T_0, w_S, lengths, 0.0, v["x_m"], strain))

    def pretension(self, v):
        return 2.0 * v["L_u"] * self._strain(v)(0.5 * v["F_nwl"])
