"""A value given on top of a scene's file (``--set``, ``values=``, ``Scene.with_values``, a sweep's points)
reaches every command that uses it; a command that does not use it says so (issue 21, item 4).

Truths: the trip time of a trapezoidal speed profile, L/v + t_ramp (written out here); the answer of the
same scene with the value edited into its file (the path that always worked); and, for the matrix, the
two sides of every report: a value a command says it does not use leaves its answer unchanged, and a value
it does not name changes it, except where the physics makes the answer independent of it (each case below,
with the closed form that shows it).
"""

from __future__ import annotations

import math
import re

import pytest

import _route3 as r3
import ropemodel as rm
from optimisation.problem import D_OPTIONAL, SIZED
from ropemodel.cli import main as cli
from ropemodel.scene import builtin_scenes, from_toml, load
from ropemodel.unread import unread
from ropemodel.trips import TRIP_EFFECTS


def trapezoid_time(length: float, speed: float, ramp: float) -> float:
    """Time of a trip that ramps linearly to ``speed`` in ``ramp``, runs, and ramps down: the distance of
    both ramps is speed·ramp, so t = 2 ramp + (length − speed·ramp)/speed."""
    assert length >= speed * ramp
    return 2 * ramp + (length - speed * ramp) / speed


def test_a_ramp_set_on_top_reaches_the_trip(tmp_path, capsys):
    path = r3.write(tmp_path, design=True)
    for ramp in (4.0, 40.0):
        t = rm.trip(load(path, emit=False).with_values({"t_ramp": f"{ramp:g} s"}))
        assert t.summary["t_trip"] == pytest.approx(trapezoid_time(r3.LENGTH, r3.SPEED, ramp), rel=1e-12)
    assert cli(["trip", str(path), "--set", "t_ramp=40s", "--json"]) == 0
    import json

    assert json.loads(capsys.readouterr().out)["t_trip"] == pytest.approx(640.0, rel=1e-12)


def test_a_ramp_set_on_top_reaches_the_sizing_as_if_edited_into_the_file(tmp_path):
    from optimisation import size

    base = load(r3.write(tmp_path), optional=SIZED + D_OPTIONAL, emit=False)
    edited = r3.write(tmp_path, name="edited.toml").read_text().replace('t_ramp = "4 s"', 't_ramp = "40 s"')
    (tmp_path / "edited.toml").write_text(edited)
    by_set = size(base.with_values({"t_ramp": "40 s"}, origin="--set"), with_sensitivities=False)
    by_file = size(tmp_path / "edited.toml", with_sensitivities=False)
    four = size(base, with_sensitivities=False)
    assert by_set.margins == pytest.approx(by_file.margins, rel=1e-12)
    assert by_set.design == by_file.design
    # a ramp ten times longer: a tenth of the start's inertia, which governs the sizing (the worst start, on the
    # 20° segment), so a thinner rope, less pretension and less drive power at that start
    assert four.governing["slip_margin_up"]["manoeuvre"] == by_set.governing["slip_margin_up"]["manoeuvre"] == "start"
    assert by_set.design["d"] < four.design["d"] and by_set.design["F_nwl"] < four.design["F_nwl"]
    assert by_set.power["N_p_up"] < four.power["N_p_up"]


def test_with_effects_keeps_every_value_with_where_it_came_from(tmp_path):
    scene = load(r3.write(tmp_path, design=True), emit=False)
    assert "t_ramp" in scene.unused                      # no transient effect: a trip's value, kept aside
    given = scene.with_values({"t_ramp": "40 s", "G_m": "310 kN"}, origin="--set")
    assert given.unused_values["t_ramp"] == 40.0 and given.origin["t_ramp"] == "--set"
    trip = given.with_effects(TRIP_EFFECTS)
    assert trip.parameters["t_ramp"] == 40.0 and trip.parameters["G_m"] == 310e3
    assert {trip.origin[k] for k in ("t_ramp", "G_m")} == {"--set"}
    assert trip.origin["L_2"] == "route" and trip.origin["mu_pm"] == "scene"
    # a value the new effects do not use is kept for the next switch, with its origin
    fig9 = load("winch_sizing_fig9", emit=False).with_values({"n_rope": 6}, origin="--set")
    off = fig9.with_effects({"checks": "none"})
    assert "n_rope" in off.unused and off.unused_values["n_rope"] == 6
    back = off.with_effects({"checks": "design"})
    assert back.parameters["n_rope"] == 6 and back.origin["n_rope"] == "--set"


