"""Start-up and braking transients of a winch scene (``model = "winch"``): the effects the
time-domain simulation (:mod:`ropemodel.dynamics`) reads.

These effects build **no algebraic equation**: the static model (Krauze et al. 2025,
:mod:`ropemodel.effects.winch`) stays exactly as it is, and ``ropemodel run`` on a
dynamic scene still gives the static forces.  They declare the quantities of the
dynamic model, so that a scene with ``dynamics = "start"`` validates its parameters
(names, units, ranges, defaults).  The dynamic model is assembled by
:func:`ropemodel.dynamics.simulate` from the variants the scene picks, and only those
are built.

Effects and variants
--------------------
``dynamics``        ``none`` (default): static scene.  ``start``: the drum's surface speed
                    ramps from rest to ``v_pj`` in ``t_ramp``; ``stop``: from steady motion
                    at ``v_pj`` down to rest in ``t_ramp``.  Simulated up to ``t_end``.
``travel``          ``up`` (default, load hauled up the incline) or ``down`` (load lowered):
                    the direction of the transient.
``rope_elasticity`` ``segments`` (default): every rope span cut into ``[numerics] segments``
                    Kelvin–Voigt elements with the rope's mass lumped at the nodes;
                    ``spring``: one element per span; ``rigid``: an inextensible rope, one
                    degree of freedom.
``tensioner``       ``constant_force`` (default): the return sheave's carriage (mass ``m_t``)
                    is pulled with ``F_nwl`` and travels within its ``stroke``;
                    ``fixed``: the carriage is locked where ``F_nwl`` put it at rest.
``ramp``            ``linear`` (default): constant acceleration v_pj/t_ramp; ``cosine``:
                    v = v_pj (1 − cos(π t/t_ramp))/2, acceleration continuous and zero at
                    both ends (peak π/2 times the linear ramp's).
``drive``           ``speed`` (default): the drum's surface speed follows the ramp exactly;
                    ``torque_limited``: it follows the ramp while the motor's force at the rim
                    stays within ±``F_drive_max``, else the motor gives ±F_drive_max and the
                    drum (inertia ``m_drive`` = J/R² at the rim) accelerates as it can.
``drum_contact``    ``rigid`` (default): the rope at the drum's tangent points moves with the drum
                    surface while it sticks.  ``capstan``: the wrapped rope's slip zone is a spring
                    in series between the drum and the tight span, stiffness from the capstan model
                    of Li et al. (eq. (12), (15), (24)) with μ = mu_d, wrap alpha_d, R = D/2, EA =
                    L_u/q_lw, preload = the slack-side force, load = the tension difference, free
                    length → 0 (the spans are the chain's); linearised at the static forces of the
                    transient's direction.  Needs the drum diameter ``D``.  The mapping, and why,
                    is in :mod:`ropemodel.dynamics.contact`.

``rope_damping`` is the Kelvin–Voigt **retardation time** τ = c/k of the rope [s]: every
element's tension is T = k (e + τ ė), k = EA/ℓ.  Stiffness-proportional, so a mode of
circular frequency ω has the damping ratio ζ = τω/2 (for the Fig. 9 load on 1150 m of
rope, ω ≈ 1.9 rad/s: τ = 0.05 s gives ζ ≈ 0.05).  The default 0.05 s is an assumption,
not a measured value (wire-rope loss factors of a few per cent at the load mode): set it
for your rope.

``v_eps`` smooths the paper's Coulomb resistances (eq. (7)-(11)) as R·tanh(v/v_eps): R in motion
(tanh(2.5/0.01) = 1 to machine precision, so the steady state is the paper's exactly), zero at
rest.  Near rest it acts as a viscous damper R/v_eps: a smaller v_eps is closer to Coulomb but
stiffer for the integrator (BDF copes), and a load brought to rest creeps towards the
frictionless holding force with time constant ≈ R/(v_eps·k) (12 s for the Fig. 9 load on its
rope), where real friction would stick anywhere within ±R of it.

Moving masses: the load G_m/g, the rope q_l·L_u/g of each side (lumped on the nodes), the
return sheave's carriage m_t (constant-force tensioner), and with ``drive = "torque_limited"``
the drum, gearing and motor m_drive (reduced to the rim).  With ``drive = "speed"`` the drum's
speed is prescribed and its inertia does not enter the rope forces.
"""

from __future__ import annotations

from ropemodel.effects.base import (
    REGISTRY,
    Submodel,
    choice,
    define_effect,
    define_numerics,
    positive_number,
    register,
)
from ropemodel.effects.winch import D_DRUM, STROKE
from ropemodel.errors import InputError
from ropemodel.quantity import Quantity

MODEL = "winch"

