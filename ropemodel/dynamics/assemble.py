"""Assemble the transient of a scene from the variants it picks, asking the effect registry.

The scene's variants that are :class:`~ropemodel.effects.transient.base.TransientSubmodel` make up the
transient, in their assembly order; every chosen submodel (static ones too, e.g. the drum's lining)
is handed to them in the :class:`~ropemodel.effects.transient.base.Setup`.  The static model
(:func:`ropemodel.problem.run`) gives the values the transient starts from: the scene's parameters and
the static forces of both directions (the resistance coefficients of the scene's ``resistance`` case,
the catalogue rope's q_l and q_lw, ...).
"""

from __future__ import annotations

from ropemodel.dynamics.system import TransientSystem
from ropemodel.effects import effects_of
from ropemodel.effects.transient.base import Setup, TransientSubmodel
from ropemodel.effects.transient.profile import Profile
from ropemodel.errors import InputError
from ropemodel.problem import run


def chosen(scene) -> dict:
    """Effect → a fresh instance of the scene's variant (the registry's classes)."""
    specs, options = effects_of(scene.model), scene.built.options
    return {effect: specs[effect].variants[variant](options, scene.effects)
            for effect, variant in scene.effects.items()}


def transient_parts(scene, submodels: dict) -> list[TransientSubmodel]:
    """The scene's transient variants in assembly order; :class:`InputError` for a scene without a transient."""
    parts = sorted((sm for sm in submodels.values() if isinstance(sm, TransientSubmodel)), key=lambda p: p.order)
    if not any(isinstance(p, Profile) for p in parts):
        raise InputError(f"scene {scene.name!r} has no transient: {_how_to_choose()}")
    return parts


def structural(submodels: dict) -> set[str]:
    """Parameters that fix the structure of the transient and must stay numbers: every transient variant's
    ``structural`` and the geometry another chosen submodel hands the transient as numbers (its
    ``transient_structural``: a route's segment lengths)."""
    out: set[str] = set()
    for sm in submodels.values():
        out.update(sm.structural if isinstance(sm, TransientSubmodel) else getattr(sm, "transient_structural", ()))
    return out


def _how_to_choose() -> str:
    from ropemodel.effects import REGISTRY

    for model, specs in REGISTRY.items():
        for effect, spec in specs.items():
            names = [v for v, cls in spec.variants.items() if issubclass(cls, Profile)]
            if names:
                return f"set [effects] {effect} = " + " or ".join(f'"{n}"' for n in names) + f" (model {model})"
    return "no model has transients"


def bind(setup: Setup, parts) -> TransientSystem:
    """Bind every variant to ``setup`` in assembly order, set the switching functions' scales, and
    return the assembled system."""
    for p in parts:
        p.bind(setup)
    setup.f_scale = max(abs(float(setup.numbers[f"F_C_{setup.travel}"])), 1.0)
    setup.v_scale = max(float(setup.numbers["v_pj"]), 1e-6)
    return TransientSystem(setup, parts)


def build(scene) -> TransientSystem:
    """The transient system of ``scene`` at its numbers (static forces from :func:`ropemodel.problem.run`)."""
    submodels = chosen(scene)
    parts = transient_parts(scene, submodels)
    static = run(scene)
    setup = Setup(dict(static.values), dict(static.values), dict(scene.numerics),
                  {p.effect: p for p in parts}, submodels)
    return bind(setup, parts)
