"""Assemble the transient of a scene from the variants it picks, asking the effect registry.

The scene's variants that are :class:`~ropemodel.effects.transient.base.TransientSubmodel` make up the
transient, in their assembly order, and the scene's machine declares the rest
(:class:`ropemodel.machines.Transient`: which variant makes a transient, how the static values are taken,
the switching functions' scales); every chosen submodel (static ones too, e.g. the drum's lining)
is handed to them in the :class:`~ropemodel.effects.transient.base.Setup`.  The static model
(:func:`ropemodel.problem.run`) gives the values the transient starts from: the scene's parameters and
the static forces of both directions (the resistance coefficients of the scene's ``resistance`` case,
the catalogue rope's q_l and q_lw, ...).
"""

from __future__ import annotations

from ropemodel.dynamics.system import TransientSystem
from ropemodel.effects import effects_of
from ropemodel.effects.transient.base import Setup, TransientSubmodel
from ropemodel.errors import InputError
from ropemodel.machines import Transient
from ropemodel.machines.base import needing
from ropemodel.problem import run


def chosen(scene) -> dict:
    """Effect → a fresh instance of the scene's variant (the registry's classes)."""
    specs, options = effects_of(scene.model), scene.built.options
    return {effect: specs[effect].variants[variant](options, scene.effects)
            for effect, variant in scene.effects.items()}


def declared(scene) -> Transient:
    """The transient ``scene``'s machine declares; :class:`InputError` for a machine without one."""
    return needing("transient", scene, "a transient")


def transient_parts(scene, submodels: dict) -> list[TransientSubmodel]:
    """The scene's transient variants in assembly order; :class:`InputError` for a scene without a transient."""
    profile = declared(scene).profile
    parts = sorted((sm for sm in submodels.values() if isinstance(sm, TransientSubmodel)), key=lambda p: p.order)
    if not any(isinstance(p, profile) for p in parts):
        raise InputError(f"scene {scene.name!r} has no transient: {_how_to_choose(scene.model, profile)}")
    return parts


def structural(submodels: dict) -> set[str]:
    """Parameters that fix the structure of the transient and must stay numbers: every transient variant's
    ``structural`` and the geometry another chosen submodel hands the transient as numbers (its
    ``transient_structural``: a route's segment lengths)."""
    out: set[str] = set()
    for sm in submodels.values():
        out.update(sm.structural if isinstance(sm, TransientSubmodel) else getattr(sm, "transient_structural", ()))
    return out


def _how_to_choose(model: str, profile: type) -> str:
    """How to give a scene of ``model`` a transient: the variants that are a ``profile``."""
    for effect, spec in effects_of(model).items():
        names = [v for v, cls in spec.variants.items() if issubclass(cls, profile)]
        if names:
            return f"set [effects] {effect} = " + " or ".join(f'"{n}"' for n in names) + f" (model {model})"
    return f"model {model} has no transients"


def bind(setup: Setup, parts, transient: Transient) -> TransientSystem:
    """Bind every variant to ``setup`` in assembly order, set the switching functions' scales (before the
    binding where the machine declares so), and return the assembled system."""
    if transient.before_bind:
        setup.v_scale, setup.f_scale = transient.scale(setup)
    for p in parts:
        p.bind(setup)
    if not transient.before_bind:
        setup.v_scale, setup.f_scale = transient.scale(setup)
    return TransientSystem(setup, parts)


def build(scene) -> TransientSystem:
    """The transient system of ``scene`` at its numbers (static values from :func:`ropemodel.problem.run`)."""
    transient = declared(scene)
    submodels = chosen(scene)
    parts = transient_parts(scene, submodels)
    values = transient.numbers(run(scene).values)
    setup = Setup(values, dict(values), dict(scene.numerics), {p.effect: p for p in parts}, submodels)
    return bind(setup, parts, transient)
