"""Design checks of the winch (effect ``checks``): every margin an output, both directions.

``none``    (default) no check is built.
``design``  margins (>= 0: the check passes):

    safety_margin_w = F_min / (n_rope · F_C_w) − 1     rope safety F_min / F_C >= n_rope
    slack_margin_w  = F_S_w − F_S_min        [N]       unwinding rope taut at the drum
    taut_margin_w   = F_C_w − F_S_min        [N]       winding rope taut at the drum (lowering on gentle slopes)
    route_margin_w  = min(F_S_least_w, F_C_least_w) − F_S_min  [N]   both ropes taut along the route
    sheave_margin   = F_nwl/2 − F_S_min      [N]       both ropes taut at the return sheave
    stroke_margin_w = stroke − ΔF_w          [m]       tensioner stroke covers eq. (23)
    drum_margin     = D / (D_ratio_min · d) − 1         drum D >= D_ratio_min · d (d the rope diameter)

for each way of travel w in (up, down).  The no-slip check is the lining effect's ``slip_margin_w``.
F_S_least_w and F_C_least_w are each rope side's least tension along the whole route, from the drum to the
return sheave, both included: at the drum, the route's joints, beside the load and the return sheave
(:func:`ropemodel.papers.route.least_rope_tension`, docs/physics.md §4).  On a gentle slope, in a dip or while a
lowering speeds up the tension can be least inside the route, far below the forces at the drum.  The tension
between two joints lies between theirs, so these are the least tension anywhere on each side, wherever the
route is cut.  route_margin holds them above F_S_min; where a side is least at an end it repeats that end's own
check (slack or taut at the drum, sheave at the return sheave): the sizing NLP then meets the same constraint
twice, as it meets the drum's checks in every place of the load, and keeps one of them in its active set
(:func:`optimisation.activeset.regular_subset`).
Krauze et al. (2025) give eq. (23) (least stroke ΔF) and the rule D >= 30 d (their
introduction, "Drum diameter D is selected based on rope diameter d, ensuring
compliance with minimum conditions D >= 30d"): hence the default D_ratio_min = 30.
The safety factor n_rope has no default: it is set by the code of practice that
applies (mine haulage regulations differ by country and duty): typed, or given by
a rule set in the scene's [rules] (ropemodel.rules; the checks read their factors
the same way either way, and each check names where its factor comes from).
"""

from __future__ import annotations

from typing import Any

from ropemodel._math import fmin
from ropemodel.effects import domains as dom
from ropemodel.effects import winch_route_vector as vec
from ropemodel.effects.base import Equation, Submodel, define_effect, register
from ropemodel.effects.transient.travel import X_M
from ropemodel.effects.winch import D_DRUM, DIRECTIONS, MODEL, STROKE, Q, per_direction, slack_masks, slack_reasons
from ropemodel.effects.winch_rope import D_ROPE, F_MIN
from ropemodel.papers import route as rt

SRC = "Krauze et al. 2025"
LEAST = "least tension along the side, docs/physics.md §4 (not in the paper)"
#: how a least tension is computed where its closed form is too long to show (a route of many segments)
LEAST_METHOD = ("the least of the side's tension at the drum, at every joint of the route, on either side of the "
                "load and at the return sheave, each F_nwl/2 plus the rope's weight and resistance summed piece by "
                "piece from the return sheave (docs/physics.md §4)")
LEAST_SENSE = ("least",)
LEAST_FORCES = ("F_S_least_up", "F_S_least_down", "F_C_least_up", "F_C_least_down")

N_ROPE = Q("n_rope", "1", "required safety factor of the rope F_min / F_C", guess=5.0, **dom.FACTOR)

define_effect(MODEL, "checks", "none", "design checks with their margins: safety, slack, stroke, drum")

#: (margin name, check text, unit of the margin) in report order; slip comes from the lining effect
CHECKS = (
    ("safety_margin", "rope safety F_min/F_C >= n_rope", "1"),
    ("slip_margin", "no slip on the drum (lining effect)", "1"),
    ("slack_margin", "unwinding rope not slack F_S >= F_S_min", "N"),
    ("taut_margin", "winding rope not slack F_C >= F_S_min", "N"),
    ("route_margin", "both ropes taut along the route: least tension >= F_S_min", "N"),
    ("sheave_margin", "both ropes taut at the return sheave: F_nwl/2 >= F_S_min", "N"),
    ("stroke_margin", "tensioner stroke >= dF", "m"),
    ("drum_margin", "drum D >= D_ratio_min d", "1"),
)


def margin_names(names) -> list[str]:
    """The margin outputs among ``names`` (every ``*_margin`` / ``*_margin_up|down``), report order."""
    out = []
    for base, _, _ in CHECKS:
        out += [n for n in (base, f"{base}_up", f"{base}_down") if n in names]
    return out


@register(MODEL, "checks", "none")
class NoChecks(Submodel):
    """Design checks off."""

    description = "no design checks"
    missing = ("No design checks (rope safety, slack rope, stroke, drum diameter): choose checks = \"design\".",)


