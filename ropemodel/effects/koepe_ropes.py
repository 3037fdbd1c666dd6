"""The ropes of a Koepe hoist: tail (balance) ropes (effect ``tail_ropes``) and head ropes (``head_ropes``).

``tail_ropes``
    ``round`` (default)  n_tail round ropes of q_tail [kg/m] each hang from the bottoms of the conveyances in a
                         free loop; h_loop [m] is the rope per side below a conveyance's lower position, half the
                         loop's turn included (docs/physics.md §7).  Output ``F_tail``, the largest static force
                         in one tail rope: at its top, hanging from a conveyance at its upper position.
    ``none``             no tail ropes.
``head_ropes``
    ``given`` (default)  q_head [kg/m] given (and, for the design checks, d_head and F_min_head).
    ``6x36-IWRC`` …      one variant per construction of ``ropemodel/data/ropes.toml``: q_head = W d_head² and
                         F_min_head = K d_head² R_r (EN 12385-4, :mod:`ropemodel.papers.en12385`) become outputs.
"""

from __future__ import annotations

from ropemodel.effects import domains as dom
from ropemodel.effects.base import Equation, Submodel, register
from ropemodel.effects.koepe import (COUNT, H, MODEL, PRACTICE, ROPE_MASS, SPAN, Q, Q_HEAD, TailRopes, positive, usual,
                                     whole_ropes)
from ropemodel.papers import en12385 as ropes
from ropemodel.papers.route import G_N

SRC = "EN 12385-4"

N_TAIL = Q("n_tail", "1", "number of tail (balance) ropes (a whole number)", guess=2.0, **COUNT,
           symbol="n_t", **usual(1.0, 10.0, "friction hoists hang 1 to 10 tail ropes (judgement)"))
Q_TAIL = Q("q_tail", "kg/m", "mass per metre of one tail rope", "kg/m", guess=15.5, symbol="q_t",
           **positive(1e-3, 1e3, ROPE_MASS),
           **usual(0.5, 60.0, "round and flat balance ropes (judgement, around the issue's 15.5 kg/m)"))
H_LOOP = Q("h_loop", "m", "tail rope per side below a conveyance's lower position, half the loop's turn included: "
           "(L_tail − H)/2", "m", **SPAN, guess=5.0, default=0.0,
           default_note="not given: 0, the largest ratio T_1/T_2 (safe for slip); it understates each tension by "
                        "g n_tail q_tail h_loop (give the real loop for rope safety)")
F_TAIL = Q("F_tail", "N", "largest static force in one tail rope, at its top with its conveyance at the upper "
           "position", "kN", equation=f"{PRACTICE}: g q_tail (H + h_loop)")
D_HEAD = Q("d_head", "m", "nominal diameter of a head rope", "mm", guess=0.046,
           **positive(0.0, 0.5, "500 mm: beyond the largest wire ropes made"),
           **usual(0.01, 0.09, "hoisting ropes of 10 to 90 mm (judgement)"))
F_MIN_HEAD = Q("F_min_head", "N", "minimum breaking force of one head rope", "kN", guess=1.3e6,
               **positive(1e-3, 1e9, dom.FORCE_POSITIVE["range_source"]),
               **usual(5e4, 1e7, "EN 12385-4 ropes of 10 to 90 mm"))
GRADE = Q("rope_grade", "Pa", "grade R_r of the head ropes (EN 12385-4: 1570-2160 N/mm^2)", "N/mm^2", guess=1770e6,
          **positive(1e6, 1e10, dom.STRENGTH["range_source"]), **usual(1570e6, 2160e6, "EN 12385-4 rope grades"))


@register(MODEL, "tail_ropes", "round")
class RoundTailRopes(TailRopes):
    """Round tail ropes in a free loop: each side carries its ropes from the conveyance to the loop's bottom,
    L_t = H + h_loop − y (:func:`ropemodel.papers.koepe.tail_rope_length`; docs/physics.md §7)."""

    description = "n_tail tail ropes of q_tail each in a free loop below the conveyances"
    citations = ("delavergne2003",)
    quantities = (N_TAIL, Q_TAIL, H_LOOP, F_TAIL, H)

    def terms(self, v):
        """(n_tail, q_tail, h_loop) for :func:`ropemodel.papers.koepe.side_tensions`."""
        return v["n_tail"], v["q_tail"], v["h_loop"]

    def equations(self, v):
        return [Equation("F_tail", v["F_tail"] - G_N * v["q_tail"] * (v["H"] + v["h_loop"]),
                         f"{PRACTICE}: the tail rope's weight below its upper conveyance, g q_tail (H + h_loop)")]

    def safety_equations(self, v) -> list[Equation]:
        """The tail ropes' safety check (``checks = "design"``): F_min_tail/(n_safety_tail F_tail) − 1 >= 0,
        written multiplied out (linear in the margin)."""
        return [Equation("tail_safety_margin",
                         v["n_safety_tail"] * v["F_tail"] * (v["tail_safety_margin"] + 1.0) - v["F_min_tail"],
                         "rope safety of a tail rope, F_min_tail/F_tail >= n_safety_tail")]

    def rules(self, values):
        return whole_ropes(values, "n_tail")


@register(MODEL, "tail_ropes", "none")
class NoTailRopes(TailRopes):
    """No tail ropes: each side carries its conveyance and head ropes only."""

    description = "no tail ropes"

    def terms(self, v):
        """No tail rope: (0, 0, 0)."""
        return 0.0, 0.0, 0.0

    def safety_equations(self, v) -> list[Equation]:
        """No tail rope to check."""
        return []


@register(MODEL, "head_ropes", "given")
class HeadRopesGiven(Submodel):
    """Head ropes given by their mass per metre q_head (and, for the checks, d_head and F_min_head)."""

    description = "head ropes: q_head given (d_head, F_min_head for the checks)"


def _construction(c: ropes.Construction) -> type[Submodel]:
    """The head ropes of construction ``c``: q_head and F_min_head from d_head and the rope grade."""

    class HeadRopes(Submodel):
        __doc__ = (f"Head ropes of {c.description}: q_head = W d_head², F_min_head = K d_head² R_r with "
                   f"W = {c.W:g} kg/m^3, K = {c.K:g} ({c.source}).")
        description = f"head ropes of {c.description}: q_head, F_min_head from d_head (K, W of {c.source})"
        citations = ("en12385_4",)
        quantities = (D_HEAD, F_MIN_HEAD, GRADE, Q_HEAD)

        def equations(self, v):
            d = v["d_head"]
            return [Equation("q_head", v["q_head"] - ropes.rope_mass_per_metre(c.W, d), f"{SRC}: m = W d^2"),
                    Equation("F_min_head", v["F_min_head"] - ropes.minimum_breaking_force(c.K, d, v["rope_grade"]),
                             f"{SRC}: F_min = K d^2 R_r")]

    HeadRopes.__name__ = HeadRopes.__qualname__ = f"HeadRopes_{c.name.replace('-', '_')}"
    return HeadRopes


for _c in ropes.constructions().values():
    register(MODEL, "head_ropes", _c.name)(_construction(_c))