def test_a_value_a_command_does_not_use_is_named_on_the_command_line(capsys):
    assert cli(["run", "winch_start", "--set", "t_ramp=8s"]) == 0
    assert "t_ramp = 8 s (--set) does not change what run computes" in capsys.readouterr().err
    assert cli(["size", "winch_sizing_fig9", "--set", "d=40mm", "--json"]) == 0
    err = capsys.readouterr().err
    assert "d = 40 mm (--set) does not change what the sizing computes: the sizing chooses it" in err
    assert cli(["curve", "capstan_li_experiment", "--to", "100N", "-n", "3", "--set", "F_T=10N"]) == 0
    assert "F_T = 10 N (--set) does not change what curve computes" in capsys.readouterr().err


# ------------------------------------------------------------------------------------------------ the matrix

def nudged(scene, name: str):
    """The scene with ``name`` moved by 10 % (or to a valid value nearby), and that value (SI)."""
    value = scene.parameters.get(name, scene.unused_values.get(name))
    for f in (1.1, 0.9, 1.5, 0.5):
        new = value * f if value not in (0.0, math.inf) else (0.05 if value == 0.0 else 5.0)
        try:
            return scene.with_values({name: new}), new
        except rm.InputError:
            continue
    raise AssertionError(f"no valid value of {name} near {value}")


def leaves(x, prefix="") -> dict[str, float | str]:
    """Every number (a float) and text of a nested answer, by its path."""
    if isinstance(x, dict):
        return {k: v for key, val in x.items() for k, v in leaves(val, f"{prefix}{key}.").items()}
    if isinstance(x, list | tuple):
        return {k: v for i, val in enumerate(x) for k, v in leaves(val, f"{prefix}{i}.").items()}
    if isinstance(x, int | float) and not isinstance(x, bool):
        return {prefix: float(x)}
    return {prefix: str(x)}


def differ(a: float | str, b: float | str, rtol: float) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return a != b
    return not (math.isnan(a) and math.isnan(b)) and abs(a - b) > rtol * max(abs(a), abs(b))


def changed(a, b, rtol: float = 1e-12) -> bool:
    """True when two answers differ: a text, or a number by more than rounding (``rtol``)."""
    x, y = leaves(a), leaves(b)
    return x.keys() != y.keys() or any(differ(x[k], y[k], rtol) for k in x)


