"""``ropemodel size SCENE [--set NAME=VALUE ...] [--discrete next-size-up|bonmin] [--dynamic [--find t_ramp]]
[--json]``.

Chooses the rope diameter d, the pretension F_nwl and the tensioner stroke (see the
``optimisation`` package): least rope mass per metre, then least pretension, then least
stroke, with every design check met in both directions.  Exit 0 with a design, 1 when
none exists (the report names the conflicting checks and by how much), 2 on bad input.
``--dynamic`` (or ``[numerics] sizing = "dynamic"`` in the scene): through the start-up and braking of both
directions (:mod:`ropemodel.cli._size_dynamic`).
"""

from __future__ import annotations

import json
import math

from ropemodel.cli._common import add_scene_arguments, sizing_scene_from_args
from ropemodel.errors import InputError
from ropemodel.progress import status

NAME = "size"
HELP = ("size the scene's machine: the lightest rope, then the rest of the design its machine declares, every check "
        "met")


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False, example="winch_sizing_fig9")
    parser.add_argument("--discrete", choices=("next-size-up", "bonmin"), default=None,
                        help="how to pick the catalogue diameter (default: next-size-up)")
    parser.add_argument("--dynamic", action="store_true",
                        help="size through start-up and braking in both directions (a scene with a transient); "
                             "the returned design verified by simulation")
    parser.add_argument("--find", metavar="NAME", default=None,
                        help="with --dynamic: t_ramp, the shortest ramp that keeps the scene's design safe")


def _num(v):
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {k: _num(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_num(x) for x in v]
    return v


def _rope_lines(design, q) -> list[str]:
    """The rope's EA and q_lw at the design and the elongation method the stroke comes from."""
    from ropemodel.effects import REGISTRY
    from ropemodel.machines.base import declared_machine

    lines = [f"{k:<12}{q[k].to_display(v):>14.6g}  {q[k].display_unit}" for k, v in design.rope.items()]
    variant = design.scene.effects.get("elongation")
    if variant:
        spec = REGISTRY[design.scene.built.name]["elongation"].variants[variant]
        lines.append(f"{declared_machine(design.scene).sizing.ELONGATION} = \"{variant}\": {spec.description}")
    return lines


def _held_lines(design) -> list[str]:
    """The transients a declared sizing simulated at the design, and the allowances they took."""
    if not design.verified:
        return []
    raised = {k: v for k, v in design.objective.items() if k.endswith("allowance") or "_allowance_" in k}
    lines = ["", "held in simulation (every trial design simulated; where one slipped, the rigid check's allowance "
                 "was raised: " + ", ".join(f"{k} = {v:.3g}" for k, v in raised.items()) + "):"]
    for r in design.verified:
        least = {k: v for k, v in r.items() if k.endswith("_min")}
        lines.append(f"  {r['transient']}: {'holds' if r['holds'] else 'SLIPS'}"
                     + "".join(f", {k} = {v / 1e3:.4g} kN" for k, v in least.items()))
    return lines


def _text(design) -> str:
    from ropemodel.envelope import where_text

    q = design.scene.built.quantities
    lines = [f"{design.scene.name}: sizing"]
    if design.continuous:
        lines.append("")
        lines.append(f"{'':<12}{'catalogue':>14}{'continuous':>14}")
        for k in design.continuous:     # the design variables
            cat = f"{q[k].to_display(design.design[k]):>14.6g}" if design.design else f"{'-':>14}"
            lines.append(f"{k:<12}{cat}{q[k].to_display(design.continuous[k]):>14.6g}  "
                         f"{'-' if q[k].display_unit == '1' else q[k].display_unit}")
        lines += [f"{k:<12}{q[k].to_display(v):>14.6g}{'':>14}  {q[k].display_unit}  (follows from the design)"
                  for k, v in (design.design or {}).items() if k not in design.continuous]
        if design.objective:
            o = design.objective
            lines += ["", f"minimised: {o['text']}", f"  {o['value']:.6g} kg at the design; per {o['integer']} "
                      f"enumerated (one continuous NLP each; those with a design): "
                      + ", ".join(f"{n}: {m:.6g} kg" for n, m in o["by_count"].items())]
        lines += _held_lines(design)
    if design.feasible:
        lines.append("")
        lines.append("active constraints:")
        lines += [f"  {a}" for a in design.active]
        for k, v in design.power.items():
            sign = q[k].sign_text(v)   # a drive power: motoring (> 0) or braking (< 0)
            lines.append(f"{k:<12}{q[k].to_display(v):>14.6g}  {q[k].display_unit}" + (f"  {sign}" if sign else "")
                         + "  (at its worst)")
        for kind, e in design.drive.items():
            lines.append(f"{'drive ' + kind:<16}{q['N_p_up'].to_display(e['value']):>10.6g}  "
                         f"{q['N_p_up'].display_unit}  (largest; {where_text(e['where'], direction=True)})")
        if design.least_drum is not None:
            lines.append(f"{'D_min':<12}{q['D'].to_display(design.least_drum):>14.6g}  {q['D'].display_unit}"
                         f"  (no drum diameter given: the least drum, D_ratio_min d)")
        lines += _rope_lines(design, q)
        lines.append("")
        lines.append(f"{'check margin':<22}{'value':>14}  {'unit':<6}{'':<6}where it is least; rule")
        for k, v in design.margins.items():
            c = q[k.split(" @ ")[0]]       # on a route: "slip_margin_up @ segment 2"
            unit = "-" if c.display_unit == "1" else c.display_unit
            shown = c.to_display(v) if abs(v) > 1e-9 else 0.0  # an active check prints as 0, not -8.9e-13
            lines.append(f"{k:<22}{shown:>14.6g}  {unit:<6}{'ok' if v >= -1e-9 else 'FAILS':<6}"
                         f"{where_text(design.governing.get(k))}; {design.scene.check_basis(k)}")
    lines.append("")
    lines.append(design.message)
    return "\n".join(lines)


def main(args) -> int:
    from optimisation.design import DEFAULT_DISCRETE, size
    from ropemodel.machines.base import declared_machine

    scene = sizing_scene_from_args(args, dynamic=None, declared_ok=True)
    if args.dynamic or scene.numerics.get("sizing") == "dynamic":
        from ropemodel.cli import _size_dynamic

        return _size_dynamic.main(scene, args, _num)
    if args.find is not None:
        raise InputError("--find needs --dynamic (size --dynamic --find t_ramp)")
    with status(f"sizing {scene.name}: {declared_machine(scene).sizing.CHOOSES}"):
        design = size(scene, method=args.discrete or DEFAULT_DISCRETE)
    if args.json:
        print(json.dumps(_num(design.to_dict()), indent=2, allow_nan=False))
    else:
        print(_text(design))
    return 0 if design.feasible else 1
