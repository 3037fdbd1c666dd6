"""``ropemodel simulate SCENE [--set NAME=VALUE ...] [--json] [-o history.csv|parquet]``: a transient."""

from __future__ import annotations

from pathlib import Path

from ropemodel.cli._common import add_scene_arguments, scene_from_args
from ropemodel.errors import InputError

NAME = "simulate"
HELP = "simulate the start-up or braking of a winch scene (dynamics = \"start\" or \"stop\")"


def _csv(frame, path):
    frame.to_csv(path, index=False)


def _parquet(frame, path):
    frame.to_parquet(path, index=False)


#: file suffix → writer of the history
WRITERS = {".csv": _csv, ".parquet": _parquet}


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False)
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write the history (SI, units in the column names) to FILE.csv or FILE.parquet")


def main(args) -> int:
    from ropemodel.dynamics import simulate

    writer = None
    if args.output:
        suffix = Path(args.output).suffix.lower()
        if suffix not in WRITERS:
            raise InputError(f"-o {args.output}: unknown format {suffix or '(none)'}; use .csv or .parquet")
        writer = WRITERS[suffix]
    sim = simulate(scene_from_args(args))
    if writer is not None:
        try:
            writer(sim.history, args.output)
        except OSError as exc:
            raise InputError(f"-o {args.output}: cannot write ({exc})") from None
    print(sim.to_json() if args.json else sim.report())
    return 0
