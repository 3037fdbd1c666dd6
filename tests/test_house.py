"""House rules that a reviewer would otherwise check by eye (issue 14): no module imports another package's
private names; modules stay short enough to read (about 400 lines) and functions short enough to follow
(about 60 lines of body). The layer contract is import-linter's (``lint-imports``, run by .ci/run)."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LIBRARY = sorted(p for d in ("ropemodel", "optimisation") for p in (ROOT / d).rglob("*.py"))
MAX_MODULE, MAX_FUNCTION = 400, 60


def _module(path: Path, root: Path) -> str:
    return ".".join(path.relative_to(root).with_suffix("").parts).removesuffix(".__init__")


def _package(module: str, path: Path) -> str:
    return module if path.name == "__init__.py" else module.rpartition(".")[0]


def private_imports(path: Path, root: Path = ROOT) -> list[str]:
    """``from other.package import _name`` (or ``import other._private``) in ``path``, other ≠ its package
    (``root``: the folder that holds the packages)."""
    module = _module(path, root)
    own = _package(module, path)
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            target = node.module
            names = [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            target, names = "", [a.name for a in node.names]
        else:
            continue
        for name in names:
            full = f"{target}.{name}" if target else name
            parts = full.split(".")
            private = [i for i, part in enumerate(parts) if part.startswith("_") and not part.startswith("__")]
            if not private:
                continue
            home = ".".join(parts[:private[0]])   # the package that owns the private name
            if home != own and not own.startswith(home + ".") and home.split(".")[0] in ("ropemodel", "optimisation"):
                found.append(f"{path.relative_to(root)}:{node.lineno} imports {full}")
            elif home.split(".")[0] not in ("ropemodel", "optimisation"):
                found.append(f"{path.relative_to(root)}:{node.lineno} imports {full} (a third party's private name)")
    return found


def test_the_checker_finds_a_private_import(tmp_path):
    """A module placed in ``ropemodel/cli/`` of a copy of the layout (never in the package itself: the suite
    runs in parallel workers and from read-only installs): another package's private name is found, its own
    package's is not, and neither is a third party's public name."""
    (tmp_path / "ropemodel" / "cli").mkdir(parents=True)
    bad = tmp_path / "ropemodel" / "cli" / "_probe_for_test.py"
    bad.write_text("from ropemodel.sweeps.files import _private\nfrom ropemodel.cli._common import warn\n"
                   "import numpy.linalg\nfrom numpy import _core\n")
    assert private_imports(bad, tmp_path) == [
        "ropemodel/cli/_probe_for_test.py:1 imports ropemodel.sweeps.files._private",
        "ropemodel/cli/_probe_for_test.py:4 imports numpy._core (a third party's private name)"]


def test_no_module_imports_another_packages_private_names():
    assert [hit for p in LIBRARY for hit in private_imports(p)] == []


@pytest.mark.parametrize("path", LIBRARY, ids=lambda p: str(p.relative_to(ROOT)))
def test_modules_and_functions_stay_short(path):
    text = path.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= MAX_MODULE
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if len(body) > 1 and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                body = body[1:]   # the docstring does not count
            assert node.end_lineno - body[0].lineno + 1 <= MAX_FUNCTION, f"{node.name} at line {node.lineno}"


def test_tests_import_their_helpers_by_module_name():
    """pytest puts ``tests/`` on the path (rootdir conftest), not the checkout: ``from tests._x import`` works
    only where the checkout happens to be importable (an editable install's path, ``python -m pytest``) and
    failed on CI's fresh clone. Helpers are imported as ``from _x import ...``."""
    bad = []
    for path in sorted((ROOT / "tests").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [node.module or ""] if isinstance(node, ast.ImportFrom) else (
                [a.name for a in node.names] if isinstance(node, ast.Import) else [])
            bad += [f"{path.name}: {n}" for n in names if n == "tests" or n.startswith("tests.")]
    assert not bad, bad


def test_every_test_named_slow_by_duration_exists():
    """An entry of ``SLOW_BY_DURATION`` whose test was renamed would silently put a long test back into the
    README's command; each must name a test function of its file."""
    from conftest import SLOW_BY_DURATION

    stale = []
    for entry in SLOW_BY_DURATION:
        path, name = entry.split("::")
        tree = ast.parse((ROOT / path).read_text(encoding="utf-8"))
        functions = {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
        if name.split("[")[0] not in functions:
            stale.append(entry)
    assert not stale, stale
