"""Ctrl-C while a command runs: exit 130 with one line, whatever the work was doing.

CasADi polls for Ctrl-C inside its solvers (``PyErr_CheckSignals`` in each IPOPT iteration, in
bonmin and the SUNDIALS integrators).  When it sees one it stops the solver and *consumes* the
KeyboardInterrupt: IPOPT returns "User_Requested_Stop" with a warning on stderr, a SUNDIALS call
raises a RuntimeError, bonmin carries on — and the command went on to print a result (measured:
``size`` interrupted in IPOPT printed a design and exited 0).  So, for the command's duration:

* the SIGINT handler records the interrupt, raises KeyboardInterrupt as Python's does, and arms
  a repeating alarm that raises it again (when no exception is already being handled) until it
  reaches the command line's handler — an interrupt consumed inside a solver comes back as
  soon as Python code runs;
* results go nowhere once interrupted: a write to stdout raises KeyboardInterrupt;
* no solver log either: what is written to stderr after the interrupt is held, and at the end
  only the command line's own lines (``warning: ``, ``error: ``, ``interrupted``) are written.
  The solvers report an interrupt through CasADi's logger, with no option to silence it: IPOPT's
  interface prints ``WARNING("KeyboardInterruptException")``, CVODES's ``rhs failed:
  KeyboardInterrupt`` and SUNDIALS's "the right-hand side routine failed";
* :attr:`Interrupts.seen` tells the command line that any failure that follows (a RuntimeError
  out of an interrupted integrator) is the interrupt's doing.

Only in the main thread of the process (signal handlers cannot be set elsewhere); otherwise a
no-op.  Handlers, alarm, stdout and stderr are restored on exit.
"""

from __future__ import annotations

import signal
import sys
import threading

#: seconds between repeated KeyboardInterrupts after a Ctrl-C that was consumed
REPEAT = 0.2
#: how the command line's own lines on stderr begin
OWN_LINES = ("warning: ", "error: ", "interrupted")


class _Guarded:
    """stdout that refuses to print once the command was interrupted."""

    def __init__(self, stream, interrupts: Interrupts):
        self._stream, self._interrupts = stream, interrupts

    def write(self, text):
        if self._interrupts.seen:
            raise KeyboardInterrupt
        return self._stream.write(text)

    def __getattr__(self, name):
        return getattr(self._stream, name)


class _Held:
    """stderr that, once the command was interrupted, holds what is written (see :meth:`release`)."""

    def __init__(self, stream, interrupts: Interrupts):
        self._stream, self._interrupts = stream, interrupts
        self._held: list[str] = []

    def write(self, text):
        if self._interrupts.seen:
            self._held.append(text)
            return len(text)
        return self._stream.write(text)

    def release(self) -> None:
        """Write the command line's own lines of what was held (the solvers' are left out)."""
        lines = "".join(self._held).splitlines(keepends=True)
        self._stream.write("".join(line for line in lines if line.startswith(OWN_LINES)))
        self._held = []

    def __getattr__(self, name):
        return getattr(self._stream, name)


class Interrupts:
    """``with Interrupts() as guard: ...``; afterwards ``guard.seen`` says whether Ctrl-C came."""

    def __init__(self):
        self.seen = False
        self._active = False

    def __enter__(self):
        self._active = threading.current_thread() is threading.main_thread()
        if self._active:
            self._old = (signal.signal(signal.SIGINT, self._sigint), signal.signal(signal.SIGALRM, self._alarm),
                         sys.stdout, sys.stderr)
            sys.stdout, sys.stderr = _Guarded(sys.stdout, self), _Held(sys.stderr, self)
        return self

    def _sigint(self, signum, frame):
        self.seen = True
        signal.setitimer(signal.ITIMER_REAL, REPEAT, REPEAT)
        raise KeyboardInterrupt

    @staticmethod
    def _alarm(signum, frame):
        if sys.exc_info()[0] is None:   # not while an exception (this one) is already on its way
            raise KeyboardInterrupt

    def stop(self) -> None:
        """No more repeated interrupts (the command line has caught one)."""
        if self._active:
            signal.setitimer(signal.ITIMER_REAL, 0.0)

    def __exit__(self, *exc):
        if self._active:
            self.stop()
            sigint, sigalrm, stdout, stderr = self._old
            signal.signal(signal.SIGALRM, sigalrm)
            signal.signal(signal.SIGINT, sigint)
            held = sys.stderr
            if isinstance(sys.stdout, _Guarded):
                sys.stdout = stdout
            if isinstance(held, _Held):
                sys.stderr = stderr
                held.release()
        return False
