"""Scenes: one installation described in a TOML file, checked whole before anything is computed.

::

    [scene]
    name = "Krauze et al. 2025, Fig. 9"
    model = "winch"            # default; also "sheave", "capstan", "koepe"
    [effects]                  # effect = variant; omitted effects take their defaults
    elongation = "krauze2025"
    [parameters]               # the paper's symbols; a dimensional value carries its unit
    L_u = "1150 m"
    alpha_u = "16 deg"
    mu_pl = 0.05               # a bare number only for a dimensionless quantity
    [numerics]                 # solver options, where the model has any
    rtol = 1e-8
    [report]                   # the filed report: document, revision, sign-off (ropemodel.scene_report)
    revision = "A"

Loading collects *every* problem before it raises one :class:`~ropemodel.errors.InputError`
that lists them all (one line each): unknown names (with the nearest valid name), a key in
the wrong table, values without a unit, wrong units, values outside their valid range,
missing parameters, broken cross-parameter rules, and given values of computed quantities
that disagree with the model.  What is valid but unusual is a warning, not an error:

* a parameter that the chosen effects do not use is accepted and named (``unused``), with
  the variant that would use it;
* a value outside the range usual for the field is named with that range and its source;
* a quantity the model computes (e.g. ``mu_pl1`` in resistance case 1) may be given: it is
  then a *check*, accepted when it agrees with the computed value to the digits typed;
* every default a scene relies on is listed (``defaults``) with why that value.
"""

from __future__ import annotations

import hashlib
import math
import os
import tomllib
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property
from importlib import resources
from pathlib import Path

from ropemodel import scene_tables as tables
from ropemodel.scene_report import Filing, read_report
from ropemodel.core.compile import forward_of
from ropemodel.core.model import Model
from ropemodel.effects import all_quantities, effects_of, models, resolve_effects
from ropemodel.errors import InputError, Problems, suggest
from ropemodel.rules import apply as rules_apply
from ropemodel.rules import describe as rules_describe
from ropemodel.views.scene import SceneViews

EXAMPLE = "krauze2025_fig9"
#: where a value read from the scene's own file came from (:meth:`Scene.with_effects` reads the file again)
FILE_ORIGINS = ("scene", "route", "default", rules_apply.FROM_RULE, rules_apply.FROM_OVERRIDE)


class SceneWarning(UserWarning):
    """Valid but worth a look: an unused parameter, a value outside the range usual for the field."""