def independent(scene, command: str, name: str) -> str | None:
    """Why the answer of ``command`` cannot depend on ``name`` in this scene, from the physics (or None).

    * L_ul splits the route at the drive for two resistance coefficients; with one (case 1, μ_pl1 = μ_pl2)
      the totals G_l = q_l L_u sin α_u and T_l = μ_pl q_l L_u cos α_u do not depend on it (Krauze et al.
      2025, eq. (2)-(4), (8)-(10)): only the split shown by run, solve, sweep and sensitivity moves.
    * λ, ω of a Voigt lining enter through e^(−α/(λω)) (Hajduk 1992, eq. (19)); at α/(λω) > 40 that is
      below 1e-17 of 1, so the answer equals the elastic limit to the last bit.
    * n_slip is the factor of the static slip check; a transient integrates the slip itself.
    * n_slip_dynamic is the factor of dynamic sizing's slip checks through a manoeuvre, and mesh_tol its
      tolerance on the rope's discretisation: a simulation slips at the onset and takes ``[numerics] segments``
      as given.  In dynamic sizing mesh_tol only chooses the elements per span (each back-off is the estimate
      itself), so 10 % more tolerance can leave the mesh, and the answer, as they are.
    * η turns the drum's power into the drive's; a transient gives the drum's forces and work only.
    * An inextensible rope (``rope_elasticity = "rigid"``) has no elongation rate to damp (rope_damping),
      and the carriage of its tensioner never moves (m_t).
    * t_end does not matter to a transient that stopped before it (an event ended it).
    * A simulation runs the scene's own manoeuvre (its ramps, its brake): the emergency stop's deceleration a_e
      is a load case of the static worst case only (ropemodel.envelope.cases).
    * An emergency stop (a_e) gentler than the ramps' stop (v_pj/t_ramp at least) never governs a worst case:
      with rigid-body inertia each force is affine in the acceleration, each check and power monotone in the
      forces and each least tension the least of affine ones, so each worst lies at an extreme acceleration
      (docs/physics.md §4); the nudge takes a_e to at most max(1.5 a_e, 0.05 m/s²).
    * A Koepe machine's inertia m_machine enters the static model only through the deceleration without brake,
      d_free = (s (T_L − T_E) + F_r)/M_total: where a_brake_min is above it in both directions the window's floor is
      a_brake_min, and a larger m_machine only lowers d_free (a transient's wheel feels it).
    * A Koepe transient's v_eps smooths the shaft resistance F_r: without one it has nothing to smooth.
    * A Koepe brake's largest deceleration bounds its window only below the slip limits (the window's top is
      min(a_slip_decel, a_brake_max), docs/physics.md §7): not given (unlimited) and nudged to 5 m/s², above
      both slip limits, the window is the same.

    A report prints every input of every equation it shows: only what enters none of them (a transient's
    t_end) can leave it unchanged.
    """
    v, e = scene.parameters, scene.effects
    if command == "report" and name == "a_e":        # its results are the worst case's, as run's
        return independent(scene, "run", name)
    if command == "report":
        return None if name in static_reads(scene)[1] or not transient(scene) else independent(scene, "simulate", name)
    if name == "a_e" and command == "simulate":
        return "the emergency stop of the static worst case"
    if name == "L_ul" and e.get("resistance") == "case1" and command in ("trip", "size", "simulate"):
        return "resistance case 1"
    if name in ("lambda", "omega") and "lambda" in v:
        omega = v["omega"] if "omega" in v else 2 * v["v_pj"] / v["D"]
        alpha = v["alpha"] if "alpha" in v else v["alpha_d"]
        if alpha / (v["lambda"] * omega) > 40:
            return "Voigt lining at its elastic limit"
    if (name == "a_e" and command in ("run", "solve", "sensitivity") and "t_ramp" in v and "v_pj" in v
            and max(1.5 * v.get("a_e", 0.0), 0.05) < v["v_pj"] / v["t_ramp"]):
        return "an emergency stop gentler than the ramps' stop"
    if name == "x_m" and command in ("run", "solve", "sensitivity", "size") and _least_at_the_sheave_anywhere(scene):
        return "on one straight incline the rope is least at the return sheave wherever the load is"
    if name == "a_brake_max" and v[name] == math.inf and scene.model == "koepe":
        r = rm.run(scene)
        if max(r["a_slip_hoist_decel"], r["a_slip_lower_decel"]) < 5.0:
            return "the brake's window is the slip limits' below 5 m/s²"
    if name == "m_machine" and scene.model == "koepe" and command != "report":
        r = rm.run(scene)
        if all(r[f"a_brake_low_{d}"] == v["a_brake_min"] for d in ("hoist", "lower")):
            return "the machine's inertia only lowers the deceleration without brake, below a_brake_min here"
    if name == "v_eps" and scene.model == "koepe" and v.get("F_r", 0.0) == 0.0:
        return "it smooths the shaft resistance, 0 here"
    if command == "simulate" and name == "n_slip":
        return "the static slip check's factor"
    if command == "simulate" and name in ("n_slip_dynamic", "mesh_tol"):
        return "dynamic sizing's: the simulator slips at the onset and takes [numerics] segments as given"
    if command == "size --dynamic" and name == "mesh_tol":
        return "a tolerance only chooses the mesh: the back-offs are the estimates, the same 10 % either side"
    if command == "simulate" and name == "eta":
        return "the drive's efficiency: a transient gives the drum's forces"
    if command == "simulate" and name in ("rope_damping", "m_t") and e.get("rope_elasticity") == "rigid":
        return "an inextensible rope"
    if command == "simulate" and name == "t_end" and rm.simulate(scene, progress=False).summary["t_end"] < v["t_end"]:
        return "the transient stopped before t_end"
    return None


