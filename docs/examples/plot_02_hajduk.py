"""
Hajduk (1992): the tension along a lined sheave's arc
=====================================================

A rope on a sheave whose lining is a chain of Voigt bodies transmits less than Euler–Eytelwein's
e^{μα}, and with a soft lining its tension first falls in a boundary layer where the rope enters
the arc. The reference table of docs/physics.md §3 (the closed form ln s + q s (1 − e^{−α/k}) = μα,
computed independently) is reproduced to its 6 decimals, and Hajduk's Fig. 5 case is drawn.
"""

import math

import pandas as pd

import ropemodel as rm

# %%
# The table: μ, q = Q S_0 and k = λω, and s = S/S_0 at α = π/2, π and 2π.
TABLE = [  # mu, q, k, s(pi/2), s(pi), s(2 pi)
    (0.2, 0.1, 0.01 * math.pi, 1.212743, 1.597677, 2.685966),
    (0.2, 0.1, 2 * math.pi, 1.329433, 1.749747, 2.921169),
    (0.2, 100, 0.01 * math.pi, 0.036301, 0.038781, 0.043839),
    (0.3, 0.1, 0.5 * math.pi, 1.460686, 2.133928, 4.312762),
    (0.3, 100, 2 * math.pi, 0.117940, 0.086236, 0.071543),
]
rows = []
for mu, q, k, *printed in TABLE:
    for alpha, s in zip((math.pi / 2, math.pi, 2 * math.pi), printed):
        scene = rm.from_dict({"scene": {"model": "sheave"}, "effects": {"lining": "voigt"},
                              "parameters": {"S_0": "10 kN", "mu": mu, "alpha": f"{alpha} rad",
                                             "Q": f"{q / 1e4} 1/N", "lambda": f"{k} s", "omega": "1 rad/s"}})
        got = rm.run(scene)["S_ratio"]
        rows.append({"mu": mu, "q": q, "k": round(k, 4), "alpha [deg]": round(math.degrees(alpha)),
                     "table": s, "ropemodel": round(got, 6)})
check = pd.DataFrame(rows)
assert (check["table"] == check["ropemodel"]).all(), check[check["table"] != check["ropemodel"]]
check

# %%
# Hajduk's Fig. 5 case (μ = 0.2, Q S_0 = 0.1, λω = 0.01π) is the table's first row: the tension along
# the whole arc, against e^{μα}. Just after the rope enters, the lining gives way and S dips below S_0.
fig5 = rm.run(rm.load_scene("sheave_hajduk_fig5"))
assert round(fig5["S_ratio"], 6) == 2.685966
fig5.plot()
