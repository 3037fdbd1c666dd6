"""The HTML of a report: a Jinja2 environment with autoescaping, the page, and helpers for sections.

Everything a section takes from a scene (names, file paths, warnings) is text and is escaped; a
section's own markup is built with :func:`fragment` (a Jinja2 template, autoescaped) or the helpers
below, which return :class:`markupsafe.Markup`.  The page is self-contained: styles inline, no
script, no font to fetch, pictures as ``data:`` URIs (:mod:`ropemodel.reports.figures`).
"""

from __future__ import annotations

import functools
import math
import re

from ropemodel.errors import require

STYLE = """
body { font-family: "DejaVu Sans", "Liberation Sans", Arial, Helvetica, sans-serif; font-size: 10pt;
       color: #111; max-width: 60rem; margin: 1.5rem auto; padding: 0 1rem; line-height: 1.35; }
h1 { font-size: 17pt; margin: 0 0 .3rem; }
h2 { font-size: 13pt; border-bottom: 2px solid #234; padding-bottom: .15rem; margin-top: 1.6rem;
     break-after: avoid; }
h3 { font-size: 11pt; margin: 1rem 0 .3rem; break-after: avoid; }
table { border-collapse: collapse; margin: .4rem 0 .8rem; font-size: 9pt; }
th, td { border: 1px solid #bbb; padding: .15rem .45rem; text-align: left; vertical-align: top; }
thead th { background: #e8edf2; }
tr { break-inside: avoid; }
td.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
code, .name { font-family: "DejaVu Sans Mono", "Liberation Mono", monospace; font-size: 8.5pt; }
.pass { background: #e3f4e6; } .fail { background: #fde2e2; }
tr.pass td:last-child, p.pass { color: #14532d; font-weight: bold; }
tr.fail td:last-child, tr.fail td:first-child, p.fail { color: #8b1111; font-weight: bold; }
.verdict { padding: .35rem .6rem; margin: .4rem 0; border-left: 5px solid; }
.verdict.pass { border-color: #2e7d32; } .verdict.fail { border-color: #c62828; }
.error { background: #fff3cd; border-left: 5px solid #b7791f; padding: .4rem .6rem; white-space: pre-wrap; }
.note { color: #444; font-size: 9pt; }
.formula { font-family: "DejaVu Serif", "Liberation Serif", "Times New Roman", serif; font-size: 10.5pt; }
.eq { display: grid; grid-template-columns: 1fr auto; column-gap: 1rem; margin: .25rem 0 .1rem;
      break-inside: avoid; }
.eqno { color: #333; max-width: 20rem; text-align: right; }
.cases { display: inline-grid; grid-template-columns: auto auto; column-gap: .8rem; vertical-align: middle;
         border-left: 2px solid #333; border-radius: 6px 0 0 6px; padding-left: .4rem; }
.numbers { margin: 0 0 .5rem 1.2rem; font-size: 8.5pt; color: #333; }
pre { background: #f6f8fa; padding: .5rem; font-size: 8.5pt; white-space: pre-wrap; break-inside: avoid; }
figure { margin: .5rem 0 1rem; break-inside: avoid; }
figure img { max-width: 100%; height: auto; }
figcaption { font-size: 9pt; color: #333; }
.figures { display: grid; grid-template-columns: repeat(auto-fit, minmax(19rem, 1fr)); column-gap: 1rem; }
nav ol { columns: 2; font-size: 9.5pt; }
a { color: #1d4e89; }
dl.head { display: grid; grid-template-columns: max-content 1fr; column-gap: 1rem; row-gap: .1rem; }
dl.head dt { font-weight: bold; } dl.head dd { margin: 0; word-break: break-all; }
@media print { body { max-width: none; margin: 0; padding: 0; } }
table.signoff td { height: 2.2rem; min-width: 9rem; } table.signoff td:first-child { font-weight: bold; }
"""

