"""The four manoeuvres a winch is sized through, and the checks made through them.

A winch starts and stops in both directions: upward start, upward stop, downward start, downward
stop.  Each manoeuvre is the scene's transient (its ramp, rope model, tensioner, drum friction) with
``dynamics`` = ``"start"`` or ``"stop"`` and ``travel`` = ``"up"`` or ``"down"``, with the load at every
candidate position (:mod:`optimisation.dynamic.positions`).

The checks through a manoeuvre (:data:`CHECKS`, each ≥ 0 at every instant; docs/physics.md §2 and §6,
"Checks through a manoeuvre"):

* rope safety: the rope force at the drum's tangent points against the static check's rope safety,
  F_min − n_rope·F_C(t) ≥ 0 and the same for F_S(t) (the margin shown as F_min/(n_rope F) − 1);
* no slip on the drum with the dynamic slip factor n_dyn = ``n_slip_dynamic`` (the static checks use
  ``n_slip``): ρ F_S(t) ≥ n_dyn F_C(t) and ρ F_C(t) ≥ n_dyn F_S(t), written from the hybrid simulator's
  switching functions slip_fwd = F_S − F_C/ρ(F_S) and slip_back = F_C − F_S/ρ(F_C) as
  F_S − n_dyn F_C/ρ = n_dyn slip_fwd − (n_dyn − 1) F_S ≥ 0 and n_dyn slip_back − (n_dyn − 1) F_C ≥ 0 [N]
  (n_dyn = 1: the switching functions themselves, the onset of slip);
* unwinding rope taut, F_S(t) − F_S_min ≥ 0, and winding rope taut, F_C(t) − F_S_min ≥ 0 [N], as in
  static sizing; every element of the rope loop in tension, T_e(t) ≥ 0 [N] (the lumped rope model's
  validity; the simulator's terminal ``slack`` event);
* the tensioner within its stroke: stroke − z(t) ≥ 0 and z(t) ≥ 0 [m] (z the take-up, the paper's
  measure of stroke ΔF, eq. (23)).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ropemodel.effects.transient.contact import traction_of
from ropemodel.machines.base import DesignBox
from ropemodel.machines.base import ManoeuvreCheck as Check

#: (dynamics, travel) of each manoeuvre, in the order they are reported
ORDER = (("start", "up"), ("stop", "up"), ("start", "down"), ("stop", "down"))
#: the simulator's events that leave the smooth mode
EVENTS = ("slip_fwd", "slip_back", "stroke_end", "stroke_start", "slack", "torque_limit")
#: the parts of the transient whose leaving the smooth mode a check through the manoeuvre keeps from happening
#: while it holds: the drum contact's slip (the slip checks, rho F_slack >= n_slip_dynamic F_tight, n_slip_dynamic
#: >= 1) and the tensioner's stops (the stroke check); a torque-limited drive's limit has no check
#: (:func:`optimisation.dynamic.verify.verified` simulates every case of a transient with another such part)
CHECKED_MODES = ("drum_contact", "tensioner")
#: what ``size --dynamic`` does, in words
OBJECTIVE = "rope, pretension and stroke through four manoeuvres"
#: the manoeuvres in words: ``all`` of them (the progress and the verdict), what they are (``kinds``: ``size
#: --dynamic``'s title) and as travelled through (``through``: the report's introduction)
TEXT = {"all": "the four manoeuvres", "kinds": "start and stop in both directions",
        "through": "the start and stop of both directions of travel (four manoeuvres)"}


def _ratio(force):
    return lambda o, a: a["F_min"] / (a["n_rope"] * o[force]) - 1


def _slip(switch: str, slack: str):
    """(ρ F_slack − n_dyn F_tight)/ρ [N] from the switching function ``switch`` (F_slack − F_tight/ρ) and the
    slack side's force ``slack``: F_slack − n_dyn (F_slack − switch) = n_dyn switch − (n_dyn − 1) F_slack."""
    return lambda o, a: a["n_slip_dynamic"] * o[switch] - (a["n_slip_dynamic"] - 1.0) * o[slack]


