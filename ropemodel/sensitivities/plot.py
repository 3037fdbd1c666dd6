"""Tornado charts of elasticities (matplotlib, imported only when plotting)."""

from __future__ import annotations

import numpy as np

from ropemodel.errors import require
from ropemodel.units import label


def plot_formats() -> tuple[str, ...]:
    """The file suffixes matplotlib can write (``.png``, ``.pdf``, ``.svg``, ...)."""
    require("matplotlib", "plots")
    from matplotlib.backend_bases import FigureCanvasBase

    return tuple(f".{k}" for k in sorted(FigureCanvasBase.get_supported_filetypes()))


def check_plot(path):
    """``path`` as a Path, or :class:`InputError` before any work if a chart cannot be written there
    (a directory, a missing directory, under a file, a suffix matplotlib cannot write)."""
    from ropemodel.sweep.files import check_output

    return check_output(path, plot_formats())


def tornado(frame, outputs=None, path=None, title: str | None = None, top: int | None = None):
    """One panel per output: bars of ∂ln y/∂ln p, largest magnitude on top; undefined ones left out.

    frame: :func:`ropemodel.sensitivity.elasticities` output.  Returns the matplotlib Figure
    (saved to ``path`` when given: checked by :func:`check_plot`, written atomically;
    :class:`~ropemodel.sweep.files.OutputError` if it cannot be).
    """
    matplotlib = require("matplotlib", "plots")
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    outputs = list(dict.fromkeys(frame["output"])) if outputs is None else list(outputs)
    fig, axes = plt.subplots(1, len(outputs), figsize=(4.2 * len(outputs), 0.35 * frame["parameter"].nunique() + 1.6),
                             squeeze=False)
    for ax, out in zip(axes[0], outputs):
        rows = frame[(frame["output"] == out) & frame["defined"]]
        rows = rows[rows["elasticity"] != 0.0]
        rows = rows.reindex(rows["elasticity"].abs().sort_values().index)
        if top:
            rows = rows.tail(top)
        e = rows["elasticity"].to_numpy()
        colors = np.where(e >= 0, "#c0392b", "#2471a3")
        ax.barh(rows["parameter"], e, color=colors)
        ax.axvline(0.0, color="k", lw=0.8)
        unit = frame.loc[frame["output"] == out, "y_unit"].iloc[0]
        ax.set_title(label(out, unit), fontsize=10)
        ax.set_xlabel("elasticity ∂ln y/∂ln p  (% per %)")
        for y, v in enumerate(e):
            ax.annotate(f"{v:+.3g}", (v, y), xytext=(3 if v >= 0 else -3, 0), textcoords="offset points",
                        ha="left" if v >= 0 else "right", va="center", fontsize=8)
        lim = max(1e-9, float(np.abs(e).max(initial=0.0))) * 1.35
        ax.set_xlim(-lim, lim)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    if path is not None:
        _save(fig, check_plot(path))
        plt.close(fig)
    return fig


def _save(fig, path) -> None:
    from ropemodel.sweep.files import OutputError, write_atomic

    def write(tmp):
        fig.savefig(tmp, dpi=120, format=path.suffix[1:].lower())

    try:
        write_atomic(path, write)
    except (OSError, ValueError, RuntimeError) as exc:  # matplotlib's writers raise several kinds
        raise OutputError(f"cannot write {path}: {getattr(exc, 'strerror', None) or exc}; nothing was written") \
            from None
