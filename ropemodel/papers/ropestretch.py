"""The rope's elongation as built: the tension profile integrated along the route, the tensioner's reeving,
constructional stretch and temperature (ropemodel's extension of Krauze et al. 2025, eq. (19)-(23);
``docs/physics.md`` §8).

Krauze et al. (2025) load each whole rope side with its largest force, ΔF_C = q_lw F_C (eq. (19)), and
let the return sheave take up the loop's whole elongation (eq. (23)).  Along the route the tension of a
side falls from its force at the drive (x = 0) to 0.5 F_nwl at the return sheave (x = L_u): by the rope's
weight and resistance per metre, w_i [N/m] in segment i, and, on the winding side, by the load's weight
and resistance J [N] at the load's position x_m.  Hooke's law integrated along the side,

    ΔL = (1/EA) ∫_0^{L_u} T(x) dx,    ∫_0^{L_u} T dx = T_0 L_u + Σ_i w_i L_i (X_{i−1} + L_i/2) + J x_m,

with T_0 = 0.5 F_nwl and X_{i−1} the start of segment i (from the drive).  The tensioner with n falls
(rope parts between its moving block and the frame) moves 1/n of the loop's change of length; a new rope
adds its constructional stretch ε_c (permanent, by core and safety factor) and a temperature change ΔT
adds α_T ΔT over the loop.

Every function works on floats, numpy arrays and CasADi expressions.  Units: N, m, Pa, K.
"""

from __future__ import annotations

from ropemodel._math import fmax, fmin

#: constructional (initial, permanent) stretch of a new stranded rope [-] by safety factor:
#: (safety factor, fibre core, steel core): lightly (8), normally (5), heavily (3) loaded
STRETCH_TABLE = ((8.0, 0.0025, 0.00125), (5.0, 0.005, 0.0025), (3.0, 0.0075, 0.005))
#: where :data:`STRETCH_TABLE` comes from
STRETCH_SOURCE = ("Certex, 'Properties of Extension of Steel Wire Ropes', phase 1, initial or permanent "
                  "(constructional) extension, approximate values in % of the rope's length; the rope makers' table "
                  "(Bridon, Wire Rope Technical Information)")
#: linear thermal expansion coefficient of a steel wire rope [1/K]
ALPHA_STEEL_ROPE = 12.5e-6
#: where :data:`ALPHA_STEEL_ROPE` comes from (and its status)
ALPHA_SOURCE = ("Bridon, Wire Rope Technical Information, thermal expansion of steel wire rope 12.5e-6 /degC "
                "(to verify; carbon steel is 11-13e-6 /K)")


def side_tension_integral(T_0, w, lengths, J, x_J):
    """∫_0^{L_u} T(x) dx [N·m] of one rope side along a route of segments (docs/physics.md §8).

    T(x) = T_0 + ∫_x^{L_u} w ds + J·[x < x_J]: T_0 [N] at the return sheave (x = L_u = Σ L_i), growing by
    w_i [N/m] along segment i toward the drive (x = 0), and by J [N] at x_J [m] (the load, on the winding
    side; J = 0 on the unwinding side).  Closed form
    T_0 L_u + Σ_i w_i L_i (X_{i−1} + L_i/2) + J min(max(x_J, 0), L_u): x_J beyond the route is at its end.
    Not in Krauze et al. (2025), whose eq. (19)-(20) take T(x) = T(0) everywhere.

    Examples
    --------
    A uniform side, w = 0: the tension T_0 over the whole length.

    >>> side_tension_integral(1e4, [0.0], [1000.0], 0.0, 0.0)
    10000000.0

    One segment of 1150 m at 16° carrying the paper's rope (q_l = 80 N/m, μ = 0.05) and the load at the
    return sheave, hauled up (J = G_ml + T_m = 151.17 kN): divided by EA = L_u/q_lw the elongation is
    below eq. (19)'s 1107.50 mm.

    >>> import math
    >>> a = math.radians(16)
    >>> w = 80 * (math.sin(a) + 0.05 * math.cos(a))
    >>> J = 467e3 * (math.sin(a) + 0.05 * math.cos(a))
    >>> round(side_tension_integral(1e4, [w], [1150.0], J, 1150.0) * 5.8e-6 / 1150 * 1e3, 2)   # mm
    1021.14
    """
    total, start = T_0 * 0.0, 0.0
    for length, w_i in zip(lengths, w):
        total = total + w_i * length * (start + 0.5 * length)
        start = start + length
    return total + T_0 * start + J * fmin(fmax(x_J, 0.0), start)


def elastic_elongation(integral, EA):
    """Hooke's law along a side: ΔL = ∫T dx / EA [m]; integral [N·m] (:func:`side_tension_integral`), EA [N].

    Examples
    --------
    >>> elastic_elongation(1e7, 1e8)      # 10 kN over 1 km on EA = 100 MN: 0.1 m
    0.1
    """
    return integral / EA


def take_up(loop_elongation, n_falls):
    """The tensioner's stroke for a change of the loop's length: ΔL_loop / n [m] with n the falls.

    A tensioner whose moving block is held by n rope falls moves 1/n of the rope it takes up: a movable
    return sheave (the loop's two sides on it) n = 2; a take-up that pulls the rope itself n = 1 (Krauze
    et al. 2025, eq. (23): the stroke is the loop's whole elongation).  Kinematics of a tackle, not in the paper.

    Examples
    --------
    >>> take_up(1.4, 2)
    0.7
    """
    return loop_elongation / n_falls


def _clamp(x, low, high):
    return fmin(fmax(x, low), high)


