"""The end states of a Koepe hoist's wind, and the worst of a result over them.

docs/physics.md §7: each side's tension is linear in the conveyances' position, so T_1, the tension ratio and
each slip acceleration (a ratio of functions linear in the position) are worst at an end of the wind.  The
states are therefore the loaded conveyance (side L) at the bottom and at the top, and the empty hoist
(m_payload = 0).  At rest the empty hoist's two ends mirror each other (one static state); in a manoeuvre
the shaft resistance acts on conveyance L and the sheaves of the two compartments may differ, so the
manoeuvres take the empty hoist at both ends and conveyance L in either compartment.

Every function works on floats, numpy arrays and CasADi expressions (``v`` maps names to any of them),
except those marked "floats only"; a model and its tables compute the same states with the same code.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from ropemodel._math import fmax, fmin, if_else
from ropemodel.papers import koepe as kp

#: the two shaft compartments; conveyance L may hang in either
COMPARTMENTS = ("a", "b")


class State(NamedTuple):
    """An end state: what it is called, whether the payload is on, whether conveyance L (the payload's) is
    at the bottom (y_L = H) or the top (y_L = 0), and its compartment ("" at rest: no sheave moves)."""

    name: str
    loaded: bool
    bottom: bool
    compartment: str = ""


_ENDS = (State("loaded at the bottom", True, True), State("loaded at the top", True, False),
         State("empty, conveyance L at the bottom", False, True), State("empty, conveyance L at the top", False, False))
#: the static states (papers.koepe.static_cases): the empty hoist's ends mirror each other at rest
STATIC = (_ENDS[0], _ENDS[1], State("empty", False, True))
#: the states of the manoeuvres: every end, conveyance L in either compartment
DYNAMIC = tuple(s._replace(compartment=c) for s in _ENDS for c in COMPARTMENTS)


class Sides(NamedTuple):
    """The static tensions [N] of side L (the payload's conveyance) and side E (the other) in a state."""

    state: State
    T_L: Any
    T_E: Any


def sides(v, tail, state: State) -> Sides:
    """T_L, T_E of :func:`ropemodel.papers.koepe.side_tensions` in ``state``; tail = (n_tail, q_tail, h_loop)."""
    y_L = v["H"] if state.bottom else 0.0 * v["H"]
    payload = v["m_payload"] if state.loaded else 0.0 * v["m_payload"]
    T_L, T_E = kp.side_tensions(y_L, v["m_conveyance"], payload, v["H"], v["H_head"], v["n_head"], v["q_head"],
                                *tail)
    return Sides(state, T_L, T_E)


def masses(v, s: Sides):
    """(M_L, M_E) [kg], the masses moving with each side: T/g and the sheaves of its compartment
    (:func:`ropemodel.papers.koepe.side_mass`)."""
    c = s.state.compartment or COMPARTMENTS[0]
    other = COMPARTMENTS[1 - COMPARTMENTS.index(c)]
    return kp.side_mass(s.T_L, v[f"m_sheave_{c}"]), kp.side_mass(s.T_E, v[f"m_sheave_{other}"])


def largest(values):
    """The largest of ``values`` (a fold of fmax)."""
    out = values[0]
    for x in values[1:]:
        out = fmax(out, x)
    return out


def smallest(values):
    """The smallest of ``values`` (a fold of fmin)."""
    out = values[0]
    for x in values[1:]:
        out = fmin(out, x)
    return out


def pick(keys, *columns) -> list:
    """Each column's value where ``keys`` is least (the first such on a tie), selected with if_else."""
    best = keys[0]
    chosen = [c[0] for c in columns]
    for i in range(1, len(keys)):
        better = keys[i] < best
        chosen = [if_else(better, c[i], x) for c, x in zip(columns, chosen)]
        best = if_else(better, keys[i], best)
    return chosen


def argleast(keys) -> int:
    """Index of the least of ``keys``, the first on a tie (as :func:`pick`).  Floats only."""
    return min(range(len(keys)), key=lambda i: (keys[i], i))


def describe(s: Sides, high: bool = False, compartment: bool = False) -> str:
    """Where a worst case is, in words: the state, which side is high, and the compartment of conveyance L."""
    text = s.state.name
    if high:
        text += ", the loaded side high" if s.T_L >= s.T_E else ", the other side high"
        if not s.state.loaded:
            text = text.replace("the loaded side high", "conveyance L's side high")
    if compartment and s.state.compartment:
        text += f", conveyance L in compartment {s.state.compartment}"
    return text
