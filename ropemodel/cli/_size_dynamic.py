"""``ropemodel size SCENE --dynamic [--find t_ramp]``: sizing through start-up and braking.

``--dynamic``: d, F_nwl and stroke such that every check holds through the four manoeuvres (start and stop,
both directions; :mod:`optimisation.dynamic`), each design verified by the hybrid simulator.
``--dynamic --find t_ramp``: the shortest ramp that keeps the scene's design safe.  Exit 0 with an answer,
1 when none exists, 2 on bad input.
"""

from __future__ import annotations

import json

from ropemodel.progress import status

#: what ``--find`` can ask for with ``--dynamic``
FINDS = ("t_ramp",)


def _row(name, values, q) -> str:
    cells = "".join(f"{q[name].to_display(v):>14.6g}" if v is not None else f"{'-':>14}" for v in values)
    return f"{name:<12}{cells}  {q[name].display_unit}"


def _manoeuvre_lines(manoeuvres, q) -> list[str]:
    kN = 1e-3
    places = len(manoeuvres[0]["positions"]) if manoeuvres else 0
    lines = ["", f"each manoeuvre with the load at {places} place{'s' if places != 1 else ''} "
                 f"(the worst peaks of them; governed where its least margin is)",
             f"{'manoeuvre':<16}{'F_C max':>10}{'F_S min':>10}{'take-up max':>13}{'factor':>8}"
             "  governed with the load at",
             f"{'':<16}{'[kN]':>10}{'[kN]':>10}{'[m]':>13}{'[-]':>8}"]
    for m in manoeuvres:
        pk = m["peaks"]
        lines.append(f"{m['manoeuvre']:<16}{pk['F_C_max'] * kN:>10.4g}{pk['F_S_min'] * kN:>10.4g}"
                     f"{pk['take_up_max']:>13.4g}{pk['dynamic_factor']:>8.3g}  {m['where']}")
    return lines


def _places(manoeuvres) -> dict:
    """``"check @ manoeuvre"`` → where the load is at its least margin."""
    return {f"{name} @ {m['manoeuvre']}": least["where"] for m in manoeuvres
            for name, least in m["least_margins"].items()}


def _transient_lines(design) -> list[str]:
    effects = ", ".join(f"{e} = {v}" + ("" if chosen else " (default)") for e, (v, chosen) in design.transient.items())
    if design.transient.get("rope_elasticity", ("",))[0] == "segments":
        effects += f" with [numerics] segments = {design.scene.numerics['segments']} per span"
    lines = ["", f"transient: {effects}"]
    if design.defaults:
        lines += ["", "defaults used"] + [f"  {k}: {why}" for k, why in design.defaults.items()]
    return lines


def design_text(design) -> str:
    """The human output of a :class:`~optimisation.dynamic.DynamicDesign` (units stated)."""
    from optimisation.dynamic.manoeuvres import declared
    from ropemodel.machines.base import declared_machine

    CHECK = declared(design.scene).CHECK
    q = design.scene.built.quantities
    lines = [f"{design.scene.name}: dynamic sizing (start and stop in both directions, verified by simulation)"]
    if design.continuous:
        lines += ["", f"{'':<12}{'catalogue':>14}{'continuous':>14}{'static':>14}"]
        for k in declared_machine(design.scene).sizing.VARIABLES:
            lines.append(_row(k, [design.design[k] if design.design else None, design.continuous[k],
                                  (design.static or {}).get(k)], q))
    if design.feasible:
        lines += ["", "active constraints: " + ", ".join(design.active)]
        lines += _manoeuvre_lines(design.manoeuvres, q)
        places = _places(design.manoeuvres)
        lines += ["", f"{'check margin (least over the manoeuvre)':<52}{'value':>14}  {'unit':<6}{'':<6}rule"
                      "; where the load is"]
        for k, v in design.margins.items():
            base = k.split(" @ ")[0]
            if base in CHECK:   # a check through a manoeuvre, in the check's own unit
                unit, shown = CHECK[base].shown, v
            else:               # a static check (on a route: "@ segment 2"), as static sizing prints it
                unit, shown = q[base].display_unit, q[base].to_display(v)
            unit = "-" if unit == "1" else unit
            shown = shown if abs(v) > 1e-9 else 0.0     # an active check prints as 0, not -8.9e-13
            where = f"; load at {places[k]}" if k in places else ""
            lines.append(f"{k:<52}{shown:>14.6g}  {unit:<6}{'ok' if v >= -1e-9 else 'FAILS':<6}"
                         f"{design.scene.check_basis(base)}{where}")
    lines += _transient_lines(design)
    lines += ["", design.message]
    return "\n".join(lines)


def ramp_text(scene, answer) -> str:
    from optimisation.dynamic.verify import by_manoeuvre

    lines = [f"{scene.name}: the shortest start and stop ramp that keeps the design safe",
             "design: " + ", ".join(f"{k} = {scene.built.quantities[k].to_display(v):.6g} "
                                    f"{scene.built.quantities[k].display_unit}" for k, v in answer.design.items()),
             "", f"t_ramp = {answer.t_ramp:.6g} s  (verified by simulation: it holds; a shorter ramp fails "
             f"{', '.join(answer.active) or 'a check'})"]
    lines += _manoeuvre_lines(by_manoeuvre(answer.verdicts), scene.built.quantities)
    return "\n".join(lines)


def main(scene, args, to_json) -> int:
    """Run ``size --dynamic`` on the prepared ``scene``; ``to_json`` turns a dict into JSON-safe numbers."""
    from optimisation.dynamic import size_dynamic
    from optimisation.dynamic.manoeuvres import declared
    from optimisation.dynamic.ramp import shortest_ramp
    from ropemodel.errors import InputError

    if args.discrete is not None:
        raise InputError("--discrete chooses how static sizing picks the catalogue diameter; --dynamic picks the "
                         "next size up and verifies it by simulation: leave --discrete out")
    if args.find is not None:
        if args.find not in FINDS:
            raise InputError(f"--find {args.find!r}: with --dynamic it finds {', '.join(FINDS)}")
        with status(f"{scene.name}: the shortest ramp that keeps the design safe"):
            answer = shortest_ramp(scene)
        print(json.dumps(to_json(answer.to_dict()), indent=2, allow_nan=False) if args.json
              else ramp_text(scene, answer))
        return 0
    with status(f"dynamic sizing {scene.name}: {declared(scene).OBJECTIVE}") as line:
        design = size_dynamic(scene, with_sensitivities=True,
                              progress=lambda step: line.update(f"dynamic sizing {scene.name}: {step}"))
    print(json.dumps(to_json(design.to_dict()), indent=2, allow_nan=False) if args.json else design_text(design))
    return 0 if design.feasible else 1
