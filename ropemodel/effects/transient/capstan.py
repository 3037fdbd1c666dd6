"""Compliance of the rope's contact with the drum from the capstan model of Li et al. (``drum_contact = "capstan"``).

The rope wrapped on the drum stretches in its slip zone, so the tangent point of the tight side creeps
relative to the drum surface; that creep is a spring in series between the drum and the tight span,
with the equivalent stiffness of Li, Liang, Dong, Qiu ("Analysis and experimental determination of
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
μ                    mu_d                            rope-on-drum friction (of the lining)
EA                   L_u/q_lw                        the rope's axial stiffness (Krauze eq. (19));
                                                     with ``rope = "catalogue"`` q_lw = L_u/(E·C·d²)
                                                     is the catalogue's, so EA = E·C·d² there
R                    D/2                             drum radius (D: ``D_DRUM``)
α1 (tight wrap)      alpha_d                         the slip zone may grow over the whole wrap
L (free length)      → 0 (not counted)               the free spans are the chain's elements; the
                                                     contact adds only the wrapped rope's part
K_1' (driven wheel)  → ∞ (not counted)               the span's far end is a free sheave or the
                                                     load: no torque, no slip zone there
===================  ==============================  =============================================

So the tight span's element next to the drum, stiffness k = EA/ℓ, becomes Li's eq. (24) with those
parts, k_eff = 1/(1/K_1 + 1/k + 1/∞), K_1 the slip zone's stiffness μEA(F_p + F_T)/(R F_T) (eq. 12)
while θ_s1 = ln(F_tight/F_slack)/μ < α_d, and μEA/(R(1 − e^{−μα_d})) (eq. 15) once it fills the wrap.
The slip zone filling the wrap, θ_s1 = α_d, is F_tight = e^{μα_d} F_slack: the Euler–Eytelwein onset
of gross slip that the transient's slip events use, so the two models agree on where sticking ends.
The slack span's tangent point lies in the stick arc at the preload (its load is zero): Li's slack
part K_2 (eq. 18) is infinite at zero load, so the slack span stays rigidly attached.

Linearisation (a limitation, stated): eq. (12) is a *tangent* stiffness that depends on the forces.
The contact spring is linear, with K_1 taken at the steady state of the transient's direction (the
static model's F_C_d, F_S_d): the state a start-up settles into and a braking starts from.  Li's law
is a loading curve from a uniform preload; the creep kinematics of a turning drum and the hysteresis
of unloading are not modelled.  The contact adds no mass and carries the rope's material damping τ
with the element (c = τ·k_eff).  Needs a friction lining (μ, α) and an elastic rope.
"""

from __future__ import annotations

import math

from ropemodel.effects.base import effects_of, register
from ropemodel.effects.transient.base import MODEL
from ropemodel.effects.transient.contact import N_SLIP_DYNAMIC, DrumContact
from ropemodel.effects.winch import D_DRUM
from ropemodel.errors import InputError
from ropemodel.papers import li_capstan as li


def contact_branch(F_tight: float, F_slack: float, mu: float, alpha: float) -> str:
    """Which of Li's laws holds: ``"stick"`` (F_T ≤ 0: no slip zone), ``"slip_zone"`` (eq. 12) or
    ``"saturated"`` (the slip zone fills the wrap, eq. 13 and 15).  Floats."""
    F_T = F_tight - F_slack
    if F_T <= 0.0:
        return "stick"
    return "saturated" if F_T >= li.tight_switch_load(F_slack, mu, alpha) else "slip_zone"


def contact_stiffness(branch: str, F_tight, F_slack, mu, EA, R, alpha):
    """K_1 [N/m] of ``branch`` (Li et al. eq. (12) or (15)); inf in the stick arc.  Floats or symbols."""
    if branch == "stick":
        return math.inf
    if branch == "saturated":
        return li.tight_saturated_stiffness(mu, EA, R, alpha)
    return li.tight_slip_zone_stiffness(F_tight - F_slack, F_slack, mu, EA, R)


def capstan_contact_stiffness(F_tight, F_slack, mu, EA, R, alpha):
    """Stiffness of the tight side's slip zone on the drum, K_1 [N/m] (Li et al. eq. (12), (15)).

    F_tight [N] tension at the tangent point, F_slack [N] > 0 tension of the stick arc (preload);
    mu [-] > 0 rope-on-drum friction; EA [N] > 0 axial stiffness; R [m] > 0 drum radius; alpha [rad] > 0
    wrap.  inf for F_T ≤ 0 (the tangent point is in the stick arc).  Floats only.
    """
    return float(contact_stiffness(contact_branch(F_tight, F_slack, mu, alpha), F_tight, F_slack, mu, EA, R, alpha))


