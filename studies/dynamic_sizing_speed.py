"""Dynamic sizing speed: a dynamic design, and a "no design" answer with its remedies, against one simulation of
the four manoeuvres (the least any method must spend to verify a design), measured in the same run.

Scenes: the shipped sizing scene (``winch_sizing_fig9``: the Fig. 9 route and load of Krauze et al. 2025,
6x36-IWRC catalogue rope, rigid drum) with a 4 s drive ramp, its transient built by dynamic sizing (defaults
stated by ``size --dynamic``); ``--fast`` stops there.  The full run adds the three-segment route of issue 21
(600 m at 12 deg, 700 m at 20 deg, 500 m at 6 deg; 300 kN; 3 m/s; 4 s ramp) and the "no design" answer of the
shipped scene with a 2 s ramp, 4 rope elements per span and 12 s manoeuvres (no design survives its start).

Contenders, each in this process, CPU seconds of the process (``time.process_time``: a shared machine's other
work does not count, and every contender runs on one thread), the shipped scene in ``rounds`` (three)
interleaved rounds, the route in one (each sizing about 10 CPU minutes); each ratio is the median over the
rounds of that round's two contenders, measured back to back (the seconds shown: medians):

* **peer** — one simulation of the four manoeuvres (start and stop, up and down) at the final design, at the
  final mesh, each with the load where that manoeuvre governs, by the project's hybrid simulator
  (:func:`ropemodel.dynamics.simulate`, ``ropemodel simulate``) at the tolerance verification needs
  (:data:`optimisation.dynamic.verify.SIM_RTOL`).  Why this peer and not scipy's ``solve_ivp`` on a plain
  numpy right-hand side: it is what a user of the library runs to check a design, it is independent of the NLP
  (its own integrator, events located, modes switched), and it is the faster of the two (a numpy right-hand
  side costs a Python call per evaluation: ``tests/test_dynamics_reference.py``'s LSODA reference of one
  start-up at rtol 1e-10 takes several times the simulator's time), so the ratios are not flattered by a slow
  peer.  The simulator solves its BDF's Newton systems by sparse LU ("csparse"), as the sizing's NLP does (with
  CasADi's default QR it took 5.4 instead of 2.3 CPU-s for the route's upward start at 32 elements).  For
  the "no design" scene, the four manoeuvres at its static optimum (the design a user would check);
* **dynamic** — ``size_dynamic(scene)`` (``ropemodel size --dynamic``): static optimum, dynamic NLP on its refined
  grid and controlled mesh, catalogue design, that design judged in every case (each manoeuvre at each place of
  the load), by simulation where a check comes near its limit and at each manoeuvre's least place (on the
  shipped scene 5 of 12 cases; on the route 6 of 36), elsewhere by the NLP's integration (``simulated`` in the
  table);
* **no design** — the same on the 2 s ramp: the scan of the design box (which finds no design, so the NLP is not
  started), the least violation, the seven remedies;
* **static** — ``optimisation.design.size(scene)`` (``ropemodel size``), for the ratio the issue asks too;
* **IPOPT re-solves** — ``size_dynamic(scene)`` with every re-solve of the dynamic NLP by IPOPT (the Newton
  step on the previous optimum's active set, :mod:`optimisation.dynamic.warm`, switched off): the peer of the
  warm re-solves, with the designs it returns compared.

Printed: the CPU seconds of each and the ratios dynamic / peer, no design / peer, dynamic / static, dynamic /
IPOPT re-solves, and whether both ways returned the same catalogue design.

    python studies/dynamic_sizing_speed.py [--fast | --route]

``--route``: the three-segment route alone, one round, without the IPOPT re-solves' sizing (about 1.7 CPU minutes).
"""

from __future__ import annotations

import contextlib
import time
from importlib import resources

import numpy as np
import pandas as pd

from ropemodel.studykit import cli, output_dir

