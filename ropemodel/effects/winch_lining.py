"""Traction of the winch drum (``model = "winch"``, effect ``lining``): does the rope slip?

Per direction d in (up, down) the drum must carry the winding-rope force F_C_d
with the unwinding-rope force F_S_d on its slack side:

    F_C_d <= F_S_d · traction_d / n_slip,
    slip_margin_d = F_S_d · traction_d / (n_slip · F_C_d) − 1   (>= 0: no slip)

Variants
--------
``none``   (default) no traction equations.
``rigid``  traction_d = e^{μ_d α_d} (Euler–Eytelwein).
``voigt``  (isotropic lining data ``Q`` [1/N], ``lambda`` [s], drum diameter ``D`` [m]
           and haulage speed ``v_pj`` [m/s]) the drum is lined with a Voigt (visco-elastic) lining, Hajduk (1992):
           traction_d = s(μ_d α_d, q = Q·F_S_d, k = λ·ω) from the exact implicit
           solution ln s + q s (1 − e^{−α_d/k}) = μ_d α_d, with the drum's angular
           speed ω = 2 v_pj / D.  The ratio depends on F_S_d itself, so the least
           pretension for no slip is an implicit problem for the core.

In a transient (:mod:`ropemodel.dynamics`) each variant gives the drum's traction ratio as a
function ρ(F_slack, v_drum) of the slack-side force and the drum's surface speed
(:meth:`RigidLining.transient_traction`); ``none`` gives none: without a lining the rope is fixed
to the drum (no friction engagement, no slip).

The least pretension F_nwl for no slip is the inverse question
``ropemodel solve SCENE --given slip_margin_up=0 --find F_nwl``.

``n_slip`` defaults to 1.0 (traction just sufficient, the onset of slip);
set it to the safety factor your code of practice requires (>= 1).
"""

from __future__ import annotations

import math

from ropemodel._math import fabs
from ropemodel.effects import domains as dom
from ropemodel.effects.base import Equation, Submodel, define_effect, register
from ropemodel.errors import InputError
from ropemodel.effects.winch import D_DRUM, DIRECTIONS, MODEL, V_PJ, per_direction
from ropemodel.papers import friction
from ropemodel.papers import hajduk1992 as hj
from ropemodel.quantity import Quantity

DRUM = (
    Quantity("mu_d", "1", "friction coefficient of the rope on the drum", **dom.FRICTION,
             warn_low=0.05, warn_high=1.0, usual_source="steel rope on steel (about 0.1) to polymer drum linings "
             "(0.25-0.6), with margin (judgement)", guess=0.2),
    Quantity("alpha_d", "rad", "wrap angle of the rope on the drum", "deg", **dom.WRAP,
             warn_low=math.pi / 2, warn_high=10 * math.pi,
             usual_source="a quarter turn to five turns on a friction drum (judgement)", guess=math.pi),
    Quantity("n_slip", "1", "required safety factor against slip of the rope on the drum", **dom.FACTOR,
             guess=1.5, default=1.0),
)

define_effect(MODEL, "lining", "none", "traction of the drum and the no-slip check per direction")


def _margin_equations(v, traction):
    """slip_margin_d for each direction, written multiplied out so that it stays
    linear in the forces: n·F_C·(m + 1) − F_S·traction = 0 (the same equation as
    :func:`ropemodel.papers.friction.slip_margin`)."""
    eqs = []
    for d in DIRECTIONS:
        m, t = v[f"slip_margin_{d}"], traction(d)
        eqs.append(Equation(f"slip_margin_{d}",
                            v["n_slip"] * v[f"F_C_{d}"] * (m + 1.0) - v[f"F_S_{d}"] * t,
                            "no-slip check on the drum, F_C ≤ F_S traction / n_slip (not in the paper)"))
    return eqs


TRACTION = per_direction("traction", "1", "tension ratio the drum transmits at the onset of slip",
                         equation="rigid: exp(mu_d alpha_d); voigt: Hajduk 1992 eq. (19) with S_0 = F_S",
                         positive=True, guess=2.0, worst=("least",))

MARGINS = per_direction("slip_margin", "1", "margin against slip on the drum (>= 0: no slip)", symbol="m_slip",
                        equation="F_S traction / (n_slip F_C) - 1", worst=("least",))


@register(MODEL, "lining", "none")
class NoLining(Submodel):
    """Drum traction off: no slip check is built."""

    description = "no traction check"
    missing = ("No check of slip on the drum: choose lining = \"rigid\" or \"voigt\".",)
    #: no friction engagement between rope and drum (the other linings have it)
    friction = False

    def transient_traction(self, values):
        """No friction engagement: the transient's rope is fixed to the drum (no traction ratio, no slip)."""
        return None


