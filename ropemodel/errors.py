"""Exceptions raised by ropemodel.

Every error a user can cause is an :class:`InputError`: the CLI turns it into one
line on stderr and exit status 2.  Numerical failures the user cannot fix by
changing a value are :class:`SolveError` (exit status 1 from the CLI).
"""

from __future__ import annotations

import difflib


class RopeModelError(Exception):
    """Base class of every error ropemodel raises on purpose."""


class InputError(RopeModelError, ValueError):
    """Bad input: unknown name, wrong unit, value out of range, unreadable file."""


class IllPosedError(InputError):
    """The requested choice of unknowns does not give a square, solvable system."""


class SolveError(RopeModelError):
    """A well-posed problem whose numerical solution failed or left the valid range."""


class InfeasibleError(RopeModelError):
    """A design problem with no feasible design (CLI exit status 1)."""


def suggest(name: str, valid) -> str:
    """Return ``" (did you mean 'x'?)"`` for the nearest valid name, or ``""``."""
    close = difflib.get_close_matches(name, list(valid), n=1, cutoff=0.5)
    return f" (did you mean '{close[0]}'?)" if close else ""


def require(module: str, extra: str):
    """Import an optional dependency, or raise :class:`InputError` naming the extra that installs it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ModuleNotFoundError:
        raise InputError(f"this needs the optional package {module.split('.')[0]!r}: "
                         f"pip install \"ropemodel[{extra}]\"") from None