define_effect(MODEL, "dynamics", "none", "time-domain transient: none, start (drive ramps up) or stop (ramps down)")
define_effect(MODEL, "travel", "up", "direction of travel of the simulated transient (up: load hauled up)")
define_effect(MODEL, "rope_elasticity", "segments", "rope model of the transient: rigid, spring or segments")
define_effect(MODEL, "tensioner", "constant_force", "return-sheave tensioner of the transient")
define_effect(MODEL, "ramp", "linear", "shape of the drive's speed ramp: linear or cosine (smooth)")
define_effect(MODEL, "drive", "speed", "drive of the transient: prescribed speed ramp, or a torque-limited motor")
define_effect(MODEL, "drum_contact", "rigid",
              "rope-on-drum contact of the transient: rigid, or capstan (Li et al. slip-zone stiffness in series)")


def _int_check(low: int, high: int):
    def check(key, value):
        if isinstance(value, bool) or not isinstance(value, int) or not (low <= value <= high):
            raise InputError(f"numerics {key} = {value!r} must be an integer in [{low}, {high}]")
        return value

    return check


define_numerics(MODEL, "segments", 8, "Kelvin-Voigt elements per rope span (rope_elasticity = segments)",
                _int_check(1, 400))
define_numerics(MODEL, "sim_rtol", 1e-8, "relative tolerance of the transient's integrator", positive_number(0.0, 1e-2))
define_numerics(MODEL, "sim_dt", 0.02, "output step of the transient's history [s]", positive_number(0.0, 10.0))
define_numerics(MODEL, "sim_integrator", "cvodes", "CasADi integrator of the transient (BDF: cvodes, idas)",
                choice("cvodes", "idas"))

_pos = dict(low=0.0, low_open=True, positive=True)

DYNAMIC = (
    Quantity("t_ramp", "s", "duration of the drive's linear speed ramp", "s", guess=5.0, **_pos),
    Quantity("t_end", "s", "end of the simulated transient", "s", guess=60.0, **_pos),
    Quantity("x_m", "m", "distance of the load from the drive along the winding rope", "m", guess=1000.0, **_pos),
    Quantity("v_eps", "m/s", "speed scale of the smoothed Coulomb resistance tanh(v/v_eps)", "m/s",
             default=0.01, warn_high=0.1, guess=0.01, **_pos),
)

#: quantities the transient reads that other winch effects declare: q_lw (elongation, Krauze eq. (19)),
#: v_pj (power), mu_d and alpha_d (lining: the drum's friction and wrap)
STATIC_INPUTS = ("q_lw", "v_pj", "mu_d", "alpha_d")


@register(MODEL, "dynamics", "none")
class NoDynamics(Submodel):
    """Static scene: no transient."""

    description = "no transient (static model only)"


class _Transient(Submodel):
    """A transient: declares the dynamic quantities and makes them parameters of the scene.

    ``equations`` builds no equation; it only *uses* the symbols of every quantity the
    dynamic model reads (its own, and those of every variant of ``rope_elasticity`` and
    ``tensioner``), so that the scene accepts, converts, range-checks and defaults them.
    """

    citations = ("krauze2025",)
    quantities = DYNAMIC

    def equations(self, v):
        names = [q.name for q in DYNAMIC] + list(STATIC_INPUTS)
        for effect in ("rope_elasticity", "tensioner"):
            for cls in REGISTRY[MODEL][effect].variants.values():
                names += [q.name for q in cls.quantities]
        for name in names:
            v[name]  # noqa: B018 - creating the symbol makes it a parameter
        return []

    def validate(self, values):
        if "x_m" in values and "L_u" in values and values["x_m"] >= values["L_u"]:
            raise InputError(f"x_m = {values['x_m']:g} m is not before the return sheave at L_u = "
                             f"{values['L_u']:g} m: the load must be on the route between drive and return "
                             f"sheave, 0 < x_m < L_u")
        if "t_end" in values and "t_ramp" in values and values["t_end"] < values["t_ramp"]:
            raise InputError(f"t_end = {values['t_end']:g} s is shorter than t_ramp = {values['t_ramp']:g} s; "
                             f"valid: t_end >= t_ramp")


@register(MODEL, "dynamics", "start")
class StartUp(_Transient):
    """Start-up: the drum's surface speed ramps linearly 0 → v_pj in t_ramp (constant acceleration)."""

    description = "start-up from rest, linear speed ramp to v_pj"


@register(MODEL, "dynamics", "stop")
class Braking(_Transient):
    """Braking: the drum's surface speed ramps linearly v_pj → 0 in t_ramp (constant deceleration)."""

    description = "braking from steady motion at v_pj, linear speed ramp to rest"


@register(MODEL, "travel", "up")
class TravelUp(Submodel):
    """The transient hauls the load up the incline (Krauze et al. 2025, upward column)."""

    description = "load hauled up"


@register(MODEL, "travel", "down")
class TravelDown(Submodel):
    """The transient lowers the load (Krauze et al. 2025, downward column)."""

    description = "load lowered"


