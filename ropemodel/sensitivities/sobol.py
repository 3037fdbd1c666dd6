"""Global sensitivity: Sobol indices over user ranges, with SALib.

Each varied input is uniform over ``[low, high]``; SALib's Saltelli/Sobol'
sampling gives ``N (D + 2)`` points (``N`` a power of two) and its estimator
the first-order index ``S1`` (share of the output's variance explained by the
input alone) and the total index ``ST`` (including all its interactions), each
with a bootstrap 95 % confidence half-width.

:func:`sobol_indices` works on any vectorised function ``{name: array} →
{output: array}``; :func:`sobol` evaluates a scene through
:func:`ropemodel.sweeps.sweep` (so every sampled point is range-checked).  An
output that does not vary over the ranges has no variance to share: its
indices are reported missing with ``defined = False`` and a note, never as a
silent NaN.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from ropemodel.errors import InputError, require
from ropemodel.problem import Problem
from ropemodel.scene import SceneLike, as_scene
from ropemodel.units import to_si


MAX_SEED = 2**32 - 1


def parse_range(name: str, spec, unit: str) -> tuple[float, float]:
    """``"LOW:HIGH"`` (values may carry units) or a (low, high) pair → SI floats, low < high."""
    if isinstance(spec, str):
        parts = spec.split(":")
        if len(parts) != 2:
            raise InputError(f"--sobol {name}={spec}: expected LOW:HIGH, e.g. {name}=10deg:20deg")
        spec = parts
    try:
        lo, hi = spec
    except (TypeError, ValueError):
        raise InputError(f"{name}: a range is (low, high), got {spec!r}") from None
    lo, hi = (to_si(name, v.strip() if isinstance(v, str) else v, unit, bare="si") for v in (lo, hi))
    if not lo < hi:
        raise InputError(f"{name}: range {spec!r} must have low < high")
    return lo, hi


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 20 else text[:20] + "..."


def check_samples(n, dimensions: int) -> None:
    """:class:`InputError` unless ``n`` base samples are a power of two >= 4 whose ``n (D + 2)`` points fit
    in memory and in the work budget (:data:`ropemodel.budget.BUDGETS`).  SALib's Sobol' sequence keeps its
    balance only at powers of two (it warns otherwise and the indices lose their convergence rate); fewer
    than 4 give no usable variance or bootstrap."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 4 or n & (n - 1):
        raise InputError(f"{_short(n)} base samples: the number must be a power of two >= 4 (4, 8, ..., 1024, "
                         f"...): SALib's Sobol' sequence is balanced only at powers of two, and fewer than 4 "
                         f"give no usable variance")
    from ropemodel import budget
    from ropemodel.sweeps.files import check_size

    budget.check("sobol", int(n) * (dimensions + 2), f"{n} base samples over {dimensions} range"
                 f"{'s' if dimensions != 1 else ''}, N(D + 2) evaluations,", "take fewer samples (--samples)")
    check_size(int(n) * (dimensions + 2), dimensions + 1, what="the Sobol samples are kept in memory")


