"""``ropemodel curve SCENE --to 100N [-n 201] [--from 0N] [--display] [--json | -o FILE.csv]``: load curve."""

from __future__ import annotations

import json

from ropemodel.cli._common import add_scene_arguments, scene_from_args
from ropemodel.errors import InputError

NAME = "curve"
HELP = "load curve of a capstan scene: K, delta_alpha, regime ... against F_T from 0 to --to"


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False)
    parser.add_argument("--to", required=True, metavar="F_MAX", help="largest load F_T with its unit, e.g. 100N")
    parser.add_argument("--from", dest="start", default="0 N", metavar="F_MIN", help="smallest load (default 0 N)")
    parser.add_argument("-n", type=int, default=201, help="number of loads (default 201)")
    parser.add_argument("--display", action="store_true", help="display units (N/mm, deg) instead of SI")
    parser.add_argument("-o", "--output", metavar="FILE.csv", help="write the curve as CSV instead of printing it")


def main(args) -> int:
    from ropemodel.capstan.curves import load_curve

    if args.json and args.output:
        raise InputError("curve: give either --json or -o FILE, not both")
    df = load_curve(scene_from_args(args), args.to, args.n, args.start, display=args.display)
    if args.output:
        try:
            df.to_csv(args.output, index=False)
        except OSError as exc:
            raise InputError(f"cannot write {args.output}: {exc}") from None
        print(f"wrote {len(df)} loads to {args.output}")
    elif args.json:
        print(json.dumps(df.to_dict(orient="records"), indent=2, allow_nan=False))
    else:
        print(df.to_string(index=False))
    return 0
