"""Winch haulage on an inclined route: Krauze, Mucha, Wydro, Klempka (2025).

K. Krauze, K. Mucha, T. Wydro, R. Klempka, "Model and analysis of rope winch
operation in underground rail transport", Archives of Mining Sciences (2025),
CC-BY 4.0.  Equation numbers below are the paper's.

Units: forces [N], lengths [m], angles [rad], unit weight q_l [N/m], unit
elongation q_lw [m/N], speed [m/s], power [W].  ``direction`` is ``+1`` for
upward travel (load hauled up the incline) and ``-1`` for downward travel; it
fixes every ± of eq. (12)-(18) as checked against the paper's Fig. 9.
"""

from __future__ import annotations

from ropemodel._math import cos, sin

UP = +1
DOWN = -1


def load_weight_along_incline(G_m, alpha_u):
    """Component of the load's weight along the incline, G_ml = G_m sin α_u [N].  Eq. (1).

    G_m [N] weight of the transported load; alpha_u [rad] inclination, |α_u| < π/2.
    """
    return G_m * sin(alpha_u)


def load_weight_normal(G_m, alpha_u):
    """Component of the load's weight normal to the incline, G_mo = G_m cos α_u [N].  Eq. (5)."""
    return G_m * cos(alpha_u)


def rope_weight_along_incline(q_l, length, alpha_u):
    """Weight component of a rope section along the incline, q_l·length·sin α_u [N].

    Eq. (3) with length = L_u − L_ul (G_l1), eq. (4) with length = L_ul (G_l2),
    eq. (6) with length = L_u (G_ls, the unwinding rope).
    q_l [N/m] rope weight per metre; length [m]; alpha_u [rad].
    """
    return q_l * length * sin(alpha_u)


def load_resistance(mu_pm, G_m, alpha_u):
    """Travel resistance of the load, T_m = μ_pm G_m cos α_u [N].  Eq. (7).

    mu_pm [-] coefficient of resistance of the load; G_m [N]; alpha_u [rad].
    """
    return mu_pm * G_m * cos(alpha_u)


def rope_resistance(mu, q_l, length, alpha_u):
    """Travel resistance of a rope section, μ·q_l·length·cos α_u [N].

    Eq. (8) with μ_pl1 and L_u − L_ul (T_l1), eq. (9) with μ_pl2 and L_ul (T_l2),
    eq. (11) with μ_pl and L_u (T_ls, the unwinding rope).
    """
    return mu * q_l * length * cos(alpha_u)


def unwinding_rope_force(F_nwl, G_ls, T_ls, direction):
    """Force in the unwinding rope, F_S = 0.5 F_nwl + G_ls ∓ T_ls [N].  Eq. (12).

    Upward travel (direction = +1): F_S = 0.5 F_nwl + G_ls − T_ls; downward
    (direction = −1): F_S = 0.5 F_nwl + G_ls + T_ls.
    Erratum: the paper prints μ_nl in the expanded form of eq. (12); the
    coefficient is μ_pl of eq. (11), as implemented here.
    F_nwl [N] initial tension from the tensioner; G_ls, T_ls [N] from eq. (6), (11).
    """
    return 0.5 * F_nwl + G_ls - direction * T_ls


def winding_rope_force(F_nwl, G_lmC, T_m, T_l, direction):
    """Force in the winding rope, F_C = 0.5 F_nwl + G_lmC ± (T_m + T_l) [N].  Eq. (13).

    Upward travel (direction = +1) adds the resistances, downward subtracts them.
    Equivalent to eq. (16) (case 1) and to the first line of eq. (18) (case 2);
    erratum: the second line of eq. (18) has a misplaced parenthesis and is not used.
    """
    return 0.5 * F_nwl + G_lmC + direction * (T_m + T_l)


def elongation(q_lw, F):
    """Elongation of the installed rope under force F, ΔF = q_lw·F [m].  Eq. (19), (20), (22).

    q_lw [m/N] unit elongation of the installed rope (the paper gives mm/kN); F [N].
    """
    return q_lw * F


def drive_power(F_C, F_S, v_pj, eta):
    """Drive power N_p = (F_C − F_S)·v_pj / η [W].

    Not in the paper: the power follows from the force balance on the drum, the
    unwinding rope's tension F_S acting back on it; η [-] is the drive efficiency
    (0 < η ≤ 1), v_pj [m/s] the haulage speed.  Negative N_p means the drive brakes.
    """
    return (F_C - F_S) * v_pj / eta
