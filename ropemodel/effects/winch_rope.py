"""The haulage rope of the winch model: effect ``rope``.

``given`` (default)  the paper's mode (Krauze et al. 2025): q_l [N/m] and q_lw [m/N] are
                     scene parameters; no equation is built.
``catalogue``        q_l, q_lw, the minimum breaking force F_min, the metallic area A_m and the
                     mass per metre m_l follow from the diameter ``d`` and the construction
                     factors (EN 12385-4): they become OUTPUTS, and the acausal core wires them
                     into the force and elongation equations.  The factors are the parameters
                     ``rope_K``, ``rope_W``, ``rope_C``.
``6x36-IWRC`` …      one variant per named construction of ``ropemodel/data/ropes.toml`` (see
                     :mod:`ropemodel.papers.en12385`): the same equations with the class's factors as
                     constants, e.g. ``[effects] rope = "6x36-IWRC"``.
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
    Q("rope_K", "1", "minimum breaking force factor K of the rope class", guess=0.356, **dom.FRACTION),
    Q("rope_W", "kg/m^3", "nominal length mass factor W of the rope class (catalogue kg/(100 m*mm^2) x 1e4)", "kg/m^3",
      guess=4090.0, **dom.domain(1000.0, 10000.0, "W = m/d^2: fibre-core ropes to denser than solid steel "
                                                  "(7850 pi/4 = 6165 kg/m^3); EN 12385-4 classes 3000-5000")),
    Q("rope_C", "1", "metallic cross-section factor C of the rope class", guess=0.46,
      **dom.domain(1e-2, 0.7854, "physics: steel fills at most a round wire's pi/4 of d^2; below 1 % no rope")),
)


@register(MODEL, "rope", "given")
class RopeGiven(Submodel):
    """The paper's rope: q_l and q_lw are given (Krauze et al. 2025, section 3)."""

    description = "rope weight q_l and unit elongation q_lw given"
    citations = ("krauze2025",)


@register(MODEL, "rope", "catalogue")
class RopeCatalogue(Submodel):
    """Rope properties from the diameter and the EN 12385-4 construction factors.

    F_min = K·d²·R_r, m_l = W·d², q_l = g·W·d², A_m = C·d², q_lw = L_u/(E·C·d²)
    (see :mod:`ropemodel.papers.en12385`).  Not in Krauze et al. (2025), who give q_l and q_lw;
    "needed by a real sizing tool" (docs/physics.md §1).
    """

    description = "q_l, q_lw, F_min, A_m, m_l from d and the construction (EN 12385-4)"
    citations = ("krauze2025", "en12385_4")
    quantities: ClassVar[tuple[Quantity, ...]] = (
        D_ROPE,
        F_MIN,
        *FACTORS,
        Q("rope_grade", "Pa", "rope grade R_r (EN 12385-4: 1570-2160 N/mm^2)", "N/mm^2", **dom.STRENGTH,
          warn_low=1570e6, warn_high=2160e6, usual_source="EN 12385-4 rope grades", guess=1770e6),
        Q("rope_E", "Pa", "modulus of the rope referred to its metallic area", "kN/mm^2", **dom.MODULUS,
          warn_low=5e10, warn_high=2.1e11, usual_source="rope makers quote 80-120 GPa on the metallic area; "
          "steel wire itself is 210 GPa", guess=1e11),
        Q("A_m", "m^2", "metallic cross-section of the rope", "mm^2", equation=f"{SRC}: A = C d^2"),
        Q("m_l", "kg/m", "mass of the rope per metre", "kg/m", equation=f"{SRC}: m = W d^2"),
    )

    def _factors(self, v):
        return v["rope_K"], v["rope_W"], v["rope_C"]

    def equations(self, v):
        K, W, C = self._factors(v)
        d = v["d"]
        return [
            Equation("F_min", v["F_min"] - ropes.minimum_breaking_force(K, d, v["rope_grade"]),
                     f"{SRC}: F_min = K d^2 R_r", formula="F_min = K d² R_r"),
            Equation("m_l", v["m_l"] - ropes.rope_mass_per_metre(W, d), f"{SRC}: m = W d^2", formula="m_l = W d²"),
            Equation("q_l", v["q_l"] - ropes.rope_weight_per_metre(W, d), "q_l = g W d^2", formula="q_l = g W d²"),
            Equation("A_m", v["A_m"] - ropes.metallic_area(C, d), f"{SRC}: A = C d^2", formula="A_m = C d²"),
            Equation("q_lw", v["q_lw"] - ropes.unit_elongation(v["L_u"], v["rope_E"], C, d),
                     "q_lw = L_u / (E C d^2)", formula="q_lw = L_u / (E C d²)"),
        ]


def _named(c: ropes.Construction) -> type[Submodel]:
    """The catalogue rope with the factors of construction ``c`` as constants."""

    class NamedConstruction(RopeCatalogue):
        __doc__ = (f"{c.description}: the catalogue rope with K = {c.K:g}, W = {c.W:g} kg/m^3, "
                   f"C = {c.C:g} ({c.source}).")
        description = f"{c.description} (K, W, C of {c.source})"
        quantities = tuple(q for q in RopeCatalogue.quantities if q.name not in ("rope_K", "rope_W", "rope_C"))

        def _factors(self, v):
            return c.K, c.W, c.C

    NamedConstruction.__name__ = NamedConstruction.__qualname__ = f"Rope_{c.name.replace('-', '_')}"
    return NamedConstruction


for _c in ropes.constructions().values():
    register(MODEL, "rope", _c.name)(_named(_c))
