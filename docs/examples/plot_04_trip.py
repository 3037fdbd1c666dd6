"""
A whole trip: power and energy along the Fig. 9 route
=====================================================

``rm.trip`` takes the load from one end of the route to the other: the drive ramps to v_pj, runs,
and ramps down. On the paper's incline with 5 s ramps, the start's inertia,
(G_m + q_l L_u)/g · a = 28.5 kN, adds to the paper's 190.95 kN.
"""

import ropemodel as rm

G = 9.80665
scene = rm.load_scene("trip_fig9")
trip = rm.trip(scene)
trip

# %%
# The peak winding force is Fig. 9's F_C_up plus the inertia of the load and the winding rope,
# written out here from the scene's numbers:
p = scene.parameters
inertia = (p["G_m"] + p["q_l"] * p["L_u"]) / G * p["v_pj"] / p["t_ramp"]       # 28.5 kN
F_C_up = rm.run(rm.load_scene())["F_C_up"]                                       # Fig. 9: 190.95 kN
assert round(F_C_up / 1e3, 2) == 190.95 and round(inertia / 1e3, 1) == 28.5
assert abs(trip.summary["F_C_max"] - (F_C_up + inertia)) < 1e-6 * F_C_up
trip.to_series()

# %%
# The drive's power over the trip: the peak at the end of the start, steady running, the stop.
trip.plot()
