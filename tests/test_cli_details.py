"""Details of the command line a user meets first (issue 21): each command's help suggests a built-in scene
that command takes; a reader that stops early (``| head``) ends every command quietly with exit 0; angles in
turns and reciprocal units as pint prints them are read."""

from __future__ import annotations

import math
import re
import subprocess
import sys

import pytest

import ropemodel as rm
from ropemodel.cli import build_parser
from ropemodel.cli import main as cli
from ropemodel.units import to_si


def help_of(command: str) -> str:
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    return re.sub(r"\s+", " ", sub.choices[command].format_help())


def capstan_data(tmp_path):
    curve = rm.load_curve("capstan_li_experiment", "100 N", n=9)
    path = tmp_path / "data.csv"
    curve[["F_T [N]", "delta_alpha [rad]"]].to_csv(path, index=False)
    return path


#: command → its arguments after the scene (a quick run of it)
ARGS = {"curve": ["--to", "100N", "-n", "3"], "identify": ["DATA"], "simulate": [], "trip": [], "size": [],
        "solve": ["--given", "dF_up=1000mm", "--find", "G_m"], "sweep": ["--vary", "G_m=300kN,400kN", "-o", "OUT"]}


@pytest.mark.parametrize("command", ARGS)
def test_the_help_suggests_a_scene_the_command_takes(command, tmp_path, capsys):
    text = help_of(command)
    suggested = re.search(r"the name of a built-in scene \('(\w+)' for", text)[1]
    args = [str(capstan_data(tmp_path)) if a == "DATA" else str(tmp_path / "o.csv") if a == "OUT" else a
            for a in ARGS[command]]
    assert cli([command, suggested, *args, "-q"]) == 0, capsys.readouterr().err


def test_simulate_help_names_every_transient():
    text = help_of("simulate")
    for dynamics in ("start", "stop", "trip"):
        assert f'"{dynamics}"' in text
    assert "trip" in re.sub(r"\s+", " ", build_parser().format_help()).split("simulate", 1)[1].split("size")[0]


def commands(tmp_path) -> dict[str, list[str]]:
    """Every command (and the helps), each a quick run with something to print."""
    return {"help": ["--help"], "run help": ["run", "--help"], "version": ["--version"], "run": ["run"],
            "run json": ["run", "--json"], "solve": ["solve", "example", "--given", "dF_up=1000mm", "--find", "G_m"],
            "size": ["size", "winch_sizing_fig9"], "trip": ["trip", "trip_fig9"],
            "simulate": ["simulate", "winch_start_stroke"], "sensitivity": ["sensitivity"],
            "sweep": ["sweep", "example", "--vary", "G_m=300kN:400kN:3", "-o", str(tmp_path / "s.csv")],
            "curve": ["curve", "capstan_li_experiment", "--to", "100N"],
            "identify": ["identify", "capstan_li_experiment", str(capstan_data(tmp_path))],
            "report": ["report", "sheave_hajduk_fig5", "-o", str(tmp_path / "r.html")]}


def test_a_closed_pipe_ends_every_command_quietly(tmp_path):
    """The reader has gone before the command writes (its end of the pipe closed at once): exit 0, nothing
    on stderr (no 'lost sys.stderr', no traceback), as ``git log | head`` does."""
    runs = {}
    for name, args in commands(tmp_path).items():
        p = subprocess.Popen([sys.executable, "-m", "ropemodel", *args, *(["-q"] if len(args) > 1 else [])],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        p.stdout.close()
        runs[name] = p
    for name, p in runs.items():
        err = p.stderr.read().decode()
        assert (p.wait(timeout=600), err) == (0, ""), name


@pytest.mark.parametrize("args", [["curve", "capstan_li_experiment", "--to", "100N", "-n", "5000"], ["--help"],
                                  ["run"]], ids=["long-curve", "help", "run"])
def test_head_c1_takes_one_byte_and_the_command_exits_0(args):
    """``| head -c1`` in a shell with pipefail: the command's own status is 0 and it says nothing (the long
    curve, ~400 kB, outgrows the pipe's buffer, so its writes meet the closed pipe)."""
    cmd = " ".join([sys.executable, "-m", "ropemodel", *args])
    done = subprocess.run(["bash", "-c", f"set -o pipefail; {cmd} | head -c1"], capture_output=True, timeout=600)
    assert (done.returncode, done.stderr.decode()) == (0, "")
    assert len(done.stdout) == 1


def test_a_wrap_angle_in_turns():
    assert to_si("alpha_d", "1.5 turns", "rad") == pytest.approx(3 * math.pi, rel=1e-15)
    assert to_si("alpha_d", "1 turn", "rad") == pytest.approx(math.radians(360), rel=1e-15)
    scene = rm.load_scene("winch_sizing_fig9", emit=False)
    assert scene.with_values({"alpha_d": "1.5 turns"}).parameters["alpha_d"] == pytest.approx(
        scene.with_values({"alpha_d": "540 deg"}).parameters["alpha_d"], rel=1e-15)


@pytest.mark.parametrize("text", ["1e-5 / N", "1e-5/N", "1e-5 1/N", "0.01 / kN", "1e-5 N^-1"])
def test_a_reciprocal_unit_as_pint_prints_it(text):
    assert to_si("Q", text, "1/N") == pytest.approx(1e-5, rel=1e-15)


def test_the_form_pint_prints_is_read_back():
    pint = pytest.importorskip("pint")
    q = pint.UnitRegistry().Quantity(1e-5, "1/N")
    assert to_si("Q", format(q, "~"), "1/N") == pytest.approx(1e-5, rel=1e-15)   # "1e-05 / N"
    assert rm.load_scene("sheave_hajduk_fig5").with_values({"Q": format(q, "~")}).parameters["Q"] == 1e-5
