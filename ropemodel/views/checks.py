"""The checks of dynamic sizing in the user's words: what ``ropemodel size --dynamic`` prints and the report's
"dynamic sizing" section shows.

The internal names of the checks (``safety_margin_S``, ``slip_margin_fwd @ upward start``, ``tension_margin[8]``)
are the keys of ``--json`` and stay there.  :data:`MANOEUVRE_WORDS` and :data:`STATIC_WORDS` are the one place
that says what each name means to a designer; :func:`check_groups` builds the checks table from a dynamic
design's attributes (``manoeuvres``, ``margins``, ``scene``): one group per manoeuvre (upward start, upward
stop, downward start, downward stop, as :mod:`optimisation.dynamic.manoeuvres` names them) and one for the
static checks of steady travel, each row the value the check judges and its limit with their units, the margin,
the instant (s) and where the load is.  :func:`readable` turns any one name into words (the active
constraints), :func:`in_words` every name in a message (no design), and :func:`factors` says which factor
each check applies and its rule; :func:`check_words` says what a check through a manoeuvre compares (the drum's
grip with the dynamic slip factor ``n_slip_dynamic`` where the scene carries it) and :func:`mesh_text` what the
mesh control did (the rope's elements per span, the largest error estimate and its back-off).  The layer sits
low: it reads only the attributes and dictionaries it is given.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass
from typing import NamedTuple


class Words(NamedTuple):
    """A check in words: ``text`` (what it compares, with its rule's symbols), ``group`` (checks of one group
    share a row in the short table: the least margin of them shows) and ``kind`` (the margin's form:
    ``"ratio"`` a fraction shown in %, ``"force"`` in kN, ``"length"`` in mm)."""

    text: str
    group: str
    kind: str


#: the checks through a manoeuvre (:data:`ropemodel.machines.winch.manoeuvres.CHECKS`)
MANOEUVRE_WORDS = {
    "safety_margin": Words("rope force F_C <= F_min/n_rope", "rope force", "ratio"),
    "safety_margin_S": Words("rope force F_S <= F_min/n_rope", "rope force", "ratio"),
    "slip_margin_fwd": Words("drum grip F_S >= F_C/rho", "grip", "force"),
    "slip_margin_back": Words("drum grip F_C >= F_S/rho", "grip", "force"),
    "slack_margin": Words("unwinding rope F_S >= F_S_min", "taut", "force"),
    "taut_margin": Words("winding rope F_C >= F_S_min", "taut", "force"),
    "tension_margin": Words("every rope element T >= 0", "elements", "force"),
    "stroke_margin": Words("take-up z <= stroke", "stroke", "length"),
    "stroke_start_margin": Words("take-up z >= 0 (start stop)", "stroke", "length"),
}
#: the manoeuvres' grip checks in words where the design carries a dynamic slip factor ``n_slip_dynamic``
WITH_DYNAMIC_SLIP = {"slip_margin_fwd": "drum grip F_S >= n_slip_dynamic F_C/rho",
                     "slip_margin_back": "drum grip F_C >= n_slip_dynamic F_S/rho"}
#: the static checks of steady travel (each per direction, ``_up``/``_down``; on a route ``@ place``)
STATIC_WORDS = {
    "safety_margin": Words("rope force F_C <= F_min/n_rope", "rope force", "ratio"),
    "slip_margin": Words("drum grip with n_slip", "grip", "ratio"),
    "slack_margin": Words("unwinding rope F_S >= F_S_min", "taut", "force"),
    "taut_margin": Words("winding rope F_C >= F_S_min", "taut", "force"),
    "route_margin": Words("rope on the route >= F_S_min", "taut", "force"),
    "sheave_margin": Words("return sheave F_nwl/2 >= F_S_min", "taut", "force"),
    "stroke_margin": Words("take-up dF <= stroke", "stroke", "length"),
    "drum_margin": Words("drum D >= D_ratio_min d", "drum", "ratio"),
}
STEADY = "steady travel (static forces, both directions)"
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


def _least(rows: list[tuple[float, str, Row]], merged: bool) -> list[Row]:
    """The rows of (margin, group, row), or (``merged``) one per group: the least margin of the group (the
    margins of a group share their form), standing for every name of it."""
    if not merged:
        return [r for _, _, r in rows]
    groups: dict[str, list[tuple[float, Row]]] = {}
    for margin, group, r in rows:
        groups.setdefault(group, []).append((margin, r))
    return [dataclasses.replace(min(members, key=lambda m: m[0])[1], names=tuple(n for _, r in members
                                                                                  for n in r.names))
            for members in groups.values()]


def check_words(name: str, parameters=None) -> str:
    """What the check through a manoeuvre ``name`` compares, in words; the grip checks with the dynamic slip
    factor where ``parameters`` (the scene's) carry ``n_slip_dynamic`` (:data:`WITH_DYNAMIC_SLIP`)."""
    if "n_slip_dynamic" in (parameters or {}) and name in WITH_DYNAMIC_SLIP:
        return WITH_DYNAMIC_SLIP[name]
    return MANOEUVRE_WORDS[name].text


def manoeuvre_rows(manoeuvre: dict, merged: bool = True, parameters=None) -> list[Row]:
    """The rows of one manoeuvre (an entry of ``DynamicDesign.manoeuvres``): each check's least margin over
    every place of the load, at its instant and place, with the value and limit it compares there
    (``parameters``: the scene's; with ``n_slip_dynamic`` the grip checks say so, :data:`WITH_DYNAMIC_SLIP`)."""
    rows = []
    for name, least in manoeuvre["least_margins"].items():
        words = MANOEUVRE_WORDS[name]._replace(text=check_words(name, parameters))
        kind = "length" if words.kind == "length" else "force"
        value = _quantity(kind, least["value"]) if "value" in least else ""
        limit = _quantity(kind, least["limit"]) if "limit" in least else ""
        row = Row(words.text, value, limit, _margin(words.kind, least["margin"]), f"{least['t']:.4g} s",
                  least["where"], least["margin"] >= -1e-9, (f"{name} @ {manoeuvre['manoeuvre']}",))
        rows.append((least["margin"], words.group, row))
    return _least(rows, merged)


def static_rows(margins: dict, merged: bool = True) -> list[Row]:
    """The rows of the static checks ``margins`` (check name → margin, SI), each in words with the direction
    of travel and the place where it is least."""
    rows = []
    for name, margin in margins.items():
        m = _STATIC.match(name)
        if m is None:
            raise KeyError(f"{name!r} is not a static check's name")
        words = STATIC_WORDS[m["base"]]
        where = ", ".join(w for w in (f"{_DIRECTION[m['dir']]} travel" if m["dir"] else "", m["place"]) if w)
        rows.append((margin, words.group, Row(words.text, "", "", _margin(words.kind, margin), "", where,
                                              margin >= -1e-9, (name,))))
    return _least(rows, merged)


def is_static(name: str) -> bool:
    """Whether ``name`` (a key of ``DynamicDesign.margins``) is a static check, not one through a manoeuvre."""
    return " @ " not in name or name.split(" @ ")[0] not in MANOEUVRE_WORDS


def check_groups(design, merged: bool = True) -> list[tuple[str, list[Row]]]:
    """The checks table of a dynamic design: (title, rows) for each manoeuvre in the order the design holds
    them, then steady travel's static checks.  ``merged``: one row per group of checks (the short table of
    the terminal), else one per check (the report)."""
    out = [(m["manoeuvre"], manoeuvre_rows(m, merged, design.scene.parameters)) for m in design.manoeuvres]
    static = {k: v for k, v in design.margins.items() if is_static(k)}
    if static:
        out.append((STEADY, static_rows(static, merged)))
    return out


def readable(name: str, parameters=None) -> str:
    """A check's internal name in words: ``slip_margin_fwd @ upward start, x_m = 575 m, t = 1.97 s`` →
    ``drum grip F_S >= F_C/rho (upward start, x_m = 575 m, t = 1.97 s)`` (``parameters``: the scene's, for the
    dynamic slip factor, :func:`check_words`); ``stroke_margin_up`` → ``take-up dF <= stroke (steady upward
    travel)``; anything else (a bound, the catalogue size) as it is."""
    m = _DYNAMIC.match(name)
    if m and m["base"] in MANOEUVRE_WORDS:
        return f"{check_words(m['base'], parameters)} ({m['rest']})"
    m = _STATIC.match(name)
    if m and m["base"] in STATIC_WORDS:
        where = ", ".join(w for w in (f"steady {_DIRECTION[m['dir']]} travel" if m["dir"] else "steady travel",
                                      m["place"]) if w)
        return f"{STATIC_WORDS[m['base']].text} ({where})"
    return name


def in_words(text: str, parameters=None) -> str:
    """``text`` (a message) with every check's internal name in it put in words (:func:`readable` of the name
    alone: ``slip_margin_fwd @ upward start`` → ``drum grip F_S >= F_C/rho @ upward start``)."""
    def words(m) -> str:
        base = m[0].split("[")[0]
        if base in MANOEUVRE_WORDS:
            return check_words(base, parameters)
        return readable(base).replace(" (steady travel)", "")

    return _NAME.sub(words, text)


def factors(scene) -> list[str]:
    """Which factor each check applies, with its rule (``scene.check_basis``): the rope's n_rope, steady
    travel's slip factor n_slip, and in the manoeuvres the dynamic slip factor ``n_slip_dynamic`` when the
    scene carries one, else none (the drum holds while rho F_S >= F_C)."""
    values = scene.parameters
    out = []
    for name, check, where in (("n_rope", "safety_margin", "rope force, every manoeuvre and steady travel"),
                               ("n_slip", "slip_margin", "drum grip in steady travel")):
        if name in values:
            out.append(f"{name} = {values[name]:g} ({where}): {scene.check_basis(check).split(': ', 1)[-1]}")
    if "n_slip_dynamic" in values:
        basis = scene.check_basis("slip_margin_fwd")
        basis = basis.split(": ", 1)[-1] if basis != "-" else scene.basis("n_slip_dynamic")
        out.append(f"n_slip_dynamic = {values['n_slip_dynamic']:g} (drum grip in the manoeuvres, rho F_S(t) >= "
                   f"n_slip_dynamic F_C(t) at every instant): {basis}")
    else:
        out.append("drum grip in the manoeuvres: no slip factor (the drum holds while rho F_S >= F_C at every "
                   "instant)")
    return out


#: what a force check's discretisation error is an error of, where that is not the margin the table shows
#: (the rope's safety: the NLP's F_min - n_rope F, n_rope times the force's own error)
CONSTRAINT_WORDS = {"safety_margin": "of F_min - n_rope F_C", "safety_margin_S": "of F_min - n_rope F_S"}


def mesh_text(mesh: dict, parameters=None) -> str:
    """What dynamic sizing's mesh control did (``DynamicDesign.mesh``), in words and kN: the rope's elements
    per span, the tolerance, the largest estimate of a force check's discretisation error, the part of it on
    the unsafe side and the check's back-off ("" without a mesh to refine)."""
    if not mesh.get("segments"):
        return ""
    forces = {c: e for c, e in mesh["errors"].items() if mesh["units"][c] == "N"}
    text = (f"rope mesh: {mesh['segments']} elements per span (from the scene's {mesh['segments_scene']}, doubled "
            f"while Richardson's estimate of a force check's discretisation error exceeded mesh_tol = "
            f"{mesh['tolerance'] * 1e-3:g} kN)")
    if forces:
        worst = max(forces, key=lambda c: forces[c])
        of = f" {CONSTRAINT_WORDS[worst]}" if worst in CONSTRAINT_WORDS else ""
        text += (f"; the largest estimate {forces[worst] * 1e-3:.3g} kN{of}, {check_words(worst, parameters)}, "
                 f"{mesh['unsafe'][worst] * 1e-3:.3g} kN of it on the unsafe side, backed off by "
                 f"{mesh['backoffs'][worst] * 1e-3:.3g} kN")
    return text + ("; each check through a manoeuvre is backed off by a little more than the part of its own "
                   "estimate on the unsafe side")
