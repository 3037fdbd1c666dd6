"""The Koepe hoist's closed forms written out here in numpy, independent of ropemodel: the truth of the scene tests.

Statics (standard practice, docs/physics.md §7): each side carries its conveyance, its head ropes from the wheel
(H_head + depth) and its tail ropes down to the loop's bottom (H + h_loop − depth).  The anti-slip factor
σ = (ρ − 1) T_2/(T_1 − T_2).  Rigid dynamics (docs/physics.md §7, the table of the four manoeuvres): the largest
acceleration of side U before slip a = (E F_D − F_U − (E − 1) q v²)/(M_U + E M_D + q R (E − 1)/μ), with
M = T/g + the sheave of the side's compartment, q = n_head q_head, E = e^{μα}.  Hajduk's lining: eq. (19),
ln(T_1/T_2) + (T_1/n) C = μα, solved here by brentq.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

import ropemodel as rm

G = 9.80665

#: the issue's example, SI
ISSUE = dict(H=905.0, H_head=56.7, m_conveyance=29.6e3, m_payload=22e3, n_head=4, q_head=8.6, n_tail=2, q_tail=15.5,
             mu=0.25, alpha=math.pi, D=4.5, v_max=10.0)

#: five hoists: with and without tail ropes, unequal head and tail rope masses (both ways), one and many ropes,
#: sheaves of different inertia in the two compartments, shaft resistance, a tail loop
HOISTS = {
    "issue": dict(ISSUE),
    "no tail, one rope": dict(H=300.0, H_head=30.0, m_conveyance=8e3, m_payload=5e3, n_head=1, q_head=6.0, n_tail=0,
                              q_tail=0.0, mu=0.25, alpha=math.pi, D=3.0, v_max=8.0),
    "tail heavier, 6 ropes": dict(H=1200.0, H_head=70.0, m_conveyance=25e3, m_payload=8e3, n_head=6, q_head=7.0,
                                  n_tail=3, q_tail=20.0, mu=0.22, alpha=math.radians(195), D=5.0, v_max=15.0),
    "sheaves, resistance, loop": dict(H=700.0, H_head=45.0, m_conveyance=18e3, m_payload=14e3, n_head=4, q_head=5.5,
                                      n_tail=2, q_tail=9.0, h_loop=6.0, m_sheave_a=3.5e3, m_sheave_b=0.8e3, F_r=6e3,
                                      mu=0.28, alpha=math.radians(200), D=4.0, v_max=12.0),
    "two ropes, light tail": dict(H=520.0, H_head=40.0, m_conveyance=12e3, m_payload=9e3, n_head=2, q_head=9.5,
                                  n_tail=1, q_tail=12.0, mu=0.3, alpha=math.radians(180), D=3.5, v_max=9.0),
}


def full(h: dict) -> dict:
    """The hoist with its optional values filled in."""
    return {"h_loop": 0.0, "m_sheave_a": 0.0, "m_sheave_b": 0.0, "F_r": 0.0, "n_tail": 0, "q_tail": 0.0, **h}


def scene(h: dict, **effects):
    """A scene of the hoist ``h`` (SI numbers), tail ropes when n_tail > 0."""
    p = dict(h)
    tails = p.get("n_tail", 0) > 0
    if not tails:
        p = {k: v for k, v in p.items() if k not in ("n_tail", "q_tail", "h_loop")}
    data = {"scene": {"name": "test hoist", "model": "koepe"},
            "effects": {"tail_ropes": "round" if tails else "none", **effects}, "parameters": p}
    return rm.from_dict(data, bare="si", emit=False)


def tensions(h: dict, y_L: float, loaded: bool):
    """(T_L, T_E) [N]: the payload's side and the other, the payload's conveyance at depth y_L."""
    h = full(h)
    m_p = h["m_payload"] if loaded else 0.0
    head, tail = h["n_head"] * h["q_head"], h["n_tail"] * h["q_tail"]
    T_L = G * (h["m_conveyance"] + m_p + head * (h["H_head"] + y_L) + tail * (h["H"] + h["h_loop"] - y_L))
    T_E = G * (h["m_conveyance"] + head * (h["H_head"] + h["H"] - y_L) + tail * (h["h_loop"] + y_L))
    return T_L, T_E


#: (name, depth of the payload's conveyance as a fraction of H, loaded)
STATIC = [("loaded at the bottom", 1.0, True), ("loaded at the top", 0.0, True), ("empty", 1.0, False)]
ENDS = [("loaded at the bottom", 1.0, True), ("loaded at the top", 0.0, True),
        ("empty, conveyance L at the bottom", 1.0, False), ("empty, conveyance L at the top", 0.0, False)]


def statics(h: dict, limit=None) -> dict:
    """Every static state's T_1, T_2, ρ, σ, and the worst (least σ); ``limit(T_2)`` the traction limit (e^{μα})."""
    limit = limit or (lambda T_2: math.exp(h["mu"] * h["alpha"]))
    rows = []
    for name, f, loaded in STATIC:
        T_L, T_E = tensions(h, f * h["H"], loaded)
        T_1, T_2 = max(T_L, T_E), min(T_L, T_E)
        rho = limit(T_2)
        rows.append(dict(name=name, T_L=T_L, T_E=T_E, T_1=T_1, T_2=T_2, rho=rho,
                         sigma=(rho - 1) * T_2 / (T_1 - T_2) if T_1 > T_2 else math.inf))
    worst = min(rows, key=lambda r: r["sigma"])
    return dict(rows=rows, worst=worst, T_max=max(r["T_1"] for r in rows),
                dT_max=max(r["T_1"] - r["T_2"] for r in rows))


