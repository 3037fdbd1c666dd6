"""The acausal core: assemble a model from submodels, check its structure, compile a solver.

* :mod:`.model` — :class:`Model`: the equations and quantities of a model built
  from a choice of effect variants.
* :mod:`.structure` — Dulmage–Mendelsohn analysis: is a choice of unknowns
  well-posed, which variables are under- or over-determined, in what order
  can the blocks be solved.
* :mod:`.compile` — one CasADi Function from the known to the unknown
  quantities: explicit blocks evaluated directly, implicit blocks by Newton.
"""

from ropemodel.core.compile import compile_solver, forward_of, solver_of, structure_of
from ropemodel.core.model import Model
from ropemodel.core.structure import Structure, analyse

__all__ = ["Model", "Structure", "analyse", "compile_solver", "forward_of", "solver_of", "structure_of"]
