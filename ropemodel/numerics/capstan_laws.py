"""Stiffness laws of a capstan drive: the variants of the ``stiffness`` effect as functions.

Each law gives the tight and slack parts K_ti, K_sl [N/m] of eq. (23) at a load
F [N] and wraps α1, α2 [rad] (Li et al., eq. 24-26), and — for the crisp laws —
the switching functions whose sign changes mark the regimes.  They work on floats,
numpy arrays and CasADi symbols.

* ``li`` — eq. (26) in the tight + slack reading, *as published*, including the
  slack side's upward jump at θ_s2 = α2 (eq. 21 is e^{μα2} times eq. 18 there).
* ``continuous`` — the same, but the slack side's saturated stiffness is
  μEA/(R(e^{μα2} − 1)) (slip zone continued over the whole wrap), continuous at
  both slip switches.  The drop of K_sl to 0 at F_T = F_p (slack side goes slack)
  is physical and kept.
* ``smooth`` — the published law with each switch replaced by a logistic weight
  σ(s·z) of dimensionless switching functions z (see :func:`switching_functions`);
  ``sharpness`` s [-]: the transitions are about F_p/s wide in load.  For
  gradient-based optimisation; its error against ``li`` is measured in
  ``studies/capstan_smooth_cost.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Callable

import casadi as ca
import numpy as np

from ropemodel._math import expm1, fmax, if_else, log1p
from ropemodel.papers import li_capstan as li

#: regime numbers reported by the scenes (see :func:`regime_number`)
REGIMES = {
    1: "both slip zones inside their wraps, F_T < F_p (eq. 26, row 1)",
    2: "slack side saturated (θ_s2 ≥ α2), tight side not, F_T < F_p (row 2)",
    3: "both sides saturated, F_T < F_p (row 3)",
    4: "F_T ≥ F_p: slack side unloaded, tight side saturated (row 4)",
    5: "completed case: tight side saturated, slack side not, F_T < F_p (possible only if α1 < α2)",
    6: "completed case: F_T ≥ F_p, tight side not yet saturated (large wraps)",
}


def switching_functions(F, F_p, mu, alpha_1, alpha_2):
    """Dimensionless switching functions (tight, slack, unloaded); a side switches where its z ≥ 0.

    z_tight = ln(1 + F/F_p) − μα1 = μ(θ_s1 − α1)            (eq. 6, 13)
    z_slack = F/F_p − (1 − e^{−μα2}) = (F − F_p(1 − e^{−μα2}))/F_p   (eq. 16, 19; finite for F ≥ F_p)
    z_unload = F/F_p − 1                                      (eq. 26, row 4)

    F [N] load ≥ 0; F_p [N] preload > 0; mu [-] > 0; alpha_1, alpha_2 [rad] wraps.
    """
    x = F / F_p
    return log1p(x) - mu * alpha_1, x + expm1(-mu * alpha_2), x - 1.0


def regime_number(F, F_p, mu, alpha_1, alpha_2):
    """The regime (1-6, see :data:`REGIMES`) of the crisp laws at load F [N] and wraps α1, α2 [rad]."""
    zt, zs, zu = switching_functions(F, F_p, mu, alpha_1, alpha_2)
    tight, slack, unloaded = zt >= 0, zs >= 0, zu >= 0
    loaded = if_else(tight, if_else(slack, 3.0, 5.0), if_else(slack, 2.0, 1.0))
    return if_else(unloaded, if_else(tight, 4.0, 6.0), loaded)


def logistic(x):
    """σ(x) = 1/(1 + e^{−x}) as (1 + tanh(x/2))/2: finite with finite derivatives for every x."""
    if isinstance(x, (ca.SX, ca.MX, ca.DM)):
        return 0.5 * (1.0 + ca.tanh(0.5 * x))
    return 0.5 * (1.0 + np.tanh(0.5 * x))


def _crisp(continuous: bool):
    def parts(F, F_p, mu, EA, R, L, alpha_1, alpha_2, sharpness=None):
        return (li.tight_side_stiffness(F, F_p, mu, EA, R, L, alpha_1),
                li.slack_side_stiffness(F, F_p, mu, EA, R, L, alpha_2, continuous))
    return parts


def smooth_weights(F, F_p, mu, alpha_1, alpha_2, sharpness=30.0):
    """The smooth law's weights (tight, slack, unloaded) σ(s·z) of the switching functions z
    (:func:`switching_functions`); sharpness s [-]."""
    return tuple(logistic(sharpness * z) for z in switching_functions(F, F_p, mu, alpha_1, alpha_2))


def _smooth_parts(F, F_p, mu, EA, R, L, alpha_1, alpha_2, sharpness=30.0):
    wt, ws, wu = smooth_weights(F, F_p, mu, alpha_1, alpha_2, sharpness)
    k_ti = ((1 - wt) * li.tight_side_stiffness_slipping(F, F_p, mu, EA, R, L)
            + wt * li.tight_side_stiffness_saturated(mu, EA, R, L, alpha_1))
    k_sl = (1 - wu) * ((1 - ws) * li.slack_side_stiffness_slipping(F, F_p, mu, EA, R, L)
                       + ws * li.slack_side_stiffness_saturated(mu, EA, R, L, alpha_2))
    return k_ti, k_sl


def inverse_stiffness(x, mu, EA, R, L, alpha_1, alpha_2, weights, continuous=False):
    """1/K = 1/(K_ti + K_sl) [m/N] of eq. (23)-(26) at the load ratio x = F/F_p ∈ [0, 1] or beyond,
    finite (with finite derivatives) everywhere, also at F = 0 with L = 0 where K is infinite.

    ``weights`` (w_t, w_s, w_u) ∈ [0, 1]: how saturated the tight side is, how saturated the
    slack side, how unloaded (0 or 1 for the crisp laws: a regime; logistic for ``smooth``).
    K_ti = (1 − w_t)/c + w_t k_ts and K_sl = (1 − w_u)((1 − w_s) k_ss' + w_s k_ss), with
    c = 1/K_ti,slipping = (2Rx + μL(1 + x))/(μEA(1 + x)) (eq. 24 with 12, 22; finite at x = 0),
    k_ts, k_ss the saturated parts (eq. 24 with 15; eq. 25 with 21, or its continuous alternative)
    and k_ss' the slack slip-zone part (eq. 25 with 18), entering only as c·k_ss' =
    (1 + 2Lx/(2Rx/μ + L(1 − x)))(1 − x)/(1 + x) (0 for x ≥ 1).  Then 1/K = c/(c·K).
    mu [-], EA [N], R [m], L [m] ≥ 0, alpha_1, alpha_2 [rad] > 0; continuous: see :data:`LAWS`.
    """
    wt, ws, wu = weights
    a = 2.0 * R / mu
    c = (a * x + L * (1.0 + x)) / (EA * (1.0 + x))
    q = fmax(1.0 - x, 0.0)
    c_kss = (1.0 + 2.0 * L * x / fmax(a * x + L * q, 1e-250)) * q / (1.0 + x)
    k_ts = li.tight_side_stiffness_saturated(mu, EA, R, L, alpha_1)
    k_ss = li.slack_side_stiffness_saturated(mu, EA, R, L, alpha_2, continuous)
    cK = (1.0 - wt) + wt * k_ts * c + (1.0 - wu) * ((1.0 - ws) * c_kss + ws * k_ss * c)
    return c / fmax(cK, 1e-250)


@dataclass(frozen=True)
class StiffnessLaw:
    """A variant of the capstan's stiffness: ``parts(F, F_p, mu, EA, R, L, α1, α2, sharpness) -> (K_ti, K_sl)``."""

    name: str
    parts: Callable
    crisp: bool
    doc: str


LAWS = {
    "li": StiffnessLaw("li", _crisp(False), True,
                       "eq. (26), tight + slack reading, as published (slack side jumps up at θ_s2 = α2)"),
    "continuous": StiffnessLaw("continuous", _crisp(True), True,
                               "eq. (26) with the slack side's saturated stiffness continued from eq. (18): "
                               "continuous at both slip switches"),
    "smooth": StiffnessLaw("smooth", _smooth_parts, False,
                           "eq. (26) as published with logistic switches of sharpness s (for optimisation)"),
}