@register(MODEL, "lining", "rigid")
class RigidLining(Submodel):
    """No-slip check with the Euler–Eytelwein ratio traction = e^{μ_d α_d} (rigid drum surface)."""

    description = "no-slip check on a rigid drum, traction = exp(mu_d alpha_d)"
    assumptions = ("Euler–Eytelwein on a rigid drum: one friction coefficient μ_d over the whole wrap, no creep "
                   "of a lining.",)
    citations = ("euler_eytelwein",)
    quantities = (
        *DRUM,
        *TRACTION,
        *MARGINS,
    )

    def equations(self, v):
        eqs = [Equation(f"traction_{d}",
                        v[f"traction_{d}"] - friction.euler_eytelwein_ratio(v["mu_d"], v["alpha_d"]),
                        "Euler-Eytelwein, Hajduk 1992 eq. (8)")
               for d in DIRECTIONS]
        return eqs + _margin_equations(v, lambda d: v[f"traction_{d}"])

    def transient_traction(self, values):
        """The transient's traction ratio ρ(F_slack, v_drum) = e^{μ_d α_d} [-] (Euler–Eytelwein, Hajduk 1992
        eq. (8)), whatever the forces and speed; values SI (floats or CasADi symbols)."""
        rho = friction.euler_eytelwein_ratio(values["mu_d"], values["alpha_d"])
        return lambda F_slack, v_drum: rho + 0 * F_slack


@register(MODEL, "lining", "voigt")
class VoigtDrumLining(Submodel):
    """No-slip check on a drum with an isotropic Voigt lining, Hajduk (1992) eq. (19).

    traction_d = s with ln s + q s (1 − e^{−α_d/k}) = μ_d α_d, q = Q·F_S_d (the slack
    side enters the arc: S_0 = F_S_d), k = λω, ω = 2 v_pj/D (the drum's rim moves
    with the rope).  The closed form is Newton in ln s
    (:func:`ropemodel.papers.hajduk1992.tension_ratio`).  q > 0 lowers the
    traction below Euler–Eytelwein, more so at high F_S: the least F_nwl for no
    slip solves an implicit equation (the acausal core's Newton).
    """

    description = "no-slip check on a drum with an isotropic Voigt lining (Hajduk 1992)"
    assumptions = ("The drum lining as isotropic Voigt bodies (Hajduk 1992): one compliance Q and one retardation "
                   "time λ, the slack side's force F_S entering the arc, a constant friction coefficient μ_d.",)
    citations = ("hajduk1992",)
    quantities = (
        *DRUM,
        Quantity("Q", "1/N", "compliance of the drum lining (radial + tangential), Hajduk 1992",
                 guess=1e-6, **dom.COMPLIANCE),
        Quantity("lambda", "s", "retardation time of the drum lining (eta/E)", guess=0.01, **dom.RETARDATION),
        D_DRUM,
        V_PJ,
        *TRACTION,
        *MARGINS,
    )

    def equations(self, v):
        k = v["lambda"] * 2.0 * v["v_pj"] / v["D"]
        eqs = []
        for d in DIRECTIONS:
            s, q = v[f"traction_{d}"], v["Q"] * v[f"F_S_{d}"]
            eqs.append(Equation(f"traction_{d}", s - hj.tension_ratio(v["mu_d"], v["alpha_d"], q, k),
                                "Hajduk 1992, eq. (19), with S_0 = F_S and ω = 2 v_pj / D",
                                governing=hj.tension_ratio_residual(s, v["mu_d"], v["alpha_d"], q, k),
                                method=hj.NEWTON_METHOD))
        return eqs + _margin_equations(v, lambda d: v[f"traction_{d}"])

    def transient_traction(self, values):
        """The transient's traction ratio of the Voigt-lined drum, Hajduk (1992) eq. (19) [-].

        ln s + q s (1 − e^{−α_d/k}) = μ_d α_d with q = Q·F_slack (the slack side enters the arc) and
        k = λω, ω = 2|v_drum|/D the drum's angular speed (ω → 0 is the limit of a slow drum, handled by
        :func:`ropemodel.papers.hajduk1992.tension_ratio`); F_slack [N], v_drum [m/s], floats or symbols.
        """
        mu, alpha, Q, lam, D = (values[k] for k in ("mu_d", "alpha_d", "Q", "lambda", "D"))

        def rho(F_slack, v_drum):
            return hj.tension_ratio(mu, alpha, Q * F_slack, lam * 2.0 * fabs(v_drum) / D)

        return rho

    def validate(self, values):
        for d in DIRECTIONS:
            F_S = values.get(f"F_S_{d}")
            if F_S is not None and F_S <= 0:
                raise InputError(f"F_S_{d} = {F_S:g} N: the Voigt lining needs a positive slack-side force "
                                 f"(S_0 = F_S > 0)")