def _least_at_the_sheave_anywhere(scene) -> bool:
    """In the static model on one straight incline with one resistance coefficient the load's place enters only
    the least tension of the winding rope (docs/physics.md §4): T(x) = F_nwl/2 + q_l g (L_u − x) + J [x < x_m].
    Where the rope rises toward the drum (g >= 0) and the load pulls toward it (J >= 0) in each direction and
    manoeuvre, T is least at the return sheave, F_nwl/2, wherever the load is (a transient splits the elastic
    rope at the load: there it matters)."""
    from ropemodel.envelope.cases import load_cases, with_ramps

    v, e = scene.parameters, scene.effects
    if scene.model != "winch" or e.get("route") != "straight" or e.get("resistance") != "case1":
        return False
    read = with_ramps(scene)
    accelerations = {c.values(read.parameters).get("a_h", read.parameters.get("a_h", 0.0))
                     for c in load_cases(read)}
    sin, cos = math.sin(v["alpha_u"]), math.cos(v["alpha_u"])
    return all(sin + s * (mu * cos + a / 9.80665) >= 0.0 for s in (1.0, -1.0) for a in accelerations
               for mu in (v["mu_pl"], v["mu_pm"]))


def sized(scene):
    from optimisation import size

    d = size(scene, with_sensitivities=False)
    return {"design": d.design, "continuous": d.continuous, "margins": d.margins, "power": d.power}


def static_reads(scene):
    """run and sensitivity: the scene's equations' inputs, and what its worst case reads (the open load cases'
    places and accelerations), the scene with its ramps where it gives t_ramp (ropemodel.envelope)."""
    from ropemodel.envelope import reads, with_ramps

    read = with_ramps(scene)
    return read, read.built.inputs_of() | reads(read), {}


def solve_reads(scene):
    read, reads, _ = static_reads(scene)
    return read, reads, {INVERSE[scene.model][1]: "solve finds it"}


def every_read(scene):
    """A command that does not say what it leaves unused (simulate): every parameter counts as read."""
    return scene, set(scene.parameters), {}


def elasticities(scene):
    """The outputs and their nonzero elasticities (the frame also echoes each parameter's value, and lists a
    parameter only while it is finite: neither is an answer)."""
    frame = rm.elasticities(scene)
    out = dict(zip(frame["output"], frame["y"]))
    out.update({f"{o} / {p}": e for o, p, e in zip(frame["output"], frame["parameter"], frame["elasticity"])
                if e == e and e != 0.0})
    return out


def trip_reads(scene):
    from ropemodel.trips import prepare, reads

    prepared = prepare(scene)
    return (prepared, *reads(prepared))


def size_reads(scene):
    from optimisation.problem import prepare, reads

    prepared = prepare(scene)
    return (prepared, *reads(prepared))


def dynamic_size_reads(scene):
    """Dynamic sizing reads what static sizing reads and its transient's parameters (the ramp, the rope model,
    the tensioner, how long each manoeuvre is followed)."""
    from optimisation.dynamic.transient import reads, transient_scene
    from optimisation.problem import prepare

    transient = transient_scene(prepare(scene))
    return (transient, *reads(transient))


def curve_reads(scene):
    from ropemodel.capstan.curves import reads

    return (scene, *reads(scene))


def identify_reads(scene):
    from ropemodel.capstan.identify import reads

    return (scene, *reads(scene))


