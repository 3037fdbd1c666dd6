"""A route of segments as arrays, and the one resolver between its arrays and the names users write.

Inside, a route of n segments is three arrays (lengths L [m], inclinations α [rad], the winding rope's
resistance μ_w [-]), listed from the drive.  At the edges (``[[route]]`` tables, a profile file, ``--set L_2=…``,
sweeps, sensitivities, the report, ``--json``) each value keeps its name: ``L_i``, ``alpha_i``, ``mu_wi`` for
segment i = 1…n (:func:`ropemodel.effects.winch_route.segment_quantities` declares them).  :func:`parse` and
:func:`name` translate one way and the other, :func:`beyond` says why a name is past a route's end, and
:class:`RouteArrays` gathers the values of a mapping by name, so a module that reads a route need not spell the
names out.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

#: the arrays' fields and the name of entry i (1 = at the drive) of each
FIELDS = {"L": "L_{i}", "alpha": "alpha_{i}", "mu_w": "mu_w{i}"}
_NAME = re.compile(r"^(?:(L|alpha)_|(mu_w))([1-9][0-9]*)$")


def name(field: str, index: int) -> str:
    """The name of entry ``index`` (0-based, from the drive) of ``field`` ("L", "alpha" or "mu_w"): ``L_1``…"""
    return FIELDS[field].format(i=index + 1)


def parse(text: str) -> tuple[str, int] | None:
    """(field, 0-based index) of a segment's name (``L_3`` → ("L", 2), ``mu_w2`` → ("mu_w", 1)); None for any
    other name (``L_u``, ``L_ul``, ``L_0``, ``L_01``, ``mu_w_2``)."""
    found = _NAME.match(text)
    return None if found is None else (found[1] or found[2], int(found[3]) - 1)


def beyond(text: str, n: int) -> str | None:
    """Why ``text``, a segment's name, names no segment of a route of ``n`` (the valid names); None where it
    does, or where ``text`` is not a segment's name."""
    where = parse(text)
    if where is None or where[1] < n:
        return None
    field = where[0]
    return (f"{text}: the route has {n} segment{'s' * (n != 1)}, so its values are {name(field, 0)} … "
            f"{name(field, n - 1)} (a longer route is one more [[route]] table, or line of its profile, each)")


def _array(values) -> np.ndarray:
    out = np.array(values, dtype=float)
    out.flags.writeable = False
    return out


@dataclass(frozen=True, eq=False)
class RouteArrays:
    """A route's segments as read-only float arrays (SI: m, rad, -), one entry per segment from the drive;
    ``own_mu``: whether each segment gives its own μ_w (else it is μ_pl, the scene's default)."""

    L: np.ndarray
    alpha: np.ndarray
    mu_w: np.ndarray
    own_mu: np.ndarray

    @property
    def n(self) -> int:
        return int(self.L.size)

    @classmethod
    def from_values(cls, values: Mapping, mu_pl: float | None = None) -> RouteArrays:
        """The segments of a mapping of named values (SI floats): L_1, L_2, … while they last, α_i of each, μ_wi
        where given, else ``mu_pl`` (default ``values["mu_pl"]``).  An empty route where there is no ``L_1``."""
        L, i = [], 1
        while (key := name("L", i - 1)) in values:
            L.append(values[key])
            i += 1
        own = [name("mu_w", k) in values for k in range(len(L))]
        default = values.get("mu_pl", np.nan) if mu_pl is None else mu_pl
        mu = [values[name("mu_w", k)] if has else default for k, has in enumerate(own)]
        return cls(_array(L), _array([values[name("alpha", k)] for k in range(len(L))]), _array(mu),
                   np.array(own, dtype=bool))
