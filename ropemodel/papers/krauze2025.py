"""Winch haulage on an inclined route: Krauze, Mucha, Wydro, Klempka (2025).

K. Krauze, K. Mucha, T. Wydro, R. Klempka, "Model and analysis of rope winch operation in
underground rail transport", Archives of Mining Sciences (2025), doi:10.24425/ams.2025.156290,
CC-BY 4.0.  Equation numbers below are the paper's; ``docs/physics.md`` §1 states them with
their errata and the paper's Fig. 9 values, which the examples reproduce.

Units: forces [N], lengths [m], angles [rad], unit weight q_l [N/m], unit elongation q_lw [m/N],
speed [m/s], power [W].  ``direction`` is ``+1`` for upward travel (load hauled up the incline)
and ``-1`` for downward travel; it fixes every ± of eq. (12)-(18) as checked against Fig. 9.
Every function works on floats, numpy arrays and CasADi expressions.
"""

from __future__ import annotations

from ropemodel._math import cos, fmax, fmin, sin

UP = +1
DOWN = -1


def load_weight_along_incline(G_m, alpha_u):
    """Component of the load's weight along the incline, eq. (1): G_ml = G_m sin α_u.

    Parameters
    ----------
    G_m : float
        Weight of the transported load [N], > 0.
    alpha_u : float
        Inclination of the route [rad], −π/2 < α_u < π/2 (the paper: up to 45°).

    Returns
    -------
    float
        G_ml [N].

    Examples
    --------
    Fig. 9 of the paper prints G_ml = 128.72 kN:

    >>> import math
    >>> round(load_weight_along_incline(467e3, math.radians(16)) / 1e3, 2)
    128.72
    """
    return G_m * sin(alpha_u)


def load_weight_normal(G_m, alpha_u):
    """Component of the load's weight normal to the incline, eq. (5): G_mo = G_m cos α_u.

    Parameters
    ----------
    G_m : float
        Weight of the load [N].
    alpha_u : float
        Inclination [rad].

    Returns
    -------
    float
        G_mo [N].

    Examples
    --------
    >>> import math
    >>> round(load_weight_normal(467e3, math.radians(16)) / 1e3, 2)   # Fig. 9: 448.91 kN
    448.91
    """
    return G_m * cos(alpha_u)


def rope_weight_along_incline(q_l, length, alpha_u):
    """Weight component of a rope section along the incline, q_l·length·sin α_u.

    Eq. (3) with length = L_u − L_ul (G_l1), eq. (4) with length = L_ul (G_l2), eq. (6) with
    length = L_u (G_ls, the unwinding rope).

    Parameters
    ----------
    q_l : float
        Rope weight per metre [N/m].
    length : float
        Length of the rope section [m].
    alpha_u : float
        Inclination [rad].

    Returns
    -------
    float
        Weight along the incline [N].

    Examples
    --------
    Fig. 9: G_l1 = 14.33 kN (650 m from K_ZN to point A), G_ls = 25.36 kN (the whole 1150 m):

    >>> import math
    >>> a = math.radians(16)
    >>> (round(rope_weight_along_incline(80.0, 650.0, a) / 1e3, 2),
    ...  round(rope_weight_along_incline(80.0, 1150.0, a) / 1e3, 2))
    (14.33, 25.36)
    """
    return q_l * length * sin(alpha_u)


def load_resistance(mu_pm, G_m, alpha_u):
    """Travel resistance of the load, eq. (7): T_m = μ_pm G_m cos α_u.

    Parameters
    ----------
    mu_pm : float
        Coefficient of resistance of the load [-].
    G_m : float
        Weight of the load [N].
    alpha_u : float
        Inclination [rad].

    Returns
    -------
    float
        T_m [N].

    Examples
    --------
    >>> import math
    >>> round(load_resistance(0.05, 467e3, math.radians(16)) / 1e3, 2)   # Fig. 9: 22.45 kN
    22.45
    """
    return mu_pm * G_m * cos(alpha_u)