CHECKS = (
    Check("safety_margin", "rope safety F_min/F_C(t) >= n_rope", "N", "1", "F_C",
          lambda o, a: a["F_min"] - a["n_rope"] * o["F_C"], _ratio("F_C")),
    Check("safety_margin_S", "rope safety F_min/F_S(t) >= n_rope", "N", "1", "F_S",
          lambda o, a: a["F_min"] - a["n_rope"] * o["F_S"], _ratio("F_S")),
    Check("slip_margin_fwd", "no slip, drum ahead: rho F_S(t) >= n_slip_dynamic F_C(t)", "N", "N", "slip_fwd",
          _slip("slip_fwd", "F_S"), _slip("slip_fwd", "F_S")),
    Check("slip_margin_back", "no slip, rope overruns: rho F_C(t) >= n_slip_dynamic F_S(t)", "N", "N", "slip_back",
          _slip("slip_back", "F_C"), _slip("slip_back", "F_C")),
    Check("slack_margin", "unwinding rope taut F_S(t) >= F_S_min", "N", "N", "F_S",
          lambda o, a: o["F_S"] - a["F_S_min"], lambda o, a: o["F_S"] - a["F_S_min"]),
    Check("taut_margin", "winding rope taut F_C(t) >= F_S_min", "N", "N", "F_C",
          lambda o, a: o["F_C"] - a["F_S_min"], lambda o, a: o["F_C"] - a["F_S_min"]),
    Check("tension_margin", "every rope element in tension T(t) >= 0", "N", "N", "T",
          lambda o, a: o["T"], lambda o, a: o["T"]),
    Check("stroke_margin", "take-up within the stroke z(t) <= stroke", "m", "m", "take_up",
          lambda o, a: a["stroke"] - o["take_up"], lambda o, a: a["stroke"] - o["take_up"]),
    Check("stroke_start_margin", "carriage off its start stop z(t) >= 0", "m", "m", "take_up",
          lambda o, a: o["take_up"], lambda o, a: o["take_up"]),
)
CHECK = {c.name: c for c in CHECKS}

#: what each check compares at an instant, (the force or take-up judged, its limit) in SI, from the same
#: series ``o`` and values ``a`` as its margin: the value and limit columns of the output
#: (:func:`optimisation.dynamic.manoeuvres.sides`, :mod:`ropemodel.views.checks`); a slip check's limit is
#: n_slip_dynamic times the switching function's (n_slip_dynamic F_C/rho, n_slip_dynamic F_S/rho), so that
#: value - limit is the margin :func:`_slip` gives
SIDES = {
    "safety_margin": (lambda o, a: o["F_C"], lambda o, a: a["F_min"] / a["n_rope"]),
    "safety_margin_S": (lambda o, a: o["F_S"], lambda o, a: a["F_min"] / a["n_rope"]),
    "slip_margin_fwd": (lambda o, a: o["F_S"], lambda o, a: a["n_slip_dynamic"] * (o["F_S"] - o["slip_fwd"])),
    "slip_margin_back": (lambda o, a: o["F_C"], lambda o, a: a["n_slip_dynamic"] * (o["F_C"] - o["slip_back"])),
    "slack_margin": (lambda o, a: o["F_S"], lambda o, a: a["F_S_min"]),
    "taut_margin": (lambda o, a: o["F_C"], lambda o, a: a["F_S_min"]),
    "tension_margin": (lambda o, a: o["T"], lambda o, a: 0.0),
    "stroke_margin": (lambda o, a: o["take_up"], lambda o, a: a["stroke"]),
    "stroke_start_margin": (lambda o, a: o["take_up"], lambda o, a: 0.0),
}


#: the slip factors, (parameter, the check it applies to), the static one first: recorded with a dynamic design
#: (``--json``'s ``slip_factors``, :func:`optimisation.dynamic.design.slip_factors`)
SLIP_FACTORS = (("n_slip", "static: rho F_S >= n_slip F_C in steady motion"),
                ("n_slip_dynamic", "dynamic: rho F_S(t) >= n_slip_dynamic F_C(t) through every manoeuvre"))


def completed(scene, design: dict) -> dict:
    """What a manoeuvre's scene needs that the scene leaves out: a rigid drum without a diameter, 40 d (its
    traction does not depend on it)."""
    return {"D": 40.0 * design["d"]} if "D" in scene.absent else {}


def values(problem, x_si, p) -> dict:
    """What the checks read besides the transient: F_min (the catalogue rope's), n_rope, n_slip_dynamic (1
    without a drum lining: no slip check), F_S_min, stroke."""
    xs = x_si / ca.DM(problem.x_scale)
    n_dyn = p[problem.params.index("n_slip_dynamic")] if "n_slip_dynamic" in problem.params else 1.0
    return {"F_min": problem.outputs(x=xs, p=p)["F_min"], "n_rope": p[problem.params.index("n_rope")],
            "n_slip_dynamic": n_dyn, "F_S_min": p[problem.params.index("F_S_min")], "stroke": x_si[2]}


def _top(problem, xs, p) -> float:
    """The pretension [N] the thickest catalogue rope's strength allows, F_min / n_rope: where the box's top
    search starts."""
    return problem.evaluate(xs, p)["F_min"] / p[problem.params.index("n_rope")]


