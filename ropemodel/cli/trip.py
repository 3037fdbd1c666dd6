"""``ropemodel trip SCENE [--direction up|down] [--json] [-o history.csv|parquet]``: a whole trip."""

from __future__ import annotations

from ropemodel.cli._common import add_scene_arguments, scene_from_args, warn, warn_unread
from ropemodel.errors import InputError

NAME = "trip"
HELP = ("a whole trip along the route: forces, drive power (> 0 motoring, < 0 braking), energy drawn while "
        "motoring and returned (or dissipated) while braking, RMS power, and what the scene's machine adds (the "
        "tensioner's travel needed)")


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False, example="trip_fig9")
    parser.add_argument("--direction", choices=("up", "down"), default=None,
                        help="the trip's direction (default: the scene's travel effect, else up)")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write the trip's history (SI, units in the column names) to FILE.csv or FILE.parquet")


def main(args) -> int:
    from ropemodel.progress import status
    from ropemodel.sweeps.files import OutputLock, check_output, write_frame
    from ropemodel.trips import prepare, reads, trip

    out = check_output(args.output) if args.output is not None else None
    scene = prepare(scene_from_args(args, announce=False))
    warn(scene.warnings)
    warn_unread(scene, "trip", *reads(scene))
    with status(f"trip of {scene.name}"):
        result = trip(scene, args.direction)
    if out is not None:
        with OutputLock(out):
            rows, columns = write_frame(result.history, out)
        if rows == 0:
            raise InputError(f"{out}: nothing to write")
    print(result.to_json() if args.json else result.report())
    return 0
