"""Reading a scene's tables: each table of a scene file checked on its own, every problem collected in a
:class:`~ropemodel.errors.Problems` (the scene itself, its cross-parameter rules and its checks
against the model are :mod:`ropemodel.scene`'s).

* :func:`read_head` — ``[scene]``: name and model; unknown tables;
* :func:`read_numerics` — ``[numerics]``: options of the model's numerical methods;
* :func:`read_route` and :func:`route_parameters` — ``[[route]]`` segments (issue "routes"), or a
  ``[route_profile]`` file of them (:mod:`ropemodel.scene_profile`);
* :func:`read_parameters` — ``[parameters]``: SI values, unit checks, values usual for the field,
  computed quantities given as checks (:class:`Check`), valid parameters that are not used;
* :func:`set_values` — values set on top of the file (``--set``, ``values=``);
* :func:`fill_missing` — defaults, and what is missing named with an example value.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ropemodel.core.model import Model
from ropemodel.effects import effects_of, misplaced, models, numerics_of, route_arrays
from ropemodel.errors import InputError, Problems, suggest
from ropemodel.scene_profile import read_profile
from ropemodel.units import last_digit, split_value, to_si

TABLES = ("scene", "effects", "parameters", "numerics", "route", "route_profile", "rules", "report")
#: keys of a ``[[route]]`` segment → the parameter each becomes (``{i}``: the segment's number from the drive)
ROUTE_KEYS = {"length": "L_{i}", "inclination": "alpha_{i}", "mu_winding": "mu_w{i}"}
SCENE_KEYS = ("name", "model", "description")
#: a route whose segments could not be read (the problem is said): one segment, not "missing" again
UNREAD_ROUTE: tuple = ((False,), {"L_1": (None, None), "alpha_1": (None, None)}, {})

@dataclass(frozen=True)
class Check:
    """A computed quantity given in a scene: the model must reproduce it to the digits typed."""

    value: float       # SI
    tolerance: float   # SI: half a unit of the last digit typed
    text: str          # as typed


def settable(model: Model, name: str, origin: str) -> str | None:
    option = "--set" if origin == "--set" else "with_values"
    if name in model.derived:
        return (f"{name} is computed from the route's segments for each load case "
                f"({model.quantities[name].description}): set the segments' values (L_i, alpha_i, mu_wi) instead")
    if name in model.parameters or name in model.edge_set:
        return None
    if name in effects_of(model.name):
        return f"{name} is an effect: it cannot be set with {option}; choose its variant in the scene's [effects]"
    if name in model.outputs:
        return (f"{name} is computed by this scene ({model.quantities[name].equation or 'an output'}), not a "
                f"parameter; use solve --given {name}=... --find <parameter>")
    return model.name_problem(name)


def options(numerics: dict, route: tuple, point_A: bool = False) -> dict:
    """The model's options: the scene's numerics and the structure of its route (if it has one)."""
    return {**numerics, "route": route, "point_A": point_A} if route else dict(numerics)


def read_route(data: dict, effects: dict, given: dict, found: Problems, base: Path | None = None):
    """The ``[[route]]`` segments, or those of the ``[route_profile]`` file (relative to ``base``, the scene
    file's folder): (structure, {parameter name: (the segment's label, value as typed)}, {parameter name: SI
    value}: a profile's, read with the units of its columns)."""
    segments, profile = data.get("route"), data.get("route_profile")
    wanted = effects.get("route") == "segments"
    if segments is None and profile is None:
        if wanted:
            found.add('route = "segments" needs the segments: one [[route]] table each, listed from the drive, '
                      'with length and inclination (e.g. length = "400 m", inclination = "22 deg"), or a '
                      '[route_profile] file = "profile.csv"')
        return (), {}, {}
    if not wanted:
        given_as = "[[route]] segments are" if profile is None else "[route_profile] is"
        found.add(f'{given_as} given but the route effect is "straight": set [effects] route = "segments"')
        return (), {}, {}
    if profile is not None:
        if segments is not None:
            found.add("[[route]] segments and a [route_profile] are both given: keep one of them")
            return UNREAD_ROUTE
        return _profile_route(profile, given, found, base)
    if not isinstance(segments, list) or not segments or not all(isinstance(s, dict) for s in segments):
        found.add("[[route]] must be a list of tables, one per segment (write [[route]] before each segment); "
                  "an empty route has no segment")
        return (), {}, {}
    _no_L_u(given, found)
    values: dict[str, tuple[str | None, object]] = {}     # name -> (label, value)
    for i, seg in enumerate(segments, start=1):
        for key, value in seg.items():
            if key not in ROUTE_KEYS:
                found.add(f"[[route]] segment {i}: unknown key {key!r}; valid: {', '.join(ROUTE_KEYS)}"
                          f"{suggest(key, ROUTE_KEYS)}")
                continue
            values[ROUTE_KEYS[key].format(i=i)] = (f"[[route]] segment {i}: {key}", value)
        for key in ("length", "inclination"):
            if key not in seg:
                found.add(f"[[route]] segment {i} has no {key} (e.g. {key} = "
                          f"{chr(34)}{'400 m' if key == 'length' else '10 deg'}{chr(34)})")
                values[ROUTE_KEYS[key].format(i=i)] = (None, None)   # said: not "missing" again
    return tuple("mu_winding" in seg for seg in segments), values, {}


