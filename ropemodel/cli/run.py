"""``ropemodel run [SCENE] [--set NAME=VALUE ...] [--worst] [--json]``: solve a scene forward."""

from __future__ import annotations

from ropemodel.cli._common import add_scene_arguments, scene_from_args, warn_unread
from ropemodel.errors import InputError

NAME = "run"
HELP = "compute every output of a scene (default: the built-in Fig. 9 example)"


def add_arguments(parser) -> None:
    add_scene_arguments(parser)
    parser.add_argument("--worst", action="store_true",
                        help="on a route of segments: put the load where the upward winding force F_C_up is "
                             "largest (the rope's, the stroke's and the drive's worst case) instead of at x_m")


def main(args) -> int:
    from ropemodel.problem import run, worst_position

    scene = scene_from_args(args)
    warn_unread(scene, "run")
    if args.worst:
        if scene.effects.get("route") != "segments":
            raise InputError("--worst needs a route of segments ([effects] route = \"segments\"): on the paper's "
                             "straight route the forces do not depend on where the load is")
        scene = scene.with_values({"x_m": worst_position(scene)}, origin="--worst")
    result = run(scene)
    print(result.to_json() if args.json else result.table())
    return 0