def identified(scene):
    """The fit of mu and EA to a measured curve: the rotation at mu = 0.25, EA = 50 kN and the built-in
    scene's geometry, with 1e-5 rad of noise (fixed seed)."""
    import numpy as np
    import pandas as pd

    from ropemodel.numerics.capstan_rotation import rotation

    p, F = load("capstan_li_experiment", emit=False).parameters, np.linspace(0.0, 100.0, 21)
    rot = rotation(F, 0.25, 5e4, p["R"], p["L"], p["alpha_0"], p["F_p"]) / p["R"]
    data = pd.DataFrame({"F_T [N]": F, "delta_alpha [rad]": rot + np.random.default_rng(0).normal(0, 1e-5, F.size)})
    fit = rm.identify(scene, data)
    return {"estimates": fit.estimates, "standard_errors": fit.standard_errors}


def solved(scene):
    """The inverse problem each model's README shows: the load from the stroke (winch), the friction from
    the tension (sheave), the friction from the rotation (capstan), the payload from the anti-slip factor
    (koepe); the given value is the base scene's."""
    given, find = INVERSE[scene.model]
    base = rm.run(SCENES[NAMES[scene.name]])[given]
    result = rm.solve(scene, {given: base}, [find])    # at the worst case: the outputs that have one
    return {k: v for k, v in result.values.items() if k in [*scene.built.outputs, find] and k != given}


INVERSE = {"winch": ("dF_up", "G_m"), "sheave": ("S", "mu"), "capstan": ("delta_alpha", "mu"),
           "koepe": ("sigma_static", "m_payload")}


def is_winch(scene):
    return scene.model == "winch"


def has_ramp(scene):
    return is_winch(scene) and ("t_ramp" in scene.parameters or "t_ramp" in scene.unused_values)


def sizes(scene):
    return is_winch(scene) and scene.effects.get("rope", "given") != "given"


def transient(scene):
    return is_winch(scene) and scene.effects.get("dynamics", "none") != "none"


def sized_dynamically(scene):
    from optimisation.dynamic import size_dynamic

    d = size_dynamic(scene)
    return {"design": d.design, "continuous": d.continuous, "feasible": float(d.feasible)}


def report_text(scene):
    """The report's sections but its inputs table (which shows every value given), its list of cases and its
    pictures: each table cell and line of text, in order."""
    html = rm.report(scene).html
    html = re.sub(r'<section id="inputs".*?</section>|<img[^>]*>|<style.*?</style>', "", html, flags=re.S)
    return {"text": [t.strip() for t in re.split(r"<[^>]+>", html) if t.strip() and "UTC" not in t
                     and not OVER.match(t.strip())]}


#: the worst case's list of cases ("Over 2 places of the load x 3 manoeuvres ..."): it echoes a given x_m as a
#: pinned place, as the inputs table echoes every value, even where no result depends on the place (a straight
#: route: Krauze et al. 2025, eq. (1)-(11)); the results it heads are compared
OVER = re.compile(r"Over .* both directions of travel\.$")


def report_reads(scene):
    """What a report's sections read: the union of the commands it runs (a transient reads everything); the
    results, equations and checks are at the scene's own values (its design too, where it gives one)."""
    from ropemodel.reports.context import load as context
    from ropemodel.reports.sections.transient import has_transient
    from ropemodel.reports.sections.trip import has_trip

    ctx = context(scene, origin="api", bare="si")
    reads = static_reads(ctx.scene)[1]          # its results are the worst case's (places, accelerations)
    if ctx.sizing:
        reads = reads | size_reads(ctx.scene)[1]
    if has_trip(ctx):
        reads = reads | trip_reads(ctx.scene)[1]
    if has_transient(ctx):
        reads = reads | set(ctx.scene.parameters)
    return ctx.scene, reads, {}


