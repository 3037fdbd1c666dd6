"""A long route of segments held as route numbers per load case (the ``segments`` route's vector form).

A route of more than :data:`VECTOR_ABOVE` segments does not put its segments' values into the model: the route
step (:mod:`ropemodel.papers.route_numbers`) reduces the route's arrays, for each load case, to a few numbers,
and the model declares these as parameters (``route_*``, SI) that its equations use, so the model's size does not
grow with the segments.  The numbers enter linearly in μ_pl, a_h, x_m and L_ul, which stay the model's
symbols, so their derivatives are the segment form's away from ties; the segments' own values (``L_i``,
``alpha_i``, ``mu_wi``) stay the scene's parameters, read and set by name (:mod:`ropemodel.effects.route_arrays`),
and no derivative in them is given.  Equations: Krauze et al. (2025) eq. (1)-(11) on a route, the least tensions
of docs/physics.md §4.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ropemodel._math import fmin, if_else
from ropemodel.effects.base import REGISTRY, Equation
from ropemodel.effects.route_arrays import RouteArrays
from ropemodel.errors import InputError
from ropemodel.effects.winch import MODEL, Q
from ropemodel.papers import route_numbers as rn
from ropemodel.papers.route import G_N
from ropemodel.quantity import Quantity

#: a route of more segments than this is held as route numbers (as many as sizing gives sensitivities in)
VECTOR_ABOVE = 100
SRC = "route of segments, docs/physics.md §4"
_WAYS = {"up": "hauling up", "down": "lowering"}


def _number(name: str, unit: str, text: str) -> Quantity:
    return Q(name, unit, f"{text} (a route number: computed per load case from the segments, {SRC})",
             equation=f"route step, {SRC}")


def _numbers() -> tuple[dict[str, Quantity], dict[str, tuple[str, ...]]]:
    """The route numbers' quantities and the case inputs each follows (``x_m``, ``a_h``)."""
    rows = [("route_L_u", "m", "length of the route, Σ L_i", ()),
            ("route_sin", "m", "Σ L_i sin α_i over the route", ()),
            ("route_mo", "m", "Σ μ_wi L_i cos α_i over the segments that give mu_winding", ()),
            ("route_cp", "m", "Σ L_i cos α_i over the segments without mu_winding (they take μ_pl)", ()),
            ("route_cos", "m", "Σ L_i cos α_i over the route", ()),
            ("route_sin_j", "1", "sin α_j of the load's segment", ("x_m",)),
            ("route_cos_j", "1", "cos α_j of the load's segment", ("x_m",)),
            ("route_mo_j", "1", "μ_wj cos α_j of the load's segment (0 without mu_winding)", ("x_m",)),
            ("route_cp_j", "1", "cos α_j of the load's segment without mu_winding (else 0)", ("x_m",)),
            ("route_B_A", "m", "A_{j+1} + sin α_j x_{j+1}: the rope's rise beside the load, weight part", ("x_m",)),
            ("route_B_mo", "m", "the same, own-coefficient resistance part", ("x_m",)),
            ("route_B_cp", "m", "the same, μ_pl resistance part", ("x_m",)),
            ("route_before", "1", "1 where a joint lies between the drive and the load", ("x_m",)),
            ("route_beyond", "1", "1 where a joint lies between the load and the return sheave", ("x_m",))]
    for way, words in _WAYS.items():
        for c in rn.WINDING:
            rows += [(f"route_P_{c}_{way}", "m", f"coefficient {c} of the winding rope's least rise at the joints "
                                                 f"before the load, {words}", ("x_m", "a_h")),
                     (f"route_Q_{c}_{way}", "m", f"coefficient {c} of the winding rope's least rise at the joints "
                                                 f"beyond the load, {words}", ("x_m", "a_h"))]
        rows += [(f"route_S_{c}_{way}", "m", f"coefficient {c} of the unwinding rope's least rise, {words}", ("a_h",))
                 for c in rn.UNWINDING]
    rows += [(f"route_A_{k}{i}", "m" if i == "0" else "1", f"Σ over [0, L_ul] of the {k} part, "
              + ("constant term" if i == "0" else "per metre of L_ul"), ()) for k in ("sin", "mo", "cp") for i in "01"]
    return ({r[0]: _number(*r[:3]) for r in rows}, {r[0]: r[3] for r in rows})


NUMBERS, FOLLOWS = _numbers()
#: the numbers of point A (built only where the scene gives L_ul)
POINT_A = tuple(n for n in NUMBERS if n.startswith("route_A_"))


def is_vector(n: int, effects: Mapping) -> bool:
    """Whether a route of ``n`` segments is held as route numbers: more than :data:`VECTOR_ABOVE`, and no chosen
    variant reads the segments one by one (``reads_route_profile``: the as-built elongation's integral)."""
    if n <= VECTOR_ABOVE:
        return False
    spec = REGISTRY[MODEL]
    return not any(getattr(spec[e].variants.get(v), "reads_route_profile", False) for e, v in effects.items()
                   if e in spec)


