"""Dynamic sizing: choose d, F_nwl and stroke so that every check holds through the winch's start-up and
braking in both directions, not only in steady motion.

Layout:

* :mod:`.manoeuvres` — the four manoeuvres (where the load is) and the checks through each;
* :mod:`.shooting` — one manoeuvre's transient inside the NLP (single shooting, cvodes with
  sensitivities; why not collocation: measured in its docstring);
* :mod:`.problem` — :class:`DynamicSizingProblem`, the static sizing NLP plus the checks on each
  manoeuvre's time grid;
* :mod:`.start` — dynamic factors of a design, the static design with a flat factor (the start);
* :mod:`.refine` — every check between the grid points (exact local minima added to the grid);
* :mod:`.verify` — every design simulated by the hybrid simulator (an independent path);
* :mod:`.design` — :func:`size_dynamic`, the whole answer (``ropemodel size --dynamic``);
* :mod:`.ramp` — the shortest start and stop ramps that keep a given design safe;
* :mod:`.diagnose` — no design: the conflicting checks and what would help;
* :mod:`.sensitivity`, :mod:`.sweep` — sensitivities and sweeps of the dynamic optimum.
"""

from optimisation.dynamic.design import DynamicDesign, size_dynamic
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.ramp import RampAnswer, shortest_ramp

__all__ = ["DynamicDesign", "DynamicSizingProblem", "RampAnswer", "shortest_ramp", "size_dynamic"]
