"""The text of ``size --dynamic`` and of ``size --dynamic --find t_ramp``, printed from a dynamic design built
here with known numbers (a sizing takes minutes; the printer is the same): the checks table in words, grouped
by manoeuvre, each row its value, limit and margin with their units, the instant and the load's place; no
internal check name outside ``--json``; the factors with their rules.  Also: the value and limit each check
compares (what the table prints) against the check's own margin, and the defaults a command lists."""

from __future__ import annotations

import json
import re
from types import SimpleNamespace

import numpy as np
import pytest
from _checks_text import INTERNAL, MANOEUVRES, groups
from _dynamic_scene import write_scene

from optimisation.dynamic.design import DynamicDesign
from optimisation.dynamic.manoeuvres import sides
from optimisation.dynamic.transient import reads, transient_scene
from optimisation.problem import SizingProblem, load_sizing
from ropemodel.cli import main
from ropemodel.cli._size_dynamic import design_text, ramp_text
from ropemodel.machines.winch import manoeuvres as winch
from ropemodel.machines.winch.manoeuvres import CHECK, CHECKS
from ropemodel.machines.winch.words import MANOEUVRE_WORDS, STATIC_WORDS, WORDS

KN, MM = 1e3, 1e-3


def _least(name: str, value: float, limit: float, t: float, x_m: float) -> dict:
    """A least margin as the simulator's verdicts give it, its margin from value and limit as each check
    defines it (written out here: docs/physics.md §6 and optimisation.dynamic.manoeuvres)."""
    if name.startswith("safety"):
        margin = limit / value - 1                  # F_min/(n_rope F) - 1
    elif name == "stroke_margin":
        margin = limit - value                      # stroke - z
    else:
        margin = value - limit                      # F_S - n_slip_dynamic F_C/rho, F - F_S_min, T - 0, z - 0
    where = {0.0: "x_m = 0 m (at the drive, on the route)", 575.0: "x_m = 575 m (middle of the route)"}[x_m]
    return {"margin": margin, "t": t, "x_m": x_m, "where": where, "value": value, "limit": limit}


def _manoeuvre(label: str, k: float) -> dict:
    """One manoeuvre's record; ``k`` scales its forces (each manoeuvre its own numbers)."""
    least = {
        "safety_margin": _least("safety_margin", 250.0 * KN * k, 299.8 * KN, 1.866, 575.0),
        # the unwinding side closer to its limit in the upward start only: its row stands for the pair there
        "safety_margin_S": _least("safety_margin_S", (280.1 if k == 1 else 40.0) * KN, 299.8 * KN, 0.5, 0.0),
        "slip_margin_fwd": _least("slip_margin_fwd", 42.05 * KN, 42.04357 * KN, 1.969, 575.0),
        "slip_margin_back": _least("slip_margin_back", 200.0 * KN, 60.0 * KN, 5.5, 575.0),
        "slack_margin": _least("slack_margin", 42.05 * KN * k, 5.0 * KN, 0.743, 575.0),
        "taut_margin": _least("taut_margin", 170.0 * KN, 5.0 * KN, 5.484, 575.0),
        "tension_margin": _least("tension_margin", 28.8 * KN, 0.0, 0.704, 0.0),
        "stroke_margin": _least("stroke_margin", 3459.0 * MM, 3611.0 * MM, 2.684, 575.0),
        "stroke_start_margin": _least("stroke_start_margin", 965.3 * MM, 0.0, 11.15, 0.0),
    }
    return {"manoeuvre": label, "ok": True, "x_m": 575.0, "where": least["safety_margin"]["where"],
            "least_margins": least, "failures": [], "positions": [{}, {}, {}],
            "peaks": {"F_C_max": 301.4 * KN * k, "F_S_min": 42.05 * KN, "take_up_max": 3.459,
                      "dynamic_factor": 1.39 * k}}


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    return transient_scene(load_sizing(write_scene(tmp_path_factory.mktemp("out")), emit=False))


@pytest.fixture(scope="module")
def static_names(scene):
    """The static checks of the scene, as dynamic sizing names them (its static constraints)."""
    return list(SizingProblem(scene).constraints)


