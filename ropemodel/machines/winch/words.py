"""The winch's checks in words (its declaration's ``words``, a :class:`ropemodel.views.checks.Vocabulary`):
what ``ropemodel size --dynamic`` prints and the report's "dynamic sizing" section shows for each check.

The checks through a manoeuvre are :data:`ropemodel.machines.winch.manoeuvres.CHECKS`; the static checks of
steady travel are :mod:`ropemodel.effects.winch_checks`'s (each per direction, ``_up``/``_down``; on a route
``@ place``).  Where the scene carries the dynamic slip factor ``n_slip_dynamic``, the grip checks through the
manoeuvres name it.
"""

from __future__ import annotations

from ropemodel.views.checks import Vocabulary, Words

#: the checks through a manoeuvre (:data:`ropemodel.machines.winch.manoeuvres.CHECKS`)
MANOEUVRE_WORDS = {
    "safety_margin": Words("rope force F_C <= F_min/n_rope", "rope force", "ratio"),
    "safety_margin_S": Words("rope force F_S <= F_min/n_rope", "rope force", "ratio"),
    "slip_margin_fwd": Words("drum grip F_S >= F_C/rho", "grip", "force"),
    "slip_margin_back": Words("drum grip F_C >= F_S/rho", "grip", "force"),
    "slack_margin": Words("unwinding rope F_S >= F_S_min", "taut", "force"),
    "taut_margin": Words("winding rope F_C >= F_S_min", "taut", "force"),
    "tension_margin": Words("every rope element T >= 0", "elements", "force"),
    "stroke_margin": Words("take-up z <= stroke", "stroke", "length"),
    "stroke_start_margin": Words("take-up z >= 0 (start stop)", "stroke", "length"),
}
#: the manoeuvres' grip checks in words where the design carries a dynamic slip factor ``n_slip_dynamic``
WITH_DYNAMIC_SLIP = {"slip_margin_fwd": "drum grip F_S >= n_slip_dynamic F_C/rho",
                     "slip_margin_back": "drum grip F_C >= n_slip_dynamic F_S/rho"}
#: the static checks of steady travel (each per direction, ``_up``/``_down``; on a route ``@ place``)
STATIC_WORDS = {
    "safety_margin": Words("rope force F_C <= F_min/n_rope", "rope force", "ratio"),
    "slip_margin": Words("drum grip with n_slip", "grip", "ratio"),
    "slack_margin": Words("unwinding rope F_S >= F_S_min", "taut", "force"),
    "taut_margin": Words("winding rope F_C >= F_S_min", "taut", "force"),
    "route_margin": Words("rope on the route >= F_S_min", "taut", "force", broad=True),    # the drum, sheave too
    "sheave_margin": Words("return sheave F_nwl/2 >= F_S_min", "taut", "force"),
    "stroke_margin": Words("take-up dF <= stroke", "stroke", "length"),
    "drum_margin": Words("drum D >= D_ratio_min d", "drum", "ratio"),
}
#: what a force check's discretisation error is an error of, where that is not the margin the table shows
#: (the rope's safety: the NLP's F_min - n_rope F, n_rope times the force's own error)
CONSTRAINT_WORDS = {"safety_margin": "of F_min - n_rope F_C", "safety_margin_S": "of F_min - n_rope F_S"}


def factors(scene) -> list[str]:
    """Which factor each check applies, with its rule (``scene.check_basis``): the rope's n_rope, steady
    travel's slip factor n_slip, and in the manoeuvres the dynamic slip factor ``n_slip_dynamic`` when the
    scene carries one, else none (the drum holds while rho F_S >= F_C)."""
    values = scene.parameters
    out = []
    for name, check, where in (("n_rope", "safety_margin", "rope force, every manoeuvre and steady travel"),
                               ("n_slip", "slip_margin", "drum grip in steady travel")):
        if name in values:
            out.append(f"{name} = {values[name]:g} ({where}): {scene.check_basis(check).split(': ', 1)[-1]}")
    if "n_slip_dynamic" in values:
        basis = scene.check_basis("slip_margin_fwd")
        basis = basis.split(": ", 1)[-1] if basis != "-" else scene.basis("n_slip_dynamic")
        out.append(f"n_slip_dynamic = {values['n_slip_dynamic']:g} (drum grip in the manoeuvres, rho F_S(t) >= "
                   f"n_slip_dynamic F_C(t) at every instant): {basis}")
    else:
        out.append("drum grip in the manoeuvres: no slip factor (the drum holds while rho F_S >= F_C at every "
                   "instant)")
    return out


WORDS = Vocabulary(manoeuvre=MANOEUVRE_WORDS, static=STATIC_WORDS, factors=factors,
                   steady="steady travel (static forces, both directions)",
                   with_factor={"n_slip_dynamic": WITH_DYNAMIC_SLIP}, constraint=CONSTRAINT_WORDS)
