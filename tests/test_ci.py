"""CI runs the README's test command as written (no drift), and that command runs the suite in parallel."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _readme_test_command() -> str:
    lines = [ln for ln in (ROOT / "README.md").read_text().splitlines() if ln.startswith('pip install -e ".[test]"')]
    assert len(lines) == 1, lines
    return lines[0].split("#")[0].strip()


def test_ci_runs_the_readme_test_command_verbatim():
    command = _readme_test_command()
    ci = [ln.strip() for ln in (ROOT / ".ci" / "run").read_text().splitlines()]
    assert command in ci
    assert re.search(r'-m "not slow"', command) and re.search(r"\s-n \S+", command), command


def test_the_documentation_shows_the_same_command():
    site = [ln.split("#")[0].strip() for ln in (ROOT / "docs" / "index.md").read_text().splitlines()
            if ln.startswith('pip install -e ".[test]"')]
    assert site == [_readme_test_command()]
