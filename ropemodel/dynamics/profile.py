"""Drive speed profiles: the drum's surface speed v_d(t) of a start-up or a braking.

A profile is a list of *phases* (t_start, t_stop, v_d(t), a_d(t)): within a phase the
speed is smooth, and the integrator is stopped and restarted at every phase boundary
(a known time event: the kink of the ramp is never stepped over).  ``direction`` is +1
for upward travel (load hauled up), −1 for downward.

The ramp's *shape* f(s) on s = t/t_ramp ∈ [0, 1], f(0) = 0, f(1) = 1, is a registry too:
``linear`` (f = s: constant acceleration v_pj/t_ramp, with steps of acceleration at both ends)
and ``cosine`` (f = (1 − cos πs)/2: acceleration (π/2)(v_pj/t_ramp) sin πs, continuous, zero
at both ends; its peak is π/2 times the linear ramp's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from ropemodel._math import cos, sin


@dataclass(frozen=True)
class Phase:
    """A smooth piece of the drive profile on [t0, t1]; v(t) [m/s], a(t) [m/s²] work on CasADi symbols."""

    t0: float
    t1: float
    v: Callable
    a: Callable


#: ramp shape → (f(s), f'(s)) on s ∈ [0, 1]
SHAPES = {
    "linear": (lambda s: s, lambda s: 1.0 + 0 * s),
    "cosine": (lambda s: 0.5 * (1 - cos(math.pi * s)), lambda s: 0.5 * math.pi * sin(math.pi * s)),
}


def start_profile(v_pj: float, t_ramp: float, t_end: float, direction: int,
                  shape: str = "linear") -> tuple[list[Phase], float]:
    """Start-up from rest: ramp 0 → direction·v_pj over t_ramp, then constant speed.

    Returns the phases and the initial speed (0: the haulage starts from rest).
    """
    f, df = SHAPES[shape]
    V = direction * v_pj
    phases = [Phase(0.0, t_ramp, lambda t: V * f(t / t_ramp), lambda t: V / t_ramp * df(t / t_ramp))]
    if t_end > t_ramp:
        phases.append(Phase(t_ramp, t_end, lambda t: V + 0 * t, lambda t: 0 * t))
    return phases, 0.0


def stop_profile(v_pj: float, t_ramp: float, t_end: float, direction: int,
                 shape: str = "linear") -> tuple[list[Phase], float]:
    """Braking from steady motion at direction·v_pj: ramp to rest over t_ramp, then at rest."""
    f, df = SHAPES[shape]
    V = direction * v_pj
    phases = [Phase(0.0, t_ramp, lambda t: V * (1 - f(t / t_ramp)), lambda t: -V / t_ramp * df(t / t_ramp))]
    if t_end > t_ramp:
        phases.append(Phase(t_ramp, t_end, lambda t: 0 * t, lambda t: 0 * t))
    return phases, V


#: dynamics variant → profile builder (v_pj, t_ramp, t_end, direction, shape) → (phases, initial speed)
PROFILES = {"start": start_profile, "stop": stop_profile}
