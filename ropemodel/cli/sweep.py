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

from ropemodel.cli._common import (add_scene_arguments, assignments, name_list, named, refuse_without, scene_from_args,
                                   sizing_scene_from_args, warn_unread)
from ropemodel.errors import InputError, Problems

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
    parser.add_argument("--chunk-size", type=int, default=None, help="points per chunk, 1 to 1e8 (default 65536)")
    parser.add_argument("--threads", type=int, default=None,
                        help="threads, a positive whole number (default: number of CPUs)")
    parser.add_argument("--backend", default=None, choices=["auto", "casadi", "compiled"],
                        help="evaluation backend (default auto: compiled C if a compiler works)")
    parser.add_argument("--si", action="store_true", help="SI units in the columns (default: display units)")
    parser.add_argument("--mark-failures", action="store_true",
                        help="keep points without a valid solution (solved = false) instead of stopping")
    parser.add_argument("--restart", action="store_true",
                        help="discard an unfinished sweep instead of resuming, or recompute a finished one")
    parser.add_argument("--sizing", action="store_true",
                        help="at every point, the sizing optimum (the design the scene's machine declares) instead of "
                             "the outputs; each optimisation warm-starts from its neighbour (not resumable; with "
                             "--dynamic: in chunks of --chunk-size points, default 8, resumable)")
    parser.add_argument("--cold", action="store_true", help="with --sizing: no warm start")
    parser.add_argument("--dynamic", action="store_true",
                        help="with --sizing: the dynamic optimum (every check through start and stop in both "
                             "directions, each point verified by simulation; a scene with a transient)")
    parser.add_argument("--no-progress", action="store_true",
                        help="no progress bar, as --quiet (default: a bar on stderr when it is a terminal)")


def main(args) -> int:
    from ropemodel.progress import enabled
    from ropemodel.sweeps import CHUNK, read_points, sweep
    from ropemodel.sweeps.points import split_label
    from ropemodel.sweeps.runner import SweepFile, SweepInterrupted

    vary = named(args.vary, "--vary", "NAME=START:STOP:N, e.g. alpha_u=5deg:45deg:1000")
    if not args.sizing:
        refuse_without(args, "--sizing", "dynamic", "cold")
    points = read_points(args.points) if args.points else None
    if points is not None and vary:
        raise InputError("give either --vary grids or --points FILE, not both")
    if args.sizing:
        return _sizing(vary, points, args)
    given, find = _given(args.given), name_list(args.find, "--find", "q_lw")
    outputs = name_list(args.outputs, "--outputs", "F_C_up,dF_up") or None
    _check_roles(given, find, list(vary) + ([split_label(str(c))[0] for c in points.columns]
                                            if points is not None else []), outputs or [])
    scene = scene_from_args(args)
    if outputs:
        scene.built.check_names(outputs, "output")
    warn_unread(scene, "this sweep", scene.built.inputs_of(outputs) if outputs else None)
    try:
        written = sweep(scene, vary or None, outputs, points=points, given=given, find=find,
                        out=args.output, chunk_size=CHUNK if args.chunk_size is None else args.chunk_size,
                        threads=args.threads, backend=args.backend or "auto", si=args.si,
                        errors="mark" if args.mark_failures else "raise",
                        progress=enabled(False if args.no_progress else None),
                        restart=args.restart, collect=False)
    except SweepInterrupted as exc:
        print(f"interrupted: {exc}", file=sys.stderr)
        return 130
    file = cast(SweepFile, written)             # collect=False: the output file, not a DataFrame
    _summary(file.path, args.json, file.rows, file.columns, file.status)
    return 0


def _given(items) -> dict[str, str | None]:
    """``--given NAME`` (values from --vary or --points) and ``--given NAME=VALUE``, every mistake at once."""
    bare = [g for g in items if "=" not in g]
    given: dict[str, str | None] = {n: None for n in name_list(bare, "--given", "F_C_up")} if bare else {}
    for name, value in assignments([g for g in items if "=" in g], "--given").items():
        if name in given:
            raise InputError(f"--given {name} given twice")
        given[name] = value
    return given


def _check_roles(given: dict, find: list[str], varied: list[str], outputs: list[str]) -> None:
    """A name has one role: given a value, varied, found, or an output; every contradiction at once."""
    found = Problems()
    for name in outputs:
        if name in given or name in varied:
            flag = "--given" if name in given else "--vary/--points"
            found.add(f"--outputs {name} and {flag} {name}: {name} is an input of this sweep, not a result; leave "
                      f"it out of --outputs or out of {flag}")
    for name in given:
        if given[name] is not None and name in varied:
            found.add(f"--given {name}={given[name]} and --vary/--points {name} both give {name}'s values: give "
                      f"them once (--given {name} alone takes them from --vary or --points)")
    for name in find:
        if name in varied:
            found.add(f"--find {name} solves for {name} at every point, so it cannot also be varied: "
                      f"leave {name} out of --vary/--points, or out of --find")
        if name in given:
            found.add(f"--find {name} and --given {name}: a name is either known (--given) or solved for (--find)")
    found.raise_if_any()


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
        from ropemodel.machines.base import design_words

        raise InputError(f"--sizing computes the design ({design_words()}); it takes no --given, --find or "
                         "--outputs")
    chunked = ("chunk_size", "restart") if args.dynamic else ()
    for flag in ("chunk_size", "threads", "backend", "si", "mark_failures", "restart"):
        if getattr(args, flag) not in (None, False) and flag not in chunked:
            raise InputError(f"--{flag.replace('_', '-')} acts on a sweep of the outputs, not on --sizing (a sizing "
                             f"sweep is one optimisation per point, not chunked, not resumable; --sizing --dynamic "
                             f"takes --chunk-size and --restart): leave it out")
    if args.dynamic and args.cold:
        raise InputError("--cold acts on static --sizing only (--dynamic starts each point from its neighbour's "
                         "design, the first from the static one): leave --cold out")
    if args.dynamic:
        return _dynamic_sizing(vary, points, args)
    out = check_output(args.output)
    with OutputLock(out):
        scene = sizing_scene_from_args(args)
        try:
            frame = sizing_sweep(scene, vary or None, points=points, warm=not args.cold,
                                 progress=enabled(False if args.no_progress else None))
        except KeyboardInterrupt:
            print("interrupted: nothing written (a sizing sweep is not resumable)", file=sys.stderr)
            return 130
        rows, columns = write_frame(frame, out)
    _summary(out, args.json, rows, columns)
    return 0


def _dynamic_sizing(vary, points, args) -> int:
    """``--sizing --dynamic``: chunked and resumable (:func:`optimisation.dynamic.sweep.dynamic_sizing_sweep`)."""
    from optimisation.dynamic.sweep import CHUNK, dynamic_sizing_sweep
    from ropemodel.progress import enabled
    from ropemodel.sweeps.files import check_output
    from ropemodel.sweeps.runner import SweepInterrupted

    out = check_output(args.output)
    scene = sizing_scene_from_args(args, dynamic=True)
    try:
        frame = dynamic_sizing_sweep(scene, vary or None, points=points, out=out, restart=args.restart,
                                     chunk_size=CHUNK if args.chunk_size is None else args.chunk_size,
                                     progress=enabled(False if args.no_progress else None))
    except SweepInterrupted as exc:
        print(f"interrupted: {exc}", file=sys.stderr)
        return 130
    _summary(out, args.json, len(frame), list(frame.columns))
    return 0
