"""The haulage rope of the winch model: effect ``rope``.

``given`` (default)  the paper's mode (Krauze et al. 2025): q_l [N/m] and q_lw [m/N] are
                     scene parameters; no equation is built.
``catalogue``        q_l, q_lw, the minimum breaking force F_min, the metallic area A_m and the
                     mass per metre m_l follow from the diameter ``d`` and the construction
                     factors (EN 12385-4): they become OUTPUTS, and the acausal core wires them
                     into the force and elongation equations.  The factors are the parameters
                     ``rope_K``, ``rope_W``, ``rope_C``.
``6x36-IWRC`` …      one variant per named construction of ``ropemodel/data/ropes.toml`` (see
                     :mod:`ropemodel.papers.en12385`): the same equations, and the class's factors as
                     outputs of their own (rope_K = 0.356, citing the catalogue), e.g.
                     ``[effects] rope = "6x36-IWRC"``.
``rope_grade`` (R_r) and ``rope_E`` are parameters of every catalogue variant.
"""

from __future__ import annotations

from typing import ClassVar

from ropemodel.papers import en12385 as ropes
from ropemodel.effects import domains as dom
from ropemodel.effects.base import Equation, Submodel, define_effect, register
from ropemodel.effects.winch import MODEL, Q
from ropemodel.quantity import Quantity

SRC = "EN 12385-4"

define_effect(MODEL, "rope", "given", "the rope: q_l, q_lw given (paper) or from a catalogue construction and d")


D_ROPE = Q("d", "m", "nominal rope diameter", "mm", guess=0.03, positive=True, warn_low=0.008, warn_high=0.06,
           usual_source="the diameters of ropemodel/data/ropes.toml (EN 12385-4 classes)",
           **dom.domain(1e-4, 0.5, "0.1 mm (a wire) to 500 mm: beyond the largest wire ropes made"))
F_MIN = Q("F_min", "N", "minimum breaking force of the rope", "kN", guess=1e6, positive=True, **dom.FORCE_POSITIVE)

FACTORS = (
    Q("rope_K", "1", "minimum breaking force factor K of the rope class", symbol="K", guess=0.356, **dom.FRACTION),
    Q("rope_W", "kg/m^3", "nominal length mass factor W of the rope class (catalogue kg/(100 m*mm^2) x 1e4)", "kg/m^3",
      symbol="W", guess=4090.0, **dom.domain(1000.0, 10000.0, "W = m/d^2: fibre-core ropes to denser than solid "
                                                              "steel (7850 pi/4 = 6165 kg/m^3); EN 12385-4 classes "
                                                              "3000-5000")),
    Q("rope_C", "1", "metallic cross-section factor C of the rope class", symbol="C", guess=0.46,
      **dom.domain(1e-2, 0.7854, "physics: steel fills at most a round wire's pi/4 of d^2; below 1 % no rope")),
)


@register(MODEL, "rope", "given")
class RopeGiven(Submodel):
    """The paper's rope: q_l and q_lw are given (Krauze et al. 2025, section 3)."""

    description = "rope weight q_l and unit elongation q_lw given"
    citations = ("krauze2025",)
    assumptions = ("The rope's weight q_l and unit elongation q_lw are given numbers, tied to no designated rope.",)
    missing = ("The rope itself: no construction, grade or standard, so no designation, no breaking force and no "
               "rope safety check; choose a catalogue construction (rope = \"6x36-IWRC\", ...).",)


