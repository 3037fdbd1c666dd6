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


#: the four manoeuvres: (dynamics, travel) → where the load is when the scene gives no x_m [fraction of L_u]
NATURAL = {("start", "up"): 1.0, ("stop", "up"): 0.0, ("start", "down"): 0.0, ("stop", "down"): 1.0}


def simulated_failures(scene, design: dict, values: dict | None = None) -> list[str]:
    """Every check of the four manoeuvres judged from ``ropemodel.dynamics.simulate`` alone (the hybrid
    simulator at rtol 1e-10), written here from the simulator's history and events, independently of the
    sizing package: rope safety F_min = K d² R_r (EN 12385-4) against n_rope·max F_C and n_rope·max F_S, no
    slip, no stroke stop reached, no slack element, take-up within the stroke, F_S and F_C ≥ F_S_min."""
    import dataclasses

    from ropemodel.dynamics import simulate
    from ropemodel.papers import en12385

    v = scene.parameters
    F_min = en12385.minimum_breaking_force(en12385.construction(scene.effects["rope"]).K, design["d"],
                                           v["rope_grade"])
    failures = []
    for (dynamics, travel), where in NATURAL.items():
        sc = scene.with_effects({"dynamics": dynamics, "travel": travel}, optional=("d", "F_nwl", "stroke"))
        sc = sc.with_values({"x_m": where * v["L_u"], **design, **(values or {})})
        sc = dataclasses.replace(sc, numerics={**sc.numerics, "sim_rtol": 1e-10, "sim_dt": 1e-3})
        sim = simulate(sc)
        s, h, tag = sim.summary, sim.history, f"{travel} {dynamics}"
        F_C, F_S = h["F_C [N]"].to_numpy(), h["F_S [N]"].to_numpy()
        tests = {"slip": s["slip"], "stroke stop": bool(s["stroke_events"]) or s["stroke_exhausted"],
                 "slack": s["slack"] or h["T_min [N]"].min() < 0, "torque limit": s["torque_limited"],
                 "rope safety": v["n_rope"] * max(F_C.max(), F_S.max()) > F_min,
                 "take-up": h["take_up [m]"].max() > design["stroke"],
                 "taut": min(F_C.min(), F_S.min()) < v["F_S_min"]}
        failures += [f"{name} in the {tag}" for name, bad in tests.items() if bad]
    return failures
