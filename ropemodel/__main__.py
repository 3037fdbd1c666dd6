"""``python -m ropemodel`` and the ``ropemodel`` console script: the command line.

Everything is imported inside :func:`console`, so Ctrl-C at any moment of the start-up
ends with one line and exit status 130, not a traceback.
"""

import sys


def console() -> None:
    """Run the command line and exit with its status."""
    try:
        from ropemodel.cli import main

        code = main()
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        code = 130
    sys.exit(code)


if __name__ == "__main__":
    console()
