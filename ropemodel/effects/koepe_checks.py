"""Design checks of the Koepe hoist (effect ``checks``): each a margin, >= 0 passes.

``none``    (default) no check is built.
``design``  the margins, each at the worst static state (:mod:`ropemodel.effects.koepe`):

    head_safety_margin = n_head F_min_head/(n_safety_head T_max) − 1    rope safety of the head ropes
    tail_safety_margin = F_min_tail/(n_safety_tail F_tail) − 1          of the tail ropes (when there are any)
    wheel_margin       = D/(D_ratio_min d_head) − 1                      wheel to head-rope diameter, D/d
    wheel_size_margin  = D − D_min                            [m]        least wheel diameter
    pull_margin        = T_rated/T_max − 1                               the machine's rated static rope pull
    difference_margin  = dT_rated/dT_max − 1                             its rated static tension difference
    antislip_margin    = sigma_static/sigma_static_min − 1               the static anti-slip factor

A safety factor multiplies the static force (the rules' "static load"): the head ropes' largest static
tension T_max shared by the n_head ropes, the tail rope's own weight below its upper conveyance.  The
factors have no default: a rule set gives them (``[rules]``, :mod:`ropemodel.effects.koepe_rules`), or the
scene.  Ratings not given are unlimited (no check).  Ratio checks are written multiplied out, so the core
can also solve them backwards (``--given head_safety_margin=0 --find m_payload``).
"""

from __future__ import annotations

import math
from typing import cast

from ropemodel.effects import domains as dom
from ropemodel.effects.base import Equation, Submodel, register
from ropemodel.effects.koepe import WHEEL, D_WHEEL, DT_MAX, MODEL, Q, T_MAX, TailRopes, partner, positive
from ropemodel.effects.koepe_ropes import D_HEAD, F_MIN_HEAD

FACTOR = dom.FACTOR
SAFETY = "rope safety check: breaking force over the static force (not in the sources of §7)"

QUANTITIES = (
    D_WHEEL, D_HEAD, F_MIN_HEAD, T_MAX, DT_MAX,
    Q("n_safety_head", "1", "required safety factor of a head rope: F_min_head over its static force", guess=6.0,
      **FACTOR),
    Q("F_min_tail", "N", "minimum breaking force of one tail rope", "kN", guess=2e6,
      **positive(1e-3, 1e9, dom.FORCE_POSITIVE["range_source"])),
    Q("n_safety_tail", "1", "required safety factor of a tail rope: F_min_tail over its static force", guess=7.0,
      **FACTOR),
    Q("D_ratio_min", "1", "least ratio of the wheel's diameter to the head ropes', D/d", guess=80.0, **FACTOR),
    Q("D_min", "m", "least diameter of the wheel", "m",
      **dom.domain(0.0, 100.0, f"0 (no least) to 100 m: {WHEEL}"), guess=1.2, default=0.0,
      default_note="not given: no least wheel diameter"),
    Q("T_rated", "N", "the machine's rated static rope pull (the largest T_max it is built for)", "kN", guess=1e6,
      **positive(0.0, 1e9, dom.FORCE["range_source"]), unlimited=True, default=math.inf,
      default_note="not given: not checked"),
    Q("dT_rated", "N", "the machine's rated static tension difference (the largest dT_max it is built for)", "kN",
      symbol="ΔT_rated", guess=3e5, **positive(0.0, 1e9, dom.FORCE["range_source"]), unlimited=True, default=math.inf,
      default_note="not given: not checked"),
    Q("sigma_static_min", "1", "least static anti-slip factor required", guess=1.75,
      **dom.domain(1.0, 100.0, "at least 1 (physics: below 1 the ropes slip at rest); 100 bounds any rule"),
      default=1.0, default_note="not given: 1, the onset of slip (rules and practice ask more)"),
    Q("head_safety_margin", "1", "margin of the head ropes' safety n_head F_min_head/(n_safety_head T_max) − 1 "
      "(>= 0 passes)", symbol="m_safety,head", equation=SAFETY),
    Q("tail_safety_margin", "1", "margin of the tail ropes' safety F_min_tail/(n_safety_tail F_tail) − 1 "
      "(>= 0 passes)", symbol="m_safety,tail", equation=SAFETY),
    Q("wheel_margin", "1", "margin of the wheel D/(D_ratio_min d_head) − 1 (>= 0 passes)",
      symbol="m_wheel", equation="D/d check with the rule's D_ratio_min"),
    Q("wheel_size_margin", "m", "margin of the wheel's diameter D − D_min (>= 0 passes)", "mm",
      symbol="m_D", equation="least wheel diameter check"),
    Q("pull_margin", "1", "margin of the rated rope pull T_rated/T_max − 1 (>= 0 passes)",
      symbol="m_pull", equation="the machine's rating against T_max", unlimited=True, unlimited_text="not checked"),
    Q("difference_margin", "1", "margin of the rated tension difference dT_rated/dT_max − 1 (>= 0 passes)",
      symbol="m_ΔT", equation="the machine's rating against dT_max", unlimited=True, unlimited_text="not checked"),
    Q("antislip_margin", "1", "margin of the static anti-slip factor sigma_static/sigma_static_min − 1 (>= 0 "
      "passes)", symbol="m_σ", equation="the anti-slip factor against the least required (antislip_cn)"),
)


@register(MODEL, "checks", "none")
class NoChecks(Submodel):
    """Design checks off."""

    description = "no design checks"


@register(MODEL, "checks", "design")
class DesignChecks(Submodel):
    """The margins of the module docstring, each >= 0 to pass."""

    description = "design checks: rope safety, D/d, least wheel, ratings, static anti-slip factor"
    citations = ("delavergne2003", "antislip_cn")
    quantities = QUANTITIES

    def equations(self, v):
        return [
            Equation("head_safety_margin",
                     v["n_safety_head"] * v["T_max"] * (v["head_safety_margin"] + 1.0) - v["n_head"] * v["F_min_head"],
                     "rope safety of a head rope, n_head F_min_head/T_max >= n_safety_head"),
            *cast(TailRopes, partner(self, "tail_ropes")).safety_equations(v),
            Equation("wheel_margin", v["D_ratio_min"] * v["d_head"] * (v["wheel_margin"] + 1.0) - v["D"],
                     "D/d check, D >= D_ratio_min d_head"),
            Equation("wheel_size_margin", v["wheel_size_margin"] - (v["D"] - v["D_min"]), "least wheel, D >= D_min"),
            Equation("pull_margin", v["T_max"] * (v["pull_margin"] + 1.0) - v["T_rated"], "rating, T_max <= T_rated"),
            Equation("difference_margin", v["dT_max"] * (v["difference_margin"] + 1.0) - v["dT_rated"],
                     "rating, dT_max <= dT_rated"),
            Equation("antislip_margin", v["sigma_static_min"] * (v["antislip_margin"] + 1.0) - v["sigma_static"],
                     "anti-slip factor, sigma_static >= sigma_static_min"),
        ]

    def where(self, values):
        hoist, lining = partner(self, "hoist").where(values), partner(self, "lining").where(values)
        out = {"head_safety_margin": hoist["T_max"], "pull_margin": hoist["T_max"],
               "difference_margin": hoist["dT_max"], "antislip_margin": lining["sigma_static"]}
        if "tail_safety_margin" in values:
            out["tail_safety_margin"] = "a tail rope hanging from a conveyance at its upper position"
        return out