#: the printed page: A4, a running header (document and revision left, title right) and footer (the scene's
#: file and digest left, the page number right), in CSS paged media (Chromium prints the margin boxes)
PAGE_RULE = """@page { size: A4; margin: 18mm 12mm 16mm 12mm;
  @top-left { content: "{{ left }}"; font-size: 8pt; color: #555; }
  @top-right { content: "{{ right }}"; font-size: 8pt; color: #555; }
  @bottom-left { content: "{{ foot }}"; font-size: 7pt; color: #777; }
  @bottom-right { content: "page " counter(page) " of " counter(pages); font-size: 8pt; color: #555; } }"""
#: characters a CSS string keeps as they are; every other is written as a CSS escape
_CSS_PLAIN = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 .,-_:;()/#+=")

PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{{ title }}</title>
<style>{{ style | safe }}
{{ rule | safe }}</style>
</head>
<body>
<h1>{{ title }}</h1>
<p class="note">Calculation report made by ropemodel {{ version }} on {{ date }}.</p>
<nav><ol>{% for s in sections %}<li><a href="#{{ s.name }}">{{ s.title }}</a></li>{% endfor %}</ol></nav>
{% for s in sections %}
<section id="{{ s.name }}">
<h2>{{ loop.index }}. {{ s.title }}</h2>
{{ s.html }}
</section>
{% endfor %}
</body>
</html>
"""


@functools.cache
def environment():
    """The Jinja2 environment of every report template (autoescaping on)."""
    jinja2 = require("jinja2", "report")
    env = jinja2.Environment(autoescape=True, undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True)
    env.filters["typeset"] = typeset
    env.filters["formula"] = formula
    return env


@functools.cache
def _template(text: str):
    return environment().from_string(text)


def fragment(template: str, **values):
    """``template`` (Jinja2 text) rendered with ``values``, escaped, as Markup."""
    from markupsafe import Markup

    return Markup(_template(template).render(**values))


def markup(html: str):
    """``html`` (a section's own markup) marked as safe: inserted into the page as it is."""
    from markupsafe import Markup

    return Markup(html)


def escape(text):
    from markupsafe import escape as _escape

    return _escape(text)


TABLE = """<table{% if cls %} class="{{ cls }}"{% endif %}>
<thead><tr>{% for h in head %}<th>{{ h }}</th>{% endfor %}</tr></thead>
<tbody>
{% for row in rows %}
<tr{% if row_class and row_class[loop.index0] %} class="{{ row_class[loop.index0] }}"{% endif %}>
{% for cell in row %}
<td{% if kinds[loop.index0] %} class="{{ kinds[loop.index0] }}"{% endif %}>{{ cell }}</td>
{% endfor %}
</tr>
{% endfor %}
</tbody>
</table>"""


def table(head, rows, kinds=None, row_class=None, cls: str = ""):
    """A table: ``head`` the column titles, ``rows`` lists of cells (text is escaped; Markup is kept);
    ``kinds`` one CSS class per column (``"num"`` right-aligns, ``"name"`` a symbol); ``row_class`` one
    class per row (``"pass"``/``"fail"``)."""
    head = list(head)
    return fragment(TABLE, head=head, rows=[list(r) for r in rows], kinds=list(kinds or [""] * len(head)),
                    row_class=list(row_class) if row_class is not None else None, cls=cls)


def show(q, value) -> str:
    """``value`` (SI) in the quantity's display unit, as :meth:`ropemodel.quantity.Quantity.show` writes it;
    a value that is not a finite number says so; a signed quantity says what its sign means
    (``"-243.584 kW (braking)"``)."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "not computed"
    sign = q.sign_text(float(value))
    return q.show(float(value)) + (f" ({sign})" if sign else "")


def error(message: str):
    """A box saying what could not be computed and why."""
    return fragment('<div class="error">{{ m }}</div>', m=message)


def verdict(ok: bool, text: str):
    """A highlighted line: passed (green) or failed (red)."""
    return fragment('<p class="verdict {{ c }}">{{ t }}</p>', c="pass" if ok else "fail", t=text)


_SUB = re.compile(r"(?<=[A-Za-zΑ-ω′)])_([A-Za-z0-9Α-ω]+(?:,[A-Za-z0-9Α-ω]+)?)")


def _superscripts(text: str) -> str:
    """``^(...)`` (balanced) and ``^x`` as <sup>; ``text`` already escaped."""
    out, i = [], 0
    while i < len(text):
        if text.startswith("^(", i):
            depth, j = 0, i + 1
            while j < len(text):
                depth += {"(": 1, ")": -1}.get(text[j], 0)
                if depth == 0:
                    break
                j += 1
            out.append(f"<sup>{_superscripts(text[i + 2:j])}</sup>")
            i = j + 1
        elif text[i] == "^" and i + 1 < len(text):
            m = re.match(r"[A-Za-z0-9_]+", text[i + 1:])
            word = m.group(0) if m else text[i + 1]
            out.append(f"<sup>{word}</sup>")
            i += 1 + len(word)
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def typeset(formula: str):
    """A plain-Unicode formula (``"F_C = 0.5 F_nwl + G_lmC"``, ``"e^(μ_d α_d)"``) as HTML with sub- and
    superscripts: F<sub>C</sub> = 0.5 F<sub>nwl</sub> …  The text is escaped first."""
    from markupsafe import Markup

    text = str(escape(formula))
    text = _superscripts(text)
    return Markup(_SUB.sub(lambda m: f"<sub>{m.group(1)}</sub>", text))


def _split(text: str, sep: str) -> list[str]:
    """``text`` split at ``sep`` where no bracket is open."""
    parts, depth, start, i = [], 0, 0, 0
    while i < len(text):
        c = text[i]
        depth += (c in "({[") - (c in ")}]")
        if depth == 0 and text.startswith(sep, i):
            parts.append(text[start:i])
            start = i = i + len(sep)
            continue
        i += 1
    return parts + [text[start:]]


def _closing(text: str) -> int:
    """The index of the bracket that closes ``text[0]``'s (-1 if none)."""
    depth = 0
    for i, c in enumerate(text):
        depth += (c in "({[") - (c in ")}]")
        if depth == 0:
            return i
    return -1


def formula(text: str):
    """A formula as HTML (:func:`typeset`); ``y = {a if c; b otherwise}`` (:mod:`ropemodel.core.infix`'s
    choice of cases) laid out as stacked cases."""
    from markupsafe import Markup

    left, eq, right = text.partition(" = ")
    braced = eq and right.startswith("{") and _closing(right) == len(right) - 1
    cases = _split(right[1:-1], "; ") if braced else []
    if len(cases) < 2:
        return typeset(text)
    rows = []
    for case in cases:
        parts = _split(case, " if ") if not case.endswith(" otherwise") else [case[:-10], "otherwise"]
        value, cond = " if ".join(parts[:-1]) or parts[-1], parts[-1]
        rows.append(f"<span>{typeset(value)}</span><span>{'if ' + typeset(cond) if cond != 'otherwise' else cond}"
                    "</span>")
    return Markup(f'{typeset(left)} = <span class="cases">{"".join(rows)}</span>')


def css_string(text: str) -> str:
    """``text`` as the inside of a CSS string: quotes, backslashes, ``<`` and every other character not plainly
    safe written as CSS escapes (``\\3c ``), so no text can end the string or the style element."""
    return "".join(c if c in _CSS_PLAIN else f"\\{ord(c):x} " for c in " ".join(str(text).split()))


def page(title: str, version: str, date: str, sections, header: tuple[str, str, str] = ("", "", "")) -> str:
    """The whole page: ``sections`` a list of (name, title, html); ``header`` the printed page's running header
    (left, right) and footer (left) texts."""
    items = [{"name": n, "title": t, "html": h} for n, t, h in sections]
    left, right, foot = (css_string(x) for x in header)
    rule = _template(PAGE_RULE).render(left=left, right=right, foot=foot)
    return _template(PAGE).render(title=title, version=version, date=date, style=STYLE, rule=rule, sections=items)
