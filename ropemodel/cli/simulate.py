"""``ropemodel simulate SCENE [--set NAME=VALUE ...] [--json] [-o history.csv|parquet]``: a transient."""

from __future__ import annotations

from ropemodel.cli._common import add_scene_arguments, scene_from_args
from ropemodel.errors import InputError

NAME = "simulate"
HELP = ("simulate the transient the scene's dynamics effect chooses: a start-up (dynamics = \"start\"), a stop or "
        "a braking (\"stop\", \"braking\"; with elastic ropes where the scene's machine has them) or a whole trip "
        "(\"trip\"), as the scene's machine offers them")


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False, example="winch_start")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write the history (SI, units in the column names) to FILE.csv or FILE.parquet")


def main(args) -> int:
    from ropemodel.dynamics import simulate
    from ropemodel.sweeps.files import OutputLock, check_output, write_frame

    out = check_output(args.output) if args.output is not None else None   # checked before any work
    sim = simulate(scene_from_args(args))
    if out is not None:
        with OutputLock(out):
            rows, _ = write_frame(sim.history, out)
        if rows == 0:
            raise InputError(f"{out}: nothing to write")
    print(sim.to_json() if args.json else sim.report())
    return 0