@pytest.fixture(scope="module")
def design(scene, static_names):
    margins = {name: 0.25 + i for i, name in enumerate(static_names)}
    margins["stroke_margin_up"] = 0.389 * MM                # the active static check
    manoeuvres = [_manoeuvre(label, 1.0 if i == 0 else 0.8) for i, label in enumerate(MANOEUVRES)]
    for m in manoeuvres:
        margins.update({f"{name} @ {m['manoeuvre']}": v["margin"] for name, v in m["least_margins"].items()})
    d = {"d": 0.048, "F_nwl": 61.5e3, "stroke": 3.611}
    return DynamicDesign(scene, True, design=d, continuous=dict(d), static=dict(d), margins=margins,
                         active=["stroke_margin_up", "slip_margin_fwd @ upward start, x_m = 575 m, t = 1.969 s",
                                 "tension_margin[8] @ downward stop, x_m = 0 m, t = 0.704 s", "d (catalogue size)"],
                         manoeuvres=manoeuvres, defaults=dict(scene.defaults),
                         transient={"rope_elasticity": ("segments", True)}, message="design found")


def test_every_check_has_words():
    """A check added to the manoeuvres or the static model without words would print its internal name."""
    assert set(MANOEUVRE_WORDS) == {c.name for c in CHECKS}
    assert {"safety_margin", "slip_margin", "slack_margin", "taut_margin", "route_margin", "sheave_margin",
            "stroke_margin", "drum_margin"} == set(STATIC_WORDS)


def test_a_tie_with_the_route_check_shows_the_narrower_check():
    """The route's check holds each side's least tension over the whole side, its ends included (docs/physics.md
    §4): where that least is at the return sheave it equals the sheave's check to the last bit, and the short
    table names the sheave (where it is), not "the rope on the route"; a strictly lower route check still
    shows."""
    tie = {"route_margin_up @ x_m = 1150 m": 31.25e3, "sheave_margin": 31.25e3, "slack_margin_up": 40e3}
    (row,) = WORDS.static_rows(tie)
    assert row.check == STATIC_WORDS["sheave_margin"].text and set(row.names) == set(tie)
    (row,) = WORDS.static_rows({**tie, "route_margin_up @ x_m = 1150 m": 31.0e3})
    assert row.check == STATIC_WORDS["route_margin"].text and row.where == "upward travel, x_m = 1150 m"


def test_the_text_shows_no_internal_name(design, static_names):
    text = design_text(design)
    assert INTERNAL.search(text) is None, INTERNAL.search(text)
    for name in [*CHECK, *static_names]:
        assert name.split(" @ ")[0] not in text
    assert "tension_margin" in json.dumps(design.to_dict())      # --json keeps them


def test_grouped_by_manoeuvre_then_steady_travel(design):
    table = groups(design_text(design))
    titles = list(table)
    assert [t.split(":")[0] for t in titles] == [*MANOEUVRES, "steady travel (static forces, both directions)"]
    # each manoeuvre's title its worst peaks, in kN, mm and as a factor
    assert titles[0] == ("upward start: peak F_C 301.4 kN (dynamic factor 1.39), least F_S 42.05 kN, "
                         "largest take-up 3459 mm")
    for title in titles[:4]:
        checks = [row.split("  ")[1] for row in table[title]]
        assert len(checks) == 5          # rope force, drum grip, ropes taut, elements, take-up: one row each
    # a pair shows its least margin: the unwinding side in the upward start, the winding side elsewhere
    assert table[titles[0]][0].startswith("  rope force F_S <= F_min/n_rope")
    assert table[titles[1]][0].startswith("  rope force F_C <= F_min/n_rope")


