"""
A route of segments against its "equivalent slope"
==================================================

A real route changes gradient. Practice often replaces it by one incline of the same length and rise;
``studies/route_trip.py`` shows what that hides: on the three-segment route of the built-in scene
``route_segments`` (400 m at 22°, 650 m at 9°, 300 m at 3°, the Fig. 9 load), the equivalent slope
puts the peak winding force of an upward trip 22 % too low, 186 kN against 239 kN (F_nwl = 30 kN).
"""

import math

import ropemodel as rm

scene = rm.load_scene("route_segments")
route = rm.run(scene)
route.plot()      # the forces step where the load crosses a joint

# %%
# The same route as one incline of the same length and rise:
p = scene.parameters
lengths = [p["L_1"], p["L_2"], p["L_3"]]
rise = sum(L * math.sin(p[f"alpha_{i}"]) for i, L in enumerate(lengths, start=1))
data = dict(scene.raw)
data["route"] = [{"length": f"{sum(lengths)} m", "inclination": f"{math.degrees(math.asin(rise / sum(lengths)))} deg"}]
flat = rm.from_dict(data)

up, flat_up = rm.trip(scene, "up"), rm.trip(flat, "up")
peaks = round(up.summary["F_C_max"] / 1e3), round(flat_up.summary["F_C_max"] / 1e3)
assert peaks == (239, 186), peaks
assert round(1 - flat_up.summary["F_C_max"] / up.summary["F_C_max"], 2) == 0.22
up

# %%
# The drive's power over the upward trip: the steep stretch at the drive comes last and costs most.
up.plot()
