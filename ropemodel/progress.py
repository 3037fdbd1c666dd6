"""Signs of life for long work: a progress bar or a status line on stderr, only where a person watches.

Shown when stderr is a terminal and not silenced (``ropemodel --quiet``, :func:`quiet`, or
``ROPEMODEL_QUIET=1``); never in a pipe, a file or a test run.  Two forms:

* :func:`bar` — a tqdm bar over a known amount of work (points of a sweep, seconds of a transient);
* :func:`status` — a context manager that shows what is being done with a spinner and the time
  elapsed, refreshed by a background thread, for work without a natural count (an IPOPT solve).

Library code calls these; it never prints otherwise.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time
from typing import Any

_QUIET = False
_FRAMES = "|/-\\"


def quiet(on: bool = True) -> None:
    """Silence every progress display of this process (``ropemodel --quiet``)."""
    global _QUIET
    _QUIET = on


def enabled(flag: bool | None = None) -> bool:
    """Whether to show progress: ``flag`` if given, else when stderr is a terminal and not silenced."""
    if flag is not None:
        return bool(flag)
    if _QUIET or os.environ.get("ROPEMODEL_QUIET"):
        return False
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


def bar(total: float, desc: str, unit: str = "it", flag: bool | None = None, **kw):
    """A tqdm progress bar on stderr (disabled where :func:`enabled` says no)."""
    import tqdm.std

    shown = enabled(flag)
    make: Any = tqdm.std.tqdm     # a bar never drawn needs no notebook widget (tqdm.auto warns without ipywidgets)
    if shown:
        import tqdm.auto

        make = tqdm.auto.tqdm
    return make(total=total, desc=desc, unit=unit, disable=not shown, file=sys.stderr,
                mininterval=0.2, **_size(), **kw)


def _size() -> dict:
    """ncols and nrows of the terminal on stderr; 80 x 24 where it says 0 x 0 (a pseudo-terminal whose size
    was never set: tqdm then took -1 rows and drew nothing)."""
    try:
        size = os.get_terminal_size(sys.stderr.fileno())
    except (AttributeError, ValueError, OSError):
        return {"ncols": 80, "nrows": 24}
    return {"ncols": size.columns or 80, "nrows": size.lines or 24}


class _Status:
    def __init__(self, text: str):
        self.text, self.start, self.stop = text, time.perf_counter(), threading.Event()
        self.stream = sys.stderr    # the terminal, even while a solver's own output is held (redirected)
        self.thread = threading.Thread(target=self._run, daemon=True)

    def update(self, text: str) -> None:
        """Show ``text`` as the current step."""
        self.text = text

    def _line(self, i: int) -> str:
        return f"\r{_FRAMES[i % 4]} {self.text} ({time.perf_counter() - self.start:.1f} s)\x1b[K"

    def _run(self):
        i = 0
        while not self.stop.wait(0.2):
            self.stream.write(self._line(i))
            self.stream.flush()
            i += 1


class _Silent:
    def update(self, text: str) -> None:
        """Nothing shown."""


@contextlib.contextmanager
def status(text: str, flag: bool | None = None):
    """``with status("sizing: continuous optimum") as s: ... s.update("catalogue size")``.

    Writes the line at once, refreshes it every 0.2 s, and clears it at the end.
    """
    if not enabled(flag):
        yield _Silent()
        return
    s = _Status(text)
    s.stream.write(s._line(0))
    s.stream.flush()
    s.thread.start()
    try:
        yield s
    finally:
        s.stop.set()
        s.thread.join()
        s.stream.write("\r\x1b[K")
        s.stream.flush()