def test_each_row_states_value_limit_margin_instant_and_place_with_units(design):
    table = groups(design_text(design))
    start = table[next(iter(table))]
    row = re.compile(r"^  (?P<check>.+?)\s{2,}(?P<value>\S+ (?:kN|mm))\s+(?P<limit>\S+ (?:kN|mm))\s+"
                     r"(?P<margin>[-+]\S+ (?:%|kN|mm))\s+(?P<t>\S+) s  (?P<where>x_m = .+)$")
    rows = {m["check"]: m for m in map(row.match, start)}
    assert None not in rows, start
    force = rows["rope force F_S <= F_min/n_rope"]        # 299.8 / 280.1 - 1 = 7.033 %
    assert (force["value"], force["limit"], force["margin"], force["t"]) == ("280.1 kN", "299.8 kN", "+7.033 %", "0.5")
    assert force["where"] == "x_m = 0 m (at the drive, on the route)"
    grip = rows["drum grip F_S >= n_slip_dynamic F_C/rho"]  # 42.05 - 42.04357 kN = 6.43 N
    assert (grip["value"], grip["limit"], grip["margin"]) == ("42.05 kN", "42.04 kN", "+0.00643 kN")
    take_up = rows["take-up z <= stroke"]                   # 3611 - 3459 mm
    assert (take_up["value"], take_up["limit"], take_up["margin"]) == ("3459 mm", "3611 mm", "+152 mm")
    assert rows["every rope element T >= 0"]["limit"] == "0 kN"
    steady = table["steady travel (static forces, both directions)"]
    assert any(r.startswith("  take-up dF <= stroke") and "+0.389 mm" in r and r.endswith("upward travel")
               for r in steady), steady


def test_active_checks_and_factors_in_words(design):
    text = design_text(design)
    assert "  drum grip F_S >= n_slip_dynamic F_C/rho (upward start, x_m = 575 m, t = 1.969 s)" in text
    assert "  every rope element T >= 0 (downward stop, x_m = 0 m, t = 0.704 s)" in text
    assert "  take-up dF <= stroke (steady upward travel)" in text
    assert "factors: n_rope = 4.5 (rope force, every manoeuvre and steady travel): user-given" in text
    assert "n_slip = 1.25 (drum grip in steady travel): user-given" in text
    # every drum contact of a transient carries the dynamic slip factor, here its default, said so
    assert re.search(r"n_slip_dynamic = 1\.1 \(drum grip in the manoeuvres, rho F_S\(t\) >= n_slip_dynamic "
                     r"F_C\(t\) at\s+every instant\): default: not given: 1\.1, engineering judgement", text), text


def test_the_report_section_says_the_same_in_words(design):
    """The report's "dynamic sizing" section: every check of every manoeuvre (one row each), in the same words,
    with its value, limit, margin, instant and place; no internal name."""
    from ropemodel.reports.sections.dynamic_sizing import dynamic_sizing

    html = str(dynamic_sizing(SimpleNamespace(design=design, scene=design.scene, sizing=True)))
    text = re.sub(r"<[^>]+>", " ", html).replace("&gt;", ">").replace("&lt;", "<")
    assert INTERNAL.search(text) is None, INTERNAL.search(text)
    checks = text[text.index("Checks through the manoeuvres"):]
    assert checks.count("pass") == len(MANOEUVRES) * len(CHECKS)
    assert re.search(r"upward start\s+rope force F_S <= F_min/n_rope\s+280.1 kN\s+299.8 kN\s+\+7.033 %\s+0.5 s", checks)
    assert "n_rope = 4.5 (rope force, every manoeuvre and steady travel)" in checks


def test_a_dynamic_slip_factor_shows_when_the_design_carries_it():
    """The slot for ``n_slip_dynamic``: a scene that has it names it (and its rule) for the manoeuvres' grip, and
    the grip rows say that they apply it."""
    basis = {"safety_margin": "n_rope: rule", "slip_margin": "n_slip: rule",
             "slip_margin_fwd": "n_slip_dynamic: practice X"}
    scene = SimpleNamespace(parameters={"n_rope": 4.5, "n_slip": 1.25, "n_slip_dynamic": 1.1},
                            check_basis=lambda name: basis.get(name, "-"))
    assert WORDS.factors(scene)[-1] == ("n_slip_dynamic = 1.1 (drum grip in the manoeuvres, rho F_S(t) >= "
                                        "n_slip_dynamic F_C(t) at every instant): practice X")
    rows = WORDS.manoeuvre_rows(_manoeuvre("upward start", 1.0), parameters=scene.parameters)
    assert "drum grip F_S >= n_slip_dynamic F_C/rho" in [r.check for r in rows]


