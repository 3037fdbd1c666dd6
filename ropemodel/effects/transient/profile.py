"""The transient itself (effect ``dynamics``): none, a start-up or a braking, and the drive's speed profile.

``none`` (default): a static scene.  ``start``: the drum's surface speed ramps from rest to v_pj in
t_ramp; ``stop``: from steady motion at v_pj to rest in t_ramp; both simulated up to t_end, in the
direction of ``travel`` (+1 upward, −1 downward), with the ``ramp`` shape.

The profile is a list of *phases* (t0, t1, v(t), a(t)): within a phase the speed is smooth, and the
integrator is stopped and restarted at every phase boundary (the ramp's pieces, then the hold at
constant speed).  A transient variant of this effect also declares the scene parameters of every
*gathered* transient variant (:func:`~ropemodel.effects.transient.base.gathered_parameters`): a
submodel is built without knowing the other effects' variants, so their parameters are declared here,
once a scene has a transient, and stay out of static scenes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar
from collections.abc import Callable

from ropemodel.effects import domains as dom
from ropemodel._math import if_else
from ropemodel.effects.base import Submodel, define_effect, register
from ropemodel.effects.transient.base import MODEL, TransientSubmodel, gathered_parameters
from ropemodel.errors import InputError
from ropemodel.papers import route as rt
from ropemodel.quantity import Quantity

define_effect(MODEL, "dynamics", "none",
              "time-domain transient: none, start (drive ramps up), stop (ramps down) or a whole trip")

T_RAMP = Quantity("t_ramp", "s", "duration of the drive's speed ramp", "s", guess=5.0, positive=True, **dom.DURATION)
T_END = Quantity("t_end", "s", "end of the simulated transient", "s", guess=60.0, positive=True, **dom.DURATION)


@dataclass(frozen=True)
class Phase:
    """A smooth piece of the drive profile on [t0, t1]; v(t) [m/s], a(t) [m/s²] work on CasADi symbols."""

    t0: object
    t1: object
    v: Callable
    a: Callable
    #: where the load is during this phase [m from the drive], when the phase moves it along the route
    #: (a trip: the load's segment is constant within a phase); None when the load stays put
    x_load: float | None = None


@register(MODEL, "dynamics", "none")
class NoDynamics(Submodel):
    """Static scene: no transient."""

    description = "no transient (static model only)"


class Profile(TransientSubmodel):
    """A transient: the drum's surface speed as phases; ``initial_fraction``, ``final_fraction`` of v_pj."""

    citations = ("krauze2025",)
    quantities: ClassVar[tuple[Quantity, ...]] = (T_RAMP, T_END)
    reads = ("v_pj",)                    # declared by the static model's power and lining effects
    order = 2
    gathered = False
    initial_fraction = 0.0

    def equations(self, v):
        super().equations(v)
        for name in gathered_parameters():
            v[name]  # noqa: B018 - creating the symbol makes it a parameter
        return []

    def rules(self, values):
        if "t_end" in values and "t_ramp" in values and values["t_end"] < values["t_ramp"]:
            return [f"t_end = {values['t_end']:g} s is shorter than t_ramp = {values['t_ramp']:g} s; "
                    f"valid: t_end >= t_ramp"]
        return []

    def bind(self, setup):
        super().bind(setup)
        vals, nums = setup.values, setup.numbers
        V, T = setup.direction * vals["v_pj"], vals["t_ramp"]
        phases = [Phase(T * p.s0, T * p.s1, self._speed(V, T, p.f), self._accel(V, T, p.df))
                  for p in setup.part("ramp").pieces(vals)]
        if nums["t_end"] > nums["t_ramp"]:
            final = V * (1 - self.initial_fraction)
            phases.append(Phase(T, vals["t_end"], lambda t: final + 0 * t, lambda t: 0 * t))
        setup.phases = phases
        setup.speed0 = V * self.initial_fraction

    def whole(self) -> Phase:
        """The whole profile on [0, t_end] as one piecewise phase (``if_else``; for the symbolic smooth mode)."""
        phases = self.setup.phases

        def piecewise(attr):
            def f(t):
                out = getattr(phases[-1], attr)(t)
                for ph in reversed(phases[:-1]):
                    out = if_else(t < ph.t1, getattr(ph, attr)(t), out)
                return out
            return f

        return Phase(0.0, phases[-1].t1, piecewise("v"), piecewise("a"))

    def publish(self, v, mode):
        phase = v["phase"]
        v.publish(v_ramp=phase.v(v["t"]), a_ramp=phase.a(v["t"]))

    def summary(self, run):
        return {"dynamics": self.variant}


