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


def write_scene(tmp_path, extra: str = "", name: str = "dyn.toml", segments: int = 4):
    """The test scene as a file (``extra``: more [parameters] lines; ``segments``: rope elements per span)."""
    path = tmp_path / name
    path.write_text(SCENE.format(extra=extra).replace("segments = 4", f"segments = {segments}"))
    return path


#: the dynamic slip factor's default (``n_slip_dynamic``): the slip reserve the tests ask of a dynamic design
N_SLIP_DYNAMIC = 1.1
#: the four manoeuvres
MANOEUVRES = (("start", "up"), ("stop", "up"), ("start", "down"), ("stop", "down"))


def route_lengths(scene) -> list[float]:
    """The segment lengths [m] of a route of segments, or [L_u]."""
    v = scene.parameters
    lengths = [v[f"L_{i}"] for i in range(1, 100) if f"L_{i}" in v]
    return lengths or [v["L_u"]]


def places(scene) -> list[float]:
    """Where a manoeuvre can happen, as dynamic sizing must check it: on each segment its two ends and its
    middle (a joint from both sides: the load on the drive-side segment at the joint, on the far one 1 mm
    beyond it)."""
    out, start = [], 0.0
    for j, length in enumerate(route_lengths(scene)):
        out += [start + (1e-3 if j else 0.0), start + length / 2, start + length]
        start += length
    return out


def simulated_failures(scene, design: dict, values: dict | None = None, where=None, manoeuvres=MANOEUVRES,
                       t_end: float | None = None, slip_factor: float | None = None) -> list[str]:
    """Every check of the manoeuvres with the load at each place of ``where`` (default :func:`places`) judged
    from ``ropemodel.dynamics.simulate`` alone (the hybrid simulator at rtol 1e-10), written here from the
    simulator's history and events, independently of the sizing package: rope safety F_min = K d² R_r
    (EN 12385-4) against n_rope·max F_C and n_rope·max F_S, no slip, no stroke stop reached, no slack element,
    take-up within the stroke, F_S and F_C ≥ F_S_min.  ``t_end`` [s]: how long each manoeuvre is followed
    (default the scene's).  ``slip_factor``: also a slip reserve at every sample, e^{mu_d alpha_d} F_slack ≥
    slip_factor F_tight (Euler–Eytelwein on a rigid lining, both directions)."""
    import dataclasses

    import numpy as np

    from ropemodel.dynamics import simulate
    from ropemodel.papers import en12385

    v = scene.parameters
    F_min = en12385.minimum_breaking_force(en12385.construction(scene.effects["rope"]).K, design["d"],
                                           v["rope_grade"])
    extra = {**({"t_end": t_end} if t_end else {}), **(values or {})}
    failures = []
    for dynamics, travel in manoeuvres:
        for x in (places(scene) if where is None else where):
            sc = scene.with_effects({"dynamics": dynamics, "travel": travel, "inertia": "none"},
                                    optional=("d", "F_nwl", "stroke", "t_end", "D"))
            drum = {"D": 40 * design["d"]} if "D" in sc.absent else {}     # a rigid lining's traction: any D
            sc = sc.with_values({"x_m": x, **design, **drum, **extra})
            sc = dataclasses.replace(sc, numerics={**sc.numerics, "sim_rtol": 1e-10, "sim_dt": 1e-3})
            sim = simulate(sc, progress=False)
            s, h, tag = sim.summary, sim.history, f"{travel} {dynamics} at x_m = {x:g} m"
            F_C, F_S = h["F_C [N]"].to_numpy(), h["F_S [N]"].to_numpy()
            tests = {"slip": s["slip"], "stroke stop": bool(s["stroke_events"]) or s["stroke_exhausted"],
                     "slack": s["slack"] or h["T_min [N]"].min() < 0, "torque limit": s["torque_limited"],
                     "rope safety": v["n_rope"] * max(F_C.max(), F_S.max()) > F_min,
                     "take-up": h["take_up [m]"].max() > design["stroke"],
                     "taut": min(F_C.min(), F_S.min()) < v["F_S_min"]}
            if slip_factor is not None:
                rho = np.exp(v["mu_d"] * v["alpha_d"])
                reserve = rho * np.minimum(F_S, F_C) - slip_factor * np.maximum(F_S, F_C)
                tests["dynamic slip factor"] = bool((reserve < 0).any())
            failures += [f"{name} in the {tag}" for name, bad in tests.items() if bad]
    return failures
