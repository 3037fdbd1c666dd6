"""Rope friction on a rigid drum: the Euler–Eytelwein (capstan) law.

L. Euler (1762); J. A. Eytelwein (1808).  Also eq. (8) of Hajduk (1992), the
``Q = 0`` case of the Voigt-lining model (:mod:`ropemodel.papers.hajduk1992`).
"""

from __future__ import annotations

from ropemodel._math import exp


def euler_eytelwein_ratio(mu, alpha):
    """Tension ratio at the onset of slip on a rigid drum, S/S_0 = e^{μα} [-].

    Euler–Eytelwein; Hajduk (1992) eq. (8).

    mu [-] rope–drum friction coefficient, > 0; alpha [rad] wrap angle, > 0.
    Valid for an inextensible rope on a rigid drum at the onset of slip, with
    no centrifugal or bending terms.

    Examples
    --------
    A full turn at μ = 0.25: e^{π/2}.

    >>> import math
    >>> round(euler_eytelwein_ratio(0.25, 2 * math.pi), 6)
    4.810477
    """
    return exp(mu * alpha)


def slip_margin(F_tight, F_slack, ratio, n_slip):
    """Margin against slip of a rope on a friction drum, F_slack·ratio/(n_slip·F_tight) − 1 [-].

    F_tight [N] force in the tight (winding) side, > 0; F_slack [N] force in the
    slack (unwinding) side, > 0; ratio [-] tension ratio the drum can transmit at
    the onset of slip (e.g. :func:`euler_eytelwein_ratio`); n_slip [-] required
    safety factor on traction, >= 1.  No slip with the required safety where the
    margin is >= 0.  (Not from a paper: the standard friction-drive check
    F_tight <= F_slack·ratio/n_slip written as a margin.)

    Examples
    --------
    Half a turn at μ = 0.2 (ratio e^{0.2π} = 1.874), 100 kN against 60 kN, n_slip = 1.1:

    >>> import math
    >>> round(slip_margin(100e3, 60e3, euler_eytelwein_ratio(0.2, math.pi), 1.1), 4)
    0.0224
    """
    return F_slack * ratio / (n_slip * F_tight) - 1.0
