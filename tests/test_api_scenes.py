"""Every function of the API takes a loaded Scene, a built-in scene's name or a TOML file's path alike
(``ropemodel.scene.as_scene``); rm.trip reads a scene as a trip needs it itself; the sizing sweeps and
sensitivities need no starting design (issue 21).

Truths: the same answer from the three forms of one scene (the file is the built-in's text, copied); the
trip time of a trapezoidal speed profile, L/v + t_ramp; the continuous sizing optimum of ``size`` (IPOPT
from the scene's start) against the sizing sweep's (Newton on a neighbour's active set): two methods.
"""

from __future__ import annotations

import json
from importlib import resources

import numpy as np
import pandas as pd
import pytest

import _route3 as r3
import optimisation
import ropemodel as rm
from ropemodel.cli import main as cli


def copy(name: str, tmp_path):
    path = tmp_path / f"{name}.toml"
    path.write_text(resources.files("ropemodel.data").joinpath(f"{name}.toml").read_text(encoding="utf-8"),
                    encoding="utf-8")
    return path


def curve_data():
    c = rm.load_curve("capstan_li_experiment", "100 N", n=9)
    return c[["F_T [N]", "delta_alpha [rad]"]].assign(**{"delta_alpha [rad]": lambda d: d["delta_alpha [rad]"]
                                                          + 1e-6 * np.sin(np.arange(len(d)))})


#: function → (built-in scene, the call, the part of its answer compared)
CALLS = {
    "Problem": ("krauze2025_fig9", lambda s: rm.Problem(s).solve(), lambda r: r.values),
    "run": ("krauze2025_fig9", rm.run, lambda r: r.values),
    "solve": ("krauze2025_fig9", lambda s: rm.solve(s, {"dF_up": "1000 mm"}, ["G_m"]), lambda r: r.values),
    "sweep": ("krauze2025_fig9", lambda s: rm.sweep(s, vary={"G_m": ["300 kN", "400 kN"]}, progress=False),
              lambda f: f.to_dict("list")),
    "elasticities": ("krauze2025_fig9", lambda s: rm.elasticities(s, outputs=["F_C_up"]), lambda f: f.to_dict("list")),
    "sobol": ("krauze2025_fig9", lambda s: rm.sobol(s, {"G_m": "300kN:500kN", "alpha_u": "10deg:20deg"}, ["F_C_up"],
                                            n=8), lambda f: f[["S1", "ST"]].to_dict("list")),   # not the bootstrap
    "load_curve": ("capstan_li_experiment", lambda s: rm.load_curve(s, "100 N", n=5), lambda f: f.to_dict("list")),
    "identify": ("capstan_li_experiment", lambda s: rm.identify(s, curve_data()), lambda r: r.estimates),
    "simulate": ("winch_start_stroke", lambda s: rm.simulate(s, progress=False), lambda r: r.summary["F_C_max"]),
    "trip": ("trip_fig9", rm.trip, lambda t: t.summary),
    "size": ("winch_sizing_fig9", lambda s: rm.size(s, with_sensitivities=False), lambda d: d.design),
    "report": ("sheave_hajduk_fig5", rm.report, lambda r: (r.shown, r.verdicts, r.incomplete)),
}


def test_every_function_of_the_facade_is_covered():
    scene_first = {n for n in rm.__all__ if n in CALLS}
    assert scene_first == set(CALLS)
    assert set(rm.__all__) - scene_first == {"IllPosedError", "InfeasibleError", "InputError", "RopeModelError",
                                             "SolveError", "__version__", "Result", "Scene", "from_dict", "from_toml",
                                             "load_scene", "tornado"}   # exceptions, types, readers, a chart


@pytest.mark.parametrize("function", CALLS)
def test_a_scene_a_name_and_a_path_give_the_same_answer(function, tmp_path):
    name, call, part = CALLS[function]
    answers = [part(call(form)) for form in (rm.load_scene(name, emit=False), name, copy(name, tmp_path))]
    assert answers[0] == answers[1] == answers[2]


def test_something_else_is_refused_in_one_line():
    with pytest.raises(rm.InputError, match="a scene is a Scene, the path of a TOML scene file or the name"):
        rm.run(42)
    with pytest.raises(rm.InputError, match="scene file not found"):
        rm.trip("no_such_scene")


def test_trip_reads_the_scene_as_a_trip_needs_it(tmp_path):
    scene = rm.load_scene(r3.write(tmp_path, design=True), emit=False)    # no dynamics, no inertia effect
    assert scene.effects["inertia"] == "none" and "t_ramp" in scene.unused
    t = rm.trip(scene)
    assert t.summary["t_trip"] == pytest.approx(r3.LENGTH / r3.SPEED + 4.0, rel=1e-12)
    assert t.scene.effects["inertia"] == "rigid" and t.scene.parameters["t_ramp"] == 4.0


def test_sizing_sweeps_and_sensitivities_need_no_starting_design(tmp_path, capsys):
    path = r3.write(tmp_path)                              # no d, F_nwl, stroke, D
    out = tmp_path / "s.csv"
    assert cli(["sweep", str(path), "--sizing", "--vary", "G_m=300kN,400kN", "-o", str(out), "-q"]) == 0
    frame = pd.read_csv(out)
    assert frame["feasible"].all()
    for g, row in zip((300e3, 400e3), frame.itertuples()):
        best = optimisation.size(rm.load_scene(path, optional=("d", "F_nwl", "stroke", "D"), emit=False)
                                 .with_values({"G_m": g}), with_sensitivities=False).continuous
        assert row._2 == pytest.approx(best["d"] * 1e3, rel=1e-6)            # d [mm]
        assert row._3 == pytest.approx(best["F_nwl"] / 1e3, rel=1e-6)        # F_nwl [kN]
    capsys.readouterr()
    assert cli(["sensitivity", str(path), "--sizing", "--sobol", "G_m=290kN:310kN", "--samples", "4", "--json",
                "-q"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert {r["output"] for r in rows} == {"d", "F_nwl", "stroke"}
