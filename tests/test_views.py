"""Results show themselves: each result type's HTML (Jupyter's ``_repr_html_``) and pandas form carry the
numbers of the same command's ``--json`` output, each with its unit; the pictures draw those numbers.

Truth: the command line's JSON (SI) and, for the units, the units the paper prints (Krauze et al. 2025,
Fig. 9: kN, mm, kW) and the SI units each JSON key is documented in (``ropemodel trip``, ``simulate``,
``size``).  A shown value times its shown unit's factor must give the JSON number to the 6 digits shown.
"""

from __future__ import annotations

import json
from html.parser import HTMLParser

import matplotlib
import numpy as np
import pandas as pd
import pytest

import ropemodel as rm
from ropemodel.cli import main as cli
from ropemodel.units import parse_unit

matplotlib.use("Agg")
SHOWN = 6e-6           # 6 significant digits: half a unit of the last digit is at most 5e-6 relative


class Tables(HTMLParser):
    """Every <table> of a page: caption, header and rows of cell texts."""

    def __init__(self, text: str):
        super().__init__()
        self.tables: list[dict] = []
        self._cell: list[str] | None = None
        self._row: list[str] = []
        self._in_caption = False
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append({"caption": "", "header": [], "rows": []})
        elif tag in ("td", "th"):
            self._cell = []
        elif tag == "tr":
            self._row = []
        elif tag == "caption":
            self._in_caption = True

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self._row.append("".join(self._cell or []))
            self._cell = None
        elif tag == "tr":
            t = self.tables[-1]
            (t["rows"] if t["header"] else t["header"]).extend([self._row] if t["header"] else self._row)
        elif tag == "caption":
            self._in_caption = False

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)
        elif self._in_caption:
            self.tables[-1]["caption"] += data

    def named(self, caption: str) -> list[dict]:
        """Rows of the table with ``caption`` as dicts header → cell."""
        t = next(t for t in self.tables if t["caption"] == caption)
        return [dict(zip(t["header"], r)) for r in t["rows"]]


def si(text: str, unit: str) -> float:
    """A shown number in SI."""
    return float(text) * (1.0 if unit == "-" else parse_unit(unit)[0])