@register(MODEL, "drum_contact", "capstan")
class CapstanDrumContact(DrumContact):
    """Contact compliance of the wrapped rope from the capstan model (Li et al., eq. (12), (15), (24))."""

    description = "slip-zone compliance of the rope on the drum in series with the tight span (Li et al.)"
    citations = ("li_capstan",)
    gathered = False
    quantities = (D_DRUM, N_SLIP_DYNAMIC)

    def rules(self, values):
        """A friction drum and an elastic rope: what the contact's slip zone is made of (the other effects'
        variants, through the registry: a lining with friction, a rope that stretches)."""
        lining, rope = (self._able(effect)[0] for effect in ("lining", "rope_elasticity"))
        return [] if lining and rope else [self.needs]

    def _able(self, effect: str) -> tuple[bool, list[str]]:
        """(the scene's variant of ``effect`` can carry a slip zone, the variants that can)."""
        spec, attribute = effects_of(MODEL)[effect], {"lining": "friction", "rope_elasticity": "elastic"}[effect]
        able = [v for v, cls in spec.variants.items() if getattr(cls, attribute, True)]
        return self.effects.get(effect, spec.default) in able, able

    @property
    def needs(self) -> str:
        linings, ropes = (" or ".join(f"\"{v}\"" for v in self._able(e)[1]) for e in ("lining", "rope_elasticity"))
        return (f"drum_contact = {self.variant!r} needs a friction drum (lining = {linings}, with its mu_d and "
                f"alpha_d) and an elastic rope (rope_elasticity = {ropes}); this scene has lining = "
                f"{self.effects.get('lining')!r}, rope_elasticity = {self.effects.get('rope_elasticity')!r}: choose "
                f"them, or drum_contact = \"rigid\"")

    def bind(self, setup):
        super().bind(setup)
        chain, nums = setup.chain, setup.numbers
        if self.ratio is None or chain.rigid:
            raise InputError(self.needs)
        d = setup.travel
        F_C, F_S = nums[f"F_C_{d}"], nums[f"F_S_{d}"]
        if min(F_C, F_S) <= 0.0:
            raise InputError(f"drum_contact = {self.variant!r} needs positive forces at the drum (F_C = {F_C:g} N, "
                             f"F_S = {F_S:g} N): the capstan model's preload F_p = min(F_C, F_S) must be > 0")
        setup.chain = self.contact(chain, setup.values, nums, d)

    def contact(self, chain, values, nums, d):
        """The chain with Li's slip-zone stiffness in series with each span's element at the drum.

        Elements: Li eq. (24) with K_0 = k, the element's EA/ℓ, and K_1' = ∞: k_eff = 1/(1/K_1 + 1/k);
        damping c = (c/k)·k_eff (the same retardation time).  The branch of Li's law is chosen at the
        scene's numbers, its formula evaluated with the values (which may be symbols).
        """
        F = {"C": values[f"F_C_{d}"], "S": values[f"F_S_{d}"]}
        Fn = {"C": nums[f"F_C_{d}"], "S": nums[f"F_S_{d}"]}
        mu, alpha, R, EA = values["mu_d"], values["alpha_d"], values["D"] / 2.0, values["L_u"] / values["q_lw"]
        K = {}
        for side, other in (("C", "S"), ("S", "C")):
            branch = contact_branch(Fn[side], Fn[other], nums["mu_d"], nums["alpha_d"])
            K[side] = contact_stiffness(branch, F[side], F[other], mu, EA, R, alpha)
        elements = []
        for el in chain.elements:
            side = "C" if el.b == 0 else "S" if el.a == 0 else None
            if side is not None and not (isinstance(K[side], float) and math.isinf(K[side])):
                k_eff = li.series_stiffness(K[side], el.k, math.inf)         # eq. (24), K_1' = ∞
                el = el._replace(k=k_eff, c=el.c / el.k * k_eff)
            elements.append(el)
        chain.elements = elements
        chain.contact = {"K_C": K["C"], "K_S": K["S"], "F_p": min(Fn.values()), "F_T": abs(Fn["C"] - Fn["S"])}
        return chain

    def summary(self, run):
        out = super().summary(run)
        out["drum_contact"] = {k: (float(v) if math.isfinite(float(v)) else None)
                               for k, v in self.setup.chain.contact.items()}
        return out

    def report(self, s):
        K = s["drum_contact"]
        sides = ", ".join(f"{side} side {K[f'K_{side}'] / 1e6:.4g} MN/m" for side in ("C", "S")
                          if K[f"K_{side}"] is not None)
        return super().report(s) + [f"  drum contact (capstan, Li et al. eq. 12 at F_p {K['F_p'] / 1e3:.2f} kN, F_T "
                                    f"{K['F_T'] / 1e3:.2f} kN): {sides or 'rigid on both sides'}"]
