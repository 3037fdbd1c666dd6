"""
Krauze et al. (2025), Fig. 9: all 25 printed values
===================================================

The paper's worked example: an endless-rope haulage over a 1150 m incline at 16°, a 467 kN load,
a 42 mm rope. ``rm.run`` reproduces every one of the 25 values Fig. 9 prints, to its last digit.
"""

import ropemodel as rm

scene = rm.load_scene()          # the built-in example, ropemodel/data/krauze2025_fig9.toml
scene

# %%
# The result shows itself as tables with units: inputs, results with their equation numbers, and the
# forces of both directions of travel side by side.
result = rm.run(scene)
result

# %%
# Fig. 9 prints these values (kN and mm, to 0.01). Every one is reproduced:
PRINTED = {
    "G_ml": 128.72, "G_l1": 14.33, "G_l2": 11.03, "G_l": 25.36, "G_mo": 448.91, "G_ls": 25.36,
    "T_m": 22.45, "T_l1": 2.50, "T_l2": 1.92, "T_l": 4.42, "T_ls": 4.42, "G_lmC": 154.08,
    "F_S_down": 39.78, "F_S_up": 30.94, "F_C_down": 137.21, "F_C_up": 190.95,
    "dF_C_down": 795.84, "dF_C_up": 1107.50, "dF_S_down": 230.73, "dF_S_up": 179.43,
    "dF_CS_down": 1026.57, "dF_CS_up": 1286.94, "dF_nwl": 116.00, "dF_down": 1142.57, "dF_up": 1402.94,
}
frame = result.to_frame()
table = frame.loc[list(PRINTED), ["value", "unit", "source"]].assign(printed=PRINTED)
table["reproduced"] = table["value"].round(2) == table["printed"]
assert len(PRINTED) == 25 and table["reproduced"].all(), table[~table["reproduced"]]
table

# %%
# The upward stroke, 1402.94 mm, is what the paper means by "the installed 1000 mm stroke is 403 mm
# short". Which load would a 1000 mm stroke allow? An inverse question: the stroke given, the load found.
heaviest = rm.solve(scene, given={"dF_up": "1000 mm"}, find=["G_m"])
assert round(heaviest["G_m"] / 1e3, 3) == 252.383
heaviest.to_frame().loc[["G_m", "dF_up"]]

# %%
# On the paper's straight route the forces do not depend on where the load is: each rope side spans
# the whole route (docs/physics.md §1). ``plot()`` draws them as the load moves from the drive to
# the return sheave.
result.plot()
