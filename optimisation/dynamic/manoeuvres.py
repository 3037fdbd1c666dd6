"""The manoeuvres of dynamic sizing, where the load is in each, and the checks made through them.

The scene's machine declares its manoeuvres (``Machine.manoeuvres``: a winch's
:mod:`ropemodel.machines.winch.manoeuvres`): ``ORDER``, the (``dynamics``, ``travel``) of each;
``CHECKS``, the checks through them (each ≥ 0 at every instant); and ``SIDES``, what each check compares (the
value and limit the output shows, :func:`sides`).  Each manoeuvre is the scene's transient with
those two effects set, and it can happen with the load anywhere on the route: a *case* (:class:`Manoeuvre`) is
one manoeuvre with the load at one candidate position (:mod:`.positions`: each segment's ends and middle, or the
scene's ``x_m``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from optimisation.dynamic.positions import Position, candidates
from ropemodel.machines.base import needing

WORDS = {"up": "upward", "down": "downward"}


@dataclass(frozen=True)
class Manoeuvre:
    """One case: ``dynamics`` ("start"/"stop"), ``travel`` ("up"/"down") and where the load is
    (``position``)."""

    dynamics: str
    travel: str
    position: Position

    @property
    def x_m(self) -> float:
        return self.position.x_m

    @property
    def label(self) -> str:
        """``"upward start"``, ``"downward stop"``, ..."""
        return f"{WORDS[self.travel]} {self.dynamics}"

    @property
    def where(self) -> str:
        """Where the load is, and which place that is (for the output)."""
        return self.position.where

    @property
    def tag(self) -> str:
        """The manoeuvre and the load's place, as the NLP's constraints name it: ``"upward start, x_m = 950 m"``."""
        return f"{self.label}, x_m = {self.position.shown} m"

    def to_dict(self) -> dict:
        return {"dynamics": self.dynamics, "travel": self.travel, "x_m": self.x_m, "where": self.position.text}


def declared(scene):
    """The manoeuvres ``scene``'s machine declares (``ORDER``, ``CHECKS``, ``CHECK``, ``SIDES``, ``EVENTS``,
    ``values``)."""
    return needing("manoeuvres", scene, "dynamic sizing")


def cases(scene) -> list[Manoeuvre]:
    """Every case of ``scene``: its machine's manoeuvres in their order, each with the load at every candidate
    position (:func:`~optimisation.dynamic.positions.candidates`)."""
    places = candidates(scene)
    return [Manoeuvre(dynamics, travel, at) for dynamics, travel in declared(scene).ORDER for at in places]


def manoeuvre_scene(scene, manoeuvre: Manoeuvre, design: dict, optional=()):
    """The scene of one case at the SI ``design`` (numbers for the transient's structure and scales; the NLP
    makes them symbols), with what the machine fills in where the scene leaves a dimension out
    (its manoeuvres' ``completed``)."""
    # t_end: when dynamic sizing chose it, it is an override of the file, set again by with_effects
    sc = scene.with_effects({"dynamics": manoeuvre.dynamics, "travel": manoeuvre.travel},
                            optional=(*optional, "t_end"))
    values = {"x_m": manoeuvre.x_m, **design}
    values.update(declared(sc).completed(sc, design))
    return sc.with_values(values)


def sides(declared_manoeuvres, name: str, o: dict, a: dict, i: int) -> dict:
    """``{"value", "limit"}`` of check ``name`` at sample ``i`` of the series ``o`` (SI), from the ``SIDES`` the
    machine's manoeuvres declare (what each check compares: the force or take-up judged and its limit, from the
    same ``o`` and ``a`` as its margin); {} for a check that declares none."""
    if name not in getattr(declared_manoeuvres, "SIDES", {}):
        return {}
    at = {k: float(np.asarray(v, float).ravel()[i]) for k, v in o.items()}
    value, limit = declared_manoeuvres.SIDES[name]
    return {"value": float(value(at, a)), "limit": float(limit(at, a))}
