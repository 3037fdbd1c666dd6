"""``ropemodel run [SCENE] [--set NAME=VALUE ...] [--at NAME=VALUE ...] [--json]``: solve a scene forward.

Where the scene leaves the load's place (``x_m``) open, or the manoeuvre (``a_h``, with the ramps' inertia),
each result is its worst over every place and manoeuvre, with where it governs (:mod:`ropemodel.envelope`);
``--at x_m=...`` (and ``--at a_h=...``) gives one point instead.
"""

from __future__ import annotations

import argparse

from ropemodel.cli._common import add_at_argument, add_scene_arguments, warn_unread, worst_case_scene
from ropemodel.errors import InputError

NAME = "run"
HELP = "compute every output of a scene (default: the built-in Fig. 9 example); on a route, each at its worst"
#: what replaced ``--worst`` (removed: the worst case is the default)
WORST_GONE = ("--worst is gone: run takes every result at its own worst place and manoeuvre by default, and says "
              "where; --at x_m=... gives one place of the load")


def add_arguments(parser) -> None:
    add_scene_arguments(parser)
    add_at_argument(parser)
    parser.add_argument("--worst", action="store_true", help=argparse.SUPPRESS)


def main(args) -> int:
    from ropemodel.envelope import run

    if args.worst:
        raise InputError(WORST_GONE)
    scene = worst_case_scene(args)
    warn_unread(scene, "run")
    result = run(scene)
    print(result.to_json() if args.json else result.table())
    return 0
