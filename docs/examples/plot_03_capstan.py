"""
Li et al.: the load curve of a capstan cable drive
==================================================

The equivalent stiffness of a preloaded capstan drive falls as the load grows and the slip zones
spread over the wrap (Li et al., eq. (26)). At no load the wrap sticks and the two free spans act
as springs in parallel, K = 2 EA/L; once the load reaches the preload the slack side has let go and
only the tight side carries it: K is that side's stiffness alone.
"""

import ropemodel as rm

scene = rm.load_scene("capstan_li_experiment")
result = rm.run(scene)
result

# %%
# The whole curve from no load to 100 N, in the display units of the paper (N/mm, degrees):
curve = rm.load_curve(scene, "100 N", n=201, display=True)
EA, L = scene.parameters["EA"], scene.parameters["L"]
assert abs(curve["K [N/mm]"].iloc[0] - 2 * EA / L / 1e3) < 1e-9          # 2 EA/L = 277.78 N/mm
beyond = curve[curve["F_T [N]"] > scene.parameters["F_p"]]
assert (beyond["regime [-]"] == 4).all() and (beyond["K_sl [N/mm]"] == 0).all()
assert (abs(beyond["K [N/mm]"] - beyond["K_ti [N/mm]"]) < 1e-9).all()    # the tight side alone
curve.iloc[::25]

# %%
# ``result.plot()`` draws K against the load and marks this scene's point.
result.plot()