#: the design box of the scan behind a "no design" (:mod:`optimisation.dynamic.scan`): every catalogue d; the
#: pretension F_nwl from 0 to where the static checks fail for every d; the stroke held at 100 m — the smooth
#: mode does not depend on the stroke (only the stroke's stops, events that leave it, do) and every check gains
#: from more of it (the stroke checks are stroke − z ≥ 0, eq. (23)), so a point without a design at this stroke
#: has none at any shorter one
BOX = DesignBox(catalogue="d", grid="F_nwl", held={"stroke": 100.0}, top=_top)


def series(sim) -> dict:
    """What the checks read of a simulated manoeuvre (:func:`ropemodel.dynamics.simulate`), over its history
    (SI): the same names as the smooth mode's outputs the NLP's checks read."""
    h = sim.history
    o = {"F_C": h["F_C [N]"].to_numpy(), "F_S": h["F_S [N]"].to_numpy()}
    if not sim.setup.chain.rigid:      # an inextensible rope: no element, no take-up (as the NLP's checks)
        o.update({"take_up": h["take_up [m]"].to_numpy(), "T": h["T_min [N]"].to_numpy()})
    ratio = traction_of(sim.setup)
    if ratio is not None:
        v = h["v_drum [m/s]"].to_numpy()
        o["slip_fwd"] = o["F_S"] - o["F_C"] / _rho(ratio, o["F_S"], v)
        o["slip_back"] = o["F_C"] - o["F_S"] / _rho(ratio, o["F_C"], v)
    return o


def _rho(ratio, force, speed) -> np.ndarray:
    """The lining's traction ratio at each sample (floats; a CasADi expression evaluated point by point)."""
    values = [ratio(float(f), float(v)) for f, v in zip(force, speed)]
    return np.array([float(ca.evalf(x)) if isinstance(x, (ca.SX, ca.MX)) else float(x) for x in values])


#: each peak a simulated manoeuvre records (:func:`peaks`) and which of two values is the worse: the worst over
#: the load's places is what the output shows of a manoeuvre (:func:`optimisation.dynamic.verify.by_manoeuvre`)
PEAKS = (("F_C_max", max), ("F_S_min", min), ("take_up_max", max), ("dynamic_factor", max))


def peaks(sim) -> dict:
    """What a simulated manoeuvre records besides its checks (SI): the peak winding-rope force F_C_max and its
    instant t_F_C_max, the least unwinding-rope force F_S_min, the largest take-up and the dynamic factor."""
    h, s = sim.history, sim.summary
    t = h["t [s]"].to_numpy()
    return {"F_C_max": s["F_C_max"], "F_S_min": s["F_S_min"], "take_up_max": float(h["take_up [m]"].max()),
            "dynamic_factor": s["dynamic_factor"], "t_F_C_max": float(t[int(np.argmax(h["F_C [N]"]))])}


def integration_peaks(problem, case, xs, p, t, o) -> dict:
    """:func:`peaks` of ``case`` (a manoeuvre at a place) read from the sizing NLP's integration of it at scaled
    design ``xs`` and parameters ``p`` (``t`` [s] and ``o``, its samples: one row each, a tension's least over the
    elements), for a case the hybrid simulator does not judge (:func:`optimisation.dynamic.verify.verified`); the
    dynamic factor against the steady force at the load's place (the NLP's static model, as the simulator's)."""
    i = int(np.argmax(o["F_C"]))
    F_C_static = problem.static_at(xs, p, case.x_m)[f"F_C_{case.travel}"]
    return {"F_C_max": float(o["F_C"][i]), "F_S_min": float(np.min(o["F_S"])),
            # an inextensible rope: the carriage does not move
            "take_up_max": float(np.max(o["take_up"])) if "take_up" in o else 0.0,
            "dynamic_factor": float(o["F_C"][i]) / F_C_static, "t_F_C_max": float(t[i])}


def peak_text(pk: dict) -> str:
    """A manoeuvre's worst peaks in words (``size --dynamic``'s title line of the manoeuvre)."""
    return (f"peak F_C {pk['F_C_max'] * 1e-3:.4g} kN (dynamic factor {pk['dynamic_factor']:.3g}), "
            f"least F_S {pk['F_S_min'] * 1e-3:.4g} kN, largest take-up {pk['take_up_max'] * 1e3:.4g} mm")


#: the report's columns of a manoeuvre's worst peaks: (heading, the cell from the peaks)
PEAK_COLUMNS = (("F_C max [kN]", lambda pk: f"{pk['F_C_max'] * 1e-3:.4g}"),
                ("F_S min [kN]", lambda pk: f"{pk['F_S_min'] * 1e-3:.4g}"),
                ("take-up max [m]", lambda pk: f"{pk['take_up_max']:.4g}"),
                ("dynamic factor [-]", lambda pk: f"{pk['dynamic_factor']:.3f}"))