def check_seed(seed) -> None:
    """:class:`InputError` unless ``seed`` is a whole number in [0, 2**32 - 1]."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed <= MAX_SEED:
        raise InputError(f"seed = {_short(seed)}: must be a whole number from 0 to {MAX_SEED}")


def sobol_indices(func, ranges: dict[str, tuple[float, float]], n: int = 1024, seed: int = 0) -> pd.DataFrame:
    """Sobol indices of ``func`` (vectorised: {name: array} → {output: array}) over uniform ``ranges``.

    Returns a tidy frame: ``output``, ``parameter``, ``S1``, ``S1_conf``, ``ST``, ``ST_conf``,
    ``defined``, ``note``.  ``n``: base samples, a power of two >= 4 (:func:`check_samples`, within the
    work budget); ``seed``: a whole number in [0, 2**32 - 1].
    """
    analyze = require("SALib.analyze.sobol", "sobol")
    sample = require("SALib.sample.sobol", "sobol")

    if not ranges:
        raise InputError("no ranges for Sobol indices")
    check_samples(n, len(ranges))
    check_seed(seed)
    names = list(ranges)
    problem = {"num_vars": len(names), "names": names, "bounds": [list(ranges[k]) for k in names]}
    X = sample.sample(problem, n, calc_second_order=False, seed=seed)
    Y = func({k: X[:, i] for i, k in enumerate(names)})
    rows = []
    for out, y in Y.items():
        y = np.asarray(y, dtype=float)
        if not np.isfinite(y).all():
            raise InputError(f"{out}: non-finite values at {int((~np.isfinite(y)).sum())} sampled points")
        if np.ptp(y) <= 1e-12 * max(1.0, float(np.abs(y).max())):
            for k in names:
                rows.append({"output": out, "parameter": k, "S1": math.nan, "S1_conf": math.nan, "ST": math.nan,
                             "ST_conf": math.nan, "defined": False, "note": "output does not vary over the ranges"})
            continue
        res = analyze.analyze(problem, y, calc_second_order=False, seed=seed)
        for i, k in enumerate(names):
            rows.append({"output": out, "parameter": k, "S1": float(res["S1"][i]), "S1_conf": float(res["S1_conf"][i]),
                         "ST": float(res["ST"][i]), "ST_conf": float(res["ST_conf"][i]), "defined": True, "note": ""})
    return pd.DataFrame(rows)


def sobol(scene: SceneLike, ranges: Mapping, outputs: Sequence[str] | None = None, n: int = 1024, seed: int = 0,
          given: Mapping | Sequence[str] = (), find: Sequence[str] = (), **sweep_options: Any) -> pd.DataFrame:
    """Global sensitivities: Sobol indices of a scene's outputs over uniform ranges of its inputs
    (Saltelli sampling and Jansen estimators by SALib; the outputs by :func:`ropemodel.sweep`).

    Parameters
    ----------
    scene : Scene or str or Path
        The scene (:func:`ropemodel.load_scene`); inputs not in ``ranges`` keep its values.
        A TOML scene file or a built-in scene's name is loaded first (:func:`ropemodel.load_scene`).
    ranges : dict
        ``{name: "LOW:HIGH"}`` with units (``"300kN:500kN"``) or ``(low, high)`` in SI units.
    outputs : list of str, optional
        Outputs to analyse (default: those :func:`ropemodel.sweep` gives: every unknown, each at its worst
        where the scene leaves the load's place or the manoeuvre open).
    n : int
        Base samples, a power of two ≥ 4; the model runs n·(k + 2) times for k ranges.
    seed : int
        Seed of the sampler and of the bootstrap confidence intervals, 0 to 2³² − 1.
    given, find : optional
        An inverse problem, as in :func:`ropemodel.solve`.
    **sweep_options
        Passed to :func:`ropemodel.sweep` (``threads``, ``backend``, ``chunk_size``).

    Returns
    -------
    pandas.DataFrame
        One row per (output, parameter): ``output``, ``parameter``, ``S1`` (first-order index [-]:
        the share of the output's variance due to the parameter alone), ``S1_conf`` (its 95 %
        bootstrap half-width), ``ST`` (total index [-], with interactions), ``ST_conf``,
        ``defined`` and ``note`` (an output that does not vary has no indices).

    Raises
    ------
    InputError
        A name that is not an input, a range outside the quantity's valid range, ``n`` or ``seed``
        out of range, the ``sobol`` extra (SALib) missing.
    SolveError
        A sampled point without a solution.

    Examples
    --------
    What the winding rope's force depends on, over 10-20 deg and 300-500 kN:

    >>> import ropemodel as rm
    >>> s = rm.sobol(rm.load_scene(), {"alpha_u": "10deg:20deg", "G_m": "300kN:500kN"},
    ...              outputs=["F_C_up"], n=256)
    >>> s[["parameter", "S1", "ST"]].round(2)
      parameter    S1    ST
    0   alpha_u  0.64  0.64
    1       G_m  0.35  0.37
    """
    scene = as_scene(scene)
    from ropemodel.sweeps import sweep

    problem = Problem(scene, given, find)
    q = problem.model.quantities
    for k in ranges:
        if k not in problem.user_knowns:
            raise InputError(f"cannot vary {k!r}: not an input of this problem; inputs: "
                             f"{', '.join(problem.user_knowns)}")
    si_ranges = {k: parse_range(k, v, q[k].unit) for k, v in ranges.items()}
    for k, (lo, hi) in si_ranges.items():
        q[k].check(lo, f"{k} (low end of its range)")
        q[k].check(hi, f"{k} (high end of its range)")
    outputs = None if outputs is None else list(outputs)   # default: the sweep's (at their worst on a route)
    options = {"progress": False, **sweep_options}     # the samples are one sweep's points: no bar unless asked

    def func(columns):
        frame = sweep(scene, pd.DataFrame(columns), outputs, given=given, find=find, si=True, **options)
        names = {c: c.split(" [")[0] for c in frame.columns[len(columns):]}
        return {o: frame[c].to_numpy() for c, o in names.items() if "@" not in o}   # not the governing places

    return sobol_indices(func, si_ranges, n, seed)
