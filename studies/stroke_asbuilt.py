"""The tensioner's stroke by method: Krauze et al. (2025) eq. (19)-(23) against the stroke as built.

Two routes, each at a fixed design: the paper's Fig. 9 route (scene ``winch_sizing_fig9`` at its starting
design, the paper's 42 mm rope diameter and 20 kN pretension, a 6x36-IWRC catalogue rope) and the
three-segment route of issue 21 (``tests/_route3.py``, 36 mm, 24.7 kN).  Methods, one row each:

- ``paper q_lw``: eq. (19)-(23) with the paper's 5.8 mm/kN (Fig. 9 only: the paper's own 1402.94 mm);
- ``krauze2025``: eq. (19)-(23) with the catalogue rope's q_lw = L_u/(E C d²);
- ``profile``: the tension profile integrated (``elongation = "asbuilt"``), elastic only, one fall;
- ``profile, 2 falls``: the same, the return sheave movable (it moves half the loop's change);
- ``+ constructional``: a new rope's constructional stretch (the rope makers' table at n_rope), 2 falls;
- ``+ 20 K``: and the rope 20 K warmer than when installed.

The stroke is the largest over both directions and over the load's places (the drive and the return-sheave
end of each segment: the elongation is linear in x_m on a segment, so its largest is at an end).

``python studies/stroke_asbuilt.py [--fast]`` writes ``stroke_asbuilt.csv`` and ``stroke_asbuilt.png``.
"""

from __future__ import annotations

import tomllib
from importlib import resources

import pandas as pd

from ropemodel.studykit import cli, output_dir, save_figure

NAME = "stroke_asbuilt"
#: the three-segment route (tests/_route3.py), written out: a study does not import the tests
ROUTE3 = """\
[scene]
name = "three-segment"
[effects]
route = "segments"
rope = "6x36-IWRC"
lining = "rigid"
checks = "design"
[[route]]
length = "600 m"
inclination = "12 deg"
[[route]]
length = "700 m"
inclination = "20 deg"
[[route]]
length = "500 m"
inclination = "6 deg"
[parameters]
mu_pm = 0.05
mu_pl = 0.05
G_m = "300 kN"
rope_grade = "1770 N/mm^2"
rope_E = "100 kN/mm^2"
mu_d = 0.2
alpha_d = "540 deg"
n_slip = 1.25
n_rope = 5
F_S_min = "0.5 kN"
d = "36 mm"
F_nwl = "24.7 kN"
D = "3 m"
"""
#: (label, [effects] elongation, [parameters] overrides)
METHODS = (
    ("krauze2025", "krauze2025", {}),
    ("profile", "asbuilt", {"c_stretch": 0.0}),
    ("profile, 2 falls", "asbuilt", {"c_stretch": 0.0, "n_falls": 2}),
    ("+ constructional", "asbuilt", {"n_falls": 2}),
    ("+ 20 K", "asbuilt", {"n_falls": 2, "dT_rope": "20 K"}),
)


def routes() -> dict[str, dict]:
    """The two scenes as dictionaries (route name → scene)."""
    fig9 = tomllib.loads(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml").read_text())
    fig9["parameters"].pop("v_pj"), fig9["parameters"].pop("eta")            # no power effect here
    fig9["effects"].pop("power")
    return {"Fig. 9 route": fig9, "three segments": tomllib.loads(ROUTE3)}


def places(d: dict) -> list[float]:
    """The load's places [m]: the drive and the return-sheave end of each segment."""
    import ropemodel as rm

    v = rm.from_dict(d, emit=False).parameters
    lengths = [v[f"L_{i}"] for i in range(1, 100) if f"L_{i}" in v] or [v["L_u"]]
    return [0.0] + [sum(lengths[:j]) for j in range(1, len(lengths) + 1)]


def stroke(d: dict, variant: str, params: dict) -> dict:
    """The largest stroke over directions and places, where, and the rope's EA and q_lw."""
    import ropemodel as rm

    best: dict = {}
    placed = variant == "asbuilt" or "route" in d          # x_m matters: the profile, or the load's segment
    for x in places(d) if placed else [None]:
        at = {"x_m": f"{x!r} m"} if placed else {}
        scene = {**d, "effects": {**d["effects"], "elongation": variant},
                 "parameters": {**d["parameters"], **params, **at}}
        r = rm.run(rm.from_dict(scene, emit=False))
        for way in ("up", "down"):
            if not best or r[f"dF_{way}"] > best["stroke"]:
                best = {"stroke": r[f"dF_{way}"], "direction": way, "x_m": float("nan") if x is None else x,
                        "EA": r["EA"], "q_lw": r["q_lw"]}
    return best


def table() -> pd.DataFrame:
    """One row per route and method (SI)."""
    rows = []
    for route, d in routes().items():
        if route == "Fig. 9 route":        # the paper's own rope, q_lw = 5.8 mm/kN given (scene krauze2025_fig9)
            paper = tomllib.loads(resources.files("ropemodel.data").joinpath("krauze2025_fig9.toml").read_text())
            rows.append({"route": route, "method": "paper q_lw", **stroke(paper, "krauze2025", {})})
        rows += [{"route": route, "method": label, **stroke(d, variant, params)} for label, variant, params in METHODS]
    return pd.DataFrame(rows)


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = output_dir(__file__, out_dir)
    t = table()
    t.to_csv(out / f"{NAME}.csv", index=False)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, (route, part) in zip(axes, t.groupby("route", sort=False)):
        ax.barh(range(len(part)), part["stroke"], color="#2471a3")
        ax.set_yticks(range(len(part)), part["method"])
        ax.invert_yaxis()
        for y, (s, way, x) in enumerate(zip(part["stroke"], part["direction"], part["x_m"])):
            where = f", x_m = {x:.0f} m" if x == x else ""           # NaN: the stroke does not depend on x_m
            ax.text(s, y, f" {s:.2f} m ({way}{where})", va="center", fontsize=8)
        ax.set_title(f"{route}: EA = {part['EA'].iloc[-1] / 1e6:.1f} MN", fontsize=10)
        ax.set_xlabel("least stroke of the tensioner [m]")
        ax.set_xlim(0, part["stroke"].max() * 1.6)
        ax.grid(axis="x", alpha=0.3)
    fig.suptitle("The stroke by method: eq. (19)-(23) against the tension profile, the reeving, a new rope's "
                 "constructional stretch and temperature", fontsize=9)
    fig.tight_layout()
    save_figure(fig, __file__, out, NAME, fast)
    return t


if __name__ == "__main__":
    cli(main, __doc__, show=lambda t: t.to_string(index=False, float_format=lambda x: f"{x:.6g}"))
