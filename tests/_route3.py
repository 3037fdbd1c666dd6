"""The three-segment route of issue 21 (600 m at 12°, 700 m at 20°, 500 m at 6°; 300 kN; 3 m/s; a 4 s ramp;
a 6x36-IWRC catalogue rope on a rigid drum), as a new user wrote it: no design, no transient effects."""

from __future__ import annotations

SCENE = """\
[scene]
name = "three-segment"
[effects]
route = "segments"
rope = "6x36-IWRC"
lining = "rigid"
checks = "design"
power = "drive"
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
v_pj = "3 m/s"
t_ramp = "4 s"
eta = 0.85
rope_grade = "1770 N/mm^2"
rope_E = "100 kN/mm^2"
mu_d = 0.2
alpha_d = "540 deg"
n_slip = 1.25
n_rope = 5
F_S_min = "0.5 kN"
"""
#: a design on it (what ``size`` recommends, a 3 m drum): the scene a trip or a run of it needs
DESIGN = 'd = "36 mm"\nF_nwl = "24.7 kN"\nD = "3 m"\nstroke = "7 m"\n'
#: the route's length [m] and speed [m/s]
LENGTH, SPEED = 1800.0, 3.0


def write(tmp_path, design: bool = False, extra: str = "", name: str = "route3.toml"):
    """The scene as a file in ``tmp_path`` (with the design, and ``extra`` lines in [parameters])."""
    path = tmp_path / name
    path.write_text(SCENE + (DESIGN if design else "") + extra, encoding="utf-8")
    return path
