"""ropemodel: rope and cable friction drives as an acausal CasADi model.

Quick start::

    import ropemodel as rm
    scene = rm.load_scene()              # built-in example: Krauze et al. 2025, Fig. 9
    result = rm.run(scene)
    result.to_series()                   # values in the paper's units, e.g. "F_C_up [kN]"
    rm.solve(scene, given={"dF_up": "1000 mm"}, find=["G_m"])["G_m"]   # SI: N

Layout: :mod:`ropemodel.papers` holds the published equations, one function
each; :mod:`ropemodel.effects` wires them into models from the effects a scene
names; :mod:`ropemodel.core` checks structure and compiles solvers;
:mod:`ropemodel.problem` poses questions; :mod:`ropemodel.cli` is the command line.
"""

from ropemodel.errors import IllPosedError, InfeasibleError, InputError, RopeModelError, SolveError
from ropemodel.problem import Problem, run, solve
from ropemodel.result import Result
from ropemodel.scene import Scene, from_dict, from_toml
from ropemodel.scene import load as load_scene

__version__ = "0.1.0"

__all__ = [
    "IllPosedError",
    "InfeasibleError",
    "InputError",
    "Problem",
    "Result",
    "RopeModelError",
    "Scene",
    "SolveError",
    "from_dict",
    "from_toml",
    "load_scene",
    "run",
    "sensitivity",
    "solve",
    "sweep",
]

_LAZY = ("sensitivity", "sweep")  # heavier imports (pyarrow, SALib): loaded on first use


def __getattr__(name):
    """``rm.sweep(scene, vary=...)`` (a callable module) and ``rm.sensitivity``, imported on first use."""
    if name in _LAZY:
        import importlib

        return importlib.import_module(f"ropemodel.{name}")
    raise AttributeError(f"module 'ropemodel' has no attribute {name!r}")