def rope_resistance(mu, q_l, length, alpha_u):
    """Travel resistance of a rope section, μ·q_l·length·cos α_u.

    Eq. (8) with μ_pl1 and L_u − L_ul (T_l1), eq. (9) with μ_pl2 and L_ul (T_l2), eq. (11) with
    μ_pl and L_u (T_ls, the unwinding rope).

    Parameters
    ----------
    mu : float
        Coefficient of resistance of the rope [-].
    q_l : float
        Rope weight per metre [N/m].
    length : float
        Length of the section [m].
    alpha_u : float
        Inclination [rad].

    Returns
    -------
    float
        Resistance [N].

    Examples
    --------
    >>> import math
    >>> round(rope_resistance(0.05, 80.0, 500.0, math.radians(16)) / 1e3, 2)   # Fig. 9: T_l2 = 1.92 kN
    1.92
    """
    return mu * q_l * length * cos(alpha_u)


def unwinding_rope_force(F_nwl, G_ls, T_ls, direction):
    """Force in the unwinding rope, eq. (12): F_S = 0.5 F_nwl + G_ls ∓ T_ls.

    Upward travel (direction = +1): F_S = 0.5 F_nwl + G_ls − T_ls; downward (direction = −1):
    F_S = 0.5 F_nwl + G_ls + T_ls.  Erratum: the paper prints μ_nl in the expanded form of
    eq. (12); the coefficient is μ_pl of eq. (11), as implemented here.

    Parameters
    ----------
    F_nwl : float
        Initial tension from the tensioner [N].
    G_ls, T_ls : float
        Weight along the incline and resistance of the unwinding rope [N], eq. (6), (11).
    direction : int
        +1 upward, −1 downward.

    Returns
    -------
    float
        F_S [N].

    Examples
    --------
    Fig. 9 (G_ls = 25.3586 kN, T_ls = 4.4218 kN): F_S = 30.94 kN up and 39.78 kN down.

    >>> (round(unwinding_rope_force(20e3, 25358.6, 4421.8, UP) / 1e3, 2),
    ...  round(unwinding_rope_force(20e3, 25358.6, 4421.8, DOWN) / 1e3, 2))
    (30.94, 39.78)
    """
    return 0.5 * F_nwl + G_ls - direction * T_ls


def winding_rope_force(F_nwl, G_lmC, T_m, T_l, direction):
    """Force in the winding rope, eq. (13): F_C = 0.5 F_nwl + G_lmC ± (T_m + T_l).

    Upward travel (direction = +1) adds the resistances, downward subtracts them.  Equivalent
    to eq. (16) (case 1) and to the first line of eq. (18) (case 2); erratum: the second line of
    eq. (18) has a misplaced parenthesis and is not used.

    Parameters
    ----------
    F_nwl : float
        Initial tension [N].
    G_lmC : float
        Weight along the incline of load and winding rope [N], eq. (14).
    T_m, T_l : float
        Resistances of the load and of the winding rope [N], eq. (7), (10).
    direction : int
        +1 upward, −1 downward.

    Returns
    -------
    float
        F_C [N].

    Examples
    --------
    Fig. 9 (G_lmC = 154.0813 kN, T_m = 22.4455 kN, T_l = 4.4218 kN): F_C = 190.95 kN up, 137.21 kN down.

    >>> up = winding_rope_force(20e3, 154081.3, 22445.5, 4421.8, UP)
    >>> down = winding_rope_force(20e3, 154081.3, 22445.5, 4421.8, DOWN)
    >>> round(up / 1e3, 2), round(down / 1e3, 2)
    (190.95, 137.21)
    """
    return 0.5 * F_nwl + G_lmC + direction * (T_m + T_l)