@dataclass(frozen=True, repr=False)
class Scene(SceneViews):
    """A validated scene.  ``parameters`` are SI floats; ``effects`` have defaults filled in.

    Attributes
    ----------
    defaults: parameter → why its default value (every default this scene relies on).
    unused: parameter given but not used by the chosen effects → the variants that would use it.
    unused_values: parameter given but not used → its SI value (kept: :meth:`with_effects` uses it when
        the new effects do).
    checks: computed quantity given in the scene → :class:`~ropemodel.scene_tables.Check` (verified when the
        scene loads).
    absent: optional parameters left out (e.g. what sizing chooses itself).
    warnings: every warning of the scene, one line each (the command line prints them once).
    origin: parameter, used or not → where its value came from (``"scene"``, ``"route"``, ``"default"``,
        ``"--set"``, ``"api"``, ...).
    digest: SHA-256 of the scene file's text (None for a scene built in Python).
    """

    name: str
    model: str
    effects: dict[str, str]
    parameters: dict[str, float]
    numerics: dict = field(default_factory=dict)
    source: str | None = None
    defaults: dict[str, str] = field(default_factory=dict)
    unused: dict[str, str] = field(default_factory=dict)
    checks: dict[str, tables.Check] = field(default_factory=dict)
    absent: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    origin: dict[str, str] = field(default_factory=dict)
    digest: str | None = None
    raw: dict = field(default_factory=dict, repr=False, compare=False)
    #: the route's structure (``[[route]]``): per segment, whether it gives its own mu_winding
    route: tuple[bool, ...] = ()
    #: the rule set of ``[rules]`` applied to this scene (:class:`ropemodel.rules.apply.Applied`), or None
    rules: rules_apply.Applied | None = None
    #: the filed report's data, ``[report]`` (:class:`ropemodel.scene_report.Filing`), or None
    filing: Filing | None = None
    #: SI values of the parameters in ``unused`` (in their domain, and meeting the rules)
    unused_values: dict[str, float] = field(default_factory=dict)

    @cached_property
    def built(self) -> Model:
        """The model with this scene's effects (only their equations are built)."""
        return Model(self.model, self.effects, tables.options(self.numerics, self.route, "L_ul" in self.parameters))

    def with_values(self, values: Mapping, bare: str = "si", origin: str = "api") -> Scene:
        """A copy with parameters replaced, every problem checked and listed at once.

        values: name → value; strings carry units, numbers are SI (``bare="si"``, the Python API) or,
        with ``bare="refuse"`` (the command line's ``--set``), allowed only for pure numbers.  A valid
        parameter that this scene's effects do not use is named in ``unused`` and its value kept
        (``unused_values``): a command that switches effects (:meth:`with_effects`) uses it.
        """
        model, found, used = self.built, Problems(), {*self.built.parameters, *self.built.edge_set}
        params, origin_of, defaults = dict(self.parameters), dict(self.origin), dict(self.defaults)
        unused, kept, notes = dict(self.unused), dict(self.unused_values), list[str]()
        tables.set_values(model, values, bare, origin, params, origin_of, unused, found, notes, kept)
        for name in values:
            if name in params:
                defaults.pop(name, None)
        if self.rules is not None:
            with found.collect():
                params.update(rules_apply.refresh(self.rules, params, origin_of, values))
        for problem in model.problems({**kept, **{k: v for k, v in params.items() if k in used}}):
            found.add(problem)
        found.raise_if_any()
        out = replace(self, parameters=params, origin=origin_of, defaults=defaults, unused=unused,
                      unused_values=kept, absent=tuple(a for a in self.absent if a not in values),
                      warnings=self.warnings + tuple(n for n in notes if n not in self.warnings))
        out.__dict__["built"] = model
        _verify_checks(out, Problems()).raise_if_any()
        return out

    def overrides(self) -> dict[str, dict[str, float]]:
        """Values this scene was given on top of its file (``--set``, ``values=``, :meth:`with_values`),
        used or not: origin → {name: SI value}."""
        out: dict[str, dict[str, float]] = {}
        for name, value in {**self.unused_values, **self.parameters}.items():
            where = self.origin.get(name, "api")
            if where not in FILE_ORIGINS:
                out.setdefault(where, {})[name] = value
        return out

    def with_effects(self, effects: dict[str, str], optional=(), emit: bool = False) -> Scene:
        """The scene file read again with ``effects`` set, every value given on top of it kept with its origin."""
        if not self.raw:
            raise InputError("this scene was not loaded from a file or dict; build it again with those effects")
        data = {k: dict(v) if isinstance(v, dict) else v for k, v in self.raw.items()}
        data["effects"] = {**data.get("effects", {}), **effects}
        given = [name for values in self.overrides().values() for name in values]   # not missing: set again below
        scene = from_dict(data, self.source, optional=(*optional, *given), emit=emit, digest=self.digest)
        for where, values in self.overrides().items():
            scene = scene.with_values(values, origin=where)
        return scene

    def basis(self, parameter: str) -> str:
        """Where ``parameter``'s value comes from: a rule (set, clause, formula, status), an override and its
        reason, a default, or "user-given"."""
        return rules_describe.basis(self, parameter)

    def check_basis(self, check: str) -> str:
        """The rule a design check applies (``check``: a margin name), or "user-given" ("-": no factor)."""
        return rules_describe.check_basis(self, check)

    def rule_values(self, values: Mapping, changed) -> dict:
        """The values the rule set gives again where its inputs among ``changed`` take ``values`` (floats,
        numpy arrays or CasADi expressions); {} without a rule set or when no rule input changed."""
        if self.rules is None:
            return {}
        return self.rules.derive(values, changed, self.ruled())

    def ruled(self) -> list[str]:
        """The parameters whose value the rule set gives (not overridden, not set by hand)."""
        return [p for p, o in self.origin.items() if o == rules_apply.FROM_RULE]

    def ruled_by(self, name: str) -> list[str]:
        """The parameters the rule set gives from ``name`` (e.g. ``["n_rope"]`` for the route's ``L_u``)."""
        if self.rules is None:
            return []
        return [p for p in self.ruled() if name in self.rules.inputs_of(p, self.parameters)]

    def required(self) -> list[str]:
        """Parameters this scene must be given (no default)."""
        q = self.built.quantities
        return [n for n in self.built.parameters if q[n].default is None]


#: what every function of the API takes as a scene: a loaded :class:`Scene`, a TOML file's path, or the
#: name of a built-in scene (see :func:`as_scene`)
SceneLike = Scene | str | os.PathLike


def as_scene(scene: SceneLike, optional: Iterable[str] = (), emit: bool = True) -> Scene:
    """A scene as every API function takes it: a :class:`Scene` as it is; a TOML file's path or a built-in
    scene's name (``"example"``, ``"trip_fig9"``) loaded by :func:`load` (``optional``, ``emit`` as there).

    >>> as_scene("example").name == as_scene(load("example")).name
    True
    """
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, str | os.PathLike):
        return load(scene, optional=optional, emit=emit)
    raise InputError(f"a scene is a Scene, the path of a TOML scene file or the name of a built-in scene; "
                     f"got {type(scene).__name__}")


