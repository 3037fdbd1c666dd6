"""Drive speed profiles: the drum's surface speed v_d(t) of a start-up or a braking.

A profile is a list of *phases* (t_start, t_stop, v_d(t), a_d(t)): within a phase the
speed is smooth, and the integrator is stopped and restarted at every phase boundary
(a known time event: the kink of the ramp is never stepped over).  ``direction`` is +1
for upward travel (load hauled up), −1 for downward.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable


@dataclass(frozen=True)
class Phase:
    """A smooth piece of the drive profile on [t0, t1]; v(t) [m/s], a(t) [m/s²] work on CasADi symbols."""

    t0: float
    t1: float
    v: Callable
    a: Callable


def start_profile(v_pj: float, t_ramp: float, t_end: float, direction: int) -> tuple[list[Phase], float]:
    """Start-up from rest: linear ramp 0 → direction·v_pj over t_ramp, then constant speed.

    Returns the phases and the initial speed (0: the haulage starts from rest).
    """
    vmax, acc = direction * v_pj, direction * v_pj / t_ramp
    phases = [Phase(0.0, t_ramp, lambda t: acc * t, lambda t: acc + 0 * t)]
    if t_end > t_ramp:
        phases.append(Phase(t_ramp, t_end, lambda t: vmax + 0 * t, lambda t: 0 * t))
    return phases, 0.0


def stop_profile(v_pj: float, t_ramp: float, t_end: float, direction: int) -> tuple[list[Phase], float]:
    """Braking from steady motion at direction·v_pj: linear ramp to rest over t_ramp, then at rest."""
    v0, dec = direction * v_pj, -direction * v_pj / t_ramp
    phases = [Phase(0.0, t_ramp, lambda t: v0 + dec * t, lambda t: dec + 0 * t)]
    if t_end > t_ramp:
        phases.append(Phase(t_ramp, t_end, lambda t: 0 * t, lambda t: 0 * t))
    return phases, v0


#: dynamics variant → profile builder (v_pj, t_ramp, t_end, direction) → (phases, initial speed)
PROFILES = {"start": start_profile, "stop": stop_profile}
