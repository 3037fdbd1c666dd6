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
    """Bad input: unknown name, wrong unit, value out of range, unreadable file.

    ``problems`` lists every problem found (one line each); the message says them all.
    """

    def __init__(self, message: str = "", problems: list[str] | None = None):
        self.problems = list(problems) if problems else [message]
        super().__init__(message or _listing(self.problems))


def _listing(problems: list[str], where: str = "") -> str:
    if len(problems) == 1:
        return problems[0]
    return f"{len(problems)} problems{where}:\n" + "\n".join(f"  - {p}" for p in problems)


class Problems:
    """Collects every problem of an input before raising one :class:`InputError` that lists them all.

    ::

        found = Problems(" in scene.toml")
        found.add("G_m = 300 has no unit; write e.g. \"300 kN\"")
        with found.collect():        # an InputError raised inside is recorded, not raised
            check_something()
        found.raise_if_any()
    """

    def __init__(self, where: str = ""):
        self.where = where
        self.items: list[str] = []

    def add(self, message: str) -> None:
        if message not in self.items:
            self.items.append(message)

    def collect(self):
        return _Collect(self)

    def __bool__(self) -> bool:
        return bool(self.items)

    def raise_if_any(self, error=None) -> None:
        if self.items:
            cls = error or InputError
            raise cls(_listing(self.items, self.where), self.items)


class _Collect:
    def __init__(self, problems: Problems):
        self.problems = problems

    def __enter__(self):
        return self.problems

    def __exit__(self, kind, exc, tb):
        if exc is not None and isinstance(exc, InputError):
            for p in exc.problems:
                self.problems.add(p)
            return True
        return False


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
