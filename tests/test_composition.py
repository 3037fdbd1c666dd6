"""The composition matrix (issue 21, item 7): every built-in scene and generated winch scenes (a straight
route, 1-6 segments and a long route of 120 held as route numbers, rigid and Voigt drum linings, the paper's
q_lw and a catalogue rope, with and without a start-up transient) through every command that takes a scene,
in text and JSON.  Each either succeeds or is refused cleanly (exit 1 or 2, a message on stderr, no traceback,
no solver log, no NaN or inf in JSON); where two commands compute the same quantity, they agree.

The generated scenes are a pairwise cover of the four factors (every pair of levels of any two factors
appears in some scene), not the whole product: 8 scenes instead of 56, so that the matrix stays in the
default suite.  Sizing, reports, sensitivities and transients are the expensive cells: on two generated scenes
(and on the built-in scenes without transients) they run in the default suite, on the others they are ``slow``.
"""

from __future__ import annotations

import json
import math
from importlib import resources

import pytest

from ropemodel.cli import main

#: lengths [m] and inclinations [deg] of the generated routes' segments, from the drive
SEGMENTS = ((600, 12), (700, 20), (500, 6), (300, 3), (400, 15), (200, 1))
#: a long route: the six segments above, each in 20 equal pieces (more than ``VECTOR_ABOVE`` = 100, so the model
#: holds it as route numbers per load case, ropemodel.effects.winch_route_vector)
LONG = 120
#: (segments, lining, rope, transient): 0 segments is a straight route; a pairwise cover of the factors, and the
#: long route with each lining, rope and transient
GENERATED = ((0, "rigid", "paper", False), (1, "voigt", "catalogue", False), (2, "rigid", "catalogue", True),
             (3, "rigid", "catalogue", False), (4, "voigt", "paper", False), (6, "rigid", "paper", True),
             (0, "voigt", "catalogue", True), (3, "voigt", "paper", True), (6, "voigt", "catalogue", False),
             (1, "rigid", "paper", True), (4, "rigid", "catalogue", True), (2, "voigt", "paper", False),
             (LONG, "rigid", "catalogue", False), (LONG, "voigt", "paper", True))
LOG_MARKS = ("Traceback", "EXIT:", "Ipopt", "CVODES", "casadi_", "This is Ipopt")