#: command → (which scenes it takes, its answer, the scene as it reads it with what it reads and sets itself,
#: the rounding of its answer: a fit's estimates move with its start within IPOPT's tolerance)
COMMANDS = {
    "run": (lambda s: True, lambda s: {k: v for k, v in rm.run(s).values.items() if k in s.built.outputs},
            static_reads, 1e-12),
    "solve": (lambda s: True, solved, solve_reads, 1e-9),
    "sensitivity": (lambda s: True, elasticities, static_reads, 1e-9),
    "trip": (has_ramp, lambda s: {d: rm.trip(s, d).summary for d in ("up", "down")}, trip_reads, 1e-12),
    "size": (sizes, sized, size_reads, 1e-9),
    "simulate": (transient, lambda s: rm.simulate(s, progress=False).summary, every_read, 1e-9),
    "size --dynamic": (sizes, sized_dynamically, dynamic_size_reads, 1e-9),
    "report": (lambda s: True, report_text, report_reads, 1e-12),
    "curve": (lambda s: s.model == "capstan", lambda s: rm.load_curve(s, "100 N", n=5).to_dict("list"),
              curve_reads, 1e-12),
    "identify": (lambda s: s.model == "capstan", identified, identify_reads, 1e-6),
}
SOLVE_SKIP = {"sheave_thirion"}    # its friction law has no closed form to invert quickly: run covers it


#: every built-in scene, and the issue's route with a design
SCENES = {**{n: load(n, emit=False) for n in builtin_scenes()},
          "route3": from_toml(r3.SCENE + r3.DESIGN, "the issue's route", emit=False)}
#: scene.name → its key in SCENES
NAMES = {s.name: n for n, s in SCENES.items()}
#: the answer of a command that refused a value in one clear error naming it
REFUSED = object()
#: the long ones: every transient but the shortest, dynamic sizing (minutes each), reports (pictures)
SLOW = {"size --dynamic", "report"}
#: a dynamic sizing per value (each a minute or more): not in CI (CONTRIBUTING, "Test tiers")
EXHAUSTIVE = {"size --dynamic"}


def _marks(name, command):
    slow = command in SLOW or (command == "simulate" and name != "winch_start_stroke")
    return [pytest.mark.slow] * slow + [pytest.mark.exhaustive] * (command in EXHAUSTIVE)


CASES = [pytest.param(n, c, id=f"{n}-{c}", marks=_marks(n, c)) for n, s in SCENES.items()
         for c, spec in COMMANDS.items() if spec[0](s) and not (c == "solve" and n in SOLVE_SKIP)]


@pytest.mark.parametrize("name, command", CASES)
def test_every_value_changes_the_answer_or_is_named_unused(name, command):
    _, answer, as_read, rtol = COMMANDS[command]
    scene = SCENES[name]
    try:
        before = answer(scene)
    except rm.InputError as exc:
        if command != "size --dynamic":
            raise
        pytest.skip(f"{name}: {exc}")          # a scene without what dynamic sizing needs (it says what)
    wrong = []

    def after(other):
        try:
            return answer(other)
        except rm.SolveError as exc:     # no solution any more: an answer that changed
            return {"no solution": str(exc)}
        except rm.InputError as exc:     # refused, naming the value: said
            assert p in str(exc), exc
            return REFUSED

    for p in [*scene.parameters, *scene.unused_values]:
        other, value = nudged(scene, p)
        read, reads, chosen = as_read(other)
        said = {**{k: "unused by the effects" for k in read.unused}, **unread(read, reads, chosen)}
        got = after(other)
        if got is REFUSED:
            continue
        moved = changed(before, got, rtol)
        why = independent(scene, command, p)
        if p in said and moved:
            wrong.append(f"{p}: said to be unused ({said[p]}), but the answer changed")
        elif p not in said and not moved and why is None:
            wrong.append(f"{p} = {value:g}: the answer did not change and nothing says it is not used")
        elif why is not None and moved:
            wrong.append(f"{p}: independent by the physics ({why}), but the answer changed")
    assert not wrong, f"{command} on {name}:\n" + "\n".join(wrong)


