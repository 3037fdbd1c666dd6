"""``ropemodel sweep SCENE --vary NAME=START:STOP:N ... -o FILE.csv|FILE.parquet``.

The points are the product of the ``--vary`` grids (START and STOP may carry
units: ``alpha_u=5deg:45deg:1000``; ``NAME=v1,v2,v3`` lists values), or the
rows of ``--points FILE`` (CSV or Parquet; columns are names in SI or
``"name [unit]"`` labels).  The output is checked and locked before any work
(a second writer of it is refused, exit 2), written in chunks, and appears only
complete.  Rerunning an interrupted sweep (Ctrl-C: exit 130; disk full: exit 1)
with the same arguments resumes it; rerunning a finished one says it is complete.
"""

from __future__ import annotations

import json
import sys
from typing import cast

from ropemodel.cli._common import (add_scene_arguments, assignments, named, scene_from_args, sizing_scene_from_args,
                                   warn_unread)
from ropemodel.errors import InputError

NAME = "sweep"
HELP = "evaluate a scene over grids or a table of points; write CSV or Parquet (resumable)"


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False)
    parser.add_argument("--vary", action="append", metavar="NAME=START:STOP:N", default=[],
                        help="a grid axis, e.g. alpha_u=5deg:45deg:1000 or G_m=300kN,467kN; "
                             "several --vary give their product")
    parser.add_argument("--points", metavar="FILE", help="CSV or Parquet table of points instead of --vary")
    parser.add_argument("--outputs", action="append", metavar="NAME[,NAME...]", default=[],
                        help="outputs to compute (default: all)")
    parser.add_argument("--given", action="append", metavar="NAME[=VALUE]", default=[],
                        help="an output taken as known (inverse sweep); its values come from --vary or VALUE")
    parser.add_argument("--find", action="append", metavar="NAME", default=[],
                        help="a parameter to solve for at every point, freed by a --given")
    parser.add_argument("-o", "--output", required=True, metavar="FILE", help="FILE.csv or FILE.parquet")
    parser.add_argument("--chunk-size", type=int, default=65536, help="points per chunk, 1 to 1e8 (default 65536)")
    parser.add_argument("--threads", type=int, default=None,
                        help="threads, a positive whole number (default: number of CPUs)")
    parser.add_argument("--backend", default="auto", choices=["auto", "casadi", "compiled"],
                        help="evaluation backend (default auto: compiled C if a compiler works)")
    parser.add_argument("--si", action="store_true", help="SI units in the columns (default: display units)")
    parser.add_argument("--mark-failures", action="store_true",
                        help="keep points without a valid solution (solved = false) instead of stopping")
    parser.add_argument("--restart", action="store_true",
                        help="discard an unfinished sweep instead of resuming, or recompute a finished one")
    parser.add_argument("--sizing", action="store_true",
                        help="at every point, the sizing optimum (d, F_nwl, stroke) instead of the outputs; "
                             "each optimisation warm-starts from its neighbour (not resumable)")
    parser.add_argument("--cold", action="store_true", help="with --sizing: no warm start")
    parser.add_argument("--dynamic", action="store_true",
                        help="with --sizing: the dynamic optimum (every check through start and stop in both "
                             "directions, each point verified by simulation; a scene with a transient)")
    parser.add_argument("--no-progress", action="store_true",
                        help="no progress bar, as --quiet (default: a bar on stderr when it is a terminal)")


def _names(items):
    return [n.strip() for item in items for n in item.split(",") if n.strip()]


def main(args) -> int:
    from ropemodel.progress import enabled
    from ropemodel.sweeps import read_points, sweep
    from ropemodel.sweeps.runner import SweepFile, SweepInterrupted

    vary = named(args.vary, "--vary", "NAME=START:STOP:N, e.g. alpha_u=5deg:45deg:1000")
    points = read_points(args.points) if args.points else None
    if points is not None and vary:
        raise InputError("give either --vary grids or --points FILE, not both")
    if args.dynamic and not args.sizing:
        raise InputError("--dynamic needs --sizing (a sweep of the dynamic sizing optimum)")
    if args.sizing:
        return _sizing(vary, points, args)
    scene = scene_from_args(args)
    outputs = _names(args.outputs) or None
    if outputs:
        scene.built.check_names(outputs, "output")
    warn_unread(scene, "this sweep", scene.built.inputs_of(outputs) if outputs else None)
    given: dict[str, str | None] = {g.strip(): None for g in args.given if "=" not in g}
    given.update(assignments([g for g in args.given if "=" in g], "--given"))
    try:
        written = sweep(scene, vary or None, outputs, points=points, given=given,
                        find=_names(args.find), out=args.output, chunk_size=args.chunk_size,
                        threads=args.threads, backend=args.backend, si=args.si,
                        errors="mark" if args.mark_failures else "raise",
                        progress=enabled(False if args.no_progress else None),
                        restart=args.restart, collect=False)
    except SweepInterrupted as exc:
        print(f"interrupted: {exc}", file=sys.stderr)
        return 130
    file = cast(SweepFile, written)             # collect=False: the output file, not a DataFrame
    _summary(file.path, args.json, file.rows, file.columns, file.status)
    return 0


def _summary(path, as_json: bool, rows: int, columns: list[str], status: str = "written") -> None:
    """One line (or JSON object) saying what the output holds (counted in the file before it was
    put in place, or found complete)."""
    if as_json:
        print(json.dumps({"output": str(path), "rows": rows, "columns": columns, "status": status}))
    elif status == "complete":
        print(f"already complete: {path} ({rows} points)")
    else:
        print(f"wrote {rows} points x {len(columns)} columns to {path}")


def _sizing(vary, points, args) -> int:
    """The sizing optimum at every point; the scene read as sizing reads it (no starting design needed)."""
    from optimisation.sweep import sizing_sweep
    from ropemodel.progress import enabled
    from ropemodel.sweeps.files import OutputLock, check_output, write_frame

    if args.given or args.find or args.outputs:
        raise InputError("--sizing computes d, F_nwl and stroke; it takes no --given, --find or --outputs")
    out = check_output(args.output)
    with OutputLock(out):
        scene = sizing_scene_from_args(args)
        try:
            if args.dynamic:
                from optimisation.dynamic.sweep import dynamic_sizing_sweep

                frame = dynamic_sizing_sweep(scene, vary or None, points=points,
                                             progress=enabled(False if args.no_progress else None))
            else:
                frame = sizing_sweep(scene, vary or None, points=points, warm=not args.cold,
                                     progress=enabled(False if args.no_progress else None))
        except KeyboardInterrupt:
            print("interrupted: nothing written (a sizing sweep is not resumable)", file=sys.stderr)
            return 130
        rows, columns = write_frame(frame, out)
    _summary(out, args.json, rows, columns)
    return 0
