"""The design report (``ropemodel report``): what the page says, that it refers to nothing outside
itself, the section registry, and the command's clean failures.  Rendering in Chromium:
``tests/test_report_render.py``.

Truths: the paper's Fig. 9 as printed (``test_krauze2025.FIG9``); each check's margin recomputed
by hand from the numbers the page prints (its definition in ``ropemodel.effects.winch_checks``);
the sign of each margin for pass/fail.
"""

from __future__ import annotations

import base64
import functools
import math
import re
from html.parser import HTMLParser

import pytest

import ropemodel as rm
from ropemodel.cli import main
from ropemodel.effects.winch_checks import margin_names
from ropemodel.errors import SolveError
from ropemodel.scene import builtin_scenes
from test_krauze2025 import FIG9

#: the built-in scenes every report test covers
SCENES = ("example", "winch_sizing_fig9", "winch_start", "sheave_hajduk_fig5", "capstan_li_experiment")


@functools.cache
def page_of(name: str) -> str:
    """The report page of a built-in scene (built once per test session)."""
    from ropemodel.reports import build, load

    report = build(load(name))
    assert report.incomplete == [], report.incomplete
    return report.html


class Page(HTMLParser):
    """Tables (class, header, rows of cell texts), every attribute, style texts and the tags of a page."""

    def __init__(self, html: str):
        super().__init__(convert_charrefs=True)
        self.tables, self.attrs, self.styles, self.tags, self.text = [], [], [], [], []
        self._cell = self._row = None
        self._in_style = False
        self.feed(html)
        self.close()

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.attrs += [(tag, k.lower(), v or "") for k, v in attrs]
        a = dict(attrs)
        if tag == "table":
            self.tables.append({"class": a.get("class", ""), "rows": []})
        elif tag == "tr":
            self._row = []
        elif tag in ("td", "th"):
            self._cell = []
        elif tag == "style":
            self._in_style = True

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self._row.append("".join(self._cell).strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.tables[-1]["rows"].append(self._row)
            self._row = None
        elif tag == "style":
            self._in_style = False

    def handle_data(self, data):
        self.text.append(data)
        if self._cell is not None:
            self._cell.append(data)
        if self._in_style:
            self.styles.append(data)

    def table(self, cls: str, index: int = 0) -> list[dict]:
        """Rows of the ``index``-th table of class ``cls`` as dicts keyed by the header."""
        found = [t for t in self.tables if cls in t["class"].split()]
        head, *rows = found[index]["rows"]
        return [dict(zip(head, r)) for r in rows]


def number(cell: str) -> tuple[float, str]:
    """``"128.723 kN"`` → (128.723, "kN")."""
    value, _, unit = cell.partition(" ")
    return float(value), unit


# --------------------------------------------------------------------------- the paper's numbers

def test_the_page_prints_every_fig9_value_of_the_paper():
    """All 25 values of Krauze et al. (2025) Fig. 9, read from the page's text, to the paper's 0.01."""
    page = Page(page_of("example"))
    pairs = {r["quantity"]: r for r in page.table("pairs")}
    singles = {r["quantity"]: r for r in page.table("singles")}
    assert len(FIG9) == 25
    for name, printed in FIG9.items():
        m = re.match(r"^(.+)_(up|down)$", name)
        cell = pairs[m[1]][m[2]] if m and m[1] in pairs else singles[name]["value"]
        value, unit = number(cell)
        assert unit == ("mm" if name.startswith("dF") else "kN"), (name, cell)
        assert round(value, 2) == pytest.approx(printed, abs=1e-9), (name, cell, printed)


def test_the_page_names_the_scene_its_digest_version_and_sources():
    import hashlib
    from importlib import resources

    html = page_of("example")
    text = resources.files("ropemodel.data").joinpath("krauze2025_fig9.toml").read_text()
    assert hashlib.sha256(text.encode()).hexdigest() in html       # the digest, computed here independently
    assert f"ropemodel version</dt><dd>{rm.__version__}" in html
    assert "built-in scene krauze2025_fig9" in html
    assert "Krauze, K. Mucha, T. Wydro, R. Klempka (2025)" in html    # the reference
    assert "eq. (13)" in html and "F<sub>C,up</sub> = 0.5 F<sub>nwl</sub> + G<sub>lmC</sub>" in html


# --------------------------------------------------------------------------- every check

def _hand_margins(values: dict) -> dict:
    """Every margin recomputed from the page's printed numbers (display units; ratios as fractions)."""
    v = values
    out = {"drum_margin": v["D"] / (v["D_ratio_min"] * v["d"]) - 1}
    for w in ("up", "down"):
        out[f"safety_margin_{w}"] = v["F_min"] / (v["n_rope"] * v[f"F_C_{w}"]) - 1
        out[f"slip_margin_{w}"] = v[f"F_S_{w}"] * v[f"traction_{w}"] / (v["n_slip"] * v[f"F_C_{w}"]) - 1
        out[f"slack_margin_{w}"] = v[f"F_S_{w}"] - v["F_S_min"]
        out[f"taut_margin_{w}"] = v[f"F_C_{w}"] - v["F_S_min"]
        # along the route (a one-piece route's unwinding rope has nothing between its ends: no F_S_least)
        out[f"route_margin_{w}"] = min(v.get(f"F_S_least_{w}", math.inf), v[f"F_C_least_{w}"]) - v["F_S_min"]
        out[f"stroke_margin_{w}"] = v["stroke"] - v[f"dF_{w}"]
    out["sheave_margin"] = v["F_nwl"] / 2 - v["F_S_min"]
    return out


def test_every_check_of_the_sizing_scene_with_its_margin_and_verdict():
    page = Page(page_of("winch_sizing_fig9"))
    scene = rm.load_scene("winch_sizing_fig9")
    names = margin_names(scene.built.outputs)
    assert len(names) == 14
    # the numbers the page prints: inputs, derived rope properties, results (display units)
    shown = {}
    for cls in ("pairs", "singles"):
        for r in page.table(cls):
            for key in ("down", "up", "value"):
                if r.get(key):
                    shown[r["quantity"] + {"down": "_down", "up": "_up", "value": ""}[key]] = number(r[key])[0]
    for cls in ("inputs", "derived", "defaults"):   # (x_m is "anywhere": each check at its worst place)
        shown.update({r["parameter" if cls != "derived" else "quantity"]: number(r["value"])[0]
                      for r in page.table(cls) if r["value"] != "anywhere"})
    hand = _hand_margins(shown)
    rows = page.table("checks", 0)                    # at the scene's own (starting) design
    assert [r["margin"] for r in rows] == names
    for r in rows:
        value = number(r["margin value"])[0]
        assert value == pytest.approx(hand[r["margin"]], rel=2e-5, abs=2e-5 * max(1.0, abs(value))), r
        assert r["result"] == ("pass" if hand[r["margin"]] >= 0 else "FAIL"), r
    failed = [r["margin"] for r in rows if r["result"] == "FAIL"]
    # 1000 mm is far too short for this rope's stretch; 1.5 wraps at mu_d = 0.2 slip when hauling up
    assert sorted(failed) == ["slip_margin_up", "stroke_margin_down", "stroke_margin_up"]
    assert f"{len(failed)} of 14 checks FAIL" in page_of("winch_sizing_fig9")


def test_the_sizing_section_shows_the_design_and_every_check_passing():
    from optimisation.design import size
    from optimisation.problem import load_sizing

    page = Page(page_of("winch_sizing_fig9"))
    design = size(load_sizing("winch_sizing_fig9", emit=False), with_sensitivities=False)
    rows = page.table("checks", 1)                    # at the recommended design
    assert [r["margin"] for r in rows] == margin_names(design.margins)
    assert all(r["result"] == "pass" for r in rows) and all(v >= 0 for v in design.margins.values())
    table = {r["design variable"]: r for r in page.table("design")}
    q = design.scene.built.quantities
    for k in ("d", "F_nwl", "stroke"):
        assert table[k]["recommended (catalogue)"] == q[k].show(design.design[k])
    for a in design.active:
        assert f"<code>{a}</code>" in page_of("winch_sizing_fig9")
    assert "All 14 checks pass." in page_of("winch_sizing_fig9")


def test_catalogue_rope_properties_are_marked_as_derived():
    page = Page(page_of("winch_sizing_fig9"))
    derived = {r["quantity"]: r["from"] for r in page.table("derived")}
    assert {"q_l", "q_lw", "F_min"} <= set(derived)
    assert set(derived.values()) == {"derived from the rope catalogue"}
    singles = {r["quantity"]: r["equation"] for r in page.table("singles")}
    assert "derived from the rope catalogue" in singles["q_lw"]


def test_a_sizing_scene_without_a_design_is_reported_at_the_recommended_design(tmp_path):
    from importlib import resources

    from ropemodel.reports import build, load

    toml = resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml").read_text()
    toml = re.sub(r'^(d|F_nwl|stroke) = .*$', "", toml, flags=re.M)
    f = tmp_path / "no_design.toml"
    f.write_text(toml)
    report = build(load(f))
    assert report.incomplete == []
    page = Page(report.html)
    assert "chosen by the sizing" in report.html and "at the recommended design" in report.html
    assert all(r["result"] == "pass" for r in page.table("checks", 0))


# --------------------------------------------------------------------------- self-contained

LINKS = ("src", "href", "xlink:href", "action", "formaction", "poster", "srcset", "data", "background", "cite",
         "longdesc", "ping", "manifest", "codebase", "archive", "profile", "usemap")


def _local(value: str) -> bool:
    return value.strip().startswith(("data:", "#"))


def _css_problems(css: str) -> list[str]:
    out = [f"@import in {css[:40]!r}"] if "@import" in css.lower() else []
    for url in re.findall(r"url\(\s*['\"]?([^'\")]*)", css, flags=re.I):
        if not _local(url):
            out.append(f"url({url})")
    return out


def _svg_problems(svg: str) -> list[str]:
    out = [] if "<!DOCTYPE" not in svg else ["an SVG with a DOCTYPE (a DTD address)"]
    for attr, value in re.findall(r"\s([\w:-]+)=\"([^\"]*)\"", svg):
        if attr.startswith("xmlns"):
            continue   # namespace names, never fetched
        if attr.lower() in LINKS or "://" in value:
            if not _local(value):
                out.append(f"{attr}={value!r} inside an SVG")
    return out + _css_problems(svg)


def network_references(html: str) -> list[str]:
    """Every reference of the page (and of the SVG pictures inside it) to something outside it."""
    page, found = Page(html), []
    found += [f"<{t}>" for t in page.tags if t in ("script", "link", "iframe", "object", "embed", "base", "frame")]
    for tag, attr, value in page.attrs:
        if attr in LINKS and not _local(value):
            found.append(f"<{tag} {attr}={value!r}>")
        if attr == "style":
            found += _css_problems(value)
        if attr == "http-equiv":
            found.append(f"<meta http-equiv={value!r}>")
        if attr == "src" and value.startswith("data:image/svg+xml;base64,"):
            found += _svg_problems(base64.b64decode(value.split(",", 1)[1]).decode("utf-8"))
    for css in page.styles:
        found += _css_problems(css)
    return found


def test_the_checker_finds_network_references():
    """The checker below can fail: each kind of outside reference is caught."""
    svg = base64.b64encode(b'<svg xmlns="http://www.w3.org/2000/svg"><image href="http://x/y.png"/></svg>').decode()
    for bad in ('<img src="https://x/a.png">', '<a href="http://x">x</a>', '<link rel="stylesheet" href="a.css">',
                '<style>@import "a.css";</style>', '<div style="background: url(http://x/a.png)"></div>',
                '<script src="a.js"></script>', f'<img src="data:image/svg+xml;base64,{svg}">',
                '<style>@font-face { src: url(//fonts.example/f.woff) }</style>'):
        assert network_references(f"<html><body>{bad}</body></html>"), bad
    good = '<html><body><a href="#x">x</a><img src="data:image/png;base64,AA=="></body></html>'
    assert network_references(good) == []


@pytest.mark.parametrize("name", builtin_scenes())
def test_the_page_refers_to_nothing_outside_itself(name):
    html = page_of(name)
    assert network_references(html) == []
    assert html.count('<img src="data:image/svg+xml;base64,') >= 1   # its pictures are inside it


# --------------------------------------------------------------------------- text and formulas

def test_formulas_are_typeset_and_text_is_escaped(tmp_path):
    from ropemodel.reports.page import typeset

    assert str(typeset("F_C = 0.5 F_nwl")) == "F<sub>C</sub> = 0.5 F<sub>nwl</sub>"
    assert str(typeset("traction = e^(μ_d α_d)")) == "traction = e<sup>μ<sub>d</sub> α<sub>d</sub></sup>"
    assert str(typeset("a < b & <script>")) == "a &lt; b &amp; &lt;script&gt;"
    from ropemodel.reports import build, load

    f = tmp_path / "s.toml"
    f.write_text('[scene]\nname = "<b>bold</b> & <script>x</script>"\n[parameters]\nL_u = "1150 m"\nL_ul = "500 m"\n'
                 'alpha_u = "16 deg"\nmu_pm = 0.05\nmu_pl = 0.05\nG_m = "467 kN"\nF_nwl = "20 kN"\nq_l = "0.08 kN/m"\n'
                 'q_lw = "5.8 mm/kN"\n')
    html = build(load(f)).html
    assert "<b>bold</b>" not in html and "<script>" not in html
    assert "&lt;b&gt;bold&lt;/b&gt; &amp; &lt;script&gt;x&lt;/script&gt;" in html


# --------------------------------------------------------------------------- sections

@pytest.fixture
def registry():
    from ropemodel.reports import SECTIONS
    from ropemodel.reports.registry import sections

    sections()
    before = list(SECTIONS)
    yield SECTIONS
    SECTIONS[:] = before


def test_a_registered_section_appears_when_it_applies(registry):
    from ropemodel.reports import build, load, section

    @section("demo", "Demo section", when=lambda ctx: ctx.scene.model == "sheave")
    def demo(ctx):
        return "<p>demo of " + str(ctx.result.values["S"] > 0) + "</p>"

    with pytest.raises(RuntimeError):
        section("demo", "again")(demo)
    sheave = build(load("sheave_hajduk_fig5"))
    assert sheave.shown[-1] == "demo" and "<p>demo of True</p>" in sheave.html
    assert '<a href="#demo">Demo section</a>' in sheave.html
    assert "demo" not in build(load("example")).shown


def test_a_section_that_cannot_be_computed_says_why(registry, tmp_path, capsys, monkeypatch):
    from ropemodel.reports import section

    @section("broken", "Broken", when=lambda ctx: True)
    def broken(ctx):
        raise SolveError("no valid solution here (test)")

    out = tmp_path / "r.html"
    assert main(["report", "example", "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert "section 'broken' could not be computed" in err and "Traceback" not in err
    assert "Not computed: no valid solution here (test)" in out.read_text()


ROUTE = """[scene]
name = "two segments"
[effects]
route = "segments"
[parameters]
mu_pm = 0.05
mu_pl = 0.05
G_m = "467 kN"
F_nwl = "20 kN"
q_l = "0.08 kN/m"
q_lw = "5.8 mm/kN"
x_m = "900 m"
[[route]]
length = "500 m"
inclination = "16 deg"
[[route]]
length = "650 m"
inclination = "10 deg"
"""


def test_the_documented_way_to_add_a_section_works(registry, tmp_path):
    """The example of ropemodel.reports's docstring, run as written: the energy section shows on a route of
    segments, with the energy of the trips the page's trip section reports, and only there."""
    import textwrap

    import ropemodel.reports
    from ropemodel.reports import build, load
    from ropemodel.trips import prepare, trip

    code = textwrap.dedent(ropemodel.reports.__doc__.split("energy.py``::\n", 1)[1].split("\nand its name", 1)[0])
    exec(compile(code, "energy.py", "exec"), {})
    scene = tmp_path / "route.toml"
    scene.write_text(ROUTE.replace("[[route]]", 'v_pj = "2.5 m/s"\nt_ramp = "5 s"\n[[route]]', 1))
    report = build(load(scene))
    assert report.incomplete == [] and report.shown[-1] == "energy" and "trip" in report.shown
    energy = Page(report.html).tables[-1]["rows"]
    for row in energy[1:]:
        direct = trip(prepare(load(scene).point), row[0]).summary["E_trip"] / 3.6e6
        assert float(row[1]) == pytest.approx(direct, abs=5e-4)
    assert network_references(report.html) == []
    assert "energy" not in build(load("example")).shown


def test_the_trip_section_of_the_papers_incline():
    """trip_fig9: the largest winding-rope force of the upward trip is the paper's F_C_up (190.95 kN, Fig. 9)
    plus the start's rigid-body inertia (G_m + q_l L_u)/g · v_pj/t_ramp, written out here; one trip picture
    each way."""
    html = page_of("trip_fig9")
    head, *body = next(t["rows"] for t in Page(html).tables if t["rows"][0][:2] == ["quantity", "upward"])
    rows = {r[0]: dict(zip(head, r)) for r in body}
    inertia = (467e3 + 80.0 * 1150.0) / 9.80665 * (2.5 / 5.0)
    assert float(rows["largest winding-rope force F_C"]["upward"]) == pytest.approx((190.95e3 + inertia) / 1e3,
                                                                                      abs=0.01)
    assert 'alt="trip up"' in html and 'alt="trip down"' in html
    assert "trip" not in build_shown("example")


def build_shown(name):
    from ropemodel.reports import build, load

    return build(load(name)).shown
