"""``ropemodel curve SCENE --to 100N [-n 201] [--from 0N] [--display] [--json | -o FILE.csv]``: load curve."""

from __future__ import annotations

import json

from ropemodel.cli._common import add_scene_arguments, scene_from_args, warn_unread
from ropemodel.errors import InputError

NAME = "curve"
HELP = "load curve of a capstan scene: K, delta_alpha, regime ... against F_T from 0 to --to"


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False, example="capstan_li_experiment")
    parser.add_argument("--to", required=True, metavar="F_MAX", help="largest load F_T with its unit, e.g. 100N")
    parser.add_argument("--from", dest="start", default="0 N", metavar="F_MIN", help="smallest load (default 0 N)")
    parser.add_argument("-n", type=int, default=201, help="number of loads (default 201)")
    parser.add_argument("--display", action="store_true", help="display units (N/mm, deg) instead of SI")
    parser.add_argument("-o", "--output", metavar="FILE.csv",
                        help="write the curve to FILE.csv or FILE.parquet instead of printing it")


def main(args) -> int:
    from contextlib import nullcontext

    from ropemodel.capstan.curves import load_curve, reads
    from ropemodel.sweeps.files import OutputLock, check_output, write_frame

    if args.json and args.output is not None:
        raise InputError("curve: give either --json or -o FILE, not both")
    out = check_output(args.output) if args.output is not None else None   # before any work
    with OutputLock(out) if out is not None else nullcontext():
        scene = scene_from_args(args)
        warn_unread(scene, "curve", *reads(scene))
        df = load_curve(scene, args.to, args.n, args.start, display=args.display)
        if out is not None:
            rows, _ = write_frame(df, out)
            print(f"wrote {rows} loads to {out}")
            return 0
    if args.json:
        print(json.dumps(df.to_dict(orient="records"), indent=2, allow_nan=False))
    else:
        print(df.to_string(index=False))
    return 0