@register(MODEL, "checks", "design")
class DesignChecks(Submodel):
    """Margins of the design checks, both directions of travel (see the module docstring).

    Ratio checks are written multiplied out (linear in the margin and the forces) so
    that the acausal core can also solve them backwards, e.g. ``--given
    safety_margin_up=0 --find G_m`` for the largest load.
    """

    description = "design checks: rope safety, slack rope, tensioner stroke, drum-to-rope ratio"
    citations = ("krauze2025", "en12385_4")
    quantities = (
        D_ROPE,
        F_MIN,
        D_DRUM,
        N_ROPE,
        Q("F_S_min", "N", "least tension allowed anywhere in either rope (drum to return sheave)", "kN", **dom.FORCE,
          default=0.0, default_note="no least tension given: the ropes need only stay taut (> 0)"),
        X_M,
        STROKE,
        Q("D_ratio_min", "1", "least drum-to-rope diameter ratio D/d", default=30.0, symbol="(D/d)_min",
          **dom.domain(1.0, 1e4, "at least 1 (a drum around its rope); rules ask 18 to 120"),
          equation=f"{SRC}, introduction: D >= 30 d"),
        *per_direction("F_S_least", "N", "least tension of the unwinding rope along the route, drum and return "
                       "sheave included (at its ends and joints)", "kN", symbol="F_S,least", equation=LEAST,
                       worst=LEAST_SENSE),
        *per_direction("F_C_least", "N", "least tension of the winding rope along the route, drum and return "
                       "sheave included (at its ends, joints and beside the load)", "kN", symbol="F_C,least",
                       equation=LEAST, worst=LEAST_SENSE),
        *per_direction("safety_margin", "1", "margin of rope safety F_min/(n_rope F_C) - 1 (>= 0 passes)",
                       symbol="m_safety", equation="rope safety check, F_min / F_C ≥ n_rope (not in the paper)",
                       worst=LEAST_SENSE),
        *per_direction("slack_margin", "N", "margin against a slack unwinding rope F_S - F_S_min (>= 0 passes)",
                       "kN", symbol="m_slack", equation="slack-rope check of the unwinding rope (not in the paper)",
                       worst=LEAST_SENSE),
        *per_direction("taut_margin", "N", "margin against a slack winding rope F_C - F_S_min (>= 0 passes; "
                       "when lowering on a gentle slope the winding rope can go slack)", "kN", symbol="m_taut",
                       equation="slack-rope check of the winding rope (not in the paper)", worst=LEAST_SENSE),
        *per_direction("route_margin", "N", "margin against a rope slack along the route min(F_S_least, "
                       "F_C_least) - F_S_min (>= 0 passes)", "kN", symbol="m_route",
                       equation="slack-rope check along the route, docs/physics.md §4 (not in the paper)",
                       worst=LEAST_SENSE),
        *per_direction("stroke_margin", "m", "stroke left over stroke - dF (>= 0 passes)", "mm", symbol="m_stroke",
                       equation=f"stroke - dF, {SRC} eq. (23)", worst=LEAST_SENSE),
        Q("sheave_margin", "N", "margin against a slack rope at the return sheave F_nwl/2 - F_S_min (>= 0 passes)",
          "kN", symbol="m_sheave", equation="slack-rope check at the return sheave (not in the paper)",
          worst=LEAST_SENSE),
        Q("drum_margin", "1", "margin of the drum D/(D_ratio_min d) - 1 (>= 0 passes)", symbol="m_drum",
          equation=f"D / (D_ratio_min d) - 1, {SRC} introduction", worst=LEAST_SENSE),
    )
    invalid_needs = LEAST_FORCES

    def equations(self, v):
        eqs = self._least_tensions(v)
        for way in DIRECTIONS:
            eqs += [
                Equation(f"safety_margin_{way}",
                         v["n_rope"] * v[f"F_C_{way}"] * (v[f"safety_margin_{way}"] + 1.0) - v["F_min"],
                         "rope safety check, F_min / F_C ≥ n_rope (not in the paper)"),
                Equation(f"slack_margin_{way}", v[f"slack_margin_{way}"] - (v[f"F_S_{way}"] - v["F_S_min"]),
                         "slack-rope check of the unwinding rope (not in the paper)"),
                Equation(f"taut_margin_{way}", v[f"taut_margin_{way}"] - (v[f"F_C_{way}"] - v["F_S_min"]),
                         "slack-rope check of the winding rope (not in the paper)"),
                Equation(f"route_margin_{way}", v[f"route_margin_{way}"] - self._route_margin(v, way),
                         "slack-rope check along the route, docs/physics.md §4 (not in the paper)"),
                Equation(f"stroke_margin_{way}", v[f"stroke_margin_{way}"] - (v["stroke"] - v[f"dF_{way}"]),
                         "stroke check against eq. (23)"),
            ]
        eqs.append(Equation("sheave_margin", v["sheave_margin"] - (0.5 * v["F_nwl"] - v["F_S_min"]),
                            "slack-rope check at the return sheave (not in the paper)"))
        eqs.append(Equation("drum_margin", v["D_ratio_min"] * v["d"] * (v["drum_margin"] + 1.0) - v["D"],
                            "drum check, the introduction's D ≥ 30 d with D_ratio_min"))
        return eqs

    def _least_tensions(self, v) -> list[Equation]:
        """F_S_least, F_C_least of each direction: the tension profile of each side along the route's pieces
        (the route effect's :meth:`profile`), with the inertia the forces include (docs/physics.md §4)."""
        a = _hook(self.sibling("inertia")).acceleration(v)
        F_end, q_l = 0.5 * v["F_nwl"], v["q_l"]
        if getattr(self.sibling("route"), "vector", False):       # a long route: its numbers per load case
            return _least_from_numbers(v, a, F_end, q_l)
        route = _hook(self.sibling("route")).profile(v)
        eqs = []
        slopes, mus = rt.as_column(route.inclinations), rt.as_column(route.mus)   # vector operations on a route
        for way, s in DIRECTIONS.items():
            unwind = rt.rope_gradient(slopes, v["mu_pl"], -s, a)
            wind = rt.rope_gradient(slopes, mus, s, a)
            pull = rt.load_pull(v["G_ml"], v["T_m"], v["G_m"], s, a)
            if len(route.lengths) > 1:     # one piece: the unwinding rope has nothing between its ends
                eqs.append(Equation(f"F_S_least_{way}", v[f"F_S_least_{way}"]
                                    - rt.least_rope_tension(F_end, q_l, route.lengths, unwind), LEAST,
                                    method=LEAST_METHOD))
            eqs.append(Equation(f"F_C_least_{way}", v[f"F_C_least_{way}"]
                                - rt.least_rope_tension(F_end, q_l, route.lengths, wind, v["x_m"], pull), LEAST,
                                method=LEAST_METHOD))
        return eqs

    def _route_margin(self, v, way: str):
        """min(F_S_least, F_C_least) − F_S_min, of the sides that have something between their ends."""
        least = v[f"F_C_least_{way}"]
        route = self.sibling("route")
        if getattr(route, "vector", False) or len(_hook(route).profile(v).lengths) > 1:
            least = fmin(v[f"F_S_least_{way}"], least)
        return least - v["F_S_min"]

    def invalid_needs_for(self, outputs):
        """The least tensions of the directions of ``outputs`` when each belongs to one, else all four."""
        ways = {o.rsplit("_", 1)[-1] for o in outputs}
        return LEAST_FORCES if not ways <= set(DIRECTIONS) else tuple(f for f in LEAST_FORCES
                                                                        if f.rsplit("_", 1)[-1] in ways)

    def invalid_mask(self, values):
        """A least tension <= 0: the rope would have to push inside the route (it is slack there)."""
        return slack_masks(values, LEAST_FORCES, " inside the route")

    def invalid(self, values):
        return slack_reasons(values, LEAST_FORCES, " inside the route")

    def frames(self, values, scene, where=None):
        return {"design checks": checks_frame(values, scene.built.quantities, scene.check_basis, where)}


