"""The report computes what the scene calls for and nothing else (issue 21, item 6): a section applies only
where its physics is in the scene, none says "Not computed", none gives a verdict over no checks, and a
whole trip is reported once, exactly (the "Trip" section), not again as a transient with a dynamic factor.

Truths: the trip time of a trapezoidal speed profile, L/v + t_ramp, and the largest force of a rigid rope
starting up, the paper's static force plus the moving masses times the ramp's acceleration (Newton), each
written out here.
"""

from __future__ import annotations

import re

import pytest

import _route3 as r3
import ropemodel as rm
from ropemodel.cli import main as cli
from ropemodel.scene import builtin_scenes
from test_report import page_of

G = 9.80665    # [m/s^2] standard gravity, as ropemodel.papers.route
#: sections whose physics a scene must call for: section → what in the scene calls for it
SPECIFIC = ("checks", "sizing", "transient", "trip", "dynamic_sizing")


def text_of(html: str) -> str:
    return re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", re.sub(r"<style.*?</style>|<img[^>]*>", "", html, flags=re.S)))


def honest(report) -> None:
    text = text_of(report.html)
    assert report.incomplete == [], report.incomplete
    assert "Not computed" not in text and "All 0" not in text and "all 0" not in " ".join(report.verdicts)


def called_for(scene) -> set[str]:
    """The specific sections a scene calls for, from what the scene says (its effects and values)."""
    e, given = scene.effects, {**scene.parameters, **scene.unused_values}
    out = set()
    if e.get("checks") == "design" or e.get("brake", "none") != "none" or (
            scene.model == "winch" and e.get("lining", "none") != "none"):
        out.add("checks")
    if scene.model == "winch" and e.get("rope", "given") != "given":
        out.add("sizing")
    if scene.model == "koepe" and e.get("dynamics", "none") == "none":     # sized (through a transient: by size)
        out.add("sizing")
    if e.get("dynamics", "none") in ("start", "stop", "braking"):      # a winch's or a Koepe hoist's transient
        out.add("transient")
    if (e.get("dynamics") == "trip" or e.get("route") == "segments") and {"v_pj", "t_ramp"} <= set(given):
        out.add("trip")
    return out


def rigid_route(tmp_path):
    """The issue's route with an inextensible rope and linear ramps: a scene that can also simulate its trip."""
    text = r3.SCENE.replace('power = "drive"\n', 'power = "drive"\nrope_elasticity = "rigid"\nramp = "linear"\n')
    path = tmp_path / "rigid.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("rigid", [False, True], ids=["route3", "route3-rigid-rope"])
def test_the_issues_route_reports_exit_0_with_every_section_computed(tmp_path, capsys, rigid):
    path = rigid_route(tmp_path) if rigid else r3.write(tmp_path)
    out = tmp_path / "r.html"
    assert cli(["report", str(path), "-o", str(out)]) == 0
    assert "could not be computed" not in capsys.readouterr().err
    text = text_of(out.read_text(encoding="utf-8"))
    assert "Not computed" not in text and "All 0" not in text
    assert "dynamic factor" not in text                # the trip is the "Trip" section's, not a transient's
    assert '<section id="transient"' not in out.read_text(encoding="utf-8")
    m = re.search(r"trip time ([\d.]+) ([\d.]+) s", text)
    assert m and float(m[1]) == float(m[2]) == pytest.approx(r3.LENGTH / r3.SPEED + 4.0, rel=1e-6)


@pytest.mark.parametrize("name", [*builtin_scenes(), "route3"])
def test_each_scene_shows_the_sections_it_calls_for_and_no_other(name, tmp_path):
    """Every built-in scene (and the issue's route): the report is complete (no section that could not be
    computed), no verdict over no checks, and its specific sections are exactly those the scene's effects
    and values call for.  The built-in scenes' pages are the ones tests/test_report.py builds (once)."""
    path = r3.write(tmp_path) if name == "route3" else name
    scene = rm.load_scene(path, optional=("d", "F_nwl", "stroke", "D"), emit=False)
    html = rm.report(path).html if name == "route3" else page_of(name)     # page_of: none incomplete
    text = text_of(html)
    assert "Not computed" not in text and "All 0" not in text
    assert {s for s in re.findall(r'<section id="([\w-]+)"', html) if s in SPECIFIC} == called_for(scene), name


def test_a_rigid_rope_start_shows_no_take_up_and_the_inertia_factor_newton_gives(tmp_path):
    """A start-up with an inextensible rope: the tensioner cannot move, so the report shows no take-up and
    says where the stroke is (eq. (23)); its dynamic factor is the ramp's rigid-body inertia alone, Newton's
    F_C max = F_C static + (G_m + q_l L_u)/g · v_pj/t_ramp (the winding side pulls the load and its own rope;
    Coulomb resistances fully developed at the end of the ramp, v_pj ≫ v_eps)."""
    path = tmp_path / "rigid_start.toml"
    path.write_text(resources_text("winch_start").replace('rope_elasticity = "segments"',
                                                         'rope_elasticity = "rigid"'), encoding="utf-8")
    scene = rm.load_scene(path, emit=False)
    report = rm.report(path)
    honest(report)
    section = text_of(re.search(r'<section id="transient">.*?</section>', report.html, re.S)[0])
    assert "take-up max" not in section and "eq. (23)" in section
    v = scene.parameters
    newton = rm.run(scene)["F_C_up"] + (v["G_m"] + v["q_l"] * v["L_u"]) / G * v["v_pj"] / v["t_ramp"]
    shown = float(re.search(r"F_C max ([\d.]+) kN", section)[1]) * 1e3
    assert shown == pytest.approx(newton, abs=10.0)          # printed to 10 N


def resources_text(name: str) -> str:
    from importlib import resources

    return resources.files("ropemodel.data").joinpath(f"{name}.toml").read_text(encoding="utf-8")
