"""HTML tables for Jupyter's ``_repr_html_``: a title, then tables of names, values and their units.

Values are printed to 6 significant digits, as the text tables of the command line print them; a
number that is infinite because an input is unlimited reads ``unlimited``.  Everything is escaped.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from html import escape

#: inline style, so the table reads the same in Jupyter, VS Code and a static page
STYLE = ("<style>.ropemodel table{border-collapse:collapse;margin:0.3em 0 0.8em 0}"
         ".ropemodel th,.ropemodel td{padding:0.15em 0.7em;text-align:left}"
         ".ropemodel td.num{text-align:right;font-variant-numeric:tabular-nums}"
         ".ropemodel caption{text-align:left;font-weight:bold;padding:0.2em 0}"
         ".ropemodel .fail{color:#b00020;font-weight:bold}</style>")


def number(value, unlimited: str = "unlimited") -> str:
    """``value`` to 6 significant digits; ``unlimited`` for +inf, ``-`` for None or NaN."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, (int, float)):
        return unlimited if value == math.inf else f"{value + 0.0:.6g}"     # + 0.0: no "-0"
    return str(value)


def unit_text(unit: str) -> str:
    """The unit as a table shows it: ``-`` for a pure number."""
    return "-" if unit in ("", "1") else unit


def table(header: Sequence[str], rows: Iterable[Sequence], caption: str = "",
          numeric: Iterable[int] = (1,)) -> str:
    """One ``<table>``: ``header`` cells, then ``rows`` (cells already formatted, or numbers: see
    :func:`number`); columns in ``numeric`` are right-aligned.  A cell given as ``("FAIL", "fail")``
    carries a CSS class."""
    numeric = set(numeric)
    out = ["<table>"]
    if caption:
        out.append(f"<caption>{escape(caption)}</caption>")
    out.append("<thead><tr>" + "".join(f"<th>{escape(h)}</th>" for h in header) + "</tr></thead><tbody>")
    for row in rows:
        cells = []
        for i, cell in enumerate(row):
            cls = ["num"] if i in numeric else []
            if isinstance(cell, tuple):
                cell, extra = cell
                cls.append(extra)
            attr = f' class="{" ".join(cls)}"' if cls else ""
            cells.append(f"<td{attr}>{escape(number(cell))}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def page(title: str, *parts: str, notes: Iterable[str] = ()) -> str:
    """The whole ``_repr_html_``: a title line, the tables, then notes (one paragraph each)."""
    body = [STYLE, '<div class="ropemodel">', f"<p><strong>{escape(title)}</strong></p>", *parts]
    body += [f"<p>{escape(n)}</p>" for n in notes if n]
    return "".join(body + ["</div>"])
