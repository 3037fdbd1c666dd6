"""Work budgets: the size of a long job estimated before it starts, refused above its budget unless lifted.

Four jobs can grow without bound from a few characters of input: the steps of a transient (its history
rows, t_end/sim_dt), the evaluations of a Sobol study (N(D+2) for N base samples and D ranges), the
size of a sizing NLP on a route of segments (every check with the load at every place that can govern,
each through the whole route) and an inverse solve on a route of segments (a root-find through the whole
route with the load at every place).  Each is counted before any work; above its budget the command refuses with
the count, the budget, why the budget is what it is and the fix, and runs anyway with ``ropemodel --no-limit``
(:func:`lift`; in Python ``with ropemodel.budget.lifted(): ...``).  A job that cannot fit in memory is
refused either way (:func:`ropemodel.sweeps.files.check_size`).  The README ("Work budgets") states the
budgets and why; progress shows on a terminal (:mod:`ropemodel.progress`).
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass

from ropemodel.errors import InputError


@dataclass(frozen=True)
class Budget:
    """The most ``unit`` a job may take without ``--no-limit``, and why that many."""

    limit: int
    unit: str
    why: str


#: every budget by name (README, "Work budgets"; the ratios quoted are measured by tests/test_budget.py)
BUDGETS = {
    "history": Budget(10**6, "history rows", "a row holds the transient's state and forces, some 20 values: 10^6 "
                                             "rows fill about 160 MB, and each costs integration"),
    "sobol": Budget(2**18, "evaluations", "the samples, their outputs and SALib's bootstrap resamples of them are "
                                          "held in memory: memory and time grow with the evaluations"),
    "route sizing": Budget(2500, "segment evaluations",
                           "an NLP that checks every check with the load at each place that can govern (dynamic "
                           "sizing's static start), or at every place (sweep --sizing), makes each through the whole "
                           "route, so it grows as those places times the segments and its solve faster still: "
                           "2500 is a route of 625 segments at 4 places, or of 49 where every place is checked "
                           "(size builds its NLP of a few places and checks every design at all of them: not "
                           "counted)"),
    "route solve": Budget(300_000, "evaluations",
                          "an inverse question (solve --find) on a route is answered with the load at every place "
                          "of the route, each a root-find through the whole route, and the worst answer is then "
                          "checked at every place again, so its time grows as the places times the segments and "
                          "faster: measured, 29 700 (99 segments) 1.6 CPU-s, 269 100 (299 segments) 18 CPU-s, "
                          "3 million (999 segments) 145 CPU-s; a route of more than 100 segments, held as route "
                          "numbers, is counted as load cases x load cases, each answer checked at every case: "
                          "131 769 (120 segments) 3.8 CPU-s, 9 million (999 segments) 36 CPU-s"),
}

_LIFTED = False


def lift(on: bool = True) -> None:
    """Let every job run whatever its size (``ropemodel --no-limit``)."""
    global _LIFTED
    _LIFTED = on


@contextlib.contextmanager
def lifted():
    """``with lifted(): ...``: budgets off inside, as they were after."""
    before = _LIFTED
    lift(True)
    try:
        yield
    finally:
        lift(before)


def check(name: str, count: float, what: str, fix: str) -> None:
    """:class:`InputError` if ``count`` exceeds budget ``name`` (and budgets are not lifted).

    what: the job and how it was counted (``"t_end = 1e+06 s at sim_dt = 0.02 s"``); fix: how to make it
    smaller (``"take a larger sim_dt, or shorten t_end"``)."""
    b = BUDGETS[name]
    if _LIFTED or count <= b.limit:
        return
    raise InputError(f"{what} is {_count(count)} {b.unit}, above the budget of {b.limit:,} ({b.why}): {fix}, "
                     f"or add --no-limit to run it anyway")


def _count(n: float) -> str:
    return f"{n:,.0f}" if n < 1e15 else f"{n:.3g}"
