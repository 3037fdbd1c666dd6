"""A whole trip along a route of segments: where the rope force and the drive power peak, energy per trip.

The built-in scene ``route_segments`` (three segments, 22°, 9°, 3° from the drive, the load of
Krauze et al. 2025 Fig. 9): an upward and a downward trip (``ropemodel.trips``), the winding and
unwinding rope forces of the upward trip and the drive power of both against the load's position
(signed: > 0 motoring, < 0 braking; lowered, the load drives the drum), with the paper's straight
incline replaced by the "equivalent slope" of the same rise as a comparison (one segment, the same
length and height): what the equivalent slope hides.

``python studies/route_trip.py [--fast]`` writes ``route_trip.csv`` (summaries) and ``route_trip.png``.
"""

from __future__ import annotations

import math

import pandas as pd

from ropemodel.studykit import cli, output_dir, save_figure

NAME = "route_trip"
#: line colour of each direction's drive power
COLOUR = {"up": "k", "down": "#1e8449"}


def equivalent_slope(scene):
    """The same route as one segment of the same length and rise (the "equivalent slope" of practice)."""
    import ropemodel as rm

    v = scene.parameters
    lengths = [v[f"L_{i}"] for i in range(1, 100) if f"L_{i}" in v]
    rise = sum(v[f"L_{i}"] * math.sin(v[f"alpha_{i}"]) for i in range(1, len(lengths) + 1))
    raw = dict(scene.raw)
    raw["route"] = [{"length": f"{sum(lengths)!r} m",
                     "inclination": f"{math.degrees(math.asin(rise / sum(lengths)))!r} deg"}]
    return rm.from_dict(raw, emit=False)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import ropemodel as rm
    from ropemodel.trips import trip

    out = output_dir(__file__, out_dir)
    scene = rm.load_scene("route_segments")
    flat = equivalent_slope(scene)
    rows, runs = [], {}
    for label, sc in (("route", scene), ("equivalent slope", flat)):
        for direction in ("up", "down"):
            t = trip(sc, direction)
            runs[label, direction] = t
            rows.append({"route": label, "direction": direction, **t.summary})
    table = pd.DataFrame(rows)
    table.to_csv(out / f"{NAME}.csv", index=False)

    fig, axes = plt.subplots(2, 1, figsize=(8, 6.6), sharex=True)
    for (label, direction), t in runs.items():
        h = t.history
        style = "-" if label == "route" else ":"
        if direction == "up":
            axes[0].plot(h["x_m [m]"], h["F_C [N]"] / 1e3, style, color="#c0392b", label=f"F_C, {label}")
            axes[0].plot(h["x_m [m]"], h["F_S [N]"] / 1e3, style, color="#2471a3", label=f"F_S, {label}")
        axes[1].plot(h["x_m [m]"], h["N_p [W]"] / 1e3, style, color=COLOUR[direction],
                     label=f"{direction}ward trip, {label}")
    axes[1].axhline(0.0, color="0.4", lw=0.8)
    axes[0].set_ylabel("rope force, upward trip [kN]")
    axes[1].set_ylabel("drive power N_p [kW]\n> 0 motoring, < 0 braking")
    axes[1].set_xlabel("load's distance from the drive x_m [m]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    up, flat_up = runs["route", "up"].summary, runs["equivalent slope", "up"].summary
    down = runs["route", "down"].summary
    fig.suptitle(f"Route of 3 segments vs its equivalent slope. Upward: peak F_C {up['F_C_max'] / 1e3:.0f} vs "
                 f"{flat_up['F_C_max'] / 1e3:.0f} kN, P_rms {up['P_rms'] / 1e3:.0f} vs {flat_up['P_rms'] / 1e3:.0f} kW."
                 f"\nDownward on the route the drive brakes: {down['E_regen'] / 1e6:.1f} MJ returned, "
                 f"{down['E_trip'] / 1e6:.2f} MJ drawn (where the 3° segment needs pulling)", fontsize=9)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)
    return table


if __name__ == "__main__":
    cli(main, __doc__, show=lambda t: t.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
