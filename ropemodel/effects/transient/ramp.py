"""The shape of the drive's speed ramp (effect ``ramp``).

A shape is the fraction f(s) of the ramp's speed change reached at s = t/t_ramp ∈ [0, 1], f(0) = 0,
f(1) = 1, given as smooth *pieces* (s0, s1, f, f'): the profile (:mod:`.profile`) stops and restarts
the integrator at every piece's end (a known time event: a kink is never stepped over).

``linear``  f = s: constant acceleration v_pj/t_ramp, with steps of acceleration at both ends.
``cosine``  f = (1 − cos πs)/2: acceleration (π/2)(v_pj/t_ramp) sin πs, continuous and zero at both
            ends; its peak is π/2 times the linear ramp's.

A new shape is a new module with a :class:`RampShape` subclass (see CONTRIBUTING.md).
"""

from __future__ import annotations

import math
from typing import NamedTuple
from collections.abc import Callable

from ropemodel._math import cos, sin
from ropemodel.effects.base import define_effect, register
from ropemodel.effects.transient.base import MODEL, TransientSubmodel

define_effect(MODEL, "ramp", "linear", "shape of the drive's speed ramp: linear or cosine (smooth)")


class Piece(NamedTuple):
    """A smooth piece of a ramp shape on s ∈ [s0, s1]: f(s) and f'(s) = df/ds (work on CasADi symbols)."""

    s0: object
    s1: object
    f: Callable
    df: Callable


class RampShape(TransientSubmodel):
    """Base class of a ramp shape: :meth:`pieces` from the scene's values (SI, floats or symbols)."""

    order = 1

    def pieces(self, values: dict) -> list[Piece]:
        raise NotImplementedError


@register(MODEL, "ramp", "linear")
class LinearRamp(RampShape):
    """Linear speed ramp: constant acceleration, with steps of acceleration at both ends."""

    description = "linear speed ramp (constant acceleration)"

    def pieces(self, values):
        return [Piece(0.0, 1.0, lambda s: s, lambda s: 1.0 + 0 * s)]


@register(MODEL, "ramp", "cosine")
class CosineRamp(RampShape):
    """Cosine speed ramp v = v_pj (1 − cos(π t/t_ramp))/2: no step of acceleration."""

    description = "cosine speed ramp (acceleration continuous, zero at both ends)"

    def pieces(self, values):
        return [Piece(0.0, 1.0, lambda s: 0.5 * (1 - cos(math.pi * s)), lambda s: 0.5 * math.pi * sin(math.pi * s))]
