"""``ropemodel report``: the page written atomically, bad input refused before any work in one line
(exit 2), Chromium or the ``report`` extra missing named with how to install it, the layering."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from ropemodel.cli import main
from test_report import Page

def test_cli_writes_the_page_atomically(tmp_path, capsys):
    out = tmp_path / "report.html"
    out.write_text("old")
    assert main(["report", "example", "--set", "alpha_u=18deg", "-o", str(out)]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {out}"
    html = out.read_text()
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    inputs = {r["parameter"]: r for r in Page(html).table("inputs")}
    assert inputs["alpha_u"]["value"] == "18 deg" and inputs["alpha_u"]["from"] == "--set on the command line"
    assert inputs["G_m"]["from"] == "scene file"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html"]   # no temporary or lock file left


def test_cli_bad_scene_lists_its_problems_and_leaves_the_output(tmp_path, capsys):
    scene = tmp_path / "bad.toml"
    scene.write_text('[scene]\nname = "bad"\n[parameters]\nL_u = 1150\nalpha_u = "16 deg"\nG_mm = "467 kN"\n')
    out = tmp_path / "r.html"
    out.write_text("old")
    assert main(["report", str(scene), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "problems" in err and "L_u" in err and "G_mm" in err
    assert "Traceback" not in err
    assert out.read_text() == "old" and sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml", "r.html"]


@pytest.mark.parametrize("args, words", [
    (["-o", "{d}/missing/r.html"], "does not exist"),
    (["-o", "{d}/file.txt/r.html"], "is a file, not a directory"),
    (["-o", "{d}"], "is a directory"),
    (["-o", "{d}/r.pdf"], "must end in .html, .htm"),
    (["--pdf", "{d}/r.html"], "must end in .pdf"),
    ([], "nothing to write"),
    (["-o", "{d}/r.html", "--set", "alpha_u=16"], "alpha_u"),
])
def test_cli_refuses_before_any_work_in_one_line(tmp_path, capsys, args, words):
    (tmp_path / "file.txt").write_text("x")
    assert main(["report", "example", *[a.format(d=tmp_path) for a in args]]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and words in err and len(err.strip().splitlines()) == 1, err


def test_cli_pdf_without_chromium_says_how_to_install_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))          # no browser on PATH
    assert main(["report", "example", "--pdf", str(tmp_path / "r.pdf")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "apt-get install chromium" in err
    assert not (tmp_path / "r.pdf").exists()


def test_cli_without_the_report_extra_names_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "jinja2", None)   # as if Jinja2 were not installed
    assert main(["report", "example", "-o", str(tmp_path / "r.html")]) == 2
    assert 'pip install "ropemodel[report]"' in capsys.readouterr().err


def test_only_the_command_imports_the_report_package():
    root = Path(__file__).resolve().parents[1]
    imports = re.compile(r"^\s*(?:from ropemodel\.reports\b|import ropemodel\.reports\b"
                         r"|from ropemodel import .*\breports\b)", re.M)
    users = [p.relative_to(root).as_posix() for d in ("ropemodel", "optimisation", "studies") for p in
             (root / d).rglob("*.py") if imports.search(p.read_text(encoding="utf-8"))]
    assert {u for u in users if not u.startswith("ropemodel/reports/")} == {"ropemodel/cli/report.py"}
    inside = "".join(p.read_text() for p in (root / "ropemodel/reports").rglob("*.py"))
    assert not re.search(r"^\s*(?:from|import) ropemodel\.cli\b", inside, re.M)


def test_cli_an_infeasible_sizing_is_reported_with_its_conflict(tmp_path, capsys):
    """By hand: the strongest catalogue rope (60 mm, K = 0.356, 1770 N/mm^2) breaks at K d^2 R_r = 2.27 MN,
    less than n_rope = 40 times the load's pull along the incline alone, 467 kN sin 16 deg: no design exists."""
    import math

    from ropemodel.papers import en12385

    strongest = 0.356 * max(en12385.diameters()) ** 2 * 1770e6
    assert strongest < 40 * 467e3 * math.sin(math.radians(16))
    out = tmp_path / "r.html"
    assert main(["report", "winch_sizing_fig9", "--set", "n_rope=40", "-o", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == f"wrote {out}" and "sizing: no design meets every check" in lines
    html = out.read_text()
    assert "No design meets every check." in html and "these checks conflict: safety_margin_up" in html


def test_unused_parameters_and_warnings_are_on_the_page(tmp_path):
    from importlib import resources

    from ropemodel.reports import build, load

    text = resources.files("ropemodel.data").joinpath("krauze2025_fig9.toml").read_text()
    scene = tmp_path / "s.toml"
    scene.write_text(text.replace('alpha_u = "16 deg"', 'alpha_u = "75 deg"\nmu_d = 0.2'))
    report = build(load(scene))
    page = Page(report.html)
    unused = {r["parameter"]: r["used by"] for r in page.table("unused")}
    assert "mu_d" in unused and "lining" in unused["mu_d"]
    text = "".join(page.text)
    assert "mu_d is not used" in text and "alpha_u = 75 deg is outside the range usual for the field" in text


def _fake_browser(tmp_path, body: str) -> Path:
    """A stand-in 'chromium' first on PATH, running the shell ``body``."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    exe = bin_dir / "chromium"
    exe.write_text(f"#!/bin/sh\n{body}\n")
    exe.chmod(0o755)
    return bin_dir


def test_cli_a_failing_browser_is_one_line_and_leaves_no_file(tmp_path, capsys, monkeypatch):
    bin_dir = _fake_browser(tmp_path, 'echo "[1:2:ERROR] dbus noise" >&2; echo "cannot print: no display" >&2; exit 3')
    monkeypatch.setenv("PATH", f"{bin_dir}:/usr/bin:/bin")
    out = tmp_path / "r.pdf"
    assert main(["report", "example", "--pdf", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.strip() == f"error: cannot write {out}: Chromium failed printing the page (exit status 3): " \
                          "cannot print: no display"
    assert "Traceback" not in err and "dbus" not in err and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bin"]


def test_a_browser_that_hangs_is_ended_with_its_helpers(tmp_path, monkeypatch):
    import time

    from ropemodel.reports import browser
    from ropemodel.sweeps.files import OutputError

    pids = tmp_path / "pids"
    bin_dir = _fake_browser(tmp_path, f"sleep 60 & echo $! > {pids}; sleep 60")
    monkeypatch.setattr(browser, "TIMEOUT", 1.0)
    page = tmp_path / "p.html"
    page.write_text("<html></html>")
    start = time.monotonic()
    with pytest.raises(OutputError, match="did not finish"):
        browser.print_pdf(page, tmp_path / "p.pdf", str(bin_dir / "chromium"))
    assert time.monotonic() - start < 30
    helper = Path(f"/proc/{int(pids.read_text())}/stat")
    for _ in range(50):   # the helper it started is ended too: gone, or a zombie awaiting its reaper
        if not helper.exists() or helper.read_text().rsplit(")", 1)[1].split()[0] in ("Z", "X"):
            break
        time.sleep(0.1)
    else:
        pytest.fail("the browser's helper process is still running")