def builtin_scenes() -> list[str]:
    """Names of the scenes shipped in the package (``ropemodel/data/*.toml``), without ``.toml``."""
    return sorted(f.name[:-5] for f in resources.files("ropemodel.data").iterdir()
                  if f.name.endswith(".toml") and "[scene]" in f.read_text())


def load(path: str | os.PathLike | None = None, optional: Iterable[str] = (), emit: bool = True,
         values: Mapping | None = None, bare: str = "si", origin: str = "api") -> Scene:
    """Load a scene: a TOML file or a built-in scene, every problem of it named at once.

    Parameters
    ----------
    path : str or Path, optional
        A TOML scene file. ``None`` or ``"example"``: the built-in example (Krauze et al. 2025,
        Fig. 9); the name of a built-in scene (:func:`builtin_scenes`, e.g.
        ``"capstan_li_experiment"``) loads that one when no such file exists.
    optional : iterable of str
        Parameters the scene may leave out (a command that chooses them itself, e.g. sizing).
    emit : bool
        Issue the scene's warnings (unused parameters, values outside the usual range) as
        :class:`SceneWarning`; the command line prints them itself.
    values : dict, optional
        Parameters to set, ``{name: value}``; they replace or complete the file's and are checked
        with them. A value is a number in SI units [N, m, rad, s, ...] (``bare="si"``), a string
        with its unit (``"467 kN"``, ``"16 deg"``) or a pint Quantity.
    bare : {"si", "refuse"}
        What a number without a unit in ``values`` means: SI (Python) or an error for a dimensional
        quantity (the command line's ``--set``). In the file, a dimensional value always needs its unit.
    origin : str
        Where ``values`` came from, as the scene records it (``scene.origin``) and reports show it.

    Returns
    -------
    Scene
        The scene: ``parameters`` (SI floats), ``effects``, ``origin`` of each value, ``unused``
        (valid parameters the chosen effects do not use) and ``warnings``.

    Raises
    ------
    InputError
        Every problem at once, one line each: unreadable file, unknown names (with the nearest
        valid one), a key in the wrong table, missing or bad units, values out of range, missing
        parameters, cross-parameter rules, a given output that disagrees with the model.

    Examples
    --------
    >>> import ropemodel as rm
    >>> scene = rm.load_scene("example", values={"alpha_u": "18 deg"})
    >>> round(scene.parameters["alpha_u"], 6)        # SI inside: rad
    0.314159
    >>> scene.parameters["G_m"]                      # the file says "467 kN"
    467000.0
    >>> rm.load_scene("example", values={"G_m": "300"})
    Traceback (most recent call last):
    ...
    ropemodel.errors.InputError: G_m = 300 has no unit; write e.g. "300 kN"
    """
    name = EXAMPLE if path is None or str(path) == "example" else None
    p = Path(path) if name is None and path is not None else Path(f"{EXAMPLE}.toml")
    stem = p.name[:-5] if p.name.endswith(".toml") else p.name
    if name is None and not p.exists() and str(path) in (stem, p.name) and stem in builtin_scenes():
        name = stem
    if name is not None:
        text = resources.files("ropemodel.data").joinpath(f"{name}.toml").read_text()
        return from_toml(text, f"built-in scene {name}", optional, emit, values, bare, origin)
    try:
        data = p.read_bytes()
    except FileNotFoundError:
        raise InputError(f"scene file not found: {p} (built-in scenes: {', '.join(builtin_scenes())})"
                         f"{suggest(stem, builtin_scenes())}") from None
    except IsADirectoryError:
        raise InputError(f"scene {p} is a directory, not a TOML file") from None
    except OSError as exc:
        raise InputError(f"cannot read scene file {p}: {exc.strerror or exc}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(f"scene file {p} is not UTF-8 text (a binary file, or another encoding): "
                         f"save it as UTF-8 TOML") from None
    return from_toml(text, str(p), optional, emit, values, bare, origin)


def from_toml(text: str, source: str | None = None, optional=(), emit: bool = True, values: Mapping | None = None,
              bare: str = "si", origin: str = "api") -> Scene:
    """Parse and validate a scene from TOML text (see :func:`from_dict`)."""
    if "\x00" in text:
        raise InputError(f"{source or 'scene'} is a binary file, not TOML text")
    text = text.removeprefix("\ufeff")   # the byte-order mark Windows editors write before UTF-8 text
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"invalid TOML in {source or 'scene'}: {exc}") from None
    except RecursionError:  # tomllib parses nested arrays and tables recursively
        raise InputError(f"invalid TOML in {source or 'scene'}: arrays or tables nested too deeply") from None
    scene = from_dict(data, source, optional=optional, emit=False, digest=hashlib.sha256(text.encode()).hexdigest(),
                      values=values, values_bare=bare, values_origin=origin)
    if emit:
        for note in scene.warnings:
            warnings.warn(note, SceneWarning, stacklevel=3)
    return scene


