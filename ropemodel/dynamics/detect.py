"""Event detection on a chunk of dense output: thresholds, the Hermite dip test, the first flagged interval.

Thresholds.  A switching function that starts a mode above ``ARM_TOL`` is *armed* and fires below 0.
One that starts within ±ARM_TOL (e.g. the slip speed at the onset of slip) is *banded*: it fires below
−ARM_TOL, so that rounding at its start cannot fire it at once, and the event is then moved back to
where it crossed 0 after its highest point, so that an excursion too short to be seen above ARM_TOL at
a detection point (a slip of 21 ms and 0.9 nm in the tests) still ends where g = 0.  Once above
ARM_TOL at a detection point it is armed.  One that starts below −ARM_TOL (inconsistent) fires only
after it has been armed.

The rate argument.  On every detection interval [t_j, t_j+1] (length δ) each switching function is
checked with its value *and its rate* at both ends: a sign change is a crossing; an excursion below
zero that begins and ends inside the interval is caught by the cubic Hermite interpolant of (g, ġ)
dipping below zero.  The cubic differs from g by at most δ⁴ max|g⁗|/384, so every excursion deeper
than that is found, whatever its length; one shallower can be missed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

ARM_TOL = 1e-9


@dataclass(frozen=True)
class SwitchState:
    """Per switching function of the current mode: ``armed`` (fires below 0) and ``banded`` (started
    within ±ARM_TOL: fires below −ARM_TOL until armed)."""

    armed: np.ndarray
    banded: np.ndarray

    @classmethod
    def at_start(cls, g: np.ndarray) -> SwitchState:
        return cls(g > ARM_TOL, g >= -ARM_TOL)

    def arm(self, more: np.ndarray) -> SwitchState:
        return SwitchState(self.armed | more, self.banded)

    def band(self) -> np.ndarray:
        """The threshold each function fires below (0 armed, −ARM_TOL banded), as an offset to add to g."""
        return np.where(self.armed, 0.0, ARM_TOL)


class Detection(NamedTuple):
    """The first flagged detection interval ``j`` of a chunk: functions that ``crossed`` their threshold
    at its end, functions whose Hermite interpolant ``dipped`` below it inside (with the places ``u`` ∈
    [0, 1] of the interpolant's minima), and the switch state at its start."""

    j: int
    crossed: np.ndarray
    dipped: np.ndarray
    u: np.ndarray
    state: SwitchState


class Crossing(NamedTuple):
    """A located event: time after the interval's start, index ``switch`` of the switching function."""

    s: float
    switch: int


def hermite_min(g0, g1, d0, d1):
    """Least value and its place u ∈ [0, 1] of the cubic Hermite interpolant with values g0, g1 and
    slopes d0, d1 (per unit u) at the ends, for arrays of functions."""
    # H(u) = g0 + d0 u + (3(g1 − g0) − 2d0 − d1) u² + (2(g0 − g1) + d0 + d1) u³
    b, c3 = 3 * (g1 - g0) - 2 * d0 - d1, 2 * (g0 - g1) + d0 + d1
    A, B, C = 3 * c3, 2 * b, d0                         # H'(u) = A u² + B u + C
    best_v, best_u = np.minimum(g0, g1), np.where(g0 <= g1, 0.0, 1.0)
    disc = B * B - 4 * A * C
    with np.errstate(divide="ignore", invalid="ignore"):
        sq = np.sqrt(np.maximum(disc, 0.0))
        lin = np.where(B != 0, -C / np.where(B != 0, B, 1.0), -1.0)
        for r in ((-B - sq) / (2 * A), (-B + sq) / (2 * A)):
            u = np.where(np.abs(A) > 1e-14 * (np.abs(B) + np.abs(C) + 1e-300), r, lin)
            ok = (disc >= 0) & (u > 0) & (u < 1) & np.isfinite(u)
            v = g0 + d0 * u + b * u * u + c3 * u ** 3
            better = ok & (v < best_v)
            best_v, best_u = np.where(better, v, best_v), np.where(better, u, best_u)
    return best_v, best_u


def first_flagged(state: SwitchState, g0, d0, G, Gd, delta):
    """The first detection interval where a function crosses or dips below its threshold.

    g0, d0: values and rates at the chunk's start; G, Gd: (functions × points) on the detection grid;
    delta: the intervals' lengths.  Returns (:class:`Detection` or None, the switch state after the
    chunk when nothing is flagged).
    """
    n_fun = len(state.armed)
    Gp, Dp = np.hstack([g0, G[:, :-1]]), np.hstack([d0, Gd[:, :-1]])       # values at the interval starts
    above = np.logical_or.accumulate(G > ARM_TOL, axis=1)
    armed_at = state.armed[:, None] | np.hstack([np.zeros((n_fun, 1), bool), above[:, :-1]])
    active = armed_at | state.banded[:, None]
    band = np.where(armed_at, 0.0, ARM_TOL)
    crossed = active & (G + band < 0)
    low, u = hermite_min(Gp + band, G + band, Dp * delta, Gd * delta)
    dipped = active & ~crossed & (Gp + band >= 0) & (G + band >= 0) & (low < 0)
    flagged = (crossed | dipped).any(axis=0)
    if not flagged.any():
        return None, state.arm(armed_at[:, -1] | (G[:, -1] > ARM_TOL))
    j = int(np.argmax(flagged))
    at_j = SwitchState(armed_at[:, j], state.banded)
    return Detection(j, np.flatnonzero(crossed[:, j]), np.flatnonzero(dipped[:, j]), u[:, j], at_j), at_j