def constructional_stretch(n, fibre_core: bool):
    """Constructional (initial, permanent) stretch ε_c [-] of a new stranded rope at safety factor n [-].

    The rope makers' table (:data:`STRETCH_TABLE`, :data:`STRETCH_SOURCE`): fibre core 0.25 / 0.50 / 0.75 %,
    steel core 0.125 / 0.25 / 0.50 % of the length, lightly (n = 8) / normally (5) / heavily (3) loaded.
    Between the rows, linear in the load fraction 1/n (ropemodel's choice: the table gives classes, not a
    curve); beyond them the end rows (n > 8: 'lightly', n < 3: 'heavily'; ropes with many bends stretch up
    to 2 % (fibre) and 1 % (steel), outside this function).  Valid for n > 0.

    Examples
    --------
    >>> [round(100 * constructional_stretch(n, fibre_core=False), 4) for n in (8.0, 5.0, 3.0)]     # %
    [0.125, 0.25, 0.5]
    >>> round(100 * constructional_stretch(4.0, fibre_core=False), 3)     # 1/4 between 1/5 and 1/3
    0.344
    """
    col = 1 if fibre_core else 2
    (n0, *e0), (n1, *e1), (n2, *e2) = STRETCH_TABLE
    x0, x1, x2 = 1.0 / n0, 1.0 / n1, 1.0 / n2
    x = 1.0 / n
    s01 = (e1[col - 1] - e0[col - 1]) / (x1 - x0)
    s12 = (e2[col - 1] - e1[col - 1]) / (x2 - x1)
    return e0[col - 1] + s01 * (_clamp(x, x0, x1) - x0) + s12 * (_clamp(x, x1, x2) - x1)


def thermal_elongation(alpha_T, dT, length):
    """α_T ΔT L [m]: a rope of length L [m] warmer by ΔT [K] than when installed; α_T [1/K].

    Examples
    --------
    >>> round(thermal_elongation(12.5e-6, 20.0, 2300.0), 6)    # a 2.3 km loop 20 K warmer: 575 mm
    0.575
    """
    return alpha_T * dT * length


def rope_strain(sigma, E_inf, r_0, sigma_E):
    """Strain of a rope whose tangent modulus rises with its tensile stress σ [Pa] (metallic area):
    ε(σ) = ∫_0^σ ds/E_t(s) with E_t(s) = E_∞ (1 − (1 − r_0) e^{−s/σ_E}), in closed form

        ε(σ) = [σ + σ_E ln((1 − (1 − r_0) e^{−σ/σ_E}) / r_0)] / E_∞.

    E_∞ [Pa] the modulus under load (rope_E, or EA/A_m), r_0 = E_0/E_∞ (0 < r_0 <= 1) the modulus at zero
    stress relative to it, σ_E [Pa] the stress over which the modulus rises (1 − 1/e of the way).  Smooth in
    every argument (no branch: IPOPT-safe); r_0 = 1 is Hooke's law ε = σ/E_∞.  Stranded ropes stiffen as
    the strands bed in under tension (Feyrer, *Wire Ropes*, 2nd ed. 2015, §1.3: the rope modulus rises with
    the rope tensile stress); this exponential form is ropemodel's smooth choice with that behaviour, not
    Feyrer's own fit (status: to verify against the source); r_0 and σ_E come from the rope maker's
    load-extension curve.  Valid for σ >= 0.

    Examples
    --------
    >>> rope_strain(300e6, 100e9, 1.0, 50e6)              # Hooke: 300 MPa on 100 GPa
    0.003
    >>> round(rope_strain(300e6, 100e9, 0.5, 50e6) * 1e3, 3)    # softer at first: more strain [1e-3]
    3.346
    """
    from ropemodel._math import exp, log

    return (sigma + sigma_E * log((1.0 - (1.0 - r_0) * exp(-sigma / sigma_E)) / r_0)) / E_inf


def side_strain_integral(T_0, w, lengths, J, x_J, strain, nodes: int = 8):
    """∫_0^{L_u} ε(T(x)) dx [m] of one rope side, the tension profile of :func:`side_tension_integral` and
    ``strain(T)`` [-] a smooth function of the tension: Gauss–Legendre with ``nodes`` points on each piece
    (the segments, each split at x_J where the winding side's tension steps by J).  Exact for a strain
    polynomial in T of degree < 2 nodes (Hooke's law with any ``nodes``).

    Examples
    --------
    >>> round(side_strain_integral(1e4, [25.0], [1000.0], 1e5, 400.0, lambda T: T / 1e8), 9)   # Hooke
    0.625
    >>> side_tension_integral(1e4, [25.0], [1000.0], 1e5, 400.0) / 1e8
    0.625
    """
    import numpy as np

    t, wt = np.polynomial.legendre.leggauss(nodes)
    ends, total = [], 0.0
    for length in lengths:
        total = total + length
        ends.append(total)
    tail, out, start = T_0, 0.0, 0.0
    tails: list = []
    for length, w_i in reversed(list(zip(lengths, w))):      # the tension at each segment's return-sheave end
        tails.insert(0, tail)
        tail = tail + w_i * length
    for w_i, end, T_end in zip(w, ends, tails):
        cut = _clamp(x_J, start, end)
        for a, b, step in ((start, cut, J), (cut, end, 0.0)):
            half, mid = 0.5 * (b - a), 0.5 * (a + b)
            for t_k, w_k in zip(t, wt):
                x = mid + half * float(t_k)
                out = out + float(w_k) * half * strain(T_end + w_i * (end - x) + step)
        start = end
    return out
