"""
Start-up transient of the Fig. 9 haulage
========================================

The static model is where the paper stops. ``rm.simulate`` integrates the start-up in time: the drive
ramps the drum to 2.5 m/s in 5 s, the elastic rope (lumped masses and Kelvin–Voigt elements) carries
the load, and the forces settle on the paper's static values. The peak winding force is 1.36 times
Fig. 9's 190.95 kN.
"""

import ropemodel as rm

sim = rm.simulate(rm.load_scene("winch_start"), progress=False)
sim

# %%
# The static force it settles on is Fig. 9's; the dynamic factor is the README's 1.36.
s = sim.summary
assert round(s["F_C_static"] / 1e3, 2) == 190.95 and round(s["dynamic_factor"], 2) == 1.36
sim.to_series()[["F_C_max [kN]", "F_C_static [kN]", "dynamic_factor [-]", "stroke_used [m]"]]

# %%
# The rope forces against time, with the static values they settle on:
sim.plot()