def test_the_mesh_in_words_and_kN(design):
    """The mesh control's record (``DynamicDesign.mesh``, SI) in the text and the report: the elements per span,
    the tolerance, the largest force estimate with its unsafe part and back-off in kN, its check in words."""
    from ropemodel.reports.sections.dynamic_sizing import dynamic_sizing

    mesh = {"segments": 8, "segments_scene": 4, "tolerance": 500.0, "units": {"safety_margin": "N",
            "slip_margin_fwd": "N", "stroke_margin": "m"}, "errors": {"safety_margin": 320.0, "slip_margin_fwd": 410.0,
            "stroke_margin": 0.02}, "unsafe": {"safety_margin": 320.0, "slip_margin_fwd": 0.0, "stroke_margin": 0.02},
            "backoffs": {"safety_margin": 388.7, "slip_margin_fwd": 4.7, "stroke_margin": 0.024}}
    with_mesh = DynamicDesign(**{**design.__dict__, "mesh": mesh})
    text = " ".join(design_text(with_mesh).split())
    assert ("rope mesh: 8 elements per span (from the scene's 4, doubled while Richardson's estimate of a force "
            "check's discretisation error exceeded mesh_tol = 0.5 kN); the largest estimate 0.41 kN, drum grip F_S >= "
            "n_slip_dynamic F_C/rho, 0 kN of it on the unsafe side, backed off by 0.0047 kN") in text
    assert "with 8 elements per span" in text and INTERNAL.search(text) is None
    html = str(dynamic_sizing(SimpleNamespace(design=with_mesh, scene=with_mesh.scene, sizing=True)))
    assert "rope mesh: 8 elements per span" in html and "the largest estimate 0.41 kN" in html
    assert "rope mesh" not in design_text(design)          # no mesh record (a rigid rope): no line


def test_no_design_says_its_conflicting_checks_in_words(scene):
    """A "no design" answer's message names the conflicting checks in words, each with its manoeuvre, place
    and instant (the message as dynamic sizing words it, internal names and all; --json keeps those)."""
    message = ("no design meets every check through the manoeuvres: these checks conflict: slip_margin_fwd @ upward "
               "start, x_m = 575 m, t = 1.969 s, tension_margin[3] @ upward stop, x_m = 0 m, t = 2 s, stroke_margin_up"
               "\n  slip_margin_fwd @ upward start, x_m = 575 m, t = 1.969 s: relaxing it alone is not enough")
    text = design_text(DynamicDesign(scene, False, message=message))
    assert INTERNAL.search(text) is None, text
    assert ("these checks conflict: drum grip F_S >= n_slip_dynamic F_C/rho @ upward start, x_m = 575 m, t = 1.969 s, "
            "every rope element T >= 0 @ upward stop, x_m = 0 m, t = 2 s, take-up dF <= stroke (steady upward "
            "travel)") in text


def test_readable_names():
    assert WORDS.readable("route_margin_down @ x_m = 1150 m") == ("rope on the route >= F_S_min (steady downward "
                                                                 "travel, x_m = 1150 m)")
    assert WORDS.readable("F_nwl lower bound") == "F_nwl lower bound"


def test_the_shortest_ramp_text_groups_its_checks_too(scene, design, monkeypatch):
    """``--find t_ramp``: the same table (no steady travel: the ramp does not change it)."""
    import optimisation.dynamic.verify as verify

    monkeypatch.setattr(verify, "by_manoeuvre", lambda verdicts: design.manoeuvres)
    answer = SimpleNamespace(design=design.design, t_ramp=3.594, verdicts=[],
                             active=["slip_margin_fwd @ upward start, x_m = 575 m, t = 1.969 s"])
    text = ramp_text(scene, answer)
    assert INTERNAL.search(text) is None
    assert "a shorter ramp fails drum grip F_S >= n_slip_dynamic F_C/rho (upward start" in text
    assert [t.split(":")[0] for t in groups(text)] == MANOEUVRES