def scene_folder(source: str | None) -> Path | None:
    """The folder of a scene file (where its ``[route_profile]`` file is found); None for a scene not read
    from a file (a relative profile path is then relative to the working folder); the package's data for a
    built-in scene."""
    if source and source.startswith("built-in scene "):
        return Path(str(resources.files("ropemodel.data")))
    return Path(source).parent if source and Path(source).is_file() else None


def _no_L_u(given: dict, found: Problems) -> None:
    if "L_u" in given:
        found.add("L_u is the sum of the [[route]] segments' lengths: remove it from [parameters]")
        given.pop("L_u")


def _profile_route(table, given: dict, found: Problems, base: Path | None):
    """``[route_profile] file = "..."``: the segments of the file (:mod:`ropemodel.scene_profile`), as
    ``[[route]]`` segments without ``mu_winding``."""
    if not isinstance(table, dict) or set(table) != {"file"} or not isinstance(table["file"], str):
        found.add('[route_profile] takes one key, file = "profile.csv" (a CSV of \'distance [m],height [m]\' or '
                  '\'length [m],inclination [deg]\', relative to the scene file)')
        return UNREAD_ROUTE
    _no_L_u(given, found)
    path = Path(table["file"]).expanduser()
    lengths, angles = read_profile(path if path.is_absolute() or base is None else base / path, found)
    if not lengths.size:
        return UNREAD_ROUTE
    pairs = zip(lengths.tolist(), angles.tolist())       # SI floats, segment by segment as [[route]] gives them
    si = {route_arrays.name(f, i): v for i, pair in enumerate(pairs) for f, v in zip(("L", "alpha"), pair)}
    return (False,) * lengths.size, {}, si


def route_parameters(model: Model, values: dict, si: dict, bare: str, params: dict, origin: dict,
                     found: Problems) -> None:
    """The route's values: ``values`` as typed, converted one by one; ``si`` (a profile's), as they are."""
    params.update(si)
    origin.update(dict.fromkeys(si, "route"))
    for name, (label, value) in values.items():
        if label is None:
            origin[name] = "route (missing)"
            continue
        q = model.quantities[name]
        try:
            params[name] = to_si(label, value, q.unit, q.display_unit, bare)
            origin[name] = "route"
        except InputError as exc:
            found.add(str(exc))
            origin[name] = "route (refused)"


def read_table(data: dict, key: str, found: Problems) -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        found.add(f"[{key}] must be a table of NAME = VALUE lines, got {type(value).__name__}")
        return {}
    return value


def read_head(data: dict, found: Problems):
    for key in data:
        if key not in TABLES:
            found.add(f"unknown table [{key}]; valid tables: {', '.join(TABLES)}{suggest(key, TABLES)}")
    head = read_table(data, "scene", found)
    for key in head:
        if key not in SCENE_KEYS:
            found.add(f"unknown key {key!r} in [scene]; valid: {', '.join(SCENE_KEYS)}{suggest(key, SCENE_KEYS)}")
    model = head.get("model", "winch")
    if not isinstance(model, str) or model not in models():
        found.add(f"unknown model {model!r}; valid models: {', '.join(models())}{suggest(str(model), models())}")
    name = head.get("name")
    if name is not None and not isinstance(name, str):
        found.add(f"[scene] name must be text, got {name!r}")
    return name, model


def read_numerics(model: str, given: dict, found: Problems) -> dict:
    specs = numerics_of(model)
    out = {k: spec.default for k, spec in specs.items()}
    for key, value in given.items():
        if key not in specs:
            valid = ", ".join(sorted(specs)) or "none"
            found.add(misplaced(model, key, "[numerics]") or
                      f"unknown numerics option {key!r} for model {model!r}; valid: {valid}{suggest(key, specs)}")
            continue
        with found.collect():
            out[key] = specs[key].check(key, value)
    return out


