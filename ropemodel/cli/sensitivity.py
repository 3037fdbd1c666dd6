"""``ropemodel sensitivity SCENE``: elasticities table (``--json``, ``--plot FILE.png``) or Sobol indices.

Without ``--sobol``: the local elasticity ∂ln y/∂ln p of every output to every
input at the scene's point, by automatic differentiation.  With ``--sobol
NAME=LOW:HIGH ...``: global Sobol indices (first order S1, total ST) of the
outputs over uniform ranges of the named inputs (SALib); ``--sizing`` takes
the sizing optimum (d, F_nwl, stroke) as the outputs.
"""

from __future__ import annotations

import json
import math

from ropemodel.cli._common import (add_at_argument, add_scene_arguments, name_list, named, refuse_without,
                                   sizing_scene_from_args, warn_unread, worst_case_scene)
from ropemodel.errors import InputError
from ropemodel.progress import status

NAME = "sensitivity"
HELP = "which inputs matter: elasticities d ln y / d ln p (AD), or Sobol indices over ranges"


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=True)
    parser.add_argument("--outputs", action="append", metavar="NAME[,NAME...]", default=[],
                        help="outputs to analyse (default: all)")
    parser.add_argument("--parameters", action="append", metavar="NAME[,NAME...]", default=[],
                        help="inputs to differentiate by (default: all)")
    parser.add_argument("--plot", metavar="FILE.png", help="tornado chart of the elasticities")
    parser.add_argument("--sobol", action="append", metavar="NAME=LOW:HIGH", default=[],
                        help="a uniform range for Sobol indices, e.g. alpha_u=10deg:20deg (repeat per input)")
    parser.add_argument("--samples", type=int, default=None,
                        help="Sobol base samples N, a power of two >= 4 (N*(D+2) evaluations; default 1024)")
    parser.add_argument("--seed", type=int, default=None, help="seed of the Sobol sequence scrambling, 0 to 2**32 - 1")
    add_at_argument(parser)
    parser.add_argument("--sizing", action="store_true",
                        help="Sobol indices of the sizing optimum (the design the scene's machine declares) instead "
                             "of the outputs")


def _num(v):
    return None if isinstance(v, float) and math.isnan(v) else v


def main(args) -> int:
    from ropemodel.sensitivities import elasticities, sobol, sobol_indices, table, tornado
    from ropemodel.sensitivities.plot import check_plot
    from ropemodel.sensitivities.sobol import check_samples, check_seed, parse_range
    from ropemodel.sweeps.files import OutputLock

    ranges = named(args.sobol, "--sobol", "NAME=LOW:HIGH, e.g. alpha_u=10deg:20deg")
    outputs = name_list(args.outputs, "--outputs", "F_C_up,dF_up") or None
    parameters = name_list(args.parameters, "--parameters", "G_m,alpha_u") or None
    if ranges and args.plot is not None:
        raise InputError("--plot draws elasticities; it does not combine with --sobol")
    if ranges:
        if parameters:
            raise InputError("--parameters chooses the inputs of elasticities; with --sobol the inputs are the "
                             "--sobol ranges: leave --parameters out")
        if args.sizing and outputs:
            from ropemodel.machines.base import design_words

            raise InputError(f"--sizing analyses the design ({design_words()}); it takes no --outputs")
        args.samples = 1024 if args.samples is None else args.samples
        args.seed = 0 if args.seed is None else args.seed
        check_samples(args.samples, len(ranges))
        check_seed(args.seed)
    else:
        refuse_without(args, "--sobol ranges", "samples", "seed", "sizing")
    plot = check_plot(args.plot) if args.plot is not None else None   # before any work
    scene = sizing_scene_from_args(args) if args.sizing and ranges else worst_case_scene(args)
    if outputs:
        scene.built.check_names(outputs, "output")
    if not (args.sizing and ranges):
        warn_unread(scene, "sensitivity", scene.built.inputs_of(outputs) if outputs else None)
    if ranges:
        if args.sizing:
            from optimisation.sweep import sizing_function

            scene.built.check_names(ranges)
            q = scene.built.quantities
            with status(f"computing the Sobol indices of the sizing optimum ({args.samples} base samples)"):
                frame = sobol_indices(sizing_function(scene), {k: parse_range(k, v, q[k].unit)
                                                               for k, v in ranges.items()}, args.samples, args.seed)
        else:
            with status(f"computing the Sobol indices ({args.samples} base samples)"):
                frame = sobol(scene, ranges, outputs, args.samples, args.seed)
        if args.json:
            print(json.dumps([{k: _num(v) for k, v in r.items()} for r in frame.to_dict("records")], indent=1))
        else:
            print(f"Sobol indices, N = {args.samples} base samples (95 % bootstrap half-widths)")
            print(frame.to_string(index=False, float_format=lambda x: f"{x:.3f}", na_rep="-"))   # not defined: -
        return 0
    frame = elasticities(scene, outputs=outputs, parameters=parameters)
    if plot is not None:
        with OutputLock(plot):
            tornado(frame, outputs, path=plot, title=scene.name)
    if args.json:
        print(json.dumps([{k: _num(v) for k, v in r.items()} for r in frame.to_dict("records")], indent=1,
                         allow_nan=False))
    else:
        print(table(frame))
    return 0