def quantities(point_A: bool) -> tuple[Quantity, ...]:
    return tuple(q for n, q in NUMBERS.items() if point_A or n not in POINT_A)


def equations(v, point_A: bool) -> list[Equation]:
    """Eq. (1)-(11) on a route from its numbers (Krauze et al. 2025; sums over the route, docs/physics.md §4)."""
    v["x_m"]  # noqa: B018 - the load's place: the numbers follow it per load case (ropemodel.envelope)
    G_m, q, mu_pl = v["G_m"], v["q_l"], v["mu_pl"]
    s_j, c_j = v["route_sin_j"], v["route_cos_j"]
    resistance = v["route_mo"] + mu_pl * v["route_cp"]
    eqs = [Equation("L_u", v["L_u"] - v["route_L_u"], SRC),
           Equation("G_ml", v["G_ml"] - G_m * s_j, f"eq. (1), {SRC}"),
           Equation("G_l", v["G_l"] - q * v["route_sin"], f"eq. (2), {SRC}"),
           Equation("G_mo", v["G_mo"] - G_m * c_j, f"eq. (5), {SRC}"),
           Equation("G_ls", v["G_ls"] - q * v["route_sin"], f"eq. (6), {SRC}"),
           Equation("T_m", v["T_m"] - v["mu_pm"] * G_m * c_j, f"eq. (7), {SRC}"),
           Equation("T_l", v["T_l"] - q * resistance, f"eq. (10), {SRC}"),
           Equation("T_ls", v["T_ls"] - q * (mu_pl * v["route_cos"]), f"eq. (11), {SRC}")]
    if point_A:
        A = v["L_ul"]
        sin2 = v["route_A_sin0"] + v["route_A_sin1"] * A
        res2 = (v["route_A_mo0"] + v["route_A_mo1"] * A) + mu_pl * (v["route_A_cp0"] + v["route_A_cp1"] * A)
        eqs += [Equation("G_l1", v["G_l1"] - q * (v["route_sin"] - sin2), f"eq. (3), {SRC}"),
                Equation("G_l2", v["G_l2"] - q * sin2, f"eq. (4), {SRC}"),
                Equation("T_l1", v["T_l1"] - q * (resistance - res2), f"eq. (8), {SRC}"),
                Equation("T_l2", v["T_l2"] - q * res2, f"eq. (9), {SRC}")]
    return eqs


def _rise(v, prefix: str, way: str, s: float, a):
    """A winding rise A + s (M + μ_pl C') + s (a/g) X from its coefficients ``route_<prefix>_<c>_<way>``."""
    c = {k: v[f"route_{prefix}_{k}_{way}"] for k in rn.WINDING}
    return c["A"] + s * (c["mo"] + v["mu_pl"] * c["cp"]) + s * (a / G_N) * c["X"]


def _drum_rises(v, s: float, a) -> tuple:
    """The winding and the unwinding rope's rises from the return sheave to the drum, G_0 and H_0 [m]."""
    L_u, mu_pl = v["route_L_u"], v["mu_pl"]
    G_0 = v["route_sin"] + s * (v["route_mo"] + mu_pl * v["route_cp"]) + s * (a / G_N) * L_u
    H_0 = v["route_sin"] - s * mu_pl * v["route_cos"] - s * (a / G_N) * L_u
    return G_0, H_0


def least_winding(v, way: str, s: float, a, F_end, q_l, load, between: bool = False):
    """The winding side's least tension [N] over the whole side, drum and return sheave included
    (:func:`ropemodel.papers.route.least_rope_tension` with the load's pull J = ``load``); ``between``: between
    its ends only.  From the route numbers: docs/physics.md §4."""
    x = fmin(v["x_m"], v["route_L_u"])
    loaded = F_end + q_l * _rise(v, "P", way, s, a) + load
    free = F_end + q_l * _rise(v, "Q", way, s, a)
    joints = fmin(if_else(v["route_before"], loaded, free), if_else(v["route_beyond"], free, loaded))
    own, plain = v["route_B_mo"] - v["route_mo_j"] * x, v["route_B_cp"] - v["route_cp_j"] * x
    beside_rise = ((v["route_B_A"] - v["route_sin_j"] * x) + s * (own + v["mu_pl"] * plain)
                   + s * (a / G_N) * (v["route_L_u"] - x))
    beside = F_end + q_l * beside_rise
    sides = fmin(if_else(x > 0.0, beside + load, beside), if_else(x < v["route_L_u"], beside, beside + load))
    inside = if_else(v["route_before"] + v["route_beyond"] > 0.0, fmin(joints, sides), sides)   # one segment: none
    if between:
        return inside
    return fmin(inside, F_end + fmin(q_l * _drum_rises(v, s, a)[0] + load, 0.0))


