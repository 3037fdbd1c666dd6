"""Section "trip": a whole trip up and down the route (``ropemodel trip``): forces, drive power and
energy, exactly piece by piece (:mod:`ropemodel.trips`), with the route's profile when it has segments.

Shown for a scene about trips (``dynamics = "trip"`` or a route of ``[[route]]`` segments), of a machine that
makes trips, that gives the speed ``v_pj`` and the ramp time ``t_ramp``.
"""

from __future__ import annotations

import math

from ropemodel.reports import figures, page
from ropemodel.reports.registry import section
from ropemodel.effects.route_arrays import RouteArrays
from ropemodel.machines import machine_of

#: summary key → (label, unit shown, factor from SI), then the keys the machine adds (its ``trips.ROWS``); the
#: braking energy's label comes from the scene's ``braking`` variant (returned to the supply or dissipated)
ROWS = {"t_trip": ("trip time", "s", 1.0), "F_C_max": ("largest winding-rope force F_C", "kN", 1e-3),
        "F_S_min": ("least unwinding-rope force F_S", "kN", 1e-3),
        "P_max": ("largest motoring drive power (> 0)", "kW", 1e-3),
        "P_brake_max": ("largest braking drive power (< 0)", "kW", 1e-3),
        "P_rms": ("r.m.s. drive power (the motor's thermal rating, braking included)", "kW", 1e-3),
        "E_trip": ("energy drawn while motoring", "kWh", 1 / 3.6e6),
        "E_regen": ("energy returned to the supply while braking", "kWh", 1 / 3.6e6),
        "E_dissipated": ("energy dissipated in the braking resistor while braking", "kWh", 1 / 3.6e6),
        "W_drum": ("net work of the drum (the load's potential energy change plus friction)", "kWh", 1 / 3.6e6)}
#: history columns drawn, one panel per unit
UNITS = ("m/s", "N", "W")


def has_trip(ctx) -> bool:
    """A scene of a machine that makes trips (:attr:`ropemodel.machines.Machine.trips`), about trips, that
    gives the speed and the ramp time (used by its effects or not)."""
    e, given = ctx.scene.effects, {**ctx.scene.parameters, **ctx.scene.unused_values}   # a trip uses v_pj, t_ramp
    trips = getattr(machine_of(ctx.scene), "trips", None)
    return (trips is not None and (e.get("dynamics") == "trip" or e.get("route") == "segments")
            and "v_pj" in given and "t_ramp" in given)


def reads(ctx) -> set[str]:
    """What the trips are computed from (:func:`ropemodel.trips.reads`)."""
    from ropemodel.trips import prepare, reads as trip_reads

    return trip_reads(prepare(ctx.scene))[0]


@section("trip", "Trip", when=has_trip, reads=reads)
def trip(ctx):
    runs = ctx.trips
    braking = next(iter(runs.values())).braking
    html = page.fragment("<p>A whole trip each way{{ at }}: the drive ramps to v_pj in t_ramp, runs, and "
                         "ramps to rest; the forces add the ramps' rigid-body inertia to the paper's eq. (12)-(13) "
                         "on the load's segment, and power and energy are integrated exactly. Powers are signed "
                         "(four-quadrant): positive while the drive motors, negative while it brakes (the load "
                         "drives the drum); the drive's braking energy is {{ where }} (braking = "
                         "\"{{ variant }}\").</p>",
                         at=", at the recommended design" if ctx.at_design else "",
                         where=braking.destination, variant=braking.variant)
    head = ["quantity", "upward", "downward", "unit"]
    shown = {**ROWS, **machine_of(ctx.scene).trips.ROWS}
    rows = [[label, *(f"{runs[d].summary[k] * f:.6g}" for d in ("up", "down")), unit]
            for k, (label, unit, f) in shown.items() if all(k in run.summary for run in runs.values())]
    html += page.table(head, rows, kinds=["", "num", "num", ""])
    profile = _profile(ctx)
    if profile:
        html += page.fragment('<figure><img src="{{ u }}" alt="route profile"><figcaption>The route from the drive '
                              "(x = 0): height against distance, one straight line per segment.</figcaption></figure>",
                              u=profile)
    for d, run in runs.items():
        uri = figures.panels(run.history, "t [s]", UNITS, title=f"{ctx.scene.name}: trip {d}")
        if uri:
            html += page.fragment('<figure><img src="{{ u }}" alt="trip {{ d }}"><figcaption>Trip {{ d }}: the '
                                  "load's speed (m/s, positive up the slope), rope forces (kN), and the drum's and "
                                  "the drive's power (kW, positive motoring, negative braking) against "
                                  "time.</figcaption></figure>", u=uri, d=d)
    return html


def _profile(ctx):
    """The route's profile (height against distance from the drive) as an SVG URI; None for one incline."""
    if not ctx.scene.route:
        return None
    segments = RouteArrays.from_values(ctx.point.parameters)
    xs, hs = [0.0], [0.0]
    for length, a in zip(segments.L.tolist(), segments.alpha.tolist()):
        xs.append(xs[-1] + length * math.cos(a))
        hs.append(hs[-1] - length * math.sin(a))   # the route falls away from the drive toward the return sheave
    fig = figures.new_figure(figures.WIDTH, 2.2)
    ax = fig.subplots()
    ax.plot(xs, hs, "-o", lw=1.4, ms=3)
    ax.set_xlabel("horizontal distance from the drive [m]")
    ax.set_ylabel("height [m]")
    ax.grid(True, lw=0.4, alpha=0.6)
    return figures.svg_uri(fig)
