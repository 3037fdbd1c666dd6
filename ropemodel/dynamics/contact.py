"""Compliance of the rope's contact with the drum, from the capstan model of Li et al. (effect ``drum_contact``).

``rigid`` (default): the rope at the drum's tangent points moves with the drum surface while it
sticks (the drum node of :mod:`ropemodel.dynamics.chain`).  ``capstan``: the rope wrapped on the
drum stretches in its slip zone, so the tangent point of the tight side creeps relative to the
drum surface; that creep is a spring in series between the drum and the tight span, with the
equivalent stiffness of Li, Liang, Dong, Qiu ("Analysis and experimental determination of
cable-driven stiffness", :mod:`ropemodel.papers.li_capstan`).

Mapping of the capstan model onto the winch drum
------------------------------------------------
===================  ==============================  =============================================
capstan (Li et al.)  winch drum                      why
===================  ==============================  =============================================
F_p (preload)        F_slack = min(F_C, F_S)         the tension of the rope in the drum's stick
                                                     (idle) arc, which the slip zone starts from
F_T (load)           F_tight − F_slack = |F_C − F_S| the tension rise the friction of the slip zone
                                                     carries up to the tight tangent point
μ                    mu_d                            rope-on-drum friction
EA                   L_u/q_lw                        the rope's axial stiffness (Krauze eq. (19));
                                                     with ``rope = "catalogue"`` q_lw = L_u/(E·C·d²)
                                                     is the catalogue's, so EA = E·C·d² there
R                    D/2                             drum radius (D: ``D_DRUM`` of the lining)
α1 (tight wrap)      alpha_d                         the slip zone may grow over the whole wrap
L (free length)      → 0 (not counted)               the free spans are the chain's elements; the
                                                     contact adds only the wrapped rope's part
K_1' (driven wheel)  → ∞ (not counted)               the span's far end is a free sheave or the
                                                     load: no torque, no slip zone there
===================  ==============================  =============================================

So the tight span's element next to the drum, stiffness k = EA/ℓ, becomes Li's eq. (24) with
those parts, k_eff = 1/(1/K_1 + 1/k + 1/∞), K_1 the slip zone's stiffness μEA(F_p + F_T)/(R F_T)
(eq. 12) while θ_s1 = ln(F_tight/F_slack)/μ < α_d, and μEA/(R(1 − e^{−μα_d})) (eq. 15) once it
fills the wrap.  The slip zone filling the wrap, θ_s1 = α_d, is F_tight = e^{μα_d} F_slack: the
Euler–Eytelwein onset of gross slip that the transient's slip events use, so the two models agree
on where sticking ends.  The slack span's tangent point lies in the stick arc at the preload (its
load is zero): Li's slack part K_2 (eq. 18) is infinite at zero load, so the slack span stays
rigidly attached.  Li's slack-side jump (eq. 21 is e^{μα2} times eq. 18 where θ_s2 = α2, see
MODELS.md §3) therefore never arises here: with this mapping the slack side has no slip zone
(and the continuous variant of :mod:`ropemodel.numerics.capstan_laws` would give the same results).

Linearisation (a limitation, stated): eq. (12) is a *tangent* stiffness that depends on the
forces.  The contact spring is linear, with K_1 taken at the steady state of the transient's
direction (the static model's F_C_d, F_S_d): the state a start-up settles into and a braking
starts from.  Li's law is a loading curve from a uniform preload; the creep kinematics of a
turning drum and the hysteresis of unloading are not modelled.  The contact adds no mass (the
wrapped rope's mass is already lumped on the drum node) and carries the rope's material damping
τ with the element (c = τ·k_eff).
"""

from __future__ import annotations

import math
from dataclasses import replace

from ropemodel.dynamics.chain import Chain
from ropemodel.errors import InputError
from ropemodel.papers import li_capstan as li


def capstan_contact_stiffness(F_tight, F_slack, mu, EA, R, alpha):
    """Stiffness of the tight side's slip zone on the drum, K_1 [N/m] (Li et al. eq. (12), (15)).

    F_tight [N] tension at the tangent point, F_slack [N] > 0 tension of the stick arc (preload);
    mu [-] > 0 rope-on-drum friction; EA [N] > 0 axial stiffness; R [m] > 0 drum radius;
    alpha [rad] > 0 wrap.  Load F_T = F_tight − F_slack.  Returns inf for F_T ≤ 0 (no slip zone:
    the tangent point is in the stick arc), eq. (12) while the slip angle eq. (6) is inside the
    wrap, eq. (15) once it reaches it (F_T ≥ F_p(e^{μα} − 1), eq. 13: gross slip).  Floats only.
    """
    F_T = F_tight - F_slack
    if F_T <= 0.0:
        return math.inf
    if F_T >= li.tight_switch_load(F_slack, mu, alpha):
        return float(li.tight_saturated_stiffness(mu, EA, R, alpha))
    return float(li.tight_slip_zone_stiffness(F_T, F_slack, mu, EA, R))


def rigid_contact(chain: Chain, values: dict, F_C: float, F_S: float) -> Chain:
    """The rope at the tangent points moves with the drum: the chain as built."""
    return chain


def capstan_contact(chain: Chain, values: dict, F_C: float, F_S: float) -> Chain:
    """The chain with Li's slip-zone stiffness in series with each span's element at the drum.

    F_C, F_S [N]: the forces at the drum's tangent points at which the contact is linearised
    (the static model's, of the transient's direction).  Elements: Li eq. (24) with K_0 = k, the
    element's EA/ℓ, and K_1' = ∞: k_eff = 1/(1/K_1 + 1/k).  Damping c = (c/k)·k_eff (same
    retardation time).  The contact stiffnesses are kept in ``chain.contact`` [N/m].
    """
    if chain.rigid:
        raise InputError("drum_contact = \"capstan\" needs an elastic rope: with rope_elasticity = \"rigid\" "
                         "the contact would be the only compliance; use \"spring\" or \"segments\"")
    if min(F_C, F_S) <= 0.0:
        raise InputError(f"drum_contact = \"capstan\" needs positive forces at the drum (F_C = {F_C:g} N, "
                         f"F_S = {F_S:g} N): the capstan model's preload F_p = min(F_C, F_S) must be > 0")
    mu, alpha, R = values["mu_d"], values["alpha_d"], values["D"] / 2.0
    EA = values["L_u"] / values["q_lw"]
    K = {"C": capstan_contact_stiffness(F_C, F_S, mu, EA, R, alpha),
         "S": capstan_contact_stiffness(F_S, F_C, mu, EA, R, alpha)}
    elements = []
    for a, b, k, c, sheave in chain.elements:
        side = "C" if b == 0 else "S" if a == 0 else None
        if side is not None and math.isfinite(K[side]):
            k_eff = float(li.series_stiffness(K[side], k, math.inf))     # eq. (24), K_1' = ∞
            c = c / k * k_eff
            k = k_eff
        elements.append((a, b, k, c, sheave))
    return replace(chain, elements=elements, contact={"K_C": K["C"], "K_S": K["S"], "F_p": min(F_C, F_S),
                                                       "F_T": abs(F_C - F_S)})


#: drum_contact variant → (chain, values, F_C, F_S) → chain
CONTACTS = {"rigid": rigid_contact, "capstan": capstan_contact}