def generated(n: int, lining: str, rope: str, transient: bool) -> str:
    """A winch scene of the matrix as TOML (a design given: d, F_nwl, D, stroke)."""
    effects = {"checks": "design", "power": "drive", "lining": lining}
    params = {"G_m": '"250 kN"', "mu_pm": "0.05", "mu_pl": "0.05", "v_pj": '"2.5 m/s"', "t_ramp": '"5 s"',
              "eta": "0.85", "mu_d": "0.25", "alpha_d": '"540 deg"', "n_slip": "1.25", "n_rope": "4.5",
              "F_S_min": '"0.5 kN"', "D": '"3 m"', "F_nwl": '"40 kN"', "stroke": '"8 m"'}
    if lining == "voigt":
        params.update(Q='"2e-6 1/N"', **{"lambda": '"0.01 s"'})
    if rope == "catalogue":
        effects["rope"] = "6x36-IWRC"
        params.update(d='"40 mm"', rope_grade='"1770 N/mm^2"', rope_E='"100 kN/mm^2"')
    else:
        params.update(q_l='"0.08 kN/m"', q_lw='"5.8 mm/kN"', d='"42 mm"', F_min='"1200 kN"')
    route = ""
    if n:
        effects["route"] = "segments"
        pieces = max(1, n // len(SEGMENTS))          # the long route: each segment in equal pieces
        route = "".join(f'[[route]]\nlength = "{L / pieces!r} m"\ninclination = "{a} deg"\n'
                        for L, a in SEGMENTS[:n] for _ in range(pieces))
    else:
        params.update(L_u='"1150 m"', L_ul='"500 m"', alpha_u='"16 deg"')
    if transient:
        effects.update(dynamics="start", travel="up", rope_elasticity="segments", tensioner="constant_force")
        params.update(t_end='"20 s"')
    return ("[scene]\nname = \"matrix\"\nmodel = \"winch\"\n[effects]\n"
            + "".join(f'{k} = "{v}"\n' for k, v in effects.items()) + route + "[parameters]\n"
            + "".join(f"{k} = {v}\n" for k, v in params.items()))


def builtin_names() -> list[str]:
    return sorted(p.name[:-5] for p in resources.files("ropemodel.data").iterdir()
                  if p.name.endswith(".toml") and p.name != "ropes.toml")


#: every command that takes a scene: (name, argv after the scene, writes a file (suffix) or prints JSON)
COMMANDS = {
    "run": ([], None), "run --json": (["--json"], "json"),
    "solve": (["--given", "F_C_up=200kN", "--find", "G_m", "--json"], "json"),
    "size": ([], None), "size --json": (["--json"], "json"),
    "trip": ([], None), "trip --json": (["--json"], "json"),
    "sensitivity": (["--json"], "json"),
    "sweep": (["--vary", "G_m=200kN:260kN:2", "-o", "{out}.csv"], None),
    "simulate": (["--json"], "json"),
    "report": (["-o", "{out}.html"], None), "report --format json": (["--format", "json", "-o", "{out}.json"], None),
    "curve": (["--to", "10kN"], None),
}
EXPENSIVE = ("size", "size --json", "report", "report --format json", "simulate", "sensitivity")
#: the generated scenes whose expensive cells run in the default suite (a straight route with the paper's rope,
#: and the issue's kind of route: three segments, a catalogue rope); the others' are slow
DEFAULT_EXPENSIVE = (0, 3)


def _reject_constant(name):
    raise ValueError(f"{name} in JSON output")


def invoke(argv, capsys):
    """(exit code, stdout, stderr) of the command line ``argv``, in process."""
    try:
        rc = main(argv)
    except SystemExit as exc:            # argparse's own refusals
        rc = exc.code
    out = capsys.readouterr()
    return rc, out.out, out.err


def check_clean(label, rc, out, err, kind):
    """Success or a clean refusal, and JSON without NaN or inf."""
    assert rc in (0, 1, 2), f"{label}: exit {rc}"
    for mark in LOG_MARKS:
        assert mark not in err and mark not in out, f"{label}: {mark!r} printed:\n{err[-2000:]}"
    if rc == 2:
        assert err.strip() and not out.strip(), f"{label}: a refusal prints its reason on stderr only"
    elif rc == 1:
        assert err.strip(), f"{label}: no solution without saying why"
    elif kind == "json":
        json.loads(out, parse_constant=_reject_constant)


def cases():
    for i, g in enumerate(GENERATED):
        for cmd in COMMANDS:
            # the long route's cells take seconds each but run's (its structure checked in the default suite)
            slow = (cmd in EXPENSIVE and (g[3] or i not in DEFAULT_EXPENSIVE)) or (g[0] == LONG and cmd[:3] != "run")
            yield pytest.param(("generated", i), cmd, id=f"gen{i}-{'-'.join(map(str, g))}-{cmd}",
                               marks=[pytest.mark.slow] if slow else [])
    for name in builtin_names():
        for cmd in COMMANDS:
            slow = cmd in EXPENSIVE and name.startswith(("winch_start", "koepe_braking", "route_segments"))
            yield pytest.param(("builtin", name), cmd, id=f"{name}-{cmd}",
                               marks=[pytest.mark.slow] if slow else [])


@pytest.mark.parametrize("which, command", list(cases()))
def test_every_scene_through_every_command_succeeds_or_is_refused_cleanly(which, command, tmp_path, capsys):
    kind, key = which
    if kind == "generated":
        scene = tmp_path / "matrix.toml"
        scene.write_text(generated(*GENERATED[key]), encoding="utf-8")
        scene_arg = str(scene)
    else:
        scene_arg = key
    args, out_kind = COMMANDS[command]
    argv = [command.split()[0], scene_arg, "-q", *(a.format(out=tmp_path / "out") for a in args)]
    rc, out, err = invoke(argv, capsys)
    check_clean(f"{' '.join(argv)}", rc, out, err, out_kind)
    if rc == 0 and any(a.startswith("{out}") for a in args):
        written = list(tmp_path.glob("out.*"))
        assert written and written[0].stat().st_size > 0, f"{argv}: nothing written"


def _json(argv, capsys):
    rc, out, err = invoke([*argv, "-q", "--json"], capsys)
    assert rc == 0, err
    return json.loads(out)


@pytest.fixture(scope="module")
def route3(tmp_path_factory):
    """The issue's three-segment route with a design (tests/_route3.py)."""
    import _route3

    return _route3.write(tmp_path_factory.mktemp("route3"), design=True)


def test_run_at_a_place_equals_the_trip_there(route3, tmp_path, capsys):
    """A trip's steady rows and ``run --at`` the same place compute the same forces (1e-9)."""
    import pandas as pd

    csv = tmp_path / "trip.csv"
    assert invoke(["trip", str(route3), "-q", "-o", str(csv)], capsys)[0] == 0
    rows = pd.read_csv(csv)
    steady = rows[rows["a [m/s^2]"] == 0.0]
    for _, row in steady.iloc[[0, len(steady) // 2, -1]].iterrows():
        x = row["x_m [m]"]
        at = _json(["run", str(route3), "--at", f"x_m={float(x)!r}m", "--at", "a_h=0m/s^2"], capsys)
        assert math.isclose(at["F_C_up"], row["F_C [N]"], rel_tol=1e-9), (x, at["F_C_up"], row["F_C [N]"])
        assert math.isclose(at["F_S_up"], row["F_S [N]"], rel_tol=1e-9), (x, at["F_S_up"], row["F_S [N]"])


def test_size_power_is_run_envelope_at_the_design(route3, capsys):
    """``size``'s drive power is ``run``'s worst-case power at the recommended design (1e-9), and the largest
    of the powers ``run --at`` gives at every segment joint in steady motion and the ramps."""
    design = _json(["size", str(route3)], capsys)
    sets = ["--set", f"d={design['d']!r}m", "--set", f"F_nwl={design['F_nwl']!r}N",
            "--set", f"stroke={design['stroke']!r}m"]
    env = _json(["run", str(route3), *sets], capsys)
    for key in ("N_p_up", "N_p_down"):
        assert math.isclose(env[key], design[key], rel_tol=1e-9), (key, env[key], design[key])
    a = 3.0 / 4.0                                     # the ramp: v_pj / t_ramp [m/s^2]
    brute = [_json(["run", str(route3), *sets, "--at", f"x_m={x}m", "--at", f"a_h={ah}m/s^2"], capsys)["N_p_up"]
             for x in (0.0, 600.0, 1300.0, 1800.0) for ah in (0.0, a, -a)]
    assert math.isclose(max(brute), design["N_p_up"], rel_tol=1e-9), (max(brute), design["N_p_up"])


def test_rigid_simulation_agrees_with_the_trip(capsys):
    """The rigid ``simulate`` of a trip and ``trip`` on the shipped route: largest winding force and least
    unwinding force (1e-9)."""
    sim = _json(["simulate", "route_segments"], capsys)
    trip = _json(["trip", "route_segments"], capsys)
    assert math.isclose(sim["F_C_max"], trip["F_C_max"], rel_tol=1e-9)
    assert math.isclose(sim["F_S_min"], trip["F_S_min"], rel_tol=1e-9)


def _numbers(tree, path=()):
    """The float leaves of a JSON tree by their key path (the places and segment names left out: where a worst
    is found can differ on a tie between a piece's end and its segment's)."""
    if isinstance(tree, dict):
        for k, v in tree.items():
            if not str(k).startswith(("L_", "alpha_", "mu_w", "x_m", "a_h", "governing", "active", "load_cases")) \
                    and "@" not in str(k):
                yield from _numbers(v, (*path, k))
    elif isinstance(tree, float):
        yield path, tree


@pytest.mark.slow
@pytest.mark.parametrize("command", ["run", "trip", "size"])
def test_a_long_route_equals_its_segments_uncut(command, tmp_path, capsys):
    """The long route (each of six segments in 20 equal pieces: held as route numbers per load case) against the
    same six segments uncut (held segment by segment, a second method): every number of ``run``, ``trip`` and
    ``size`` in JSON to 1e-9 (a sum over 120 pieces against one over 6: rounding), at a pretension that keeps both
    ropes taut.  A force's worst place on a straight segment is at one of its ends (linear along it), and every
    end of the six is a place of both."""
    got = {}
    for n in (LONG, len(SEGMENTS)):
        scene = tmp_path / f"route{n}.toml"
        scene.write_text(generated(n, "rigid", "catalogue", False), encoding="utf-8")
        got[n] = dict(_numbers(_json([command, str(scene), "--set", "F_nwl=80kN"], capsys)))
    long, uncut = got[LONG], got[len(SEGMENTS)]
    common = [k for k in uncut if k in long]
    if command != "trip":                                 # the least tensions (run) and their margins compared too
        assert any(str(p).startswith(("F_C_least", "route_margin")) for k in common for p in k)
    for key in common:
        assert long[key] == pytest.approx(uncut[key], rel=1e-9, abs=1e-6), key
    assert len(common) >= 10


@pytest.mark.slow
def test_the_least_winding_tension_near_the_return_sheave_is_found(tmp_path):
    """Brute force (a second method): ``run`` with the load pinned at 41 places 5 m apart near the return sheave
    and each manoeuvre, and T(x) of the six-segment route on a dense grid written here in numpy from the formula
    (docs/physics.md §4), against the envelope of the six-segment route: F_C_least_up and F_S_least_down are the
    least over every place and manoeuvre, and are the least of T(x) over the whole side.  Measured before the
    least included the side's ends: the envelope 40.211 kN, the route cut in 10-m pieces 40.011 kN, the pinned
    load 40.005 kN at x_m = 2695 m while stopping (F_nwl/2 = 40 kN at the return sheave: it depended on where the
    route was cut)."""
    import warnings

    import numpy as np

    import ropemodel as rm

    scene = tmp_path / "route6.toml"
    scene.write_text(generated(len(SEGMENTS), "rigid", "catalogue", False), encoding="utf-8")
    sc = rm.load_scene(scene).with_values({"F_nwl": "80 kN"})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        envelope = rm.run(sc)
        pinned = [rm.run(sc.with_values({"x_m": f"{x} m", "a_h": f"{a} m/s^2"}))
                  for a in (0.0, 0.5, -0.5) for x in np.arange(2500.0, 2701.0, 5.0)]
    for name in ("F_C_least_up", "F_S_least_down"):
        assert envelope[name] <= min(r[name] for r in pinned) + 1e-6, name
    truth = _dense_least(float(envelope["q_l"]), F_end=40e3)
    assert envelope["F_S_least_down"] == pytest.approx(truth["unwinding_down"], rel=1e-9)
    assert envelope["F_C_least_up"] == pytest.approx(truth["winding_up"], rel=1e-9)


def _dense_least(q_l: float, F_end: float) -> dict:
    """The least tension of each side of the six-segment route (:func:`generated`: μ_pl = 0.05 on every
    segment, G_m = 250 kN, μ_pm = 0.05, steady and the ramps' ±0.5 m/s²) over the whole side, drum to return
    sheave, and over the load's places: T(x) = F_end + q_l Σ g_i ℓ_i(x) + J [x < x_m] (docs/physics.md §4) on a
    grid of 12 001 points with the joints, and the load at 2 401 places with both sides of every joint; numpy,
    from the formula."""
    import numpy as np

    L = np.array([float(a) for a, _ in SEGMENTS])
    alpha = np.radians([float(b) for _, b in SEGMENTS])
    ends = np.cumsum(L)
    x = np.union1d(np.linspace(0.0, ends[-1], 12001), ends)
    m = np.union1d(np.linspace(0.0, ends[-1], 2401), np.concatenate([ends, ends + 1e-9]))[:-1]
    seg_x = np.minimum(np.searchsorted(ends, x, side="left"), L.size - 1)
    seg_m = np.minimum(np.searchsorted(ends, m, side="left"), L.size - 1)
    out = {}
    for way, s in (("up", 1.0), ("down", -1.0)):
        for side, sign in (("winding", s), ("unwinding", -s)):
            worst = np.inf
            for a in (0.0, 0.5, -0.5):
                g = np.sin(alpha) + sign * (0.05 * np.cos(alpha) + a / 9.80665)
                rise = np.concatenate([np.cumsum((L * g)[::-1])[::-1], [0.0]])     # at joints 0 … n
                T0 = F_end + q_l * (rise[seg_x + 1] + g[seg_x] * (ends[seg_x] - x))
                if side == "unwinding":
                    worst = min(worst, T0.min())
                    continue
                J = 250e3 * (np.sin(alpha[seg_m]) + s * (0.05 * np.cos(alpha[seg_m]) + a / 9.80665))
                T_m = F_end + q_l * (rise[seg_m + 1] + g[seg_m] * (ends[seg_m] - m))   # T0 at the load
                before = np.minimum.accumulate(T0)[np.searchsorted(x, m, side="right") - 1]
                after = np.minimum.accumulate(T0[::-1])[::-1][np.searchsorted(x, m, side="left")]
                worst = min(worst, float(np.min(np.minimum(np.minimum(before, T_m) + J, np.minimum(after, T_m)))))
            out[f"{side}_{way}"] = worst
    return out
