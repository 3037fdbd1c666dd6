"""What a Koepe transient is (effect ``dynamics``), its direction (``travel``) and where it starts.

``dynamics``
    ``none`` (default)  a static scene.
    ``braking``         from steady motion at v_max the brake is applied (the law of ``brake_control``), until
                        t_end; the ropes' vibration after the wheel stops is part of it.
    ``start``           from rest the drive ramps the wheel's speed to v_max: the acceleration rises to
                        a_drive in t_jerk, holds, and falls to 0 in t_jerk; then the hoist runs at v_max to t_end.
``travel``
    ``hoist`` (default) the loaded conveyance moves up; ``lower``: down.

Where the transient starts: ``y_start``, the loaded conveyance's depth below its upper position.  Not given, a
braking stops the loaded conveyance at the end of the wind it moves towards (hoisting: the top; lowering: the
bottom; the nominal stopping distance from the rigid hoist), and a start begins at the end it leaves: the ends
are where the slip limits are least (docs/physics.md §7).  Where the head-rope span there is too short for the
mesh's rope run, the start moves away from the end by what the mesh needs, and the summary says so.

A transient variant of ``dynamics`` declares the scene parameters of the transient variants the scene picks
(a submodel is built without knowing the others' variants; their parameters stay out of static scenes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar
from collections.abc import Callable

from ropemodel.effects.base import REGISTRY, Submodel, define_effect, register
from ropemodel.effects.koepe import MODEL, SHAFT, Q
from ropemodel.effects.koepe_transient import mesh as mh
from ropemodel.effects.transient.base import TransientSubmodel
from ropemodel.quantity import Quantity

define_effect(MODEL, "dynamics", "none", "time-domain transient with elastic head ropes: none, braking or start")
define_effect(MODEL, "travel", "hoist", "direction of the transient: hoist (loaded conveyance up) or lower")

T_END = Q("t_end", "s", "end of the simulated transient", "s", low=0.0, low_open=True, high=1e4, unlimited=True,
          range_source="10^4 s: longer than any wind of a Koepe hoist (4 km at 1 m/s is 4000 s)", default=math.inf,
          guess=10.0,
          default_note="not given: the manoeuvre's nominal duration (rigid hoist) and 5 s of the ropes' vibration")
Y_START = Q("y_start", "m", "depth of the loaded conveyance below its upper position at the start of the transient",
            "m", low=0.0, high=4e4, range_source=SHAFT, unlimited=True, default=math.inf, guess=400.0,
            default_note="not given: a braking ends at the end of the wind it moves towards, a start begins at "
                         "the end it leaves")
#: seconds of the ropes' vibration simulated after the nominal manoeuvre when t_end is not given
SETTLE = 5.0


@dataclass(frozen=True)
class Phase:
    """A smooth piece of the wheel's law on [t0, t1]: ``f(t)`` is the wheel's force [N] or acceleration
    [m/s²] (the law says which); ``held``: the wheel is at rest in it."""

    t0: float
    t1: float
    f: Callable
    held: bool = False


@register(MODEL, "dynamics", "none")
class NoDynamics(Submodel):
    """Static scene: no transient."""

    description = "no transient (static model only)"


@register(MODEL, "travel", "hoist")
class TravelHoist(TransientSubmodel):
    """The loaded conveyance moves up during the transient (the rope runs from side L over the wheel to E)."""

    description = "loaded conveyance moving up"
    order = 0
    sign = +1.0

    def bind(self, setup):
        super().bind(setup)
        setup.direction, setup.travel = self.sign, self.variant

    def summary(self, run):
        return {"direction": self.variant}


@register(MODEL, "travel", "lower")
class TravelLower(TravelHoist):
    """The loaded conveyance moves down during the transient."""

    description = "loaded conveyance moving down"
    sign = -1.0


class KoepeProfile(TransientSubmodel):
    """A Koepe transient: the start position, the mesh's rope run, the phases of the wheel's law, t_end."""

    citations = ("delavergne2003",)
    quantities: ClassVar[tuple[Quantity, ...]] = (T_END, Y_START)
    reads = ("v_max",)
    order = 2
    gathered = False
    #: the transient effects whose chosen variants this profile uses (their parameters become the scene's)
    uses: ClassVar[tuple[str, ...]] = ("travel", "head_elasticity", "wheel_contact")
    #: the wheel's speed at t = 0 as a fraction of v_max
    initial_fraction = 0.0
    #: what moves the wheel (:class:`~ropemodel.effects.koepe_transient.control.WheelLaw`), set when bound
    wheel_law: Any = None

    def equations(self, v):
        super().equations(v)
        for effect in self.uses:
            spec = REGISTRY[MODEL][effect]
            cls = spec.variants[self.effects.get(effect, spec.default)]
            for name in (*(q.name for q in cls.quantities), *getattr(cls, "reads", ())):
                v[name]  # noqa: B018 - creating the symbol makes it a parameter of the scene
        return []

    def law(self, setup):
        """The part that moves the wheel (:class:`~ropemodel.effects.koepe_transient.control.WheelLaw`)."""
        raise NotImplementedError

    def start_position(self, travel: float, reel: float, N: int) -> tuple[float, str]:
        """(y_start [m], what it is) when not given."""
        raise NotImplementedError

    def bind(self, setup):
        super().bind(setup)
        nums, s = setup.numbers, setup.direction
        setup.speed0 = s * nums["v_max"] * self.initial_fraction
        law = self.wheel_law = self.law(setup)
        travel, duration = law.nominal(setup)
        t_end = nums.get("t_end", math.inf)
        self.t_end = float(t_end) if math.isfinite(t_end) else duration + SETTLE
        travel += law.final_speed * max(self.t_end - duration, 0.0) * float(nums["v_max"])
        N = setup.options["segments"]
        self.reel = mh.reel_for(travel)
        given = nums.get("y_start", math.inf)
        if math.isfinite(given):
            self.y_start, self.y_source = float(given), "given"
        else:
            self.y_start, self.y_source = self.start_position(travel, self.reel, N)
        setup.phases = [ph for ph in law.phases(setup, self.t_end) if ph.t1 > ph.t0]
        self.travel_nominal = travel

    def rules(self, values):
        y, H = values.get("y_start"), values.get("H")
        if y is not None and H is not None and math.isfinite(y) and y > H:
            return [f"y_start = {y:g} m is below the lower end of the wind, H = {H:g} m: valid 0 <= y_start <= H "
                    f"(leave it out to start at the end of the wind)"]
        return []

    def _room(self, reel: float, N: int) -> float:
        """Depth [m] the conveyance whose span shortens needs below its upper position for the mesh's run."""
        return max(0.0, mh.least_span(reel, N) - float(self.setup.numbers["H_head"]))

    def summary(self, run):
        y = self.y_start - run.history["x [m]"].to_numpy()         # where the loaded conveyance is, ropes rigid
        H = float(self.setup.numbers["H"])
        return {"dynamics": self.variant, "y_start": self.y_start, "y_start_source": self.y_source,
                "travel_nominal": self.travel_nominal, "reel": self.reel,
                "overwind": float(max(-y.min(), y.max() - H, 0.0))}

    def report(self, s):
        lines = [f"  loaded conveyance at y = {s['y_start']:.6g} m below its upper position at the start "
                 f"({s['y_start_source']}); nominal run {s['travel_nominal']:.4g} m"]
        if s["overwind"] > 0:
            lines.append(f"  OVERWIND: a conveyance runs {s['overwind']:.3g} m beyond an end of the wind (start it "
                         f"further from the end: y_start)")
        return lines


