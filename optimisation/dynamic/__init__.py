"""Dynamic sizing: choose the design so that every check holds through the machine's manoeuvres (a winch: d,
F_nwl and stroke through its start-up and braking in both directions), not only in steady motion.  The
manoeuvres and the checks through them, the machine declares (:attr:`ropemodel.machines.Machine.manoeuvres`).

Layout:

* :mod:`.transient` — the transient it sizes through, built from any winch sizing scene (what it cannot
  default asked for, each default stated);
* :mod:`.positions` — where the load can be when a manoeuvre happens (each segment's ends and middle);
* :mod:`.manoeuvres` — the cases (a declared manoeuvre with the load at one place), the declaration read;
* :mod:`.screen` — which cases the NLP integrates (those that govern a check), screened cheaply;
* :mod:`.shooting` — one manoeuvre's transient inside the NLP (single shooting, cvodes with
  sensitivities; why not collocation: measured in its docstring);
* :mod:`.problem` — :class:`DynamicSizingProblem`, the static sizing NLP plus the checks on each
  integrated case's time grid;
* :mod:`.start` — dynamic factors of a design, the static design with a flat factor (the start);
* :mod:`.refine` — every check between the grid points (exact local minima added to the grid) and in
  the cases left out;
* :mod:`.verify` — every design simulated by the hybrid simulator in every case (an independent path);
* :mod:`.design` — :func:`size_dynamic`, the whole answer (``ropemodel size --dynamic``);
* :mod:`.ramp` — the shortest start and stop ramps that keep a given design safe;
* :mod:`.warm` — a re-solve on the previous optimum's active set (Newton, kept at a KKT point);
* :mod:`.diagnose` — no design: the conflicting checks and what would help;
* :mod:`.scan` — the scan of the design box that backs a "no design";
* :mod:`.sensitivity`, :mod:`.sweep` — sensitivities and sweeps of the dynamic optimum (in chunks, on dask,
  resumable).
"""

from optimisation.dynamic.design import DynamicDesign, size_dynamic
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.ramp import RampAnswer, shortest_ramp

__all__ = ["DynamicDesign", "DynamicSizingProblem", "RampAnswer", "shortest_ramp", "size_dynamic"]