@register(MODEL, "rope_elasticity", "segments")
class RopeSegments(Submodel):
    """Each rope span cut into ``segments`` Kelvin–Voigt elements (stiffness EA/ℓ, EA = L_u/q_lw from
    Krauze et al. 2025 eq. (19)-(20)); the rope's mass q_l ℓ/g lumped half on each node."""

    description = "lumped-mass rope, [numerics] segments Kelvin-Voigt elements per span"
    quantities = (
        Quantity("rope_damping", "s", "Kelvin-Voigt retardation time c/k of the rope (zeta = tau omega / 2)", "s",
                 low=0.0, default=0.05, warn_high=1.0, guess=0.05),
    )


@register(MODEL, "rope_elasticity", "spring")
class RopeSpring(Submodel):
    """Each rope span one Kelvin–Voigt element; its mass lumped half on each end."""

    description = "one Kelvin-Voigt spring per rope span"
    quantities = RopeSegments.quantities


@register(MODEL, "rope_elasticity", "rigid")
class RopeRigid(Submodel):
    """Inextensible rope: load and both rope sides move as one body (needs a constant-force tensioner)."""

    description = "inextensible rope, one degree of freedom"


@register(MODEL, "tensioner", "constant_force")
class ConstantForceTensioner(Submodel):
    """Return sheave on a carriage pulled with F_nwl (Krauze et al. 2025), free within its stroke.

    The take-up ``z`` is the rope length the tensioner has taken in (the loop's elongation,
    the paper's measure of stroke ΔF, eq. (23)); the carriage travels z/2 (180° wrap on the
    return sheave).  ``z`` runs from 0 (unstretched rope just taut) to ``stroke``.
    """

    description = "carriage pulled with F_nwl, stroke limits [0, stroke]"
    quantities = (
        Quantity("m_t", "kg", "mass of the return sheave and its carriage", "kg", low=0.0, low_open=True,
                 default=1000.0, guess=1000.0),
        STROKE,
    )


@register(MODEL, "ramp", "linear")
class LinearRamp(Submodel):
    """Linear speed ramp: constant acceleration, with steps of acceleration at both ends."""

    description = "linear speed ramp (constant acceleration)"


@register(MODEL, "ramp", "cosine")
class CosineRamp(Submodel):
    """Cosine speed ramp v = v_pj (1 − cos(π t/t_ramp))/2: no step of acceleration."""

    description = "cosine speed ramp (acceleration continuous, zero at both ends)"


@register(MODEL, "drive", "speed")
class SpeedDrive(Submodel):
    """The drum's surface speed is prescribed by the ramp (a stiff speed-controlled drive)."""

    description = "drum speed follows the ramp exactly"


@register(MODEL, "drive", "torque_limited")
class TorqueLimitedDrive(Submodel):
    """Speed-controlled drive whose motor force at the drum rim is limited to ±F_drive_max.

    Not in the paper.  F_drive_max = motor torque limit × gear ratio / drum radius; m_drive = the
    inertia of drum, gearing and motor reduced to the rim (J/R²).  Both required (no default).
    Builds no equation; only this variant makes them parameters of the scene.
    """

    description = "motor force at the rim limited to F_drive_max; drum inertia m_drive"
    quantities = (
        Quantity("F_drive_max", "N", "largest force the motor gives at the drum rim (torque limit / radius)",
                 "kN", guess=3e5, **_pos),
        Quantity("m_drive", "kg", "inertia of drum, gearing and motor reduced to the drum rim (J/R^2)", "kg",
                 guess=1e4, **_pos),
    )

    def equations(self, v):
        for q in self.quantities:
            v[q.name]  # noqa: B018 - creating the symbol makes it a parameter
        return []


@register(MODEL, "tensioner", "fixed")
class FixedTensioner(Submodel):
    """Return sheave locked where F_nwl put it with the haulage at rest (a fixed take-up)."""

    description = "carriage locked at its position at rest under F_nwl"


@register(MODEL, "drum_contact", "rigid")
class RigidDrumContact(Submodel):
    """The rope at the drum's tangent points moves with the drum surface while it sticks."""

    description = "rope on the drum rigidly attached while it sticks"


@register(MODEL, "drum_contact", "capstan")
class CapstanDrumContact(Submodel):
    """Contact compliance of the wrapped rope from the capstan model (Li et al., eq. (12), (15), (24)).

    Builds no equation; only this variant makes the drum diameter ``D`` (the lining's ``D_DRUM``)
    a parameter of the scene.  The mapping of the capstan model's quantities onto the drum (preload
    = slack-side force, load = tension difference, R = D/2, μ = mu_d, wrap alpha_d, EA = L_u/q_lw,
    free length → 0) and its limits are documented in :mod:`ropemodel.dynamics.contact`.
    """

    description = "slip-zone compliance of the rope on the drum in series with the tight span (Li et al.)"
    citations = ("li_capstan",)
    quantities = (D_DRUM,)

    def equations(self, v):
        v["D"]  # noqa: B018 - creating the symbol makes it a parameter
        return []
