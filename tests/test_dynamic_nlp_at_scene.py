"""IPOPT at the scene's parameters solves the whole dynamic NLP: its static checks and every check through the
integrated manoeuvres (one constraint per check, element and grid point, named as such).  The static sizing NLP
folds the scene's parameters into its static checks over its load cases (issue 22.4); on the dynamic problem,
whose cases are the manoeuvres, that fold raised AttributeError ("'Manoeuvre' object has no attribute 'key'"),
which ``hasattr`` in :func:`optimisation.ipopt.solver` took for "no fold" — the whole NLP by accident, the fold
attempted again at every solver built; had it built, it would have dropped every dynamic check."""

from __future__ import annotations

from _dynamic_scene import write_scene

from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.ipopt import solver
from optimisation.problem import load_sizing


def test_ipopt_at_the_scene_parameters_keeps_the_checks_through_the_manoeuvres(tmp_path):
    problem = DynamicSizingProblem(load_sizing(write_scene(tmp_path), emit=False))
    through = [c for c in problem.constraints if " @ " in c and ", t = " in c]
    assert through and len(problem.constraints) == len(problem.static_constraints) + len(through)
    assert problem.at_scene["g"].numel() == len(problem.constraints)
    assert solver(problem, at_scene=True).size1_out("g") == len(problem.constraints)
