"""``ropemodel solve SCENE --given NAME=VALUE ... --find NAME ... [--at x_m=...]``: the inverse problem.

Where the scene leaves the load's place or the manoeuvre open, each given output is met at its worst over
every place and manoeuvre (a margin given as 0: the answer passes everywhere), and the answer names the case
that governs it (:func:`ropemodel.envelope.solve`)."""

from __future__ import annotations

from ropemodel.cli._common import (add_at_argument, add_scene_arguments, assignments, name_list, warn_unread,
                                   worst_case_scene)
from ropemodel.errors import InputError

NAME = "solve"
HELP = "solve a scene for parameters (--find) from given outputs (--given)"


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False)
    add_at_argument(parser)
    parser.add_argument("--given", action="append", metavar="NAME=VALUE", default=[],
                        help="an output with a known value, e.g. dF_up=1000mm")
    parser.add_argument("--find", action="append", metavar="NAME", default=[],
                        help="a parameter to solve for, freed by a --given value")


def main(args) -> int:
    from ropemodel.envelope import solve

    given = assignments(args.given, "--given")
    find = name_list(args.find, "--find", "q_lw")
    if not given and not find:
        raise InputError("solve needs --given NAME=VALUE and --find NAME (use 'run' for the forward problem)")
    scene = worst_case_scene(args)
    warn_unread(scene, "solve", chosen={f: "solve finds it from the --given values" for f in find})
    result = solve(scene, given, find, bare="refuse")
    print(result.to_json() if args.json else result.table())
    return 0
