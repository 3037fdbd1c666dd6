"""``python -m ropemodel`` and the ``ropemodel`` console script: the command line.

Everything is imported inside :func:`console`, so Ctrl-C at any moment of the start-up
ends with one line and exit status 130, not a traceback.  Once the command has ended
(or been interrupted), a further Ctrl-C is ignored: it cannot turn a finished command
into a traceback or a death by signal while the interpreter shuts down.

Not covered, because no code of this package runs yet: the first milliseconds of the
interpreter itself (its ``site`` import), where Python prints its own traceback.
"""

import os
import signal
import sys


def console() -> None:
    """Run the command line and exit with its status."""
    try:
        from ropemodel.cli import main

        code = main()
    except KeyboardInterrupt:
        code = _interrupted()
    _exit(code)


def _interrupted() -> int:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    sys.stderr.write("interrupted\n")
    return 130


def _exit(code: int) -> None:
    """Exit with ``code``; Ctrl-C no longer counts.  After an interruption the process ends at once
    (``os._exit``, streams flushed): an interrupt raised inside some library's C call can leave the
    interpreter about to re-raise SIGINT at exit, which would report death by signal instead of 130."""
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except KeyboardInterrupt:   # arrived in the instant before: ignored like the ones after
        pass
    if code == 130:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(130)
    sys.exit(code)


if __name__ == "__main__":
    console()
