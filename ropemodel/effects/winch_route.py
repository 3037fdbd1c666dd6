"""The route of a winch haulage (effect ``route``): where the weights and resistances of the paper come from.

``straight`` (default)  the paper's single incline of length ``L_u`` at ``alpha_u`` with point A at ``L_ul``:
                        Krauze et al. (2025) eq. (1)-(11).
``segments``            a route of straight segments, each a ``[[route]]`` table of the scene
                        (``length``, ``inclination``, optional ``mu_winding``), listed from the drive
                        toward the return sheave; ``L_u`` is their sum and the load is at ``x_m``.  The
                        paper's sums over the route (:mod:`ropemodel.papers.route`); one segment is the
                        paper's case 1, two of equal inclination its case 2.  The segments' values are
                        parameters ``L_1``, ``alpha_1``, ``mu_w1``, ``L_2``, … (so ``--set``, sweeps and
                        sensitivities reach them); a segment without ``mu_winding`` takes ``mu_pl``.
                        Point A is optional here: given ``L_ul``, the winding rope's weight and
                        resistance are also split there (G_l1, G_l2, T_l1, T_l2 of eq. (3), (4), (8), (9)).
"""

from __future__ import annotations

import functools
import math
from typing import Any, NamedTuple

import casadi as ca

from ropemodel.effects.base import Equation, Submodel, Symbols, register
from ropemodel.effects import domains as dom
from ropemodel.effects.transient.travel import X_M, beyond_route
from ropemodel.effects.winch import JUDGEMENT, MODEL, POSITIVE, ROPE_MU, SRC, Q, usual
from ropemodel.papers import krauze2025 as kr
from ropemodel.papers import route as rt
from ropemodel.effects import winch_route_vector as vec

INPUTS = (
        Q("G_m", "N", "weight of the transported load", "kN", guess=4e5,
          **usual(1e3, 5e6, f"{JUDGEMENT} (467 kN): from one light car to a heavy train"), **POSITIVE,
          **dom.FORCE_POSITIVE),
        Q("L_u", "m", "length of the inclined route", "m", guess=1000.0,
          **usual(20.0, 5000.0, f"{JUDGEMENT} (1150 m): rope-winch routes are tens of metres to a few km"),
          **POSITIVE, **dom.ROUTE_LENGTH),
        Q("L_ul", "m", "distance of point A from the guiding sheave K_K", "m", guess=500.0, **dom.ROUTE_POSITION),
        Q("alpha_u", "rad", "inclination of the route", "deg", **dom.INCLINATION, guess=0.3,
          **usual(-math.pi / 4, math.pi / 4,
                  f"{SRC}, introduction: rope winches serve workings inclined up to 45 deg")),
        Q("mu_pm", "1", "coefficient of resistance of the load", guess=0.05,
          **usual(0.005, 0.2, f"{JUDGEMENT} (0.05): mine cars roll at about 0.01, a sliding load up to 0.2"),
          **dom.RESISTANCE),
        Q("mu_pl", "1", "coefficient of resistance of the unwinding rope", guess=0.05, **ROPE_MU, **dom.RESISTANCE),
        Q("mu_pl1", "1", "coefficient of resistance of the winding rope from K_ZN to point A", guess=0.05,
          **ROPE_MU, **dom.RESISTANCE),
        Q("mu_pl2", "1", "coefficient of resistance of the winding rope from point A to the drive", guess=0.05,
          **ROPE_MU, **dom.RESISTANCE),
        Q("q_l", "N/m", "weight of the rope per metre", "kN/m", guess=80.0,
          **usual(1.0, 200.0, "EN 12385-4 ropes of 8 to 60 mm, q_l = g W d^2 (the paper's 42 mm rope: 0.08 kN/m)"),
          **POSITIVE, **dom.domain(1e-3, 1e5, "0.1 g/m (a 0.1-mm wire) to 10 t/m, ten times a 500-mm steel rope "
                                              "(g W d^2, about 10 kN/m)")),
)
OUTPUTS = (
        Q("G_ml", "N", "load weight along the incline", "kN", equation=f"{SRC}, eq. (1)"),
        Q("G_l1", "N", "weight along the incline of the winding rope from K_ZN to A", "kN", equation=f"{SRC}, eq. (3)"),
        Q("G_l2", "N", "weight along the incline of the winding rope from A to the drive", "kN",
          equation=f"{SRC}, eq. (4)"),
        Q("G_l", "N", "weight along the incline of the winding rope", "kN", equation=f"{SRC}, eq. (2)"),
        Q("G_mo", "N", "load weight normal to the incline", "kN", equation=f"{SRC}, eq. (5)"),
        Q("G_ls", "N", "weight along the incline of the unwinding rope", "kN", equation=f"{SRC}, eq. (6)"),
        Q("T_m", "N", "travel resistance of the load", "kN", equation=f"{SRC}, eq. (7)"),
        Q("T_l1", "N", "resistance of the winding rope from K_ZN to A", "kN", equation=f"{SRC}, eq. (8)"),
        Q("T_l2", "N", "resistance of the winding rope from A to the drive", "kN", equation=f"{SRC}, eq. (9)"),
        Q("T_l", "N", "resistance of the winding rope", "kN", equation=f"{SRC}, eq. (10)"),
        Q("T_ls", "N", "resistance of the unwinding rope", "kN", equation=f"{SRC}, eq. (11)"),
)
_Q = {q.name: q for q in INPUTS + OUTPUTS}


