"""The documentation's text where the tests read what it claims: README.md and the site's pages (docs/**/*.md).

The README is short (issue 26); the numbers it used to hold live in the site's pages now.  A test finds a
section by its heading wherever it is, so a section may move between pages without its test losing it.
"""

from __future__ import annotations

import re
from pathlib import Path

from ropemodel.docs import pages

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def _headings(text: str) -> list[tuple[int, int, str]]:
    """(offset, level, title) of each Markdown heading outside fenced code blocks."""
    out, fence, pos = [], "", 0
    for line in text.splitlines(keepends=True):
        m = re.match(r"^(`{3,}|~{3,})", line)
        if m and not fence:
            fence = m.group(1)
        elif fence and line.strip() == fence:
            fence = ""
        elif not fence and (h := re.match(r"^(#{1,6}) (.*?)\s*$", line)):
            out.append((pos, len(h.group(1)), h.group(2)))
        pos += len(line)
    return out


def section(heading: str) -> str:
    """The text under ``heading`` (its title, without the ``#``), up to the next heading of its level or
    higher, in README.md or a page of the site; where the title heads sections in several files (a page's
    own heading over text it took from the README), their texts joined.  No such heading: AssertionError."""
    found = []
    for path in pages(ROOT):
        text = path.read_text(encoding="utf-8")
        hs = _headings(text)
        for i, (start, level, title) in enumerate(hs):
            if title == heading:
                end = next((s for s, lv, _ in hs[i + 1:] if lv <= level), len(text))
                found.append(text[start:end])
    assert found, f"no section {heading!r} in README.md or docs/**/*.md"
    return "\n".join(found)
