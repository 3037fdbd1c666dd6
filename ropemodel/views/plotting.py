"""matplotlib, imported only when a picture is drawn (the ``plots`` extra)."""

from __future__ import annotations

from typing import Any


def axes(ax: Any = None) -> Any:
    """``ax``, or the axes of a new figure; a clear ImportError without matplotlib."""
    if ax is not None:
        return ax
    try:
        import matplotlib.pyplot as plt
    except ImportError as exc:   # the plots extra is not installed
        raise ImportError("plot() draws with matplotlib: pip install 'ropemodel[plots]'") from exc
    return plt.subplots(figsize=(7.0, 4.0), layout="constrained")[1]


def finish(ax: Any, title: str, xlabel: str, ylabel: str) -> Any:
    """Title, axis labels, a grid and a legend where there are labelled lines; returns ``ax``."""
    ax.set_title(title, fontsize="medium")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize="small")
    return ax