def from_dict(data: dict, source: str | None = None, *, bare: str = "refuse", optional=(), emit: bool = True,
              digest: str | None = None, values: Mapping | None = None, values_bare: str = "si",
              values_origin: str = "api") -> Scene:
    """Validate a scene given as nested dicts (the TOML structure); every problem at once.

    bare: ``"refuse"`` (a file's rule: a dimensional value needs its unit) or ``"si"`` (numbers are
    SI, for scenes built in Python).  optional, emit, values (read with ``values_bare``, from
    ``values_origin``): as in :func:`load`.
    """
    where = f" in {source}" if source else ""
    found = Problems(where)
    notes: list[str] = []
    if not isinstance(data, dict):
        raise InputError(f"a scene is a table of tables, got {type(data).__name__}")
    name, model_name = tables.read_head(data, found)
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in data.items()}
    known = model_name in models()
    effects = resolve_effects(model_name, tables.read_table(data, "effects", found), found) if known else {}
    numerics = tables.read_numerics(model_name, tables.read_table(data, "numerics", found), found) if known else {}
    given = tables.read_table(data, "parameters", found)
    if not known:
        for key in given:   # names can still be checked against every model's quantities
            universe = {n for m in models() for n in all_quantities(m)}
            if key not in universe:
                found.add(f"unknown parameter {key!r}{suggest(key, universe)}")
        found.raise_if_any()
    route, route_values, route_si = tables.read_route(data, effects, given, found, tables.scene_folder(source))
    model = Model(model_name, effects, tables.options(numerics, route, "L_ul" in given))
    params, checks, unused, origin, kept = tables.read_parameters(model, given, bare, found, notes)
    tables.route_parameters(model, route_values, route_si, bare, params, origin, found)
    if values:
        tables.set_values(model, values, values_bare, values_origin, params, origin, unused, found, notes, kept)
    rules = rules_apply.read_rules(data, model, params, origin, given, found)
    filing = read_report(data, found)
    defaults, absent = tables.fill_missing(model, params, origin, tuple(optional), found)
    for problem in model.problems({**kept, **params}):   # an unused value meets the rules too (x_m <= L_u)
        found.add(problem)
    scene = Scene(str(name if name is not None else source or "unnamed"), model_name, effects, params, numerics,
                  source, defaults, unused, checks, absent, tuple(notes), origin, digest,
                  {k: v for k, v in data.items()}, route, rules, filing, kept)
    scene.__dict__["built"] = model
    _verify_checks(scene, found)
    found.raise_if_any()
    if emit:
        for note in scene.warnings:
            warnings.warn(note, SceneWarning, stacklevel=2)
    return scene


def _verify_checks(scene: Scene, found: Problems) -> Problems:
    """Each computed quantity given in the scene against the model's value (to the digits typed).

    Parameters that are missing or were refused enter as NaN, so every check that does not depend on them is still
    verified (a mistake elsewhere does not hide this one); a long route's numbers are derived from its segments."""
    if not scene.checks:
        return found
    model = scene.built
    out = forward_of(model)(**{k: scene.parameters.get(k, math.nan) for k in model.parameters},
                            **model.derive(scene.parameters))
    for name, chk in scene.checks.items():
        got = float(out[name])
        if math.isnan(got) or abs(got - chk.value) <= chk.tolerance + 1e-12 * abs(got):
            continue
        q = model.quantities[name]
        ways = [w for w in _input_variants(model, name)]
        way = (f"to give {name} as an input, choose {' or '.join(ways)}" if ways
               else f"remove {name} from [parameters] or change the inputs it is computed from")
        found.add(f"{name} = {chk.text} disagrees with the value this scene computes, {q.show(got)} "
                  f"({model.equation_of(name).source}, {model.defined_by[name]} = "
                  f"{model.effects[model.defined_by[name]]!r}); {way}")
    return found


def _input_variants(model: Model, name: str) -> list[str]:
    """``effect = 'variant'`` choices under which ``name`` is a parameter instead of computed."""
    effect = model.defined_by[name]
    out = []
    for variant in effects_of(model.name)[effect].variants:
        if variant == model.effects[effect]:
            continue
        trial = Model(model.name, {**model.effects, effect: variant}, model.options)
        if name in trial.parameters:
            out.append(f"{effect} = {variant!r}")
    return out