def least_unwinding(v, way: str, s: float, a, F_end, q_l, between: bool = False):
    """The unwinding side's least tension [N] over the whole side: F_end + q_l min(H_0, A − s μ_pl C − s (a/g) X,
    0) (its drum, its least inner joint, the return sheave); ``between``: its least inner joint only."""
    inside = F_end + q_l * (v[f"route_S_A_{way}"] - s * v["mu_pl"] * v[f"route_S_C_{way}"]
                            - s * (a / G_N) * v[f"route_S_X_{way}"])
    if between:
        return inside
    return fmin(inside, F_end + fmin(q_l * _drum_rises(v, s, a)[1], 0.0))


def derive(values: Mapping, acceleration, point_A: bool) -> dict:
    """The route numbers at ``values`` (SI: the segments by name, ``mu_pl``, ``x_m`` and ``a_h``, any of these
    four a numpy array over points, and ``L_ul`` where point A is given); ``acceleration(values)`` the a_h the
    forces include.  Arrays where any input is one."""
    arrays = {k: np.asarray(values[k], dtype=float) for k in ("x_m", "mu_pl", "L_ul") if k in values}
    a = np.asarray(acceleration(values), dtype=float)
    segments = RouteArrays.from_values(values, mu_pl=0.0)
    shape = np.broadcast_shapes(*(v.shape for v in arrays.values()), a.shape)
    sums = rn.route_sums(segments.L, segments.alpha, segments.mu_w, segments.own_mu)
    x = np.broadcast_to(arrays.get("x_m", np.inf), shape).ravel()
    mu_pl, a = np.broadcast_to(arrays["mu_pl"], shape).ravel(), np.broadcast_to(a, shape).ravel()
    out = {k: np.empty(x.size) for k in NUMBERS if point_A or k not in POINT_A}
    keys = np.stack([a, mu_pl], axis=1) if x.size else np.zeros((0, 2))
    for a_k, mu_k in np.unique(keys, axis=0):
        at = np.flatnonzero((a == a_k) & (mu_pl == mu_k))
        got = rn.places(sums, x[at], float(a_k), float(mu_k))
        for k in out:
            if k[6:] in got:
                out[k][at] = got[k[6:]]
    ends = sums["ends"]
    out.update({"route_L_u": ends[-1], "route_sin": sums["A"][0], "route_mo": sums["mo"][0],
                "route_cp": sums["cp"][0], "route_cos": sums["C"][0]})
    if point_A:
        L_ul = np.broadcast_to(arrays["L_ul"], shape).ravel()
        for A in np.unique(L_ul):
            split = rn.split_at(sums, float(A))
            for k, value in split.items():
                if f"route_{k}" in out:
                    out[f"route_{k}"][L_ul == A] = value
    if shape == ():
        return {k: float(np.asarray(v).ravel()[0]) for k, v in out.items()}
    return {k: np.broadcast_to(v, (x.size,)).reshape(shape) for k, v in out.items()}


def derive_through(values: Mapping, acceleration, point_A: bool, edges: Mapping) -> dict:
    """The route numbers at one point (SI numbers ``values``) as CasADi expressions of the segments' values named
    in ``edges`` (name -> its expression, e.g. a symbol): :func:`ropemodel.papers.route_numbers.through` at the
    indices :func:`derive` selects there.  A plain segment's mu_wi (μ_pl there) is not one of them."""
    import casadi as ca

    from ropemodel.effects.route_arrays import parse

    segments = RouteArrays.from_values(values, mu_pl=0.0)
    sums = rn.route_sums(segments.L, segments.alpha, segments.mu_w, segments.own_mu)
    got = rn.places(sums, np.array([float(values.get("x_m", np.inf))]), float(acceleration(values)),
                    float(values["mu_pl"]))
    kind = type(next(iter(edges.values()))) if edges else ca.MX          # SX or MX, as the values given
    columns = {f: kind(ca.DM(getattr(segments, f))) for f in ("L", "alpha", "mu_w")}
    for name, expr in edges.items():
        field, k = parse(name)  # type: ignore[misc]
        if field == "mu_w" and not segments.own_mu[k]:
            raise InputError(f"{name} is mu_pl on its segment (it gives no mu_winding of its own): vary mu_pl")
        unit = ca.DM.zeros(segments.n)
        unit[k] = 1.0
        columns[field] = columns[field] + unit * (expr - float(getattr(segments, field)[k]))
    L, alpha, mu = columns["L"], columns["alpha"], columns["mu_w"]
    split = rn.split_at(sums, float(values["L_ul"]))["jA"] if point_A else None
    out = {f"route_{k}": v for k, v in rn.through(L, alpha, mu, segments.own_mu, {k: np.ravel(v)[0] for k, v in
                                                                                  got.items()}, split).items()}
    c = ca.cos(alpha)
    own = ca.DM(segments.own_mu.astype(float))
    out.update({"route_L_u": ca.sum1(L), "route_sin": ca.sum1(L * ca.sin(alpha)), "route_mo": ca.sum1(L * own * mu * c),
                "route_cp": ca.sum1(L * (1.0 - own) * c), "route_cos": ca.sum1(L * c)})
    return {k: v for k, v in out.items() if k in NUMBERS and (point_A or k not in POINT_A)}