@register(MODEL, "rope", "catalogue")
class RopeCatalogue(Submodel):
    """Rope properties from the diameter and the EN 12385-4 construction factors.

    F_min = K·d²·R_r, m_l = W·d², q_l = g·W·d², A_m = C·d², q_lw = L_u/(E·C·d²)
    (see :mod:`ropemodel.papers.en12385`).  Not in Krauze et al. (2025), who give q_l and q_lw;
    "needed by a real sizing tool" (docs/physics.md §1).
    """

    description = "q_l, q_lw, F_min, A_m, m_l from d and the construction (EN 12385-4)"
    citations = ("krauze2025", "en12385_4")
    #: the named construction of the catalogue (None: factors given as parameters)
    construction: ClassVar[ropes.Construction | None] = None
    assumptions = (
        "EA = E C d² from the catalogue's metallic-area factor C and the modulus E the scene gives: the rope's "
        "stiffness is not measured on the installed rope.",
        "F_min = K d² R_r is the catalogue's minimum breaking force of the class, not the rope's test certificate.",
        "The rope's weight is the catalogue's nominal length mass, W d².",
    )
    missing = ("A measured EA (or q_lw) of the installed rope: the elongation and the stroke rest on the "
               "catalogue and the modulus E given.",
               "The rope's test certificate: its actual breaking force, to confirm F_min.")
    quantities: ClassVar[tuple[Quantity, ...]] = (
        D_ROPE,
        F_MIN,
        *FACTORS,
        Q("rope_grade", "Pa", "rope grade R_r (EN 12385-4: 1570-2160 N/mm^2)", "N/mm^2", **dom.STRENGTH,
          symbol="R_r", warn_low=1570e6, warn_high=2160e6, usual_source="EN 12385-4 rope grades", guess=1770e6),
        Q("rope_E", "Pa", "modulus of the rope referred to its metallic area", "kN/mm^2", **dom.MODULUS,
          symbol="E", warn_low=5e10, warn_high=2.1e11,
          usual_source="rope makers quote 80-120 GPa on the metallic area; steel wire itself is 210 GPa", guess=1e11),
        Q("A_m", "m^2", "metallic cross-section of the rope", "mm^2", equation=f"{SRC}: metallic cross-section"),
        Q("m_l", "kg/m", "mass of the rope per metre", "kg/m", equation=f"{SRC}: nominal length mass"),
    )

    def equations(self, v):
        K, W, C = v["rope_K"], v["rope_W"], v["rope_C"]
        d = v["d"]
        return [
            Equation("F_min", v["F_min"] - ropes.minimum_breaking_force(K, d, v["rope_grade"]),
                     f"{SRC}: minimum breaking force"),
            Equation("m_l", v["m_l"] - ropes.rope_mass_per_metre(W, d), f"{SRC}: nominal length mass"),
            Equation("q_l", v["q_l"] - ropes.rope_weight_per_metre(W, d), f"{SRC}: nominal length mass times g"),
            Equation("A_m", v["A_m"] - ropes.metallic_area(C, d), f"{SRC}: metallic cross-section"),
            Equation("q_lw", v["q_lw"] - ropes.unit_elongation(v["L_u"], v["rope_E"], C, d),
                     "Hooke's law over the route with EA = E C d² (not in the paper)"),
        ]


def _named(c: ropes.Construction) -> type[Submodel]:
    """The catalogue rope with the factors of construction ``c``: each factor an equation (K = 0.356) citing
    the catalogue, so that formulas show ``F_min = K d² R_r`` and the value of K with its source."""

    class NamedConstruction(RopeCatalogue):
        __doc__ = (f"{c.description}: the catalogue rope with K = {c.K:g}, W = {c.W:g} kg/m^3, "
                   f"C = {c.C:g} ({c.source}).")
        description = f"{c.description} (K, W, C of {c.source})"
        construction = c

        def equations(self, v):
            factors = [Equation(f"rope_{k}", v[f"rope_{k}"] - value, f"{c.source}, ropemodel/data/ropes.toml")
                       for k, value in (("K", c.K), ("W", c.W), ("C", c.C))]
            return factors + super().equations(v)

    NamedConstruction.__name__ = NamedConstruction.__qualname__ = f"Rope_{c.name.replace('-', '_')}"
    return NamedConstruction


for _c in ropes.constructions().values():
    register(MODEL, "rope", _c.name)(_named(_c))