class Profile(NamedTuple):
    """The route as straight pieces from the drive: their lengths [m], inclinations [rad] and the winding
    rope's resistance coefficient on each [-] (symbols of the model, or numbers)."""

    lengths: list
    inclinations: list
    mus: list


@register(MODEL, "route", "straight")
class StraightRoute(Submodel):
    """The paper's route: one incline of length L_u at α_u, point A at L_ul, Krauze et al. (2025) eq. (1)-(11)."""

    description = "one straight incline (L_u, alpha_u), eq. (1)-(11)"
    assumptions = ("The route is one straight incline of length L_u at α_u, the rope lying along it.",)
    citations = ("krauze2025",)
    quantities = INPUTS + OUTPUTS

    def equations(self, v):
        a = v["alpha_u"]
        eqs = [
            Equation("G_ml", v["G_ml"] - kr.load_weight_along_incline(v["G_m"], a), "eq. (1)"),
            Equation("G_l1", v["G_l1"] - kr.rope_weight_along_incline(v["q_l"], v["L_u"] - v["L_ul"], a), "eq. (3)"),
            Equation("G_l2", v["G_l2"] - kr.rope_weight_along_incline(v["q_l"], v["L_ul"], a), "eq. (4)"),
            Equation("G_l", v["G_l"] - (v["G_l1"] + v["G_l2"]), "eq. (2)"),
            Equation("G_mo", v["G_mo"] - kr.load_weight_normal(v["G_m"], a), "eq. (5)"),
            Equation("G_ls", v["G_ls"] - kr.rope_weight_along_incline(v["q_l"], v["L_u"], a), "eq. (6)"),
            Equation("T_m", v["T_m"] - kr.load_resistance(v["mu_pm"], v["G_m"], a), "eq. (7)"),
            Equation("T_l1", v["T_l1"] - kr.rope_resistance(v["mu_pl1"], v["q_l"], v["L_u"] - v["L_ul"], a),
                     "eq. (8)"),
            Equation("T_l2", v["T_l2"] - kr.rope_resistance(v["mu_pl2"], v["q_l"], v["L_ul"], a), "eq. (9)"),
            Equation("T_l", v["T_l"] - (v["T_l1"] + v["T_l2"]), "eq. (10)"),
            Equation("T_ls", v["T_ls"] - kr.rope_resistance(v["mu_pl"], v["q_l"], v["L_u"], a), "eq. (11)"),
        ]
        return eqs

    def profile(self, v) -> Profile:
        """The incline as one piece, or, where the winding rope's resistance changes at point A (case 2), two
        pieces either side of it: μ_pl2 toward the drive, μ_pl1 beyond (eq. (17))."""
        if getattr(self.sibling("resistance"), "split_at_A", False):
            return Profile([v["L_ul"], v["L_u"] - v["L_ul"]], [v["alpha_u"]] * 2, [v["mu_pl2"], v["mu_pl1"]])
        return Profile([v["L_u"]], [v["alpha_u"]], [v["mu_pl1"]])

    def rules(self, values):
        out = beyond_route(values)
        if "L_ul" in values and "L_u" in values and values["L_ul"] > values["L_u"]:
            out.append(f"L_ul = {values['L_ul']:g} m is beyond L_u = {values['L_u']:g} m: point A must lie on the "
                       f"route, 0 <= L_ul <= L_u")
        return out


#: "L_1", "L_2", …: the segments' length names, made once (a route of 10 000 segments is read many times)
_LENGTH_NAMES: list[str] = []


def segment_lengths(values) -> list:
    """L_1, L_2, … of a route of segments, from a mapping of its values (none on a straight route)."""
    global _LENGTH_NAMES
    out: list = []
    names = _LENGTH_NAMES
    while True:
        if len(out) == len(names):     # a longer list, each entry still "L_<its index + 1>" (threads share it)
            names = _LENGTH_NAMES = [f"L_{i}" for i in range(1, 2 * len(out) + 2)]
        if names[len(out)] not in values:
            return out
        out.append(values[names[len(out)]])


