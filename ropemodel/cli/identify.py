"""``ropemodel identify SCENE DATA.csv [--fit mu,EA] [--sigma 0.01deg] [--json]``: fit μ, EA to test data."""

from __future__ import annotations

import json

from ropemodel.cli._common import add_scene_arguments, name_list, scene_from_args, warn_unread
from ropemodel.errors import SolveError
from ropemodel.progress import status
from ropemodel.units import to_si

NAME = "identify"
HELP = ("fit mu and EA (optionally F_p, L) of a capstan scene to measured loads and rotations "
        "(CSV columns 'F_T [N]' or 'T [N*m]', and 'delta_alpha [deg]')")


def add_arguments(parser) -> None:
    add_scene_arguments(parser, optional=False, example="capstan_li_experiment")
    parser.add_argument("data", help="CSV file with columns F_T (or T) and delta_alpha, units in brackets")
    parser.add_argument("--fit", default="mu,EA", help="parameters to fit, comma-separated (default mu,EA)")
    parser.add_argument("--sigma", help="known noise of delta_alpha, > 0 with its unit, e.g. 0.01deg "
                                        "(default: from the residuals)")


def main(args) -> int:
    from ropemodel.capstan.identify import CONVERGED, identify, reads

    sigma = to_si("--sigma", args.sigma, "rad", "deg") if args.sigma is not None else None
    scene = scene_from_args(args)
    fit = name_list(args.fit, "--fit", "mu,EA")
    warn_unread(scene, "identify", *reads(scene, fit))
    with status(f"identifying {', '.join(fit)} from {args.data}"):
        res = identify(scene, args.data, fit, sigma=sigma)
    if res.status not in CONVERGED:   # no estimates from a fit that did not converge
        raise SolveError(f"identification did not converge: IPOPT {res.status} after {res.iterations} iterations; "
                         f"no estimates are reported")
    if not any(res.identifiable.values()):   # nothing identified: no estimate is a result
        raise SolveError(f"the data determine none of {', '.join(fit)} ({res.messages[0]}); "
                         f"no estimates are reported")
    if args.json:
        print(json.dumps(res.to_dict(), indent=2, allow_nan=False))
    else:
        print(res.table().to_string(index=False))
        print(f"\n{res.n_points} points, residual sum of squares {res.rss:.4g} rad^2, IPOPT {res.status} "
              f"after {res.iterations} iterations")
        for m in res.messages:
            print(f"warning: {m}")
    return 0
