"""A scene's ``[report]`` table: what the filed report says about itself.

::

    [report]
    document = "CALC-H3-014"          # the document number the report is filed under
    project = "Level 4 incline haulage"
    title = "Winch H-3: rope, pretension and stroke"    # default: "Design report: <scene name>"
    revision = "B"                     # default: the last of [[report.history]]
    prepared_by = "A. Engineer"
    prepared_on = 2026-11-20           # a TOML date, or "2026-11-20"
    checked_by = "B. Checker"
    checked_on = 2026-11-22
    approved_by = "C. Approver"
    approved_on = 2026-11-24

    [[report.history]]                 # every revision, oldest first
    revision = "A"
    date = 2026-10-01
    description = "first issue"

    [report.rope]                      # the rope as bought, for its designation (EN 12385-2)
    construction = "6x36WS"            # the construction within the catalogue's class
    lay = "sZ"                         # sZ, zS, zZ, sS, aZ, aS
    finish = "U"                       # U (bright), A, B (zinc), A(Zn/Al), B(Zn/Al)
    maker = "..."
    certificate = "..."                # the test certificate's number

The table is part of the scene file, so the file's SHA-256 on the page covers the sign-off too.  Every key
is optional; an unknown key is refused, with every other problem of the scene.  Dates must be real dates;
a check cannot precede the preparation, an approval the check; the history's dates may not go back, its
revisions are distinct, and the revision the report carries is the history's last.
"""

from __future__ import annotations

import datetime as dt
from dataclasses import dataclass

from ropemodel.errors import Problems, suggest

ROLES = ("prepared", "checked", "approved")
TEXT_KEYS = ("document", "project", "title", "revision")
KEYS = TEXT_KEYS + tuple(f"{r}_{s}" for r in ROLES for s in ("by", "on")) + ("history", "rope")
HISTORY_KEYS = ("revision", "date", "description", "by")
#: [report.rope] key → what it is
ROPE_KEYS = {"construction": "the rope's construction within its class (e.g. 6x36WS)",
             "lay": "type and direction of lay", "finish": "surface finish of the wires",
             "maker": "the rope maker", "certificate": "the number of the rope's test certificate"}
#: type and direction of lay (EN 12385-2, ISO 17893): the wires' lay in the strand, then the strands' in the rope
LAYS = {"sZ": "right-hand ordinary (regular) lay", "zS": "left-hand ordinary (regular) lay",
        "zZ": "right-hand Lang's lay", "sS": "left-hand Lang's lay", "aZ": "right-hand alternate lay",
        "aS": "left-hand alternate lay"}
#: surface finish of the wires (EN 12385-2)
FINISHES = {"U": "uncoated (bright)", "A": "zinc coated, class A", "B": "zinc coated, class B",
            "A(Zn/Al)": "zinc-aluminium coated, class A", "B(Zn/Al)": "zinc-aluminium coated, class B"}


@dataclass(frozen=True)
class Signature:
    """One line of the sign-off block: who, and when (either may be missing: signed by hand)."""

    role: str
    name: str | None = None
    date: dt.date | None = None


@dataclass(frozen=True)
class Revision:
    """One revision of the document."""

    revision: str
    date: dt.date
    description: str
    by: str = ""


@dataclass(frozen=True)
class Filing:
    """The ``[report]`` table, checked (see the module docstring)."""

    document: str | None = None
    project: str | None = None
    title: str | None = None
    revision: str | None = None
    signatures: tuple[Signature, ...] = tuple(Signature(r) for r in ROLES)
    history: tuple[Revision, ...] = ()
    rope: tuple[tuple[str, str], ...] = ()

    def rope_field(self, key: str) -> str | None:
        """A ``[report.rope]`` value, or None."""
        return dict(self.rope).get(key)


def _unknown(keys, valid, where: str, found: Problems) -> None:
    for key in keys:
        if key not in valid:
            found.add(f"unknown key {key!r} in {where}; valid: {', '.join(valid)}{suggest(str(key), valid)}")


def _text(value, where: str, found: Problems) -> str | None:
    if value is None:
        return None
    if not isinstance(value, str) or not value.strip():
        found.add(f"{where} must be text (a name, a number in quotes), got {value!r}")
        return None
    return value.strip()


