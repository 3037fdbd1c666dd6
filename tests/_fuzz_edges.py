"""Values at the edges of every input's physical domain, generated from the Quantity declarations.

For each command's base scene (``_fuzz.BASES``, and the extra scenes run through ``run``), every input
of the scene's model at both ends of its valid range (:mod:`ropemodel.effects.domains`): just inside
each end (the end itself where it is closed) the command must give a sound result or fail cleanly
(exit 0 with no NaN or inf anywhere in its output, or exit 1/2 with one message); just outside, it must
refuse with exit 2 naming the input.  The inputs the scene does not use get the same values: outside
their domain they are refused all the same (naming them), inside they are a warning (tried through
``run`` only: the warning is the same in every command).  Two corners per
scene put every input at once at the inside of its upper, then of its lower end.  A new parameter is
fuzzed by declaring its Quantity: nothing here names one.
"""

from __future__ import annotations

import tomllib

from _fuzz import BASES, EXTRA_RUN_SCENES, INPUT, Case, _scene_argv, builtin, set_value

SOUND = frozenset({0, 1, 2})


def _step(q, end: float) -> float:
    """How far beyond (or inside) an end a value is taken: a millionth of the end or of the usual value."""
    return max(abs(end), abs(q.guess), 1e-300) * 1e-6


def edges(q) -> list[tuple[str, float, bool]]:
    """(label, SI value, inside the domain) at both ends of ``q``'s valid range."""
    out = []
    for side, end, is_open, sign in (("low", q.low, q.low_open, -1.0), ("high", q.high, q.high_open, +1.0)):
        inside = end - sign * _step(q, end) if is_open else end
        outside = end if is_open else end + sign * _step(q, end)
        out += [(f"{side} end inside ({inside!r})", inside, True),
                (f"{side} end outside ({outside!r})", outside, False)]
    return out


def toml_value(q, si: float) -> str:
    """``si`` as a scene file writes it: in the SI unit (exact, no conversion), a bare number if pure."""
    return repr(si) if q.dimensionless else f'"{si!r} {q.unit}"'


def _model(scene_name: str):
    import ropemodel as rm

    return rm.load_scene(scene_name, emit=False).built


def _inputs(model) -> tuple[list[str], list[str]]:
    """(used, unused) inputs of ``model``: its parameters, and every other input of any of its variants."""
    from ropemodel.docs import _roles

    used = [n for n in model.parameters if not n[-1].isdigit()]   # a route's L_1 ... live in [[route]]
    every = _roles(model.name)[0]
    return used, [n for n in every if n not in model.symbols and not n[-1].isdigit()]


def _targets():
    return [(c, BASES[c][0]) for c in BASES] + [("run", s) for s in EXTRA_RUN_SCENES]


def edge_cases() -> list[Case]:
    """Every input of every command's scene at both ends of its domain, and just outside."""
    cases = []
    for command, name in _targets():
        text, model = builtin(name), _model(name)
        used, unused = _inputs(model)
        for key in used + unused:
            q = model.universe[key]
            role = "used" if key in used else "unused"
            for label, si, inside in edges(q):
                if inside and role == "unused" and command != "run":   # a warning: the same in every command
                    continue
                argv, files = _scene_argv(command, name, set_value(text, "parameters", key, toml_value(q, si)))
                cases.append(Case(command, "edge", f"{name}: {key} ({role}) {label}", argv, files,
                                  SOUND if inside else INPUT, expect="sound" if inside else "fail",
                                  words=() if inside else (key,)))
    return cases


def corner_cases() -> list[Case]:
    """Every input of a scene at once at the inside of its upper end, then of its lower end."""
    cases = []
    for command, name in _targets():
        text, model = builtin(name), _model(name)
        given = tomllib.loads(text).get("parameters", {})
        for corner in ("high", "low"):
            new = text
            for key in (k for k in _inputs(model)[0] if k in given or model.quantities[k].default is None):
                q = model.quantities[key]
                si = next(v for label, v, inside in edges(q) if inside and label.startswith(corner))
                new = set_value(new, "parameters", key, toml_value(q, si))
            argv, files = _scene_argv(command, name, new)
            cases.append(Case(command, "edge", f"{name}: every input at its {corner} end", argv, files, SOUND,
                              expect="sound"))
    return cases
