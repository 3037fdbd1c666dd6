"""Scenes: one installation described in a TOML file.

::

    [scene]
    name = "Krauze et al. 2025, Fig. 9"
    model = "winch"            # default; also "sheave", "capstan"
    [effects]                  # effect = variant; omitted effects take their defaults
    elongation = "krauze2025"
    [parameters]               # the paper's symbols; a number is SI, a string carries its unit
    L_u = "1150 m"
    alpha_u = "16 deg"
    [numerics]                 # solver options, where the model has any
    rtol = 1e-8

Loading checks every name (suggesting the nearest valid one), converts every
value to SI, checks ranges and the submodels' cross-parameter rules, and fills
in documented defaults.  :class:`InputError` on anything wrong.
"""

from __future__ import annotations

import tomllib
import warnings
from dataclasses import dataclass, field, replace
from functools import cached_property
from importlib import resources
from pathlib import Path

from ropemodel.core.model import Model
from ropemodel.effects import effects_of, resolve_effects
from ropemodel.effects.base import numerics_of
from ropemodel.errors import InputError, suggest
from ropemodel.units import to_si

TABLES = ("scene", "effects", "parameters", "numerics")
EXAMPLE = "krauze2025_fig9.toml"


class BeyondSourceWarning(UserWarning):
    """A valid value outside the range the source paper covers."""


@dataclass(frozen=True)
class Scene:
    """A validated scene.  ``parameters`` are SI floats; ``effects`` have defaults filled in."""

    name: str
    model: str
    effects: dict[str, str]
    parameters: dict[str, float]
    numerics: dict = field(default_factory=dict)
    source: str | None = None

    @cached_property
    def built(self) -> Model:
        """The model with this scene's effects (only their equations are built)."""
        return Model(self.model, self.effects, self.numerics)

    def with_values(self, values: dict) -> "Scene":
        """A copy with parameters replaced (values SI numbers or unit strings), re-validated."""
        params = dict(self.parameters)
        model = self.built
        model.check_names(values)
        for k, v in values.items():
            if k not in model.parameters:
                raise InputError(f"{k} is computed by this scene ({model.quantities[k].equation}), "
                                 f"not a parameter; use solve --given {k}=... --find <parameter>")
            params[k] = to_si(k, v, model.quantities[k].unit)
        out = replace(self, parameters=params)
        out.__dict__["built"] = model
        _check_values(model, params)
        return out


def builtin_scenes() -> list[str]:
    """Names of the scenes shipped in the package (``ropemodel/data/*.toml``), without ``.toml``."""
    return sorted(f.name[:-5] for f in resources.files("ropemodel.data").iterdir()
                  if f.name.endswith(".toml") and "[scene]" in f.read_text())


def load(path: str | Path | None = None) -> Scene:
    """Load a scene file.

    ``None`` (or ``"example"``) loads the built-in example (Krauze et al. 2025, Fig. 9);
    the name of a built-in scene (see :func:`builtin_scenes`, e.g.
    ``"capstan_li_experiment"``) loads that one when no such file exists.
    """
    if path is None or str(path) == "example":
        path = EXAMPLE[:-5]
    p = Path(path)
    name = p.name[:-5] if p.name.endswith(".toml") else p.name
    if not p.exists() and str(path) in (name, p.name) and name in builtin_scenes():
        text = resources.files("ropemodel.data").joinpath(f"{name}.toml").read_text()
        return from_toml(text, source=f"built-in scene {name}")
    try:
        text = p.read_text()
    except FileNotFoundError:
        raise InputError(f"scene file not found: {p} (built-in scenes: {', '.join(builtin_scenes())})"
                         f"{suggest(name, builtin_scenes())}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read scene file {p}: {exc}") from None
    return from_toml(text, source=str(p))


def from_toml(text: str, source: str | None = None) -> Scene:
    """Parse and validate a scene from TOML text."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"invalid TOML in {source or 'scene'}: {exc}") from None
    return from_dict(data, source)


def from_dict(data: dict, source: str | None = None) -> Scene:
    """Validate a scene given as nested dicts (the TOML structure)."""
    where = f" in {source}" if source else ""
    for key, val in data.items():
        if key not in TABLES:
            raise InputError(f"unknown table [{key}]{where}; valid tables: {', '.join(TABLES)}{suggest(key, TABLES)}")
        if not isinstance(val, dict):
            raise InputError(f"[{key}]{where} must be a table")
    head = data.get("scene", {})
    for key in head:
        if key not in ("name", "model"):
            raise InputError(f"unknown key {key!r} in [scene]{where}; valid: name, model{suggest(key, ['name', 'model'])}")
    model_name = head.get("model", "winch")
    effects_of(model_name)
    effects = resolve_effects(model_name, data.get("effects"))
    numerics = _check_numerics(model_name, data.get("numerics", {}))
    model = Model(model_name, effects, numerics)
    given = data.get("parameters", {})
    model.check_names(given)
    params: dict[str, float] = {}
    for name, value in given.items():
        if name not in model.parameters:
            raise InputError(f"{name} is computed by this scene ({model.quantities[name].equation}), not a parameter")
        params[name] = to_si(name, value, model.quantities[name].unit)
    missing = []
    for name in model.parameters:
        if name not in params:
            default = model.quantities[name].default
            if default is None:
                missing.append(name)
            else:
                params[name] = default
    if missing:
        raise InputError(f"missing parameter{'s' if len(missing) > 1 else ''}{where}: "
                         + ", ".join(f"{n} ({model.quantities[n].description}, {model.quantities[n].unit})"
                                     for n in missing))
    _check_values(model, params)
    scene = Scene(str(head.get("name", source or "unnamed")), model_name, effects, params, numerics, source)
    scene.__dict__["built"] = model
    return scene


def _check_values(model: Model, params: dict[str, float]) -> None:
    model.validate(params)
    for name, value in params.items():
        q = model.quantities[name]
        if q.beyond_source(value):
            warnings.warn(f"{name} = {q.to_display(value):.6g}{q.unit_text} is beyond the range the source "
                          f"covers ({q.description})", BeyondSourceWarning, stacklevel=3)


def _check_numerics(model: str, numerics: dict) -> dict:
    specs = numerics_of(model)
    out = {k: spec.default for k, spec in specs.items()}
    for key, value in numerics.items():
        if key not in specs:
            valid = ", ".join(sorted(specs)) or "none"
            raise InputError(f"unknown numerics option {key!r} for model {model!r}; valid: {valid}"
                             f"{suggest(key, specs)}")
        out[key] = specs[key].check(key, value)
    return out