def results_of(frame, inputs) -> list[dict]:
    """Each row of a sweep without its input columns (``name [unit]``, or ``name`` for a pure number)."""
    keep = [c for c in frame.columns if c.split(" [")[0] not in inputs]
    return [{k.split(" [")[0]: v for k, v in row.items()} for row in frame[keep].to_dict("records")]


def idle_names(caught) -> set[str]:
    """The inputs a sweep warned that no output depends on (``a, b varied, but no output ...``)."""
    return {n.strip() for w in caught if " varied, but no output" in str(w.message)
            for n in str(w.message).split(" varied")[0].split(",")}


@pytest.mark.parametrize("name", SCENES)
def test_every_value_reaches_a_sweep(name):
    """Each parameter swept alone over its value and the nudged one (``--vary``), then all of them in one
    table of points (``--points``, a row per nudged parameter): the results move along it, or the sweep
    warned that no output depends on it; a value the scene's effects do not use cannot be swept."""
    import warnings

    import pandas as pd

    from ropemodel.envelope import free

    scene = SCENES[name]
    knowns = rm.Problem(scene).knowns
    wrong, rows = [], {}
    for p in [k for k in scene.parameters if k in knowns]:
        other, value = nudged(scene, p)
        base = scene.parameters[p]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            # (errors="mark": a nudge that takes a case outside the model, a rope slack, is an answer that moved)
            frame = rm.sweep(scene, vary={p: [base, value] if math.isfinite(base) else [value]}, si=True,
                             progress=False, backend="casadi", errors="mark")
        results = results_of(frame, {p})
        if not math.isfinite(base):        # "not given" (unlimited, or the worst place): not a value to sweep,
            point = rm.run(scene, {p: value}).values     # so the sweep's one point is run's there
            same = [k for k in results[0] if k in point]
            if not same or changed({k: results[0][k] for k in same}, {k: point[k] for k in same}):
                wrong.append(f"{p} = {value:g}: the sweep's point is not run's")
            continue
        moved = changed(results[0], results[1])
        said = p in idle_names(caught)
        if moved == said and independent(scene, "run", p) is None:
            wrong.append(f"{p}: results {'moved' if moved else 'did not move'}, warned: {said}")
        if p not in free(scene):          # a given case input would pin its case in every row of the table
            rows[p] = value
    finite = [p for p in rows if all(math.isfinite(scene.parameters[q]) for q in rows)]
    table = pd.DataFrame([{q: scene.parameters[q] for q in finite}] +
                         [{q: (rows[p] if q == p else scene.parameters[q]) for q in finite} for p in finite])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        frame = rm.sweep(scene, points=table, si=True, progress=False, backend="casadi", errors="mark")
    results, said = results_of(frame, set(finite)), idle_names(caught)
    for i, p in enumerate(finite, start=1):
        if changed(results[0], results[i]) == (p in said) and independent(scene, "run", p) is None:
            wrong.append(f"{p}: the table's row moved: {changed(results[0], results[i])}, warned: {p in said}")
    from ropemodel.envelope import with_ramps

    for p in with_ramps(scene).unused_values:     # (t_ramp without a transient: the worst case's ramps)
        with pytest.raises(rm.InputError, match=p):
            rm.sweep(scene, vary={p: [scene.unused_values[p]] * 2}, progress=False)
    assert not wrong, f"sweep of {name}:\n" + "\n".join(wrong)


@pytest.mark.parametrize("name", SCENES)
def test_every_value_reaches_the_report_scene(name):
    """The scene a report computes from (read as sizing reads it where it sizes) holds every value given, used
    or kept aside, with where it came from (the pages themselves: the slow report case above)."""
    from ropemodel.reports.context import load as context

    scene = SCENES[name]
    for p in [*scene.parameters, *scene.unused_values]:
        _, value = nudged(scene, p)
        ctx = context(scene, {p: value}, origin="values", bare="si")
        kept = {**ctx.scene.unused_values, **ctx.scene.parameters}
        assert kept[p] == value and ctx.scene.origin[p] == "values", (name, p)
