"""ropemodel: rope and cable friction drives as an acausal CasADi model.

Quick start::

    import ropemodel as rm
    scene = rm.load_scene()              # built-in example: Krauze et al. 2025, Fig. 9
    result = rm.run(scene)
    result.to_series()                   # values in the paper's units, e.g. "F_C_up [kN]"
    rm.solve(scene, given={"dF_up": "1000 mm"}, find=["G_m"])["G_m"]   # SI: N

One function per command of the command line, each with a numpydoc docstring and a doctested
example (``help(rm.sweep)``): :func:`load_scene`, :func:`run` (``ropemodel run``), :func:`solve`,
:func:`sweep`, :func:`elasticities` and :func:`sobol` (``sensitivity``; charts: :func:`tornado`),
:func:`load_curve` (``curve``), :func:`identify`, :func:`simulate`, :func:`trip`, :func:`size`
(from :mod:`optimisation`) and :func:`report`.  Python takes SI floats, strings with units
(``"467 kN"``) or pint Quantities.

Layout: :mod:`ropemodel.papers` holds the published equations, one function each;
:mod:`ropemodel.numerics` the numerical methods they need; :mod:`ropemodel.effects`
wires them into models from the effects a scene names; :mod:`ropemodel.core` checks
structure, compiles solvers and evaluates them over arrays; :mod:`ropemodel.scene`
and :mod:`ropemodel.problem` pose questions; the analyses (:mod:`ropemodel.sweeps`,
:mod:`ropemodel.sensitivities`, :mod:`ropemodel.capstan`, :mod:`ropemodel.sheave`,
:mod:`ropemodel.dynamics`), :mod:`optimisation` (sizing), :mod:`ropemodel.reports` and
:mod:`ropemodel.cli` build on them.

The public names are imported on first use (PEP 562), so ``import ropemodel`` and
``ropemodel --help`` cost almost nothing.
"""

from __future__ import annotations

import importlib

from ropemodel.errors import IllPosedError, InfeasibleError, InputError, RopeModelError, SolveError

#: public name → module it lives in (imported when first used); one function per command
_LAZY = {
    "Problem": "ropemodel.problem", "run": "ropemodel.envelope", "solve": "ropemodel.envelope",
    "Result": "ropemodel.result",
    "Scene": "ropemodel.scene", "from_dict": "ropemodel.scene", "from_toml": "ropemodel.scene",
    "load_scene": "ropemodel.scene",
    "sweep": "ropemodel.sweeps.runner",
    "elasticities": "ropemodel.sensitivities.local", "sobol": "ropemodel.sensitivities.sobol",
    "tornado": "ropemodel.sensitivities.plot",
    "load_curve": "ropemodel.capstan.curves", "identify": "ropemodel.capstan.identify",
    "simulate": "ropemodel.dynamics.simulate", "trip": "ropemodel.trips",
    "size": "optimisation.design", "report": "ropemodel.reports.build",
}
_ALIASES = {"load_scene": "load"}

__all__ = ["IllPosedError", "InfeasibleError", "InputError", "RopeModelError", "SolveError", "__version__",
           *sorted(_LAZY)]


def _version() -> str:
    """The installed distribution's version (written once, in pyproject.toml)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ropemodel")
    except PackageNotFoundError:  # a source tree that is not installed
        return "0+unknown"


def __getattr__(name: str):
    if name == "__version__":
        return _version()
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), _ALIASES.get(name, name))
        globals()[name] = value
        return value
    raise AttributeError(f"module 'ropemodel' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
