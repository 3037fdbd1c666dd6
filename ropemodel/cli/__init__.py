"""Command line: ``ropemodel COMMAND ...``.

Each module in this package defines one command: a ``NAME``, a ``HELP`` line,
``add_arguments(parser)`` and ``main(args) -> int``.  They are discovered at
start-up, so a new command is a new module.  Errors become one line on stderr:
bad input exits 2, a failed solve or an infeasible design exits 1, Ctrl-C exits 130
(:mod:`ropemodel.cli._interrupt`).  A reader that stops early (``ropemodel run | head``) ends the
command quietly with exit 0, as ``git log | head`` does.
"""

from __future__ import annotations

import argparse
import importlib
import os
import pkgutil
import sys
import warnings

from ropemodel.errors import InputError, RopeModelError

EXIT_OK, EXIT_FAIL, EXIT_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
NO_LIMIT = ("run a job above its work budget (a transient's history rows, a Sobol study's evaluations, a sizing "
            "NLP on a long route; the refusal says how big it is)")


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error and exit status 2."""

    def error(self, message):
        raise InputError(f"{self.prog}: {message}")


def _commands():
    mods = []
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if not info.name.startswith("_"):
            mods.append(importlib.import_module(f"{__name__}.{info.name}"))
    return {m.NAME: m for m in mods}


class _Version(argparse.Action):
    """``--version``: the installed version, looked up only when asked for."""

    def __call__(self, parser, namespace, values, option_string=None):
        from ropemodel import __version__

        print(f"ropemodel {__version__}")
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="ropemodel", description="Rope and cable friction drives: forces, traction, stiffness.")
    parser.add_argument("--version", action=_Version, nargs=0, help="show the version and exit")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress bars or status lines on stderr")
    parser.add_argument("--no-limit", action="store_true", help=NO_LIMIT)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, mod in _commands().items():
        p = sub.add_parser(name, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.add_argument("-q", "--quiet", action="store_true", default=argparse.SUPPRESS,
                       help="no progress bars or status lines on stderr")
        p.add_argument("--no-limit", action="store_true", default=argparse.SUPPRESS, help=NO_LIMIT)
        p.set_defaults(_main=mod.main)
    return parser


def _warning(message, category, filename, lineno, file=None, line=None):
    print(f"warning: {message}", file=sys.stderr)


def main(argv=None) -> int:
    """Entry point of the ``ropemodel`` console script."""
    from ropemodel.cli._interrupt import Interrupts

    warnings.showwarning = _warning
    guard = Interrupts()
    try:
        with guard:
            code = _run(argv, guard)
    except KeyboardInterrupt:
        code = None
    except Exception:
        if not guard.seen:
            raise
        code = None   # a failure after Ctrl-C (e.g. an interrupted integrator) is the interrupt's doing
    try:
        sys.stdout.flush()         # what is still buffered: its reader may have gone since
    except BrokenPipeError:
        code = _reader_gone()
    if code is None or guard.seen and code != EXIT_INTERRUPTED:
        print("interrupted", file=sys.stderr)
        code = EXIT_INTERRUPTED
    return code


def _run(argv, guard) -> int:
    """The command's exit status; its errors as one line on stderr (none after Ctrl-C: the interrupt
    says what happened)."""
    try:
        args = build_parser().parse_args(argv)
        if args.quiet:
            from ropemodel import progress

            progress.quiet()
        from ropemodel import budget

        budget.lift(args.no_limit)   # this command's, not a previous one's in the same process
        if not getattr(args, "_main", None):
            raise InputError("no command given; try 'ropemodel run' or 'ropemodel --help'")
        return args._main(args)
    except RopeModelError as exc:
        if guard.seen:
            raise KeyboardInterrupt from None
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_INPUT if isinstance(exc, InputError) else EXIT_FAIL
    except BrokenPipeError:  # output piped into e.g. `head`, which closed early
        return _reader_gone()


def _reader_gone() -> int:
    """The reader of our output stopped early (``| head``): nothing more is written, exit 0.  The standard
    streams are pointed at the null device, so the interpreter's final flush cannot fail again."""
    null = os.open(os.devnull, os.O_WRONLY)
    for stream in (sys.stdout, sys.stderr):
        try:
            os.dup2(null, stream.fileno())
        except (OSError, ValueError):   # a stream without a file descriptor (e.g. replaced by a test)
            pass
    os.close(null)
    return EXIT_OK


def run_console() -> None:
    """Run the command line and exit (kept for scripts that called it; see :mod:`ropemodel.__main__`)."""
    from ropemodel.__main__ import console

    console()