def command_json(capsys, *argv) -> dict:
    assert cli([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_result_html_matches_run_json(capsys):
    data = command_json(capsys, "run", "krauze2025_fig9")
    page = Tables(rm.run(rm.load_scene())._repr_html_())
    shown = {}
    for r in page.named("results"):
        shown[r["name"]] = (r["value"], r["unit"])
    for r in page.named("by direction of travel"):
        shown |= {f"{r['name']}_down": (r["down"], r["unit"]), f"{r['name']}_up": (r["up"], r["unit"])}
    assert set(shown) == {k for k, v in data.items() if isinstance(v, float)}          # every number, no more
    for name, (text, unit) in shown.items():
        assert si(text, unit) == pytest.approx(data[name], rel=SHOWN), name
    # the paper's own units (Fig. 9 prints kN, mm and kW)
    assert {n: shown[n][1] for n in ("F_C_up", "G_ml", "dF_up", "dF_nwl", "N_p_up")} == {
        "F_C_up": "kN", "G_ml": "kN", "dF_up": "mm", "dF_nwl": "mm", "N_p_up": "kW"}
    assert shown["F_C_up"][0] == "190.949" and shown["dF_up"][0] == "1402.94"          # Fig. 9: 190.95, 1402.94
    inputs = {r["name"]: (r["value"], r["unit"]) for r in page.named("inputs")}
    assert inputs["alpha_u"] == ("16", "deg") and inputs["q_lw"] == ("5.8", "mm/kN")


def test_result_to_frame_matches_json(capsys):
    data = command_json(capsys, "run", "krauze2025_fig9")
    frame = rm.run(rm.load_scene()).to_frame(si=True)
    results = frame[frame["role"] == "result"]
    assert {k: v for k, v in results["value"].items()} == pytest.approx(
        {k: v for k, v in data.items() if isinstance(v, float)}, rel=1e-12)
    assert frame.loc["F_C_up", "source"] == "eq. (13)" and frame.loc["G_m", "unit"] == "N"
    shown = rm.run(rm.load_scene()).to_frame()
    assert shown.loc["F_C_up", "unit"] == "kN" and shown.loc["F_C_up", "value"] == pytest.approx(190.95, abs=5e-3)


def test_inverse_result_shows_what_was_found(capsys):
    data = command_json(capsys, "solve", "krauze2025_fig9", "--given", "dF_up=1000mm", "--find", "G_m")
    page = Tables(rm.solve(rm.load_scene(), {"dF_up": "1000 mm"}, ["G_m"])._repr_html_())
    (found,) = page.named("found")
    assert found["name"] == "G_m" and found["unit"] == "kN"
    assert si(found["value"], found["unit"]) == pytest.approx(data["G_m"], rel=SHOWN)


def test_sheave_result_shows_the_tension_along_the_arc(capsys):
    data = command_json(capsys, "run", "sheave_hajduk_fig5")
    result = rm.run(rm.load_scene("sheave_hajduk_fig5"))
    page = Tables(result._repr_html_())
    rows = {r["name"]: r for r in page.named("results")}
    assert si(rows["S"]["value"], rows["S"]["unit"]) == pytest.approx(data["S"], rel=SHOWN)
    arc = page.named("tension along the arc")
    last = arc[-1]
    assert float(last["alpha [deg]"]) == pytest.approx(360.0)
    assert float(last["S/S_0 [-]"]) == pytest.approx(data["S_ratio"], rel=SHOWN)     # the arc ends at S
    ax = result.plot()
    x, y = ax.lines[0].get_data()
    assert x[-1] == pytest.approx(360.0) and y[-1] == pytest.approx(data["S_ratio"], rel=1e-9)
    assert ax.lines[1].get_data()[1][-1] == pytest.approx(np.exp(0.2 * 2 * np.pi), rel=1e-12)   # e^{mu alpha}


def test_trip_html_and_series_match_trip_json(capsys):
    data = command_json(capsys, "trip", "trip_fig9")
    trip = rm.trip(rm.load_scene("trip_fig9"))
    rows = {r["name"]: r for r in Tables(trip._repr_html_()).named("summary")}
    units = {"t_trip": "s", "F_C_max": "kN", "F_S_min": "kN", "P_max": "kW", "P_brake_max": "kW", "P_rms": "kW",
             "E_trip": "kWh", "E_regen": "kWh", "W_drum": "kWh", "stroke_needed": "m"}
    numbers = {k for k, v in data.items() if isinstance(v, (int, float)) and k != "pieces"}
    assert set(rows) == numbers                                    # every number of the JSON, with its unit
    for name, unit in units.items():
        assert rows[name]["unit"] == unit, name
        assert si(rows[name]["value"], unit) == pytest.approx(data[name], rel=SHOWN, abs=1e-9), name
    series = trip.to_series(si=True)
    assert series["E_trip [J]"] == data["E_trip"] and series["P_max [W]"] == data["P_max"]
    # the picture: the drive's power N_p(t), largest where the JSON says, its integral the motoring energy
    t, P = trip.plot().lines[0].get_data()
    assert P.max() * 1e3 == pytest.approx(data["P_max"], rel=1e-12)
    assert np.trapezoid(np.clip(P, 0, None), t) * 1e3 == pytest.approx(data["E_trip"], rel=1e-9)
    assert trip.to_frame().columns[0] == "t [s]"


def test_transient_html_matches_simulate_json(capsys):
    data = command_json(capsys, "simulate", "winch_start")
    sim = rm.simulate(rm.load_scene("winch_start"), progress=False)
    rows = {r["name"]: r for r in Tables(sim._repr_html_()).named("summary")}
    units = {"F_C_max": "kN", "F_S_min": "kN", "F_C_static": "kN", "dynamic_factor": "-", "stroke_used": "m",
             "x_m": "m", "t_end": "s", "v_load_end": "m/s", "T_min": "kN"}
    for name, unit in units.items():
        assert rows[name]["unit"] == unit, name
    numbers = {k for k, v in data.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    assert set(rows) == numbers                                    # every number of the summary, with a unit
    for name, r in rows.items():
        assert si(r["value"], r["unit"]) == pytest.approx(data[name], rel=SHOWN, abs=1e-12), name
    assert rows["dynamic_factor"]["value"] == "1.35685"            # the README's 1.36
    ax = sim.plot()
    t, F_C = ax.lines[0].get_data()
    assert F_C.max() * 1e3 == pytest.approx(data["F_C_max"], rel=1e-12) and t[-1] == data["t_end"]


def test_design_html_matches_size_json(capsys):
    data = command_json(capsys, "size", "winch_sizing_fig9")
    design = rm.size("winch_sizing_fig9", with_sensitivities=False)
    page = Tables(design._repr_html_())
    (table,) = page.tables
    rows = {r[0]: dict(zip(table["header"], r)) for r in table["rows"]}
    assert {n: rows[n]["unit"] for n in ("d", "F_nwl", "stroke", "N_p_up")} == {
        "d": "mm", "F_nwl": "kN", "stroke": "mm", "N_p_up": "kW"}
    for name in ("d", "F_nwl", "stroke", "N_p_up", "N_p_down"):
        assert si(rows[name]["design"], rows[name]["unit"]) == pytest.approx(data[name], rel=SHOWN), name
    for name, margin in data["margins"].items():
        r = rows[name]
        assert si(r["design"], r["unit"]) == pytest.approx(margin, rel=SHOWN, abs=1e-12), name
        assert si(r["continuous"], r["unit"]) == pytest.approx(data["continuous"]["margins"][name], rel=SHOWN,
                                                                abs=1e-9), name
        assert r["check"] == ("pass" if margin >= 0 else "FAIL")
    assert [n for n, r in rows.items() if r["limits the design"]] == [
        a for a in data["active"] if a in rows]
    frame = design.to_frame(si=True)
    assert frame.loc["d", "design"] == data["d"] and frame.loc["stroke", "continuous"] == data["continuous"]["stroke"]


def test_infeasible_design_says_why():
    """No design: the page is the answer's message, line by line (what size prints; the diagnosis itself is
    tested in tests/test_sizing.py), and the frame is empty."""
    from optimisation.design import Design

    message = "no design meets every check: these checks conflict: a, b\n  a: must give 1 N (alone)"
    design = Design(rm.load_scene("winch_sizing_fig9"), False, message=message)
    text = design._repr_html_()
    assert ": no design" in text and all(f"<p>{line}</p>" in text for line in message.splitlines())
    assert design.to_frame().empty


def test_sweep_shows_its_units(capsys, tmp_path):
    out = tmp_path / "s.csv"
    assert cli(["sweep", "krauze2025_fig9", "--vary", "alpha_u=10deg:20deg:3", "-o", str(out), "-q"]) == 0
    written = pd.read_csv(out)
    frame = rm.sweep(rm.load_scene(), vary={"alpha_u": "10deg:20deg:3"}, progress=False)
    text = frame._repr_html_()
    assert "F_C_up [kN]" in text and "alpha_u [deg]" in text
    pd.testing.assert_frame_equal(frame, written, rtol=1e-12)
    file = rm.sweep(rm.load_scene(), vary={"alpha_u": "10deg:20deg:3"}, out=tmp_path / "t.parquet",
                    collect=False, progress=False)
    page = Tables(file._repr_html_())
    assert [r["column"] for r in page.named("columns")] == list(written.columns)
    assert "3 points" in file._repr_html_()
    pd.testing.assert_frame_equal(file.to_frame(), written, rtol=1e-12)


def test_route_picture_is_the_forces_where_the_load_is(capsys):
    """On a route of segments the forces step where the load crosses a joint: each segment's level is
    ``ropemodel run --at x_m=... --at a_h=0`` with the load in it (the picture of the worst case: steady
    motion, the starts and stops are in its envelope)."""
    result = rm.run(rm.load_scene("route_segments"))
    ax = result.plot()
    assert ax.get_title().endswith("steady motion")
    x, F = ax.lines[0].get_data()                                   # F_C, up [kN]
    for x_m in (200.0, 700.0, 1200.0):
        data = command_json(capsys, "run", "route_segments", "--at", f"x_m={x_m:g}m", "--at", "a_h=0m/s^2")
        assert np.interp(x_m, x, F) * 1e3 == pytest.approx(data["F_C_up"], rel=1e-12)
    data = command_json(capsys, "run", "krauze2025_fig9")
    F = rm.run(rm.load_scene()).plot().lines[0].get_data()[1]      # the paper's route: wherever the load is
    assert np.ptp(F) == 0 and F[0] * 1e3 == pytest.approx(data["F_C_up"], rel=1e-12)
    assert F[0] == pytest.approx(190.95, abs=5e-3)                  # Fig. 9 prints 190.95 kN


def test_capstan_picture_is_the_load_curve(capsys):
    result = rm.run(rm.load_scene("capstan_li_experiment"))
    ax = result.plot()
    F, K = ax.lines[0].get_data()
    assert K[0] == pytest.approx(2 * 50e3 / 0.36 / 1e3, rel=1e-12)     # no load: two free spans 2 EA/L [N/mm]
    data = command_json(capsys, "run", "capstan_li_experiment", "--set", "F_T=30N")
    assert np.interp(30.0, F, K) * 1e3 == pytest.approx(data["K"], rel=1e-9)


def test_scene_repr_is_one_line():
    for name in ("krauze2025_fig9", "route_segments", "winch_start", "capstan_li_experiment"):
        text = repr(rm.load_scene(name))
        assert "\n" not in text and len(text) < 240, text
    assert repr(rm.load_scene()) == ("<Scene 'Krauze et al. 2025, Fig. 9': winch, 11 parameters, power=drive, "
                                     "from built-in scene krauze2025_fig9>")
    rows = Tables(rm.load_scene()._repr_html_()).named("parameters")
    assert {r["name"]: (r["value"], r["unit"]) for r in rows}["G_m"] == ("467", "kN")


def test_plot_without_matplotlib_says_how(monkeypatch):
    import builtins

    real = builtins.__import__

    def no_matplotlib(name, *args, **kwargs):
        if name.startswith("matplotlib"):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_matplotlib)
    with pytest.raises(ImportError, match=r"ropemodel\[plots\]"):
        rm.trip(rm.load_scene("trip_fig9")).plot()
