"""The checks of dynamic sizing in the user's words: what ``ropemodel size --dynamic`` prints and the report's
"dynamic sizing" section shows.

The internal names of the checks (``safety_margin_S``, ``slip_margin_fwd @ upward start``, ``tension_margin[8]``)
are the keys of ``--json`` and stay there.  What each name means to a designer is the machine's to say: its
declaration's ``words``, a :class:`Vocabulary` (a winch's: :data:`ropemodel.machines.winch.words.WORDS`) holding
the checks through a manoeuvre and the static checks in words (:class:`Words`), the words a check takes where the
scene carries a factor, and the factors with their rules.  The vocabulary's methods do the rest:
:meth:`~Vocabulary.check_groups` builds the checks table from a dynamic design's attributes (``manoeuvres``,
``margins``, ``scene``): one group per manoeuvre (as :mod:`optimisation.dynamic.manoeuvres` names them) and one
for the static checks of steady travel, each row the value the check judges and its limit with their units, the
margin, the instant (s) and where the load is.  :meth:`~Vocabulary.readable` turns any one name into words (the
active constraints), :meth:`~Vocabulary.in_words` every name in a message (no design), and
:meth:`~Vocabulary.factors` says which factor each check applies and its rule; :meth:`~Vocabulary.check_words`
says what a check through a manoeuvre compares and :meth:`~Vocabulary.mesh_text` what the mesh control did (the
rope's elements per span, the largest error estimate and its back-off).  The layer sits low: it reads only the
attributes and dictionaries it is given, and the machine's words come in with the vocabulary.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple


class Words(NamedTuple):
    """A check in words: ``text`` (what it compares, with its rule's symbols), ``group`` (checks of one group
    share a row in the short table: the least margin of them shows), ``kind`` (the margin's form:
    ``"ratio"`` a fraction shown in %, ``"force"`` in kN, ``"length"`` in mm) and ``broad`` (a check whose
    places include its group's other checks' places, so that it ties with one of them where the least is
    there: in a tie the narrower check's words show, which say where)."""

    text: str
    group: str
    kind: str
    broad: bool = False


_DIRECTION = {"up": "upward", "down": "downward"}
_STATIC = re.compile(r"^(?P<base>[a-z_]+?)(?:_(?P<dir>up|down))?(?: @ (?P<place>.+))?$")
_NAME = re.compile(r"\b[a-z]+(?:_[a-z]+)*_margin(?:_(?:S|fwd|back|up|down))?(?:\[\d+\])?(?![\w\[])")
_DYNAMIC = re.compile(r"^(?P<base>[a-zA-Z_]+)(?:\[\d+\])? @ (?P<rest>.+)$")


@dataclass(frozen=True)
class Row:
    """One row of the checks table, as text: ``check`` (words), ``value`` and ``limit`` (with units; "" for a
    static check), ``margin`` (with its unit), ``t`` (the instant, "" for a static check), ``where`` (the
    load's place, or the direction of travel), ``ok`` and ``names`` (the internal names the row stands for)."""

    check: str
    value: str
    limit: str
    margin: str
    t: str
    where: str
    ok: bool
    names: tuple[str, ...]


def _number(x: float, signed: bool = False) -> str:
    """Four significant digits, never an exponent for a number of 1 or more (12345 mm, not 1.234e+04)."""
    text = f"{x:+.4g}" if signed else f"{x:.4g}"
    return (f"{x:+.0f}" if signed else f"{x:.0f}") if "e+" in text else text


def _margin(kind: str, margin: float) -> str:
    if abs(margin) < 1e-9:          # an active check prints as 0, not -8.9e-13
        margin = 0.0
    if kind == "ratio":
        return f"{_number(100 * margin, signed=True)} %"
    if kind == "length":
        return f"{_number(1e3 * margin, signed=True)} mm"
    return f"{_number(1e-3 * margin, signed=True)} kN"


def _quantity(kind: str, si: float) -> str:
    return f"{_number(1e3 * si)} mm" if kind == "length" else f"{_number(1e-3 * si)} kN"


def _least(rows: list[tuple[float, Words, Row]], merged: bool) -> list[Row]:
    """The rows of (margin, words, row), or (``merged``) one per group: the least margin of the group (the
    margins of a group share their form; of equal ones a narrower check's, :attr:`Words.broad`), standing for
    every name of it."""
    if not merged:
        return [r for _, _, r in rows]
    groups: dict[str, list[tuple[float, Words, Row]]] = {}
    for margin, words, r in rows:
        groups.setdefault(words.group, []).append((margin, words, r))
    return [dataclasses.replace(min(members, key=lambda m: (m[0], m[1].broad))[2],
                                names=tuple(n for _, _, r in members for n in r.names))
            for members in groups.values()]


@dataclass(frozen=True)
class Vocabulary:
    """A machine's checks in words (its declaration's ``words``) and what is said with them.

    ``manoeuvre``: each check through a manoeuvre (a name of the machine's manoeuvres' ``CHECKS``) → its
    :class:`Words`; ``static``: each static check (a margin's base name, per direction ``_up``/``_down``, on a
    route ``@ place``) → its :class:`Words`; ``with_factor``: a scene parameter → the words of the checks through
    a manoeuvre that apply it, where the scene carries it; ``constraint``: what a force check's discretisation
    error is an error of, where that is not the margin the table shows; ``factors(scene)``: which factor each
    check applies, with its rule, one sentence each; ``steady``: the title of the static checks' group."""

    manoeuvre: dict
    static: dict
    factors: Callable[[Any], list[str]]
    steady: str
    with_factor: dict = field(default_factory=dict)
    constraint: dict = field(default_factory=dict)

    def check_words(self, name: str, parameters=None) -> str:
        """What the check through a manoeuvre ``name`` compares, in words; with a factor's words where
        ``parameters`` (the scene's) carry that factor (:attr:`with_factor`)."""
        for factor, words in self.with_factor.items():
            if factor in (parameters or {}) and name in words:
                return words[name]
        return self.manoeuvre[name].text

    def manoeuvre_rows(self, manoeuvre: dict, merged: bool = True, parameters=None) -> list[Row]:
        """The rows of one manoeuvre (an entry of ``DynamicDesign.manoeuvres``): each check's least margin over
        every place of the load, at its instant and place, with the value and limit it compares there
        (``parameters``: the scene's, for the checks' words, :meth:`check_words`)."""
        rows = []
        for name, least in manoeuvre["least_margins"].items():
            words = self.manoeuvre[name]._replace(text=self.check_words(name, parameters))
            kind = "length" if words.kind == "length" else "force"
            value = _quantity(kind, least["value"]) if "value" in least else ""
            limit = _quantity(kind, least["limit"]) if "limit" in least else ""
            row = Row(words.text, value, limit, _margin(words.kind, least["margin"]), f"{least['t']:.4g} s",
                      least["where"], least["margin"] >= -1e-9, (f"{name} @ {manoeuvre['manoeuvre']}",))
            rows.append((least["margin"], words, row))
        return _least(rows, merged)

    def static_rows(self, margins: dict, merged: bool = True) -> list[Row]:
        """The rows of the static checks ``margins`` (check name → margin, SI), each in words with the direction
        of travel and the place where it is least."""
        rows = []
        for name, margin in margins.items():
            m = _STATIC.match(name)
            if m is None:
                raise KeyError(f"{name!r} is not a static check's name")
            words = self.static[m["base"]]
            where = ", ".join(w for w in (f"{_DIRECTION[m['dir']]} travel" if m["dir"] else "", m["place"]) if w)
            rows.append((margin, words, Row(words.text, "", "", _margin(words.kind, margin), "", where,
                                                  margin >= -1e-9, (name,))))
        return _least(rows, merged)

    def is_static(self, name: str) -> bool:
        """Whether ``name`` (a key of ``DynamicDesign.margins``) is a static check, not one through a
        manoeuvre."""
        return " @ " not in name or name.split(" @ ")[0] not in self.manoeuvre

    def check_groups(self, design, merged: bool = True) -> list[tuple[str, list[Row]]]:
        """The checks table of a dynamic design: (title, rows) for each manoeuvre in the order the design holds
        them, then steady travel's static checks.  ``merged``: one row per group of checks (the short table of
        the terminal), else one per check (the report)."""
        out = [(m["manoeuvre"], self.manoeuvre_rows(m, merged, design.scene.parameters)) for m in design.manoeuvres]
        static = {k: v for k, v in design.margins.items() if self.is_static(k)}
        if static:
            out.append((self.steady, self.static_rows(static, merged)))
        return out

    def readable(self, name: str, parameters=None) -> str:
        """A check's internal name in words: ``slip_margin_fwd @ upward start, x_m = 575 m, t = 1.97 s`` →
        ``drum grip F_S >= F_C/rho (upward start, x_m = 575 m, t = 1.97 s)`` (``parameters``: the scene's, for
        the factors' words, :meth:`check_words`); ``stroke_margin_up`` → ``take-up dF <= stroke (steady upward
        travel)``; anything else (a bound, the catalogue size) as it is."""
        m = _DYNAMIC.match(name)
        if m and m["base"] in self.manoeuvre:
            return f"{self.check_words(m['base'], parameters)} ({m['rest']})"
        m = _STATIC.match(name)
        if m and m["base"] in self.static:
            where = ", ".join(w for w in (f"steady {_DIRECTION[m['dir']]} travel" if m["dir"] else "steady travel",
                                          m["place"]) if w)
            return f"{self.static[m['base']].text} ({where})"
        return name

    def in_words(self, text: str, parameters=None) -> str:
        """``text`` (a message) with every check's internal name in it put in words (:meth:`readable` of the
        name alone: ``slip_margin_fwd @ upward start`` → ``drum grip F_S >= F_C/rho @ upward start``)."""
        def words(m) -> str:
            base = m[0].split("[")[0]
            if base in self.manoeuvre:
                return self.check_words(base, parameters)
            return self.readable(base).replace(" (steady travel)", "")

        return _NAME.sub(words, text)

    def mesh_text(self, mesh: dict, parameters=None) -> str:
        """What dynamic sizing's mesh control did (``DynamicDesign.mesh``), in words and kN: the rope's elements
        per span, the tolerance, the largest estimate of a force check's discretisation error, the part of it
        on the unsafe side and the check's back-off ("" without a mesh to refine)."""
        if not mesh.get("segments"):
            return ""
        forces = {c: e for c, e in mesh["errors"].items() if mesh["units"][c] == "N"}
        text = (f"rope mesh: {mesh['segments']} elements per span (from the scene's {mesh['segments_scene']}, "
                f"doubled while Richardson's estimate of a force check's discretisation error exceeded mesh_tol = "
                f"{mesh['tolerance'] * 1e-3:g} kN)")
        if forces:
            worst = max(forces, key=lambda c: forces[c])
            of = f" {self.constraint[worst]}" if worst in self.constraint else ""
            text += (f"; the largest estimate {forces[worst] * 1e-3:.3g} kN{of}, "
                     f"{self.check_words(worst, parameters)}, {mesh['unsafe'][worst] * 1e-3:.3g} kN of it on the "
                     f"unsafe side, backed off by {mesh['backoffs'][worst] * 1e-3:.3g} kN")
        return text + ("; each check through a manoeuvre, with the load at each place within reach of its limit, is "
                       "backed off by a little more than the part of its own estimate there on the unsafe side or "
                       "than the most a coarser mesh from the scene's judged it worse, whichever is more")
