"""A small winch sizing scene with transients for the dynamic sizing tests (Fig. 9 route and load, 4 rope
elements per span, 12 s manoeuvres with a 4 s linear ramp)."""

from __future__ import annotations

SCENE = """
[scene]
name = "dynamic sizing test"
model = "winch"

[effects]
rope = "6x36-IWRC"
checks = "design"
lining = "rigid"
power = "drive"
dynamics = "start"
travel = "up"
rope_elasticity = "segments"
tensioner = "constant_force"

[parameters]
L_u = "1150 m"
L_ul = "500 m"
alpha_u = "16 deg"
mu_pm = 0.05
mu_pl = 0.05
G_m = "467 kN"
v_pj = "2.5 m/s"
eta = 0.85
rope_grade = "1770 N/mm^2"
rope_E = "100 kN/mm^2"
mu_d = 0.2
alpha_d = "540 deg"
n_slip = 1.25
n_rope = 4.5
F_S_min = "5 kN"
D = "1.6 m"
t_ramp = "4 s"
t_end = "12 s"
rope_damping = "0.05 s"
m_t = "1000 kg"
{extra}
[numerics]
segments = 4
"""


def write_scene(tmp_path, extra: str = "", name: str = "dyn.toml"):
    """The test scene as a file (``extra``: more [parameters] lines)."""
    path = tmp_path / name
    path.write_text(SCENE.format(extra=extra))
    return path