@register(MODEL, "dynamics", "braking")
class Braking(KoepeProfile):
    """From steady motion at v_max, the brake of ``brake_control``; the ropes' vibration after the stop."""

    description = "emergency braking from v_max with elastic head ropes (brake law: brake_control)"
    uses = (*KoepeProfile.uses, "brake_control")
    initial_fraction = 1.0

    def law(self, setup):
        return setup.part("brake_control")

    def start_position(self, travel, reel, N):
        H, room = float(self.setup.numbers["H"]), self._room(reel, N)
        depth = max(travel, room)
        y = depth if self.setup.direction > 0 else H - depth
        where = "the top" if self.setup.direction > 0 else "the bottom"
        text = f"default: the stop ends at {where} of the wind"
        if depth > travel:
            text = (f"default: the stop ends {depth - travel:.4g} m short of {where} of the wind (the mesh's "
                    f"rope run needs a head-rope span of {room + float(self.setup.numbers['H_head']):.4g} m)")
        return min(max(y, 0.0), H), text


@register(MODEL, "dynamics", "start")
class Start(KoepeProfile):
    """From rest, the drive's ramp to v_max (:class:`~ropemodel.effects.koepe_transient.control.DriveRamp`)."""

    description = "start from rest to v_max with elastic head ropes (drive ramp a_drive, t_jerk)"
    quantities = (*KoepeProfile.quantities,
                  Q("a_drive", "m/s^2", "the drive's acceleration of the start", "m/s^2", low=0.0, low_open=True,
                    high=100.0, range_source="100 m/s² (ten g): far beyond any hoist's drive", guess=0.8,
                    warn_high=2.0, usual_source="mine hoists accelerate at 0.5 to 1.5 m/s² "
                                                                       "(judgement)"),
                  Q("t_jerk", "s", "time the drive's acceleration takes to rise to a_drive (and to fall back)", "s",
                    low=0.0, low_open=True, high=100.0, guess=1.0,
                    range_source="100 s: far beyond any drive's rise of acceleration (about a second)"))

    def law(self, setup):
        from ropemodel.effects.koepe_transient.control import DriveRamp

        return DriveRamp(setup)

    def start_position(self, travel, reel, N):
        H = float(self.setup.numbers["H"])
        if self.setup.direction > 0:
            return H, "default: the start from the bottom of the wind"
        return 0.0, "default: the start from the top of the wind"