def _date(value, where: str, found: Problems) -> dt.date | None:
    """A TOML date or an ISO text "YYYY-MM-DD" as a date."""
    if value is None:
        return None
    if isinstance(value, dt.date) and not isinstance(value, dt.datetime):
        return value
    if isinstance(value, str):
        try:
            return dt.date.fromisoformat(value.strip())
        except ValueError:
            pass
    found.add(f"{where} = {value!r} is not a date: write it as 2026-11-20 (year-month-day)")
    return None


def _signatures(raw: dict, found: Problems) -> tuple[Signature, ...]:
    out = []
    for role in ROLES:
        name = _text(raw.get(f"{role}_by"), f"[report] {role}_by", found)
        date = _date(raw.get(f"{role}_on"), f"[report] {role}_on", found)
        if date is not None and name is None and f"{role}_by" not in raw:
            found.add(f"[report] {role}_on = {date} without {role}_by: name who {role} it")
        out.append(Signature(role, name, date))
    dated = [(s.role, s.date) for s in out if s.date is not None]
    for (first, earlier), (then, later) in zip(dated, dated[1:]):
        if later < earlier:
            found.add(f"[report] {then}_on = {later} is before {first}_on = {earlier}: a document is {first} "
                      f"before it is {then}")
    return tuple(out)


def _history(raw, found: Problems) -> tuple[Revision, ...]:
    if raw is None:
        return ()
    if not isinstance(raw, list) or not all(isinstance(r, dict) for r in raw):
        found.add("[[report.history]] must be a list of tables: revision, date, description (and by)")
        return ()
    out = []
    for i, entry in enumerate(raw, start=1):
        where = f"[[report.history]] entry {i}"
        _unknown(entry, HISTORY_KEYS, where, found)
        rev = _text(entry.get("revision"), f"{where}: revision", found)
        date = _date(entry.get("date"), f"{where}: date", found)
        text = _text(entry.get("description"), f"{where}: description", found)
        by = _text(entry.get("by"), f"{where}: by", found) or ""
        missing = [k for k in ("revision", "date", "description") if k not in entry]
        if missing:
            found.add(f"{where} needs {', '.join(missing)}")
        if rev is not None and date is not None and text is not None:
            out.append(Revision(rev, date, text, by))
    revisions = [r.revision for r in out]
    for rev in sorted({r for r in revisions if revisions.count(r) > 1}):
        found.add(f"[[report.history]] lists revision {rev!r} {revisions.count(rev)} times: each revision once")
    for a, b in zip(out, out[1:]):
        if b.date < a.date:
            found.add(f"[[report.history]]: revision {b.revision!r} ({b.date}) is dated before revision "
                      f"{a.revision!r} ({a.date}): list the revisions oldest first")
    return tuple(out)


def _rope(raw, found: Problems) -> tuple[tuple[str, str], ...]:
    if raw is None:
        return ()
    if not isinstance(raw, dict):
        found.add("[report.rope] must be a table: construction, lay, finish, maker, certificate")
        return ()
    _unknown(raw, tuple(ROPE_KEYS), "[report.rope]", found)
    out = {k: v for k in ROPE_KEYS if (v := _text(raw.get(k), f"[report.rope] {k}", found)) is not None}
    for key, valid in (("lay", LAYS), ("finish", FINISHES)):
        if key in out and out[key] not in valid:
            found.add(f"[report.rope] {key} = {out[key]!r} is not an EN 12385-2 {ROPE_KEYS[key]}; valid: "
                      + ", ".join(f"{k} ({v})" for k, v in valid.items()) + suggest(out[key], valid))
            del out[key]
    return tuple(out.items())


def read_report(data: dict, found: Problems) -> Filing | None:
    """The scene's ``[report]`` as a :class:`Filing` (None without one); every problem goes to ``found``."""
    raw = data.get("report")
    if raw is None:
        return None
    if not isinstance(raw, dict):
        found.add("[report] must be a table: document, revision, prepared_by, prepared_on, ...")
        return None
    _unknown(raw, KEYS, "[report]", found)
    texts = {k: _text(raw.get(k), f"[report] {k}", found) for k in TEXT_KEYS}
    history = _history(raw.get("history"), found)
    revision = texts["revision"]
    if history and revision is None:
        revision = history[-1].revision
    elif history and revision != history[-1].revision:
        found.add(f"[report] revision = {revision!r} is not the last revision of [[report.history]] "
                  f"({history[-1].revision!r}): add it to the history, or correct the revision")
    return Filing(texts["document"], texts["project"], texts["title"], revision, _signatures(raw, found), history,
                  _rope(raw.get("rope"), found))