@pytest.mark.parametrize("name", [c.name for c in CHECKS])
def test_value_and_limit_are_what_the_margin_compares(name):
    """The value and limit printed for a check, at its least instant, against its margin written out here:
    F_min/(n_rope F) - 1 for the rope's safety, limit - value for the stroke, value - limit for the rest."""
    rng = np.random.default_rng(7)
    n = 50
    o = {"F_C": rng.uniform(50e3, 300e3, n), "F_S": rng.uniform(10e3, 80e3, n), "T": rng.uniform(0, 5e4, n),
         "take_up": rng.uniform(0, 3.5, n)}
    rho = 3.2
    o["slip_fwd"], o["slip_back"] = o["F_S"] - o["F_C"] / rho, o["F_C"] - o["F_S"] / rho
    a = {"F_min": 1.6e6, "n_rope": 4.5, "n_slip_dynamic": 1.1, "F_S_min": 5e3, "stroke": 3.611}
    margin = np.asarray(CHECK[name].margin(o, a), float)
    i = int(np.argmin(margin))
    s = sides(winch, name, o, a, i)
    if name.startswith("safety"):
        assert s["limit"] == pytest.approx(1.6e6 / 4.5, rel=1e-15)
        assert s["limit"] / s["value"] - 1 == pytest.approx(margin[i], rel=1e-12)
    elif name == "stroke_margin":
        assert s["limit"] - s["value"] == pytest.approx(margin[i], rel=1e-12)
    else:
        assert s["value"] - s["limit"] == pytest.approx(margin[i], rel=1e-12, abs=1e-9)
    if name.startswith("slip"):      # the limit of a grip check: n_slip_dynamic times the other side over rho
        other = "F_C" if name.endswith("fwd") else "F_S"
        assert s["limit"] == pytest.approx(1.1 * o[other][i] / rho, rel=1e-12)


@pytest.mark.parametrize("command", [["run", "winch_sizing_fig9"],
                                     ["run", "winch_sizing_fig9", "--at", "x_m=300m"],
                                     ["solve", "winch_sizing_fig9", "--given", "F_C_up=200kN", "--find", "G_m"]])
def test_a_static_command_lists_no_transient_default(command, capsys):
    """A ramp time gives a static command its ramps' inertia (a trip's transient effects come with it): the
    transient's own defaults (v_eps, rope_damping, m_t) are not what it computes from, so not listed."""
    for json_flag in ([], ["--json"]):
        assert main([*command, "--set", "t_ramp=4s", *json_flag]) == 0
        out = capsys.readouterr().out
        listed = set(json.loads(out)["defaults"]) if json_flag else set(
            re.findall(r"^  (\w+): ", out[out.index("defaults used"):], flags=re.M))
        assert not listed & {"v_eps", "rope_damping", "m_t"}, listed
        assert "D_ratio_min" in listed       # a default a check reads stays
        if not json_flag:                    # nor in the inputs table (a read default stays there too)
            shown = set(re.findall(r"^(\w+) ", out[out.index("inputs"):out.index("\n\n", out.index("inputs"))],
                                   flags=re.M))
            assert not shown & TRANSIENT_DEFAULTS, shown
            assert {"D_ratio_min", "t_ramp", "G_m"} <= shown or "G_m" in command, shown


#: the transient's own parameters with defaults, which no static output reads
TRANSIENT_DEFAULTS = {"v_eps", "rope_damping", "m_t", "mesh_tol", "n_slip_dynamic"}


def test_a_transient_value_the_user_gives_to_a_static_command_stays_listed(capsys):
    """Only unread defaults leave the inputs table: a value the user gave and the outputs do not read is listed,
    and the command warns of it."""
    assert main(["run", "route_segments", "--set", "rope_damping=0.1s"]) == 0
    captured = capsys.readouterr()
    section = captured.out[captured.out.index("inputs"):captured.out.index("\n\n", captured.out.index("inputs"))]
    shown = set(re.findall(r"^(\w+) ", section, flags=re.M))
    assert "rope_damping" in shown and not shown & (TRANSIENT_DEFAULTS - {"rope_damping"}), shown
    assert "rope_damping" in captured.err and "does not change what run computes" in captured.err


def test_an_inextensible_rope_lists_no_carriage_mass(tmp_path):
    """Dynamic sizing with a rigid rope: the tensioner's carriage does not move, its mass is no default used
    and not read; with an elastic rope it is both."""
    elastic = write_scene(tmp_path).read_text().replace('m_t = "1000 kg"\n', "")
    rigid = elastic.replace('rope_elasticity = "segments"', 'rope_elasticity = "rigid"')
    for text, listed in ((elastic, True), (rigid, False)):
        path = tmp_path / "s.toml"
        path.write_text(text)
        sc = transient_scene(load_sizing(path, emit=False))
        assert ("m_t" in sc.defaults) is listed
        assert ("m_t" in reads(sc)[0]) is listed        # a --set m_t=... warns that it changes nothing
