"""Pictures of a report: matplotlib figures as SVG ``data:`` URIs (vector, self-contained, no fonts).

Text is drawn as paths (``svg.fonttype = "path"``), so the picture needs no font on the reader's
machine; the SVG's document type line (a DTD address) and metadata are left out, so the picture
refers to nothing outside itself.  Figures are sized for an A4 page (:data:`WIDTH` inches).
"""

from __future__ import annotations

import base64
import io
import re
import sys

import numpy as np

from ropemodel.errors import require

#: width of a full-width picture [in] (A4 less margins, at 100 %)
WIDTH = 7.0
_RC = {"svg.fonttype": "path", "svg.hashsalt": "ropemodel-report", "font.size": 9.0}
_UNIT = re.compile(r"^(?P<name>.*?) \[(?P<unit>[^\]]*)\]$")
#: SI unit of a history column → (unit shown, factor)
SHOWN = {"N": ("kN", 1e-3), "m/s": ("m/s", 1.0), "m": ("m", 1.0), "W": ("kW", 1e-3), "J": ("kJ", 1e-3)}


def new_figure(width: float = WIDTH, height: float = 3.0):
    """A matplotlib Figure not registered with pyplot (nothing global to close)."""
    require("matplotlib", "report")
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def svg_uri(fig) -> str:
    """The figure as an SVG ``data:`` URI; the figure is closed if pyplot knows it."""
    import matplotlib

    buf = io.BytesIO()
    with matplotlib.rc_context(_RC):
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None, "Format": None, "Type": None})
    if "matplotlib.pyplot" in sys.modules:   # a figure made through pyplot (the tornado chart) is released
        sys.modules["matplotlib.pyplot"].close(fig)
    text = buf.getvalue().decode("utf-8")
    text = re.sub(r"<!DOCTYPE[^>]*>", "", text, count=1)
    return "data:image/svg+xml;base64," + base64.b64encode(text.encode("utf-8")).decode("ascii")


def columns_by_unit(frame) -> dict[str, list[str]]:
    """Numeric columns named ``"name [unit]"``, grouped by unit (in order of first appearance)."""
    groups: dict[str, list[str]] = {}
    for col in frame.columns:
        m = _UNIT.match(str(col))
        if m and np.issubdtype(frame[col].dtype, np.number):
            groups.setdefault(m["unit"], []).append(col)
    return groups


def panels(frame, x: str, units, title: str = "", height: float = 2.1):
    """One panel per unit in ``units`` (present in ``frame``), every column of that unit against ``x``;
    SI units shown as :data:`SHOWN` says (N as kN).  Returns the SVG data URI, or None if nothing to plot."""
    groups = columns_by_unit(frame)
    units = [u for u in units if u in groups and any(c != x for c in groups[u])]
    if not units:
        return None
    fig = new_figure(WIDTH, height * len(units) + 0.4)
    axes = fig.subplots(len(units), 1, sharex=True, squeeze=False)[:, 0]
    xs = frame[x].to_numpy(dtype=float)
    for ax, unit in zip(axes, units):
        shown, f = SHOWN.get(unit, (unit, 1.0))
        for col in groups[unit]:
            if col != x:
                m = _UNIT.match(col)         # every grouped column matches
                ax.plot(xs, frame[col].to_numpy(dtype=float) * f, lw=1.2, label=m["name"] if m else col)
        ax.set_ylabel(f"[{shown}]")
        ax.grid(True, lw=0.4, alpha=0.6)
        ax.legend(fontsize=7.5, loc="best", ncols=min(4, len(groups[unit])))
    axes[-1].set_xlabel(x)
    if title:
        fig.suptitle(title, fontsize=10)
    return svg_uri(fig)


def tornado(frame, output: str, top: int = 8, width: float = WIDTH / 2):
    """A tornado chart of ``output``'s elasticities (its ``top`` largest), as an SVG data URI, or None when
    no elasticity of it is defined and nonzero.  Drawn by :func:`ropemodel.sensitivities.tornado`, resized
    to ``width`` inches."""
    from ropemodel.sensitivities import tornado as draw

    rows = frame[(frame["output"] == output) & frame["defined"] & (frame["elasticity"] != 0.0)]
    if rows.empty:
        return None
    keep = rows.reindex(rows["elasticity"].abs().sort_values(ascending=False).index).head(top)
    fig = draw(keep, [output])
    fig.set_size_inches(width, 0.3 * len(keep) + 1.3)
    fig.tight_layout()
    return svg_uri(fig)
