"""The Python API documents itself: one function per command, each with a real signature, type hints and a
numpydoc docstring (parameters, returns, raises, an example); the examples run in tests/test_doctests.py."""

import inspect
import pydoc
import re
from importlib import resources

import pytest

import optimisation
import ropemodel as rm

#: command of the command line → its function
COMMANDS = {
    "run": rm.run, "solve": rm.solve, "size": optimisation.size, "sweep": rm.sweep,
    "sensitivity": rm.elasticities, "sensitivity --sobol": rm.sobol, "curve": rm.load_curve,
    "identify": rm.identify, "simulate": rm.simulate, "trip": rm.trip, "report": rm.report,
}
PUBLIC = {**{f.__name__: f for f in COMMANDS.values()}, "load_scene": rm.load_scene, "tornado": rm.tornado}
SECTIONS = ("Parameters", "Returns", "Raises", "Examples")


def sections(doc: str) -> dict[str, str]:
    """numpydoc sections of ``doc``: title → body."""
    parts = re.split(r"^(\w[\w ]*)\n-{3,}\n", doc, flags=re.M)
    return {parts[i].strip(): parts[i + 1] for i in range(1, len(parts) - 1, 2)}


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_help_shows_every_section_and_parameter(name):
    func = PUBLIC[name]
    doc = inspect.getdoc(func)
    found = sections(doc)
    assert set(SECTIONS) <= set(found), f"{name}: missing {set(SECTIONS) - set(found)}"
    assert ">>> " in found["Examples"]
    params = found["Parameters"]
    for p in inspect.signature(func).parameters.values():
        shown = "**" + p.name if p.kind is p.VAR_KEYWORD else p.name
        assert re.search(rf"(^|[\s,]){re.escape(shown)}\b", params, re.M), f"{name}: {p.name} not documented"
    assert doc.splitlines()[0] in pydoc.render_doc(func)   # help() shows it


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_real_signature_with_type_hints(name):
    sig = inspect.signature(PUBLIC[name])
    assert sig.return_annotation is not inspect.Signature.empty, name
    for p in sig.parameters.values():
        assert p.kind is not p.VAR_POSITIONAL, f"{name}(*{p.name}) hides its parameters"
        assert p.annotation is not inspect.Parameter.empty, f"{name}: {p.name} has no type hint"


def test_dimensional_parameters_state_their_units():
    """A parameter that is a physical quantity names its unit in brackets where it is described."""
    for func, names in ((rm.load_curve, ("F_max",)), (rm.identify, ("sigma",)), (rm.load_scene, ("values",))):
        params = sections(inspect.getdoc(func))["Parameters"]
        for n in names:
            text = params[params.index(n):]
            text = text[:text.index("\n", text.index("\n") + 1) + 200]
            assert re.search(r"\[(N|rad|m|N, m, rad, s, \.\.\.)\]", text), (func.__name__, n)


def test_typed_package():
    assert resources.files("ropemodel").joinpath("py.typed").is_file()
    assert resources.files("optimisation").joinpath("py.typed").is_file()


def test_the_public_names_are_the_commands_functions():
    assert rm.sweep.__module__ == "ropemodel.sweeps.runner" and callable(rm.report) and callable(rm.size)
    assert set(rm.__all__) >= {"run", "solve", "sweep", "elasticities", "sobol", "load_curve", "identify",
                               "simulate", "trip", "report", "size", "load_scene", "tornado"}
