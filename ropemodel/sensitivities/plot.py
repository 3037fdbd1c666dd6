"""Tornado charts of elasticities (matplotlib, imported only when plotting)."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ropemodel.errors import require
from ropemodel.units import label

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure


def plot_formats() -> tuple[str, ...]:
    """The file suffixes matplotlib can write (``.png``, ``.pdf``, ``.svg``, ...)."""
    require("matplotlib", "plots")
    from matplotlib.backend_bases import FigureCanvasBase

    return tuple(f".{k}" for k in sorted(FigureCanvasBase.get_supported_filetypes()))


def check_plot(path):
    """``path`` as a Path, or :class:`InputError` before any work if a chart cannot be written there
    (a directory, a missing directory, under a file, a suffix matplotlib cannot write)."""
    from ropemodel.sweeps.files import check_output

    return check_output(path, plot_formats())


#: panels per row of a tornado chart, and the chart's width [in]: an A4 page's text width at 120 dpi
COLUMNS = 3
WIDTH = 12.0


def influence(frame, outputs=None) -> list[str]:
    """Outputs ordered by their largest defined |elasticity|, most influenced first (ties: frame order)."""
    outputs = list(dict.fromkeys(frame["output"])) if outputs is None else list(outputs)
    defined = frame[frame["defined"]]
    top = {o: float(np.abs(defined.loc[defined["output"] == o, "elasticity"].to_numpy()).max(initial=0.0))
           for o in outputs}
    return sorted(outputs, key=lambda o: -top[o])


def tornado(frame: pd.DataFrame, outputs: Sequence[str] | None = None, path: str | os.PathLike | None = None,
            title: str | None = None, top: int | None = None, columns: int = COLUMNS) -> Figure:
    """Tornado chart of elasticities: one panel per output, bars of ∂ln y/∂ln p, largest on top.

    Parameters
    ----------
    frame : pandas.DataFrame
        :func:`ropemodel.sensitivities.elasticities` output; undefined elasticities are left out.
    outputs : list of str, optional
        Outputs to draw (default: all), laid out on a grid of ``columns`` panels per row, the most
        influenced output (the largest elasticity in absolute value) first, so the chart keeps a page's width
        (:data:`WIDTH` in) however many outputs it has.
    path : str or Path, optional
        Save the chart there (``.png``, ``.svg``, ``.pdf``, ... — checked by :func:`check_plot`
        before drawing, written atomically).
    title : str, optional
        The figure's title.
    top : int, optional
        Only the ``top`` most influential parameters of each output.
    columns : int
        Panels per row (1 to 6).

    Returns
    -------
    matplotlib.figure.Figure
        The chart (closed when saved to ``path``).

    Raises
    ------
    InputError
        ``path`` cannot be written (a directory, a missing directory, a suffix matplotlib cannot
        write), ``columns`` outside 1 to 6, or the ``plots`` extra (matplotlib) is missing.
    OutputError
        The file could not be written.

    Examples
    --------
    >>> import ropemodel as rm
    >>> e = rm.elasticities(rm.load_scene(), outputs=["F_C_up", "F_S_up", "dF_up", "F_C_down"])
    >>> fig = rm.tornado(e, columns=2)
    >>> [ax.get_title() for ax in fig.axes]     # most influenced first (largest |elasticity| 1.11, 1.0, ...)
    ['F_C_down [kN]', 'dF_up [mm]', 'F_S_up [kN]', 'F_C_up [kN]']
    >>> [round(float(x), 1) for x in fig.get_size_inches()]     # two panels a row, two rows [in]
    [8.0, 9.4]
    """
    from ropemodel.errors import InputError

    if not (isinstance(columns, int) and 1 <= columns <= 6):
        raise InputError(f"columns = {columns!r}: give a whole number of panels per row, 1 to 6")
    checked = check_plot(path) if path is not None else None
    matplotlib = require("matplotlib", "plots")
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    outputs = influence(frame, outputs)
    ncol = min(columns, max(1, len(outputs)))
    nrow = -(-len(outputs) // ncol)
    height = 0.3 * frame["parameter"].nunique() + 1.4
    fig, axes = plt.subplots(nrow, ncol, figsize=(min(WIDTH, 4.0 * ncol), height * nrow), squeeze=False)
    for ax, out in zip(axes.flat, outputs):
        _panel(ax, frame, out, top)
    for ax in list(axes.flat)[len(outputs):]:
        ax.set_visible(False)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    if checked is not None:
        _save(fig, checked)
        plt.close(fig)
    return fig


def _panel(ax, frame, out: str, top: int | None) -> None:
    rows = frame[(frame["output"] == out) & frame["defined"]]
    rows = rows[rows["elasticity"] != 0.0]
    rows = rows.reindex(rows["elasticity"].abs().sort_values().index)
    if top:
        rows = rows.tail(top)
    e = rows["elasticity"].to_numpy()
    ax.barh(rows["parameter"], e, color=np.where(e >= 0, "#c0392b", "#2471a3"))
    ax.axvline(0.0, color="k", lw=0.8)
    unit = frame.loc[frame["output"] == out, "y_unit"].iloc[0]
    ax.set_title(label(out, unit), fontsize=10)
    ax.set_xlabel("elasticity ∂ln y/∂ln p  (% per %)", fontsize=8)
    for y, v in enumerate(e):
        ax.annotate(f"{v:+.3g}", (v, y), xytext=(3 if v >= 0 else -3, 0), textcoords="offset points",
                    ha="left" if v >= 0 else "right", va="center", fontsize=8)
    lim = max(1e-9, float(np.abs(e).max(initial=0.0))) * 1.35
    ax.set_xlim(-lim, lim)


def _save(fig, path) -> None:
    from ropemodel.sweeps.files import OutputError, write_atomic

    def write(tmp):
        fig.savefig(tmp, dpi=120, format=path.suffix[1:].lower())

    try:
        write_atomic(path, write)
    except (OSError, ValueError, RuntimeError) as exc:  # matplotlib's writers raise several kinds
        raise OutputError(f"cannot write {path}: {getattr(exc, 'strerror', None) or exc}; nothing was written") \
            from None
