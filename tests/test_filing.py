"""A report to file: the scene's ``[report]`` table (document, revision, sign-off, history, the rope as bought),
the rope's designation, the normative numbers with their source and status, the assumptions and the data
still missing.  The printed PDF (page numbers, running header, the sign-off block): tests/test_report_render.py.

Truths: the scene text written here; the rope catalogue read here with tomllib (ropemodel/data/ropes.toml);
the rule set's data file read here; the designation's elements in the order EN 12385-2 / ISO 17893 give them,
written out by hand.
"""

from __future__ import annotations

import functools
import re
import tomllib
from importlib import resources

import pytest

from ropemodel.errors import InputError
from ropemodel.scene import from_toml
from test_report import Page

BASE = resources.files("ropemodel.data").joinpath("winch_sizing_fig9.toml").read_text()
FILED = BASE + """
[report]
document = "CALC-H3-014"
project = "Level 4 incline haulage"
title = "Winch H-3: rope, pretension and stroke"
prepared_by = "A. Engineer"
prepared_on = 2026-11-20
checked_by = "B. Checker"
checked_on = "2026-11-22"

[[report.history]]
revision = "A"
date = 2026-10-01
description = "first issue"

[[report.history]]
revision = "B"
date = 2026-11-20
description = "rope re-sized"
by = "A. Engineer"

[report.rope]
construction = "6x36WS"
lay = "sZ"
finish = "U"
"""


def catalogue() -> dict:
    return tomllib.loads(resources.files("ropemodel.data").joinpath("ropes.toml").read_text())


@functools.cache
def filed(text: str = FILED, name: str = "filed.toml"):
    """The context and the page of a scene written here."""
    import pathlib
    import tempfile

    from ropemodel.reports import build, load

    with tempfile.TemporaryDirectory() as d:
        path = pathlib.Path(d) / name
        path.write_text(text)
        ctx = load(path)
        report = build(ctx)
    assert report.incomplete == [], report.incomplete
    return ctx, report.html


def test_the_report_table_is_read():
    f = from_toml(FILED, bare="refuse").filing
    assert (f.document, f.project, f.revision) == ("CALC-H3-014", "Level 4 incline haulage", "B")  # the last revision
    assert [(s.role, s.name, str(s.date)) for s in f.signatures] == [
        ("prepared", "A. Engineer", "2026-11-20"), ("checked", "B. Checker", "2026-11-22"), ("approved", None, "None")]
    assert [r.revision for r in f.history] == ["A", "B"] and f.history[1].by == "A. Engineer"
    assert dict(f.rope) == {"construction": "6x36WS", "lay": "sZ", "finish": "U"}
    assert from_toml(BASE, bare="refuse").filing is None


def test_every_mistake_of_the_report_table_at_once():
    bad = BASE + """
[report]
documnt = "X"
revision = "C"
prepared_by = 3
checked_by = "B"
checked_on = "2026-02-30"
approved_by = "C"
approved_on = 2026-01-01
prepared_on = 2026-03-01
[[report.history]]
revision = "B"
date = 2026-02-01
description = "second"
[[report.history]]
revision = "B"
date = 2026-01-01
description = "first"
[report.rope]
lay = "ZS"
colour = "red"
"""
    with pytest.raises(InputError) as info:
        from_toml(bad, bare="refuse")
    problems = info.value.problems
    expected = ["unknown key 'documnt' in [report]", "did you mean 'document'?",
                "[report] prepared_by must be text", "checked_on = '2026-02-30' is not a date",
                "approved_on = 2026-01-01 is before prepared_on = 2026-03-01",
                "lists revision 'B' 2 times", "revision 'B' (2026-01-01) is dated before revision 'B'",
                "revision = 'C' is not the last revision of [[report.history]]",
                "lay = 'ZS' is not an EN 12385-2 type and direction of lay", "unknown key 'colour' in [report.rope]"]
    for words in expected:
        assert any(words in p for p in problems), (words, problems)


def test_the_document_section_carries_the_sign_off_and_the_history():
    ctx, html = filed()
    page = Page(html)
    assert "<h1>Winch H-3: rope, pretension and stroke</h1>" in html
    signoff = {r[""]: r for r in page.table("signoff")}
    assert list(signoff) == ["Prepared by", "Checked by", "Approved by"]
    assert (signoff["Prepared by"]["name"], signoff["Prepared by"]["date"]) == ("A. Engineer", "2026-11-20")
    assert (signoff["Approved by"]["name"], signoff["Approved by"]["signature"]) == ("", "")      # signed by hand
    assert [r["revision"] for r in page.table("history")] == ["A", "B"]
    header = re.search(r'@top-left \{ content: "([^"]*)"', html)[1]
    assert re.sub(r"\\([0-9a-f]{1,6}) ?", lambda m: chr(int(m[1], 16)), header) == "CALC-H3-014 · revision B"


def test_the_running_header_cannot_leave_its_style():
    from ropemodel.reports.page import css_string

    text = 'A "quoted" title</style><script>x</script> \\ end'
    out = css_string(text)
    assert '"' not in out and "<" not in out and ">" not in out
    assert out.count("\\") == text.count('"') + text.count("<") + text.count(">") + text.count("\\")
    _, html = filed(FILED.replace('title = "Winch H-3: rope, pretension and stroke"', f"title = '{text}'"),
                    "quoted.toml")
    assert html.count("</style>") == 1 and "<script>" not in html


