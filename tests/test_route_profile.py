"""A route read from a surveyed profile file (``[route_profile] file = "..."``): the segments it gives, the same
results as the route written as ``[[route]]`` tables, and every bad file refused naming its line and column.

Truths: the segments of a (distance, height) profile written out here in numpy (L = hypot(dx, dh),
alpha = atan2(-dh, dx), rising toward the drive); the ``[[route]]`` form of the same segments (a second way in).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import ropemodel as rm
from ropemodel.cli import main

PARAMETERS = {"mu_pm": 0.05, "mu_pl": 0.05, "G_m": "467 kN", "F_nwl": "30 kN", "q_l": "0.08 kN/m",
              "q_lw": "5.8 mm/kN"}


def _scene_file(tmp_path, csv_text: str, name: str = "incline.csv", x_m: str | None = "900 m"):
    (tmp_path / name).write_text(csv_text)
    lines = ['[effects]', 'route = "segments"', '', '[route_profile]', f'file = "{name}"', '', '[parameters]']
    lines += [f'{k} = {v!r}'.replace("'", '"') for k, v in PARAMETERS.items()]
    if x_m:
        lines.append(f'x_m = "{x_m}"')
    path = tmp_path / "scene.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_distance_height_gives_the_segments_by_hand(tmp_path):
    """Chainage and elevation from the drive, in km and ft: each step a straight segment."""
    x_km = np.array([0.0, 0.4, 1.05, 1.35])
    h_ft = np.array([900.0, 400.0, 100.0, 120.0])
    text = "distance [km],height [ft]\n" + "".join(f"{float(x)!r},{float(h)!r}\n" for x, h in zip(x_km, h_ft))
    scene = rm.load_scene(str(_scene_file(tmp_path, text)))
    dx, dh = np.diff(x_km * 1e3), np.diff(h_ft * 0.3048)
    for i, (L, a) in enumerate(zip(np.hypot(dx, dh), np.arctan2(-dh, dx)), start=1):
        assert scene.parameters[f"L_{i}"] == pytest.approx(L, rel=1e-15)
        assert scene.parameters[f"alpha_{i}"] == pytest.approx(a, rel=1e-15)
    assert f"L_{len(dx) + 1}" not in scene.parameters


def test_columns_in_either_order_with_comments_and_a_byte_order_mark(tmp_path):
    text = "\ufeff# surveyed 2026\ninclination [deg],length [m]\n\n22,400\n9,650\n# the last one\n3,300\n"
    scene = rm.load_scene(str(_scene_file(tmp_path, text)))
    assert [scene.parameters[f"L_{i}"] for i in (1, 2, 3)] == [400.0, 650.0, 300.0]
    assert scene.parameters["alpha_3"] == pytest.approx(math.radians(3.0), rel=1e-15)


def test_the_same_results_as_route_tables(tmp_path):
    """run on a profile file equals run on the same route as [[route]] tables, every output to 1e-12."""
    rows = [(400.0, 22.0), (650.0, 9.0), (300.0, 3.0), (120.0, 12.5)]
    profile = rm.load_scene(str(_scene_file(tmp_path, "length [m],inclination [deg]\n"
                                            + "".join(f"{L},{a}\n" for L, a in rows), x_m=None)))
    tables = rm.from_dict({"effects": {"route": "segments"},
                           "route": [{"length": f"{L} m", "inclination": f"{a} deg"} for L, a in rows],
                           "parameters": PARAMETERS})
    a, b = rm.run(profile), rm.run(tables)
    assert set(a.values) == set(b.values)
    for k, v in b.values.items():
        assert a.values[k] == pytest.approx(v, rel=1e-12, abs=1e-9), k


BAD = [
    ("distance [m],height\n0,0\n10,1\n", r"line 1, column 2 \(height\): no unit"),
    ("distance,height [m]\n0,0\n10,1\n", r"line 1, column 1 \(distance\): no unit"),
    ("length [m],inclination [%]\n10,2\n", r"line 1, column 2 \(inclination\): unit \[%\] is not an angle"),
    ("length [kg],inclination [deg]\n10,2\n", r"column 1 \(length\): unit \[kg\] is not a length"),
    ("chainage [m],height [m]\n0,0\n10,1\n", r"line 1: header .*expected two columns with their units"),
    ("distance [m],height [m]\n0,0\n", r"1 point; a route needs at least 2"),
    ("distance [m],height [m]\n", r"0 points; a route needs at least 2"),
    ("length [m],inclination [deg]\n", r"no segment"),
    ("distance [m],height [m]\n0,0\n10,nan\n20,1\n", r"line 3, column 2 \(height\): 'nan' is not a finite number"),
    ("distance [m],height [m]\n0,0\n10,abc\n20,1\n", r"line 3, column 2 \(height\): 'abc' is not a finite number"),
    ("distance [m],height [m]\n0,0\n10,1\n10,2\n", r"line 4, column 1 \(distance\): a step of zero length"),
    ("height [m],distance [m]\n0,0\n1,10\n2,5\n", r"line 4, column 2 \(distance\): the distance decreases"),
    ("distance [m],height [m]\n0,0\n10\n", r"line 3: 1 columns, expected 2"),
    ("length [m],inclination [deg]\n0,2\n", r"line 2, column 1 \(length\): 0 m; a segment's length must be > 0"),
    ("length [m],inclination [deg]\n10,95\n", r"line 2, column 2 \(inclination\): 95 deg; must be between"),
    # finite as typed, not once in SI: named, not left out (the route would lose a segment)
    ("length [km],inclination [deg]\n1,2\n1e306,2\n", r"line 3, column 1 \(length\): 1e\+306 is beyond the largest"),
]


@pytest.mark.parametrize("text, pattern", BAD)
def test_bad_profiles_are_refused_naming_line_and_column(tmp_path, capsys, text, pattern):
    path = _scene_file(tmp_path, text)
    assert main(["run", str(path)]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert "Traceback" not in err
    assert "incline.csv" in err
    assert re.search(pattern, err), err
    assert "missing parameter" not in err      # the segments are not asked for again


def test_every_problem_of_a_file_at_once(tmp_path, capsys):
    path = _scene_file(tmp_path, "distance [m],height [m]\n0,0\n10,nan\n20,1\n15,2\n15,3\n")
    assert main(["run", str(path)]) == 2
    err = capsys.readouterr().err
    assert "line 3, column 2" in err and "line 5, column 1" in err and "line 6, column 1" in err


@pytest.mark.parametrize("extra, pattern", [
    ('[[route]]\nlength = "10 m"\ninclination = "2 deg"\n', "both given: keep one"),
    ("", None),
])
def test_profile_and_tables_together_or_a_missing_file(tmp_path, capsys, extra, pattern):
    path = _scene_file(tmp_path, "length [m],inclination [deg]\n10,2\n")
    path.write_text(path.read_text() + extra)
    if pattern is None:     # a missing file, named with where it is looked for
        (tmp_path / "incline.csv").unlink()
        pattern = "file not found"
    assert main(["run", str(path)]) == 2
    assert pattern in capsys.readouterr().err


def test_a_profile_on_a_straight_route_is_refused(tmp_path, capsys):
    path = _scene_file(tmp_path, "length [m],inclination [deg]\n10,2\n")
    path.write_text(path.read_text().replace('route = "segments"', ""))
    assert main(["run", str(path)]) == 2
    assert '[route_profile] is given but the route effect is "straight"' in capsys.readouterr().err


def _incline(n: int):
    """The surveyed 2 km incline at n points (10 deg on average, a 700 m undulation of +-15 m): x, h [m], the
    profile file's text and its segments' lengths [m] and inclinations [rad] written out in numpy."""
    x = np.linspace(0.0, 2000.0, n)
    h = 500.0 - x * math.tan(math.radians(10.0)) - 15.0 * np.sin(2.0 * math.pi * x / 700.0)
    text = "distance [m],height [m]\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, h))
    return text, np.hypot(np.diff(x), np.diff(h)), np.arctan2(-np.diff(h), np.diff(x))


def _assert_numpy_forces(values, L, a):
    """The worst drum forces over every joint, eq. (12)-(13) summed over the segments in numpy (§4)."""
    q, G_m, mu, F_end = 80.0, 467e3, 0.05, 15e3
    rise, drag = q * np.sum(L * np.sin(a)), mu * q * np.sum(L * np.cos(a))
    for way, s in (("up", 1.0), ("down", -1.0)):
        F_C = F_end + rise + s * drag + G_m * (np.sin(a) + s * mu * np.cos(a))
        assert values[f"F_C_{way}"] == pytest.approx(np.max(F_C), rel=1e-12)
        assert values[f"F_S_{way}"] == pytest.approx(F_end + rise - s * drag, rel=1e-12)


def test_a_surveyed_profile_against_numpy(tmp_path):
    """300 surveyed points (an undulating 2 km incline): run's worst forces over every place of the load equal
    the forces written out in numpy at every joint (docs/physics.md §4, eq. (12)-(13) summed over segments)."""
    text, L, a = _incline(300)
    r = rm.run(rm.load_scene(str(_scene_file(tmp_path, text, x_m=None))))
    _assert_numpy_forces(r.values, L, a)
    assert r.where["F_C_up"].startswith(f"segment {int(np.argmax(np.sin(a) + 0.05 * np.cos(a))) + 1},")


def test_a_thousand_point_profile_equals_its_tables_and_numpy(tmp_path):
    """A 1000-point surveyed profile (the route's sums built as vectors, the places that can govern evaluated):
    every output of ``run`` equals the same route written as [[route]] tables to 1e-12, and its worst drum forces
    the numpy sums over the segments with the load at every joint (docs/physics.md §4)."""
    text, L, a = _incline(1000)
    profile = rm.run(rm.load_scene(str(_scene_file(tmp_path, text, x_m=None))))
    tables = rm.run(rm.from_dict({"effects": {"route": "segments"}, "parameters": PARAMETERS, "route": [
        {"length": f"{float(length)!r} m", "inclination": f"{float(angle)!r} rad"} for length, angle in zip(L, a)]}))
    assert set(profile.values) == set(tables.values)
    for k, v in tables.values.items():
        assert profile.values[k] == pytest.approx(v, rel=1e-12, abs=1e-9), k
    _assert_numpy_forces(profile.values, L, a)