NAME = "dynamic_sizing_speed"
#: the issue's goals, as ratios to the peer
GOAL_DESIGN = 10.0
GOAL_NO_DESIGN = 30.0
ROUTE3 = {
    "scene": {"name": "three-segment", "model": "winch"},
    "effects": {"route": "segments", "rope": "6x36-IWRC", "lining": "rigid", "checks": "design", "power": "drive"},
    "route": [{"length": "600 m", "inclination": "12 deg"}, {"length": "700 m", "inclination": "20 deg"},
              {"length": "500 m", "inclination": "6 deg"}],
    "parameters": {"mu_pm": 0.05, "mu_pl": 0.05, "G_m": "300 kN", "v_pj": "3 m/s", "t_ramp": "4 s", "eta": 0.85,
                   "rope_grade": "1770 N/mm^2", "rope_E": "100 kN/mm^2", "mu_d": 0.2, "alpha_d": "540 deg",
                   "n_slip": 1.25, "n_rope": 5, "F_S_min": "0.5 kN"},
}


def shipped(t_ramp: float):
    """The shipped sizing scene with a drive ramp of ``t_ramp`` [s], as ``size --dynamic`` reads it."""
    import ropemodel as rm
    from optimisation.problem import load_sizing

    scene = rm.load_scene(str(resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml")))
    return load_sizing(scene.with_values({"t_ramp": t_ramp}), emit=False)


def short_ramp():
    """The shipped scene with a 2 s ramp, 4 rope elements per span and 12 s manoeuvres (the scene of
    ``tests/_dynamic_scene.py``, whose ``size --dynamic`` answers "no design", exit 1)."""
    import dataclasses

    from optimisation.dynamic.transient import transient_scene

    scene = transient_scene(shipped(2.0)).with_values({"t_end": 12.0})
    return dataclasses.replace(scene, numerics={**scene.numerics, "segments": 4})


def route3():
    import ropemodel as rm
    from optimisation.problem import D_OPTIONAL, SIZED, load_sizing

    return load_sizing(rm.from_dict(ROUTE3, optional=SIZED + D_OPTIONAL, emit=False), emit=False)


def cpu(fn):
    """(result, CPU seconds of this process)."""
    t0 = time.process_time()
    out = fn()
    return out, time.process_time() - t0


def peer(scene, design: dict, places: dict, segments: int | None = None) -> float:
    """CPU seconds of one simulation of the four manoeuvres at ``design`` (SI), each with the load at
    ``places[manoeuvre label]`` (x_m [m]; default the middle of the route), with ``segments`` rope elements per
    span (the sizing's final mesh; default the scene's)."""
    from optimisation.dynamic.manoeuvres import cases
    from optimisation.dynamic.mesh import with_segments
    from optimisation.dynamic.transient import transient_scene
    from optimisation.dynamic.verify import simulation_scene
    from ropemodel.dynamics import simulate

    sc = transient_scene(scene)
    sc = with_segments(sc, segments) if segments else sc
    every = cases(sc)
    chosen = []
    for label in dict.fromkeys(m.label for m in every):
        mine = [m for m in every if m.label == label]
        want = places.get(label, mine[len(mine) // 2].x_m)
        chosen.append(min(mine, key=lambda m: abs(m.x_m - want)))
    scenes = [simulation_scene(sc, m, design) for m in chosen]
    return cpu(lambda: [simulate(s) for s in scenes])[1]


@contextlib.contextmanager
def ipopt_resolves():
    """Within: every re-solve of the dynamic NLP by IPOPT (no Newton step on the previous active set)."""
    from optimisation.dynamic import refine

    keep = refine.on_active_set
    refine.on_active_set = lambda *args, **kwargs: None
    try:
        yield
    finally:
        refine.on_active_set = keep


def static_optimum(scene) -> dict:
    from optimisation.design import solve_best
    from optimisation.problem import SizingProblem

    problem = SizingProblem(scene)
    return problem.to_si(solve_best(problem).xs)


def design_case(name: str, scene, rounds: int, ipopt: bool = True) -> dict:
    """The dynamic design of ``scene`` against the peer at its catalogue design and against static sizing (and,
    ``ipopt``, against the same sizing with every re-solve by IPOPT)."""
    from optimisation.design import size
    from optimisation.dynamic import size_dynamic
    from optimisation.dynamic.verify import SIMULATED

    seen: dict = {}
    for _ in range(rounds):
        design, t_dyn = cpu(lambda: size_dynamic(scene))
        places = {m["manoeuvre"]: m["x_m"] for m in design.manoeuvres}
        t_peer = peer(scene, design.design, places, design.mesh.get("segments"))
        t_static = cpu(lambda: size(scene, with_sensitivities=False))[1]
        cold, t_cold = design, np.nan
        if ipopt:
            with ipopt_resolves():
                cold, t_cold = cpu(lambda: size_dynamic(scene))
        for key, value in (("dynamic [CPU s]", t_dyn), ("peer [CPU s]", t_peer), ("static [CPU s]", t_static),
                           ("IPOPT re-solves [CPU s]", t_cold), ("ratio to peer", t_dyn / t_peer),
                           ("ratio to static", t_dyn / t_static), ("ratio to IPOPT re-solves", t_dyn / t_cold)):
            seen.setdefault(key, []).append(value)
    simulated = sum(p["judged_by"] == SIMULATED for m in design.manoeuvres for p in m["positions"])
    return {"case": name, "answer": "design" if design.feasible else "no design", "rounds": rounds,
            **{key: float(np.median(values)) for key, values in seen.items()}, "segments": design.mesh.get("segments"),
            "simulated": f"{simulated} of {sum(len(m['positions']) for m in design.manoeuvres)}",
            "design": _shown(design.design) if design.feasible else None,
            "same design": (design.feasible and cold.feasible and design.design == cold.design) if ipopt else None,
            "goal": GOAL_DESIGN if design.feasible else GOAL_NO_DESIGN, "message": design.message.splitlines()[0]}


def _shown(design: dict) -> str:
    """The catalogue design in the units a designer reads: ``"50 mm, 100.9 kN, 6.293 m"``."""
    return f"{design['d'] * 1e3:g} mm, {design['F_nwl'] / 1e3:g} kN, {design['stroke']:g} m"


def no_design_case(name: str, scene, rounds: int = 1) -> dict:
    """The "no design" answer of ``scene`` (with its scan and remedies) against the peer at its static optimum, in
    ``rounds`` rounds (medians; each ratio that of its own round's two contenders)."""
    from optimisation.design import size
    from optimisation.dynamic import size_dynamic

    seen: dict = {}
    for _ in range(rounds):
        design, t_dyn = cpu(lambda: size_dynamic(scene))
        t_peer = peer(scene, static_optimum(scene), {})
        t_static = cpu(lambda: size(scene, with_sensitivities=False))[1]
        for key, value in (("dynamic [CPU s]", t_dyn), ("peer [CPU s]", t_peer), ("static [CPU s]", t_static),
                           ("ratio to peer", t_dyn / t_peer), ("ratio to static", t_dyn / t_static)):
            seen.setdefault(key, []).append(value)
    return {"case": name, "answer": "design" if design.feasible else "no design", "rounds": rounds,
            **{key: float(np.median(values)) for key, values in seen.items()},
            "goal": GOAL_DESIGN if design.feasible else GOAL_NO_DESIGN, "message": design.message}


def main(out_dir=None, fast: bool = False, rounds: int = 3, route: bool = False) -> pd.DataFrame:
    """The table of contenders (one row a scene); ``fast``: the shipped scene alone; ``route``: the three-segment
    route alone, one round, without the IPOPT re-solves' sizing (half the time)."""
    out = output_dir(__file__, out_dir)
    if route:
        rows = [design_case("three-segment route, 4 s ramp", route3(), 1, ipopt=False)]
    else:
        rows = [design_case("shipped scene, 4 s ramp", shipped(4.0), rounds)]
    if not fast and not route:
        rows.append(design_case("three-segment route, 4 s ramp", route3(), 1))
        rows.append(no_design_case("shipped scene, 2 s ramp, 4 elements (no design)", short_ramp(), rounds))
    df = pd.DataFrame(rows)
    df["meets goal"] = df["ratio to peer"] <= df["goal"]
    df.to_csv(out / f"{NAME}.csv", index=False)
    return df


def show(df: pd.DataFrame) -> str:
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        return df.drop(columns=["message"]).round(2).to_string(index=False)


if __name__ == "__main__":
    import argparse
    import sys

    if "--route" in sys.argv:       # the route alone (``cli`` takes --fast and --out)
        parser = argparse.ArgumentParser(description="the three-segment route's dynamic design against its peer")
        parser.add_argument("--route", action="store_true")
        parser.add_argument("--out", default=None)
        print(show(main(parser.parse_args().out, route=True)))
    else:
        cli(main, __doc__, show)
