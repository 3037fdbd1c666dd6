"""Hold what CasADi writes to stderr while a solver works, so that a failure is reported once, in the
user's terms, and never as a solver log.

When a Function called inside another fails (an integrator whose right-hand side meets NaN at an
IPOPT trial point, say), CasADi writes the failing Function's name and every input to its error
stream before it raises, whatever the Function's options (``Function::operator()`` in CasADi 3.8:
``print_in(uerr(), arg, true)``).  IPOPT then backs off and carries on, so these dumps are noise even
when the solve succeeds (measured: three dumps of a dozen lines each while dynamic sizing searched
for the least drum friction of a design that has none).  The Python bindings route that stream
through ``sys.stderr``, so redirecting it holds them.  A progress line keeps its own reference to the
terminal (:mod:`ropemodel.progress`) and stays visible.
"""

from __future__ import annotations

import contextlib
import io
import sys
from collections.abc import Iterator


@contextlib.contextmanager
def held_solver_output() -> Iterator[io.StringIO]:
    """``with held_solver_output() as held: ...``: sys.stderr goes to ``held`` (a StringIO) meanwhile."""
    held = io.StringIO()
    saved = sys.stderr
    sys.stderr = held
    try:
        yield held
    finally:
        sys.stderr = saved