def test_the_rope_designation_in_the_order_of_en_12385_2():
    _, html = filed()
    rows = {r["element"]: r["value"] for r in Page(html).table("rope")}
    K = catalogue()["constructions"]["6x36-IWRC"]["K"]
    F_min = K * 42.0**2 * 1770.0 / 1e3                      # kN: K d² R_r with d in mm and R_r in N/mm²
    # diameter, construction-core, grade, finish, lay (EN 12385-2 / ISO 17893), as the scene gives them
    assert rows["designation"] == "42 6x36WS-IWRC 1770 U sZ"
    assert rows["minimum breaking force"] == f"{F_min:.6g} kN"
    assert rows["lay"] == "sZ (right-hand ordinary (regular) lay)"
    _, bare = filed(BASE, "bare.toml")
    assert {r["element"]: r["value"] for r in Page(bare).table("rope")}["designation"] == "42 6x36-IWRC 1770 ? ?"


def test_normative_numbers_with_their_source_and_status():
    from ropemodel.reports import filing

    ctx, _ = filed()
    numbers = {n["name"]: n for n in filing.normative_numbers(ctx.scene)}
    c = catalogue()
    row = c["constructions"]["6x36-IWRC"]
    for key in ("K", "C"):
        assert numbers[f"rope_{key}"]["value"] == f"{row[key]:.6g}"
        assert numbers[f"rope_{key}"]["source"] == row["source"]
        assert numbers[f"rope_{key}"]["status"] == c["status"]["factors"] == "to verify"
    assert numbers["n_rope"]["status"] == "user-given"                   # the scene's own factor, no rule set
    assert numbers["D_ratio_min"]["status"] == "engineering judgement"   # the default, D >= 30 d
    assert numbers["g"]["value"] == "9.80665 m/s^2" and numbers["g"]["status"] == "confirmed"
    statuses = set(filing.STATUS_TEXT)
    assert all(n["status"] in statuses for n in numbers.values())


def test_a_rule_sets_factor_carries_its_rules_status():
    from ropemodel.reports import filing

    text = BASE.replace("n_rope = 4.5 ", "# n_rope from the rules ").replace("n_slip = 1.25 ", "# n_slip ")
    text += '\n[rules]\nset = "us-30cfr-57"\n'
    ctx, html = filed(text, "ruled.toml")
    rules = tomllib.loads(resources.files("ropemodel.data").joinpath("rules/us-30cfr-57.toml").read_text())
    friction = next(r for r in rules["rules"] if r["id"] == "friction-drum-rope")
    numbers = {n["name"]: n for n in filing.normative_numbers(ctx.scene)}
    assert numbers["n_rope"]["status"] == friction["status"] and friction["clause"] in numbers["n_rope"]["source"]
    assert not any("A rule set ([rules]" in m for m in filing.missing(ctx.scene, ctx.result.values))


def test_assumptions_and_missing_data_name_the_catalogue_stiffness():
    ctx, html = filed(BASE, "bare.toml")
    page = Page(html)
    text = "".join(page.text)
    assert "EA = E C d² from the catalogue's metallic-area factor C" in text
    assert "A measured EA (or q_lw) of the installed rope" in text
    assert "The rope's wire finish (U, A, B, ...) ([report.rope] finish)" in text
    assert "A rule set ([rules] set = \"...\"): the factors n_rope" in text
    # every default the scene relied on, with its reason (D_ratio_min is a normative number instead)
    assert set(ctx.scene.defaults) >= {"D_ratio_min"}
    for name, why in ctx.scene.defaults.items():
        if name != "D_ratio_min":
            assert why in text, name


def test_the_sheet_carries_the_filing_data():
    from ropemodel.reports.sheet import sheet

    ctx, _ = filed()
    data = sheet(ctx)
    assert data["document"]["document"] == "CALC-H3-014" and data["document"]["revision"] == "B"
    assert data["document"]["signoff"][0] == {"role": "prepared", "name": "A. Engineer", "date": "2026-11-20"}
    assert data["basis"]["rope"]["designation"] == "42 6x36WS-IWRC 1770 U sZ"
    assert any("test certificate" in m for m in data["basis"]["missing"])


def test_the_basis_names_only_the_defaults_the_report_computes_from():
    """A whole trip is computed piece by piece, with no transient (issue 21, item 6: the report computes what
    the scene calls for and nothing else): the defaults only a transient reads (its speed threshold, the rope's
    damping, the tensioner carriage's mass, an unlimited stroke) are no assumption of a trip's report, while
    its drive efficiency and the static acceleration printed in its equations are.  A start-up's report runs
    the transient, so its speed threshold is one."""
    from ropemodel.reports import load
    from ropemodel.reports.sheet import sheet

    def defaults(name: str) -> set[str]:
        lines = sheet(load(name))["basis"]["assumptions"]
        return {line.split(" = ")[0] for line in lines if "(default)" in line}

    assert defaults("trip_fig9") == {"eta", "a_h"}
    assert defaults("winch_start") == {"v_eps"}