def read_parameters(model: Model, given: dict, bare: str, found: Problems, notes: list):
    """SI values of the given parameters; checks (computed quantities given); unused ones (who would use
    them, and their SI values: in their domain, as any value)."""
    params: dict[str, float] = {}
    checks: dict[str, Check] = {}
    unused: dict[str, str] = {}
    origin: dict[str, str] = {}
    kept: dict[str, float] = {}
    quantities = model.universe
    for key, value in given.items():
        if key not in quantities:
            found.add(misplaced(model.name, key, "[parameters]") or
                      f"unknown parameter {key!r} for model {model.name!r}{suggest(key, quantities)}")
            continue
        q = quantities[key]
        try:
            si = q.to_si(value, bare)
        except InputError as exc:
            found.add(str(exc))
            origin[key] = "scene (refused)"
            continue
        if key in model.outputs:
            checks[key] = Check(si, half_digit(q, value, si, bare), str(value))
        elif key in model.derived:
            found.add(str(settable(model, key, "[parameters]")))
        elif key in model.parameters or key in model.edge_set:
            params[key], origin[key] = si, "scene"
            note = q.unusual(si)
            if note:
                notes.append(note)
        else:
            keep_unused(model, key, si, "scene", origin, unused, kept, notes, found)
    return params, checks, unused, origin, kept


def keep_unused(model: Model, key: str, si: float, where: str, origin: dict, unused: dict, kept: dict,
                notes: list, found: Problems) -> None:
    """A valid parameter the chosen effects do not use: named (with the variants that would use it), its
    value and origin kept for a command that switches effects.  A value outside its physical domain is an
    error all the same (no effect could use it)."""
    problem = model.universe[key].range_problem(si)
    if problem:
        found.add(f"{problem}; {key} is not used by this scene's effects, but no value outside its valid range "
                  f"is accepted")
        return
    unused[key] = " or ".join(model.owners(key)) or "no effect of this model"
    kept[key], origin[key] = si, where
    note = f"{key} is not used: it belongs to {unused[key]}"
    if note not in notes:
        notes.append(note)


def set_values(model: Model, values: Mapping, bare: str, origin_label: str, params: dict, origin: dict,
               unused: dict, found: Problems, notes: list, kept: dict) -> None:
    """Parameters set on top of the file (``--set``, ``values=``): they replace the file's values (an unused
    one is named in ``unused`` and its SI value kept in ``kept``)."""
    for key, value in values.items():
        problem = settable(model, key, origin_label)
        if problem and (key in model.derived or not (key in model.universe and key not in model.symbols)):
            found.add(problem)
            continue
        q = model.universe[key]
        try:
            si = q.to_si(value, bare)
        except InputError as exc:
            found.add(str(exc))
            origin[key] = f"{origin_label} (refused)"
            continue
        if key not in model.parameters and key not in model.edge_set:
            keep_unused(model, key, si, origin_label, origin, unused, kept, notes, found)
            continue
        params[key], origin[key] = si, origin_label
        note = q.unusual(si)
        if note:
            notes.append(note)


def half_digit(q, value, si: float, bare: str) -> float:
    """Half a unit of the last digit typed in ``value``, in SI (how precisely a check was given)."""
    text = value if isinstance(value, str) else repr(value)
    num, unit = split_value(text) if isinstance(value, str) else (float(value), "")
    step = last_digit(text)
    bigger = q.to_si(f"{num + step!r} {unit}".strip(), bare) if unit or q.dimensionless or bare == "si" else si
    return 0.5 * abs(bigger - si)


def fill_missing(model: Model, params: dict, origin: dict, optional: tuple, found: Problems):
    defaults, absent, missing = {}, [], []
    for name in model.parameters:
        if name in params or name in origin:
            continue
        q = model.quantities[name]
        if q.default is not None:
            params[name], origin[name] = q.default, "default"
            defaults[name] = q.default_note or f"default {q.show(q.default)}"
        elif name in optional:
            absent.append(name)
        else:
            missing.append(name)
    for name in missing:
        q = model.quantities[name]
        shown = f'"{example_value(q)}{q.unit_text}"' if not q.dimensionless else example_value(q)
        found.add(f"missing parameter {name} ({q.description}), e.g. {name} = {shown}")
    return defaults, tuple(absent)


def example_value(q) -> str:
    return f"{q.to_display(q.guess):.4g}"