def _least_from_numbers(v, a, F_end, q_l) -> list[Equation]:
    """F_S_least, F_C_least of each direction on a route held as route numbers (:mod:`.winch_route_vector`)."""
    eqs = []
    for way, s in DIRECTIONS.items():
        pull = rt.load_pull(v["G_ml"], v["T_m"], v["G_m"], s, a)
        eqs += [Equation(f"F_S_least_{way}", v[f"F_S_least_{way}"] - vec.least_unwinding(v, way, s, a, F_end, q_l),
                         LEAST, method=LEAST_METHOD),
                Equation(f"F_C_least_{way}", v[f"F_C_least_{way}"]
                         - vec.least_winding(v, way, s, a, F_end, q_l, pull), LEAST, method=LEAST_METHOD)]
    return eqs


def _hook(submodel) -> Any:
    """A sibling submodel, asked for a hook its effect's variants all have (``profile``, ``acceleration``)."""
    return submodel


def checks_frame(values: dict, quantities: dict, basis=None, where: dict | None = None):
    """Table of every margin present in ``values`` (a pandas DataFrame): check, direction, margin
    (display unit), pass/fail, the rule its factor comes from (``basis(margin name) -> text``) and, when
    ``where`` gives it (margin → text), where the margin is least."""
    import pandas as pd

    text = {base: t for base, t, _ in CHECKS}
    rows = []
    for n in margin_names(values):
        base, _, way = n.rpartition("_") if n.endswith(("_up", "_down")) else (n, "", "")
        q = quantities[n]
        unit = "-" if q.display_unit == "1" else q.display_unit
        rows.append({"check": text[base], "direction": way or "-", "margin": q.to_display(values[n]),
                     "unit": unit, "pass": "yes" if values[n] >= 0 else "NO", "rule": basis(n) if basis else "-",
                     "where": (where or {}).get(n, "")})
    columns = ["check", "direction", "margin", "unit", "pass", "rule"] + (["where"] if where else [])
    return pd.DataFrame(rows, columns=["check", "direction", "margin", "unit", "pass", "rule", "where"])[columns]