def manoeuvres(h: dict, T_L, T_E, M_L, M_E):
    """(F_U, F_D, M_U, M_D) of the four manoeuvres: docs/physics.md §7's table, F_r on the payload's conveyance."""
    F_r = full(h)["F_r"]
    return {"hoist_accel": (T_L + F_r, T_E, M_L, M_E), "hoist_decel": (T_E, T_L + F_r, M_E, M_L),
            "lower_accel": (T_E, T_L - F_r, M_E, M_L), "lower_decel": (T_L - F_r, T_E, M_L, M_E)}


def rigid_slip(h: dict, F_U, F_D, M_U, M_D):
    """The rigid wheel's slip acceleration at v_max, the ropes on the wheel included."""
    E, q, R = math.exp(h["mu"] * h["alpha"]), h["n_head"] * h["q_head"], h["D"] / 2
    return (E * F_D - F_U - (E - 1) * q * h["v_max"] ** 2) / (M_U + E * M_D + q * R * (E - 1) / h["mu"])


def slips(h: dict, slip=rigid_slip) -> dict:
    """Each manoeuvre's least slip acceleration over the end states and compartments, and where: {m: (a, state)}."""
    hh = full(h)
    out: dict = {}
    for name, f, loaded in ENDS:
        T_L, T_E = tensions(h, f * h["H"], loaded)
        for m_L, m_E in ((hh["m_sheave_a"], hh["m_sheave_b"]), (hh["m_sheave_b"], hh["m_sheave_a"])):
            for m, args in manoeuvres(h, T_L, T_E, T_L / G + m_L, T_E / G + m_E).items():
                a = slip(h, *args)
                if m not in out or a < out[m][0]:
                    out[m] = (a, name)
    return out


def coasting(h: dict, sign: float) -> float:
    """The largest deceleration with neither drive nor brake over the end states, (s (T_L − T_E) + F_r)/M_total."""
    hh = full(h)
    arc = h["n_head"] * h["q_head"] * h["D"] / 2 * h["alpha"]
    out = []
    for _, f, loaded in ENDS:
        T_L, T_E = tensions(h, f * h["H"], loaded)
        M = (T_L + T_E) / G + hh["m_sheave_a"] + hh["m_sheave_b"] + arc + hh.get("m_machine", 0.0)
        out.append((sign * (T_L - T_E) + hh["F_r"]) / M)
    return max(out)


def hajduk_ratio(T_2: float, n: float, mu: float, alpha: float, C: float) -> float:
    """s = T_1/T_2 from eq. (19), ln s + s (T_2/n) C = μα, by brentq."""
    q = C * T_2 / n
    return brentq(lambda s: math.log(s) + q * s - mu * alpha, 1e-300, math.exp(mu * alpha) * (1 + 1e-12),
                  xtol=1e-300, rtol=1e-15)


def crept(alpha: float, lam: float, v: float, R: float) -> float:
    """1 − e^{−α/k}, k = λ v/R (1 at k = 0: fully crept)."""
    k = lam * v / R
    return 1.0 if k == 0 else -math.expm1(-alpha / k)


def voigt_slip(h: dict, F_U, F_D, M_U, M_D):
    """The Voigt lining's slip acceleration at rest: brentq on a of ln(T_U/T_D) + (T_U/n) C − μα = 0,
    T_U = F_U + M_U a, T_D = F_D − M_D a, C = Q_R + Q_T (fully crept)."""
    C = h["Q_R"] + h.get("Q_T", 0.0)

    def f(a):
        T_U, T_D = F_U + M_U * a, F_D - M_D * a
        return math.log(T_U / T_D) + T_U / h["n_head"] * C - h["mu"] * h["alpha"]

    lo, hi = -F_U / M_U * (1 - 1e-12), F_D / M_D * (1 - 1e-12)     # the two tensions stay positive
    return brentq(f, lo, hi, xtol=1e-14, rtol=1e-14)


def rel(a, b) -> float:
    """Relative difference."""
    return float(np.abs(a - b) / max(abs(b), 1e-300))
