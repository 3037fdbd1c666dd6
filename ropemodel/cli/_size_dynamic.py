"""``ropemodel size SCENE --dynamic [--find t_ramp]``: sizing through start-up and braking.

``--dynamic``: d, F_nwl and stroke such that every check holds through the four manoeuvres (start and stop,
both directions; :mod:`optimisation.dynamic`), each design verified by the hybrid simulator.
``--dynamic --find t_ramp``: the shortest ramp that keeps the scene's design safe.  Exit 0 with an answer,
1 when none exists, 2 on bad input.
"""

from __future__ import annotations

import json
import textwrap

from ropemodel.progress import status
from ropemodel.machines.base import declared_machine

#: what ``--find`` can ask for with ``--dynamic``
FINDS = ("t_ramp",)
#: the longest line of prose (the transient, the defaults) on a terminal
WIDTH = 100


def _row(name, values, q) -> str:
    cells = "".join(f"{q[name].to_display(v):>14.6g}" if v is not None else f"{'-':>14}" for v in values)
    return f"{name:<12}{cells}  {q[name].display_unit}"


def _header(m: dict, peak_text) -> str:
    """A manoeuvre's title line: its worst peaks over every place of the load (``peak_text``: the machine's
    manoeuvres' words for them)."""
    return f"{m['manoeuvre']}: {peak_text(m['peaks'])}" + ("" if m.get("ok", True) else "  FAILS")


def checks_lines(groups, manoeuvres, places: int, scene) -> list[str]:
    """The checks table (:meth:`ropemodel.views.checks.Vocabulary.check_groups`): a title line per manoeuvre
    (its peaks) and steady travel, one row per check in words with value, limit, margin, instant and the load's
    place."""
    width = max((len(r.check) for _, rows in groups for r in rows), default=0) + 2
    peak_text = declared_machine(scene).manoeuvres.peak_text
    titles = {m["manoeuvre"]: _header(m, peak_text) for m in manoeuvres}
    lines = ["", f"checks, each at its least over the load's {places} place{'s' if places != 1 else ''} and "
                 "every instant of the manoeuvre",
             f"  {'check':<{width}}{'value':>11}{'limit':>12}{'margin':>14}{'at t':>10}  load at"]
    for title, rows in groups:
        lines.append(titles.get(title, title))
        lines += [(f"  {r.check:<{width}}{r.value:>11}{r.limit:>12}{r.margin:>14}{r.t:>10}  {r.where}"
                   + ("" if r.ok else "  FAILS")).rstrip() for r in rows]
    return lines


def _words(scene):
    """The checks of ``scene``'s machine in words (its declaration's ``words``)."""
    return declared_machine(scene).words


def _active_lines(active, scene) -> list[str]:
    return ["", "what fixes the design (active):"] + [f"  {_words(scene).readable(a, scene.parameters)}"
                                                      for a in active]


def _factor_lines(scene) -> list[str]:
    return [""] + [ln for i, x in enumerate(_words(scene).factors(scene))
                   for ln in textwrap.wrap(x, WIDTH, initial_indent="factors: " if i == 0 else " " * 9,
                                           subsequent_indent=" " * 11)]


def _transient_lines(design) -> list[str]:
    effects = ", ".join(f"{e} = {v}" + ("" if chosen else " (default)") for e, (v, chosen) in design.transient.items())
    if design.transient.get("rope_elasticity", ("",))[0] == "segments":
        effects += f" with {design.mesh.get('segments') or design.scene.numerics['segments']} elements per span"
    lines = ["", *textwrap.wrap(f"transient: {effects}", WIDTH, subsequent_indent="  ")]
    lines += textwrap.wrap(_words(design.scene).mesh_text(design.mesh, design.scene.parameters), WIDTH,
                           subsequent_indent="  ")
    if design.defaults:
        lines += ["", "defaults used"] + [ln for k, why in design.defaults.items()
                                          for ln in textwrap.wrap(f"{k}: {why}", WIDTH, initial_indent="  ",
                                                                  subsequent_indent="    ")]
    return lines


def design_text(design) -> str:
    """The human output of a :class:`~optimisation.dynamic.DynamicDesign`: the designs, what fixes them, the
    checks table grouped by manoeuvre in words and units (internal names only in ``--json``), the factors and
    their rules, the transient and the defaults it took."""
    q = design.scene.built.quantities
    kinds = declared_machine(design.scene).manoeuvres.TEXT["kinds"]
    lines = [f"{design.scene.name}: dynamic sizing ({kinds}, verified by simulation)"]
    if design.continuous:
        lines += ["", f"{'':<12}{'catalogue':>14}{'continuous':>14}{'static':>14}"]
        for k in declared_machine(design.scene).sizing.VARIABLES:
            lines.append(_row(k, [design.design[k] if design.design else None, design.continuous[k],
                                  (design.static or {}).get(k)], q))
    if design.feasible:
        places = len(design.manoeuvres[0]["positions"]) if design.manoeuvres else 0
        lines += _active_lines(design.active, design.scene)
        lines += checks_lines(_words(design.scene).check_groups(design), design.manoeuvres, places,
                              design.scene)
        lines += _factor_lines(design.scene)
    lines += _transient_lines(design)
    lines += ["", _words(design.scene).in_words(design.message, design.scene.parameters)]
    return "\n".join(lines)


def ramp_text(scene, answer) -> str:
    from optimisation.dynamic.verify import by_manoeuvre

    manoeuvres = by_manoeuvre(answer.verdicts)
    places = len(manoeuvres[0]["positions"]) if manoeuvres else 0
    words = _words(scene)
    fails = "; ".join(words.readable(a, scene.parameters) for a in answer.active) or "a check"
    lines = [f"{scene.name}: the shortest start and stop ramp that keeps the design safe",
             "design: " + ", ".join(f"{k} = {scene.built.quantities[k].to_display(v):.6g} "
                                    f"{scene.built.quantities[k].display_unit}" for k, v in answer.design.items()),
             "", f"t_ramp = {answer.t_ramp:.6g} s  (verified by simulation: it holds; a shorter ramp fails {fails})"]
    groups = [(m["manoeuvre"], words.manoeuvre_rows(m, parameters=scene.parameters)) for m in manoeuvres]
    return "\n".join(lines + checks_lines(groups, manoeuvres, places, scene) + _factor_lines(scene))


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
