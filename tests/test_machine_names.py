"""The generic layers name no machine: a machine is a plug-in (issue 25, item 6).

The rule: in :mod:`optimisation`, :mod:`ropemodel.dynamics`, :mod:`ropemodel.reports`, :mod:`ropemodel.cli` and
:mod:`ropemodel.trips`, no *code* — no identifier (name, attribute, argument, function or class, keyword), no
imported module and no string literal — contains a machine's name (``winch``, ``koepe``) or a name only one
machine has (:data:`MACHINE_NAMES`: the winch's design variables ``F_nwl`` and ``stroke``, the Koepe's rope
counts and masses ``n_head``, ``q_head``, ``d_head``, ``F_min_head``, ``n_tail``, ``q_tail``, ``h_loop``).  What
a machine has to say, it declares in :mod:`ropemodel.machines`, and the drivers read it from there.

Not code, so not checked: docstrings and comments (they may name a machine as an example, and run doctests on
the built-in scenes), and the names of built-in scenes inside strings (``winch_sizing_fig9``: a scene is data).
The files of :data:`NOT_YET_MOVED` (none now) would still name a machine, each for the reason given; the test fails
when one of them no longer does (take it off the list) as well as when any other file does.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from ropemodel.scene import builtin_scenes

ROOT = Path(__file__).resolve().parents[1]
#: the generic layers
LAYERS = ("optimisation", "ropemodel/dynamics", "ropemodel/reports", "ropemodel/cli", "ropemodel/trips.py")
#: names only one machine has (besides the machines' own names)
MACHINE_NAMES = ("F_nwl", "stroke", "n_head", "q_head", "d_head", "F_min_head", "n_tail", "q_tail", "h_loop")
PATTERN = re.compile("|".join(["winch", "koepe", *MACHINE_NAMES]), re.IGNORECASE)
#: files that still name a machine, and why
NOT_YET_MOVED: dict[str, str] = {}


def _files() -> list[Path]:
    out = []
    for layer in LAYERS:
        p = ROOT / layer
        out += [p] if p.is_file() else sorted(p.rglob("*.py"))
    return out


def _docstrings(tree) -> set[int]:
    """ids of the string expressions that are documentation (docstrings, attribute docstrings)."""
    return {id(node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)}


def _words(node, docs: set[int]) -> list[str]:
    if isinstance(node, ast.Name):
        return [node.id]
    if isinstance(node, ast.Attribute):
        return [node.attr]
    if isinstance(node, ast.arg):
        return [node.arg]
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return [node.name]
    if isinstance(node, ast.alias):
        return [node.name, node.asname or ""]
    if isinstance(node, ast.ImportFrom):
        return [node.module or ""]
    if isinstance(node, ast.keyword):
        return [node.arg or ""]
    if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
        return [node.value]
    return []


def machine_names(path: Path, scenes=None) -> list[str]:
    """``line: word`` of every machine name in the code of ``path`` (see the module's rule)."""
    scenes = sorted(builtin_scenes() if scenes is None else scenes, key=len, reverse=True)
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docs, found = _docstrings(tree), []
    for node in ast.walk(tree):
        for word in _words(node, docs):
            for scene in scenes:
                word = word.replace(scene, "")
            if PATTERN.search(word):
                found.append(f"{getattr(node, 'lineno', '?')}: {word[:80]!r}")
    return found


def test_the_rule_finds_names_in_code_not_in_docs(tmp_path):
    """The scanner itself: a name in code is found, the same name in a docstring or a scene's name is not."""
    f = tmp_path / "m.py"
    f.write_text('"""A winch, F_nwl."""\nx = run("winch_start")\nF_nwl = 1\ny = a.stroke\nz = "koepe"\n')
    assert [w.split(": ")[1] for w in machine_names(f, ["winch_start"])] == ["'F_nwl'", "'stroke'", "'koepe'"]


@pytest.mark.parametrize("path", _files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_a_generic_layer_names_no_machine(path):
    rel = str(path.relative_to(ROOT))
    found = machine_names(path)
    if rel in NOT_YET_MOVED:
        assert found, f"{rel} no longer names a machine: take it off NOT_YET_MOVED"
    else:
        assert not found, f"{rel} names a machine in its code (declare it in ropemodel/machines):\n" + "\n".join(found)
