"""Sizing: choose a machine's design so that every check holds (a winch: the rope diameter d, the pretension
F_nwl and the tensioner stroke).  What is chosen, minimised and kept, the machine declares
(:attr:`ropemodel.machines.Machine.sizing`); nothing here names a machine.

Layout (problem definition kept apart from the solvers):

* :mod:`optimisation.problem` — :class:`SizingProblem`: decision variables, scaling, the
  lexicographic objective and every design check as a constraint, all built from the
  scene's own compiled equations (``ropemodel.problem.Problem(scene).function``) and the declaration;
* :mod:`optimisation.ipopt` — the continuous optimum with IPOPT (exact derivatives);
* :mod:`optimisation.discrete` — catalogue diameters: next size up, or bonmin;
* :mod:`optimisation.infeasibility` — which checks conflict, and by how much;
* :mod:`optimisation.sensitivity` — ∂x*/∂p from the KKT system at the optimum;
* :mod:`optimisation.design` — :func:`size`, the whole answer (what ``ropemodel size`` prints).
"""

from optimisation.design import Design, size
from optimisation.problem import SizingProblem

__all__ = ["Design", "SizingProblem", "size"]
