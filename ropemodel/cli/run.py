"""``ropemodel run [SCENE] [--set NAME=VALUE ...] [--json]``: solve a scene forward."""

from __future__ import annotations

from ropemodel.cli._common import add_scene_arguments, scene_from_args

NAME = "run"
HELP = "compute every output of a scene (default: the built-in Fig. 9 example)"


def add_arguments(parser) -> None:
    add_scene_arguments(parser)


def main(args) -> int:
    from ropemodel.problem import run

    result = run(scene_from_args(args))
    print(result.to_json() if args.json else result.table())
    return 0