def elongation(q_lw, F):
    """Elongation of the installed rope under force F, ΔF = q_lw·F: eq. (19), (20), (22).

    Parameters
    ----------
    q_lw : float
        Unit elongation of the installed rope [m/N] (the paper gives mm/kN).
    F : float
        Force [N].

    Returns
    -------
    float
        Elongation [m].

    Examples
    --------
    >>> round(elongation(5.8e-6, 190949.0) * 1e3, 2)   # Fig. 9: ΔF_C = 1107.50 mm upward
    1107.5
    """
    return q_lw * F


def drum_power(F_C, F_S, u):
    """Power the drum gives the rope, signed: P_drum = (F_C − F_S)·u (not in the paper).

    The force balance on the drum: the winding rope pulls the load with F_C and the unwinding rope
    acts back on the drum with F_S, so the drum's torque is (F_C − F_S) D/2 and its rim moves with
    the load.  ``u`` is the load's signed speed along the route, positive up the slope (toward the
    drive): u = s·v_pj with s = +1 upward and −1 downward (physics reference §1 and §4).  The
    four-quadrant convention follows: P_drum > 0, the drive motors (it lifts the load or pulls it
    against the resistances); P_drum < 0, it brakes (the load drives the drum, as when a load is
    lowered on a slope steeper than its resistances can hold).  Valid where the forces are: both
    ropes taut (F_C, F_S > 0) and the rope not slipping on the drum.

    Erratum: an earlier version of the physics reference (``docs/physics.md`` §1, and ropemodel with
    it) wrote N_p = (F_C − F_S)·v_pj/η for both directions with v_pj ≥ 0, which counts lowering a
    load as motoring and divides a braking power by η.  Lowering, the drum pays out the winding
    rope: u = −v_pj.

    Parameters
    ----------
    F_C, F_S : float
        Forces in the winding and unwinding rope [N], eq. (12)-(13) of the direction of ``u``.
    u : float
        The load's signed speed [m/s]: +v_pj upward, −v_pj downward.

    Returns
    -------
    float
        P_drum [W]: > 0 motoring, < 0 braking.

    Examples
    --------
    Fig. 9 (F_C, F_S of eq. (12)-(13), v_pj = 2.5 m/s): 400.03 kW upward, −243.58 kW downward (braking).

    >>> up = drum_power(190948.546, 30936.833, +2.5)
    >>> down = drum_power(137214.018, 39780.441, -2.5)
    >>> round(up / 1e3, 3), round(down / 1e3, 3)
    (400.029, -243.584)
    """
    return (F_C - F_S) * u


def drive_power(P_drum, eta):
    """The drive's power N_p from the drum's, signed (four-quadrant; not in the paper).

    N_p = P_drum/η while the drive motors (P_drum > 0: the drive train's losses come on top of what
    the drum gives), N_p = P_drum·η while it brakes (P_drum < 0: the losses are taken from what the
    load gives back, and N_p is what reaches the motor, to be returned to the supply or dissipated).
    Written max(P_drum, 0)/η + min(P_drum, 0)·η, which is that and evaluates no branch: finite for
    every P_drum and every η > 0, on floats, arrays and CasADi symbols alike.

    Parameters
    ----------
    P_drum : float
        Power at the drum [W], :func:`drum_power`.
    eta : float
        Efficiency of the drive train from motor to drum rim [-], 0 < η ≤ 1 (η = 1: the power at the
        drum rim).

    Returns
    -------
    float
        N_p [W]: > 0 motoring (drawn), < 0 braking (returned by the drive).

    Examples
    --------
    Fig. 9 at η = 1 (the paper gives no efficiency) and at η = 0.8: η divides motoring power and
    multiplies braking power.

    >>> round(drive_power(400029.283, 1.0) / 1e3, 3), round(drive_power(-243583.942, 1.0) / 1e3, 3)
    (400.029, -243.584)
    >>> round(drive_power(400029.283, 0.8) / 1e3, 3), round(drive_power(-243583.942, 0.8) / 1e3, 3)
    (500.037, -194.867)
    """
    return fmax(P_drum, 0.0) / eta + fmin(P_drum, 0.0) * eta
