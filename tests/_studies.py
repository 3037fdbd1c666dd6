"""Load a study script (``studies/<name>.py``) as a module, for the study tests."""

from __future__ import annotations

import importlib.util
from pathlib import Path

STUDIES = Path(__file__).resolve().parents[1] / "studies"


def load_study(name: str, publish: bool = False):
    """The module ``studies/<name>.py``, freshly executed.

    Unless ``publish``, a full-mode run writes its figure only to the output folder it is given, not to
    ``studies/figures/`` (the README's pictures are drawn by ``studies/run_all.py``, never by a test).
    """
    spec = importlib.util.spec_from_file_location(f"study_{name}", STUDIES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    if not publish and hasattr(mod, "save_figure"):
        save = mod.save_figure

        def unpublished(fig, script, out, fig_name, fast, *args, **kwargs):
            save(fig, script, out, fig_name, True, *args, **kwargs)

        mod.save_figure = unpublished
    return mod
