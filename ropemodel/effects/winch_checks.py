"""Design checks of the winch (effect ``checks``): every margin an output, both directions.

``none``    (default) no check is built.
``design``  margins (>= 0: the check passes):

    safety_margin_w = F_min / (n_rope · F_C_w) − 1     rope safety F_min / F_C >= n_rope
    slack_margin_w  = F_S_w − F_S_min        [N]       unwinding rope never slack
    taut_margin_w   = F_C_w − F_S_min        [N]       winding rope never slack (lowering on gentle slopes)
    stroke_margin_w = stroke − ΔF_w          [m]       tensioner stroke covers eq. (23)
    drum_margin     = D / (D_ratio_min · d) − 1         drum D >= D_ratio_min · d (d the rope diameter)

for each way of travel w in (up, down).  The no-slip check is the lining effect's ``slip_margin_w``.
Krauze et al. (2025) give eq. (23) (least stroke ΔF) and the rule D >= 30 d (their
introduction, "Drum diameter D is selected based on rope diameter d, ensuring
compliance with minimum conditions D >= 30d"): hence the default D_ratio_min = 30.
The safety factor n_rope has no default: it is set by the code of practice that
applies (mine haulage regulations differ by country and duty): typed, or given by
a rule set in the scene's [rules] (ropemodel.rules; the checks read their factors
the same way either way, and each check names where its factor comes from).
"""

from __future__ import annotations

from ropemodel.effects.base import Equation, Submodel, define_effect, register
from ropemodel.effects.winch import D_DRUM, DIRECTIONS, MODEL, STROKE, Q, per_direction
from ropemodel.effects.winch_rope import D_ROPE, F_MIN

SRC = "Krauze et al. 2025"

N_ROPE = Q("n_rope", "1", "required safety factor of the rope F_min / F_C", low=1.0, guess=5.0)

define_effect(MODEL, "checks", "none", "design checks with their margins: safety, slack, stroke, drum")

#: (margin name, check text, unit of the margin) in report order; slip comes from the lining effect
CHECKS = (
    ("safety_margin", "rope safety F_min/F_C >= n_rope", "1"),
    ("slip_margin", "no slip on the drum (lining effect)", "1"),
    ("slack_margin", "unwinding rope not slack F_S >= F_S_min", "N"),
    ("taut_margin", "winding rope not slack F_C >= F_S_min", "N"),
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
        Q("F_S_min", "N", "least tension allowed in either rope (unwinding F_S and winding F_C)", "kN", low=0.0,
          default=0.0, default_note="no least tension given: the ropes need only stay taut (> 0)"),
        STROKE,
        Q("D_ratio_min", "1", "least drum-to-rope diameter ratio D/d", low=1.0, default=30.0, symbol="(D/d)_min",
          equation=f"{SRC}, introduction: D >= 30 d"),
        *per_direction("safety_margin", "1", "margin of rope safety F_min/(n_rope F_C) - 1 (>= 0 passes)",
                       symbol="m_safety", equation="rope safety check, F_min / F_C ≥ n_rope (not in the paper)"),
        *per_direction("slack_margin", "N", "margin against a slack unwinding rope F_S - F_S_min (>= 0 passes)",
                       "kN", symbol="m_slack", equation="slack-rope check of the unwinding rope (not in the paper)"),
        *per_direction("taut_margin", "N", "margin against a slack winding rope F_C - F_S_min (>= 0 passes; "
                       "when lowering on a gentle slope the winding rope can go slack)", "kN", symbol="m_taut",
                       equation="slack-rope check of the winding rope (not in the paper)"),
        *per_direction("stroke_margin", "m", "stroke left over stroke - dF (>= 0 passes)", "mm", symbol="m_stroke",
                       equation=f"stroke - dF, {SRC} eq. (23)"),
        Q("drum_margin", "1", "margin of the drum D/(D_ratio_min d) - 1 (>= 0 passes)", symbol="m_drum",
          equation=f"D / (D_ratio_min d) - 1, {SRC} introduction"),
    )

    def equations(self, v):
        eqs = []
        for way in DIRECTIONS:
            eqs += [
                Equation(f"safety_margin_{way}",
                         v["n_rope"] * v[f"F_C_{way}"] * (v[f"safety_margin_{way}"] + 1.0) - v["F_min"],
                         "rope safety check, F_min / F_C ≥ n_rope (not in the paper)"),
                Equation(f"slack_margin_{way}", v[f"slack_margin_{way}"] - (v[f"F_S_{way}"] - v["F_S_min"]),
                         "slack-rope check of the unwinding rope (not in the paper)"),
                Equation(f"taut_margin_{way}", v[f"taut_margin_{way}"] - (v[f"F_C_{way}"] - v["F_S_min"]),
                         "slack-rope check of the winding rope (not in the paper)"),
                Equation(f"stroke_margin_{way}", v[f"stroke_margin_{way}"] - (v["stroke"] - v[f"dF_{way}"]),
                         "stroke check against eq. (23)"),
            ]
        eqs.append(Equation("drum_margin", v["D_ratio_min"] * v["d"] * (v["drum_margin"] + 1.0) - v["D"],
                            "drum check, the introduction's D ≥ 30 d with D_ratio_min"))
        return eqs

    def frames(self, values, scene):
        return {"design checks": checks_frame(values, scene.built.quantities, scene.check_basis)}


def checks_frame(values: dict, quantities: dict, basis=None):
    """Table of every margin present in ``values`` (a pandas DataFrame): check, direction, margin
    (display unit), pass/fail, and the rule its factor comes from (``basis(margin name) -> text``)."""
    import pandas as pd

    text = {base: t for base, t, _ in CHECKS}
    rows = []
    for n in margin_names(values):
        base, _, way = n.rpartition("_") if n.endswith(("_up", "_down")) else (n, "", "")
        q = quantities[n]
        unit = "-" if q.display_unit == "1" else q.display_unit
        rows.append({"check": text[base], "direction": way or "-", "margin": q.to_display(values[n]),
                     "unit": unit, "pass": "yes" if values[n] >= 0 else "NO", "rule": basis(n) if basis else "-"})
    return pd.DataFrame(rows, columns=["check", "direction", "margin", "unit", "pass", "rule"])
