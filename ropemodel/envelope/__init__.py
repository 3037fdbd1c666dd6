"""The worst case of every output over where the load is and what the haulage does.

A number a designer buys equipment from is taken at its worst over the route, both directions and every
manoeuvre.  :mod:`.cases` lists the load cases a scene leaves open (the load's place ``x_m``, the
acceleration ``a_h`` of the ramps and of an emergency stop); :mod:`.worst` evaluates a compiled
:class:`~ropemodel.problem.Problem` at all of them at once and keeps each output's worst (the sense its
quantity declares) with the case that governs it; :mod:`.result` shows it; :mod:`.answer` gives the
commands ``run`` and ``solve`` at the worst case.
"""

from ropemodel.envelope.answer import run, solve
from ropemodel.envelope.cases import CASE_INPUTS, MANOEUVRES, RAMPS, LoadCase, free, load_cases, reads, with_ramps
from ropemodel.envelope.result import EnvelopeResult
from ropemodel.envelope.worst import Envelope, Extreme, case_columns, envelope, where_text

__all__ = ["CASE_INPUTS", "MANOEUVRES", "RAMPS", "Envelope", "EnvelopeResult", "Extreme", "LoadCase", "case_columns",
           "envelope", "free", "load_cases", "reads", "run", "solve", "where_text", "with_ramps"]