@functools.lru_cache(maxsize=1 << 16)     # Quantity is frozen: a route of 10 000 segments declares them once
def segment_quantities(i: int, has_mu: bool) -> tuple:
    """The parameters of segment ``i`` (1 = at the drive): ``L_i``, ``alpha_i``, ``mu_wi``."""
    return (
        Q(f"L_{i}", "m", f"length of route segment {i} (segments counted from the drive)", "m", guess=500.0,
          **usual(1.0, 5000.0, f"{JUDGEMENT}: a segment of a rope-winch route"), **POSITIVE, **dom.ROUTE_LENGTH),
        Q(f"alpha_{i}", "rad", f"inclination of route segment {i} (> 0: rising toward the drive)", "deg",
          **dom.INCLINATION, guess=0.3,
          **usual(-math.pi / 4, math.pi / 4, f"{SRC}, introduction: workings inclined up to 45 deg")),
        Q(f"mu_w{i}", "1", f"resistance coefficient of the winding rope in route segment {i}"
          + ("" if has_mu else " (not given: mu_pl)"), guess=0.05, **ROPE_MU, **dom.RESISTANCE,
          equation="" if has_mu else "route segment without mu_winding: mu_pl"),
    )


@register(MODEL, "route", "segments")
class SegmentedRoute(Submodel):
    """A route of straight segments (``[[route]]`` tables), the load at ``x_m``: :mod:`ropemodel.papers.route`.

    ``x_m`` not given (:data:`ropemodel.effects.transient.travel.X_M`) is every place on the route: the
    commands take each result at its worst (:mod:`ropemodel.envelope`); evaluated at one point, the load is
    then on the last segment.

    Builds L_u = Σ L_i, the load's weight and resistance on its segment (eq. (1), (5), (7)) and the
    sums over the route of the rope's weight and resistance (eq. (2), (6), (10), (11)); the forces
    follow by eq. (12)-(14).  The structure (number of segments, which give ``mu_winding``) is the
    option ``route``: a tuple of booleans, one per segment.
    """

    description = "a route of straight segments, the load at x_m"
    assumptions = ("The route is a chain of straight segments, the rope lying along each; the forces are those "
                   "with the load at x_m.",)
    citations = ("krauze2025",)
    quantities = (*INPUTS, *OUTPUTS, X_M)

    def __init__(self, options=None, effects=None):
        super().__init__(options, effects)
        # a model built without a scene's [[route]] (e.g. to list its quantities) gets one segment
        self.segments = tuple(self.options.get("route") or (False,))
        #: point A given (L_ul in the scene): the winding rope is also split there (eq. (3), (4), (8), (9))
        self.point_A = bool(self.options.get("point_A"))
        edges = tuple(q for i, has in enumerate(self.segments, start=1) for q in segment_quantities(i, has))
        self.quantities = self.quantities + edges
        #: a long route is held as route numbers per load case (:mod:`ropemodel.effects.winch_route_vector`): its
        #: segments' values are then the scene's parameters at the edges (``edges``), not the model's symbols, and
        #: the numbers (``derived``: name -> the case inputs it follows) are computed by :meth:`derive`
        self.vector = vec.is_vector(len(self.segments), self.effects)
        self.edges: tuple[str, ...] = ()
        self.derived: dict[str, tuple[str, ...]] = {}
        if self.vector:
            numbers = vec.quantities(self.point_A)
            self.quantities = self.quantities + numbers
            self.edges = tuple(q.name for q in edges)
            self.derived = {q.name: vec.FOLLOWS[q.name] for q in numbers}
        #: the transient takes the segments' lengths as numbers (:meth:`transient_route`: where the rope's
        #: elements and the load are), so they fix its structure
        self.transient_structural = tuple(f"L_{i}" for i in range(1, len(self.segments) + 1))

    def equations(self, v):
        if self.vector:
            return vec.equations(v, self.point_A)
        n = len(self.segments)
        L, alpha, mu = self.profile(v)
        x, G_m = v["x_m"], v["G_m"]
        src = "route of segments"
        plain = [i for i, has in enumerate(self.segments, start=1) if not has]
        residuals = ca.vertsplit(ca.vertcat(*[v[f"mu_w{i}"] for i in plain]) - v["mu_pl"]) if plain else []
        eqs = [Equation(f"mu_w{i}", r, "mu_winding not given: mu_pl") for i, r in zip(plain, residuals)]
        if self.point_A:
            A, q = v["L_ul"], v["q_l"]
            eqs += [Equation("G_l1", v["G_l1"] - rt.rope_weight_between(q, L, alpha, A, v["L_u"]), f"eq. (3), {src}"),
                    Equation("G_l2", v["G_l2"] - rt.rope_weight_between(q, L, alpha, 0.0, A), f"eq. (4), {src}"),
                    Equation("T_l1", v["T_l1"] - rt.rope_resistance_between(q, L, alpha, mu, A, v["L_u"]),
                             f"eq. (8), {src}"),
                    Equation("T_l2", v["T_l2"] - rt.rope_resistance_between(q, L, alpha, mu, 0.0, A),
                             f"eq. (9), {src}")]
        # the load's segment's inclination α_j, looked up once for eq. (1), (5), (7) (each lookup passes every
        # segment: on a long route, three would triple the work at each place of the load)
        a_j = rt.at_position(x, L, alpha)
        return eqs + [
            Equation("L_u", v["L_u"] - rt.route_length(L), src),
            Equation("G_ml", v["G_ml"] - kr.load_weight_along_incline(G_m, a_j), f"eq. (1), {src}"),
            Equation("G_l", v["G_l"] - rt.rope_weight_along_route(v["q_l"], L, alpha), f"eq. (2), {src}"),
            Equation("G_mo", v["G_mo"] - kr.load_weight_normal(G_m, a_j), f"eq. (5), {src}"),
            Equation("G_ls", v["G_ls"] - rt.rope_weight_along_route(v["q_l"], L, alpha), f"eq. (6), {src}"),
            Equation("T_m", v["T_m"] - kr.load_resistance(v["mu_pm"], G_m, a_j), f"eq. (7), {src}"),
            Equation("T_l", v["T_l"] - rt.rope_resistance_along_route(v["q_l"], L, alpha, mu), f"eq. (10), {src}"),
            Equation("T_ls", v["T_ls"] - rt.rope_resistance_along_route(v["q_l"], L, alpha, [v["mu_pl"]] * n),
                     f"eq. (11), {src}"),
        ]

    def profile(self, v) -> Profile:
        """The segments: L_i, α_i, μ_wi; of the model's symbols (:class:`Symbols`), the same lists each time (their
        columns are made once: :func:`ropemodel.papers.route_vector.column`)."""
        if self.vector:
            raise RuntimeError("a route held as route numbers has no profile of symbols (winch_route_vector)")
        kept = self.__dict__.get("_profile")
        if kept is not None and kept[0] is v:
            return kept[1]
        n = range(1, len(self.segments) + 1)
        out = Profile([v[f"L_{i}"] for i in n], [v[f"alpha_{i}"] for i in n], [v[f"mu_w{i}"] for i in n])
        if isinstance(v, Symbols):       # only ever grows: the lists stay the model's
            self.__dict__["_profile"] = (v, out)
        return out

    def derive(self, values) -> dict:
        """The route numbers at ``values`` (SI; arrays over points allowed): :func:`.winch_route_vector.derive`."""
        inertia: Any = self.sibling("inertia")
        return vec.derive(values, inertia.acceleration, self.point_A)

    def derive_through(self, values, edges) -> dict:
        """The route numbers at one point as expressions of the segments' values ``edges`` (name -> expression):
        :func:`.winch_route_vector.derive_through` (a sensitivity in a segment's value)."""
        inertia: Any = self.sibling("inertia")
        return vec.derive_through(values, inertia.acceleration, self.point_A, edges)

    def transient_route(self, values: dict, numbers: dict):
        """The route as the transient's rope model asks it (:class:`ropemodel.effects.transient.route.Segments`):
        lengths as numbers (geometry), inclinations and coefficients as the values (may be symbols; a segment
        without mu_winding: mu_pl, which a route held as route numbers does not list per segment)."""
        from ropemodel.effects.transient.route import Segments

        n = range(1, len(self.segments) + 1)
        return Segments(values, [float(numbers[f"L_{i}"]) for i in n], [values[f"alpha_{i}"] for i in n],
                        [values["mu_pl"] if self.vector and f"mu_w{i}" not in values else values[f"mu_w{i}"]
                         for i in n])

    def rules(self, values):
        lengths = [values.get(f"L_{i}") for i in range(1, len(self.segments) + 1)]
        if any(v is None for v in lengths):
            return []
        total, out = sum(lengths), []
        for name, what in (("x_m", "the load"), ("L_ul", "point A")):
            # x_m not given (inf): anywhere on the route
            if name in values and math.isfinite(values[name]) and not 0.0 <= values[name] <= total:
                out.append(f"{name} = {values[name]:g} m is beyond the route: {what} must be on it, 0 <= {name} <= "
                           f"L_u = {total:g} m (the sum of the segments)")
        return out