@register(MODEL, "dynamics", "start")
class StartUp(Profile):
    """Start-up: the drum's surface speed ramps 0 → v_pj in t_ramp with the ``ramp`` shape."""

    description = "start-up from rest, speed ramp to v_pj"

    @staticmethod
    def _speed(V, T, f):
        return lambda t: V * f(t / T)

    @staticmethod
    def _accel(V, T, df):
        return lambda t: V / T * df(t / T)


@register(MODEL, "dynamics", "stop")
class Braking(Profile):
    """Braking: the drum's surface speed ramps v_pj → 0 in t_ramp with the ``ramp`` shape."""

    description = "braking from steady motion at v_pj, speed ramp to rest"
    initial_fraction = 1.0

    @staticmethod
    def _speed(V, T, f):
        return lambda t: V * (1 - f(t / T))

    @staticmethod
    def _accel(V, T, df):
        return lambda t: -V / T * df(t / T)


@register(MODEL, "dynamics", "trip")
class Trip(Profile):
    """A whole trip along the route: ramp 0 → v_pj in t_ramp, run at v_pj, ramp down to rest in t_ramp.

    The load starts at one end of the route (upward: at the return sheave, x_m = L_u; downward: at the
    drive) and travels to the other; a route shorter than v_pj·t_ramp never reaches full speed (a
    triangle at the same acceleration).  The phases are cut where the load crosses a joint of the route
    (known times: the drum's speed is prescribed and the rope inextensible), and each phase carries the
    load's place, so its segment is constant within a phase.  Linear ramps and an inextensible rope only
    (an elastic rope's spans are frozen over a transient, and a trip moves the load along the whole
    route): the transient version of :func:`ropemodel.trips.trip`, with which it agrees.
    """

    description = "a whole trip: ramp up, run, ramp down, the load along the whole route"
    quantities = (T_RAMP,)

    def rules(self, values):
        return []

    def bind(self, setup):
        TransientSubmodel.bind(self, setup)
        if setup.part("ramp").variant != "linear" or setup.part("rope_elasticity").variant != "rigid":
            raise InputError('dynamics = "trip" needs ramp = "linear" and rope_elasticity = "rigid" (a trip moves '
                             "the load along the whole route; the elastic rope's spans are frozen over a transient)")
        if setup.part("travel").x_m_given:
            raise InputError("dynamics = \"trip\" starts at one end of the route and ends at the other: "
                             "leave x_m out")
        nums = setup.numbers
        L_u = float(nums["L_u"])
        kinematics = rt.trip_phases(L_u, float(nums["v_pj"]), float(nums["t_ramp"]))
        start, sign = (L_u, 1.0) if setup.travel == "up" else (0.0, -1.0)
        cuts = sorted({t for t0, t1, _, _ in kinematics for t in (t0, t1)}
                      | {rt.time_at_distance(kinematics, sign * (start - end)) for end in _joints(nums)})
        phases = []
        for t0, t1 in zip(cuts[:-1], cuts[1:]):
            if t1 <= t0:
                continue
            k = next(p for p in kinematics if p[0] <= 0.5 * (t0 + t1) <= p[1])
            x = start - sign * rt.distance_travelled(kinematics, 0.5 * (t0 + t1))
            phases.append(Phase(t0, t1, _linear(setup.direction, k[2], k[3], k[0]), _const(setup.direction * k[3]), x))
        setup.phases, setup.speed0 = phases, 0.0
        setup.numbers["t_end"] = setup.values["t_end"] = cuts[-1]

    def summary(self, run):
        return {"dynamics": self.variant}


def _joints(numbers: dict) -> list[float]:
    """Distances from the drive of the joints between the route's segments (none on a straight route)."""
    ends, total, i = [], 0.0, 1
    while f"L_{i}" in numbers:
        total += float(numbers[f"L_{i}"])
        ends.append(total)
        i += 1
    return ends[:-1]


def _linear(direction, v0, a, t0):
    return lambda t: direction * (v0 + a * (t - t0))


def _const(a):
    return lambda t: a + 0 * t
