"""What a command does not read of the values a scene was given on top of its file (``--set``, ``values=``,
:meth:`~ropemodel.scene.Scene.with_values`): a value it sets itself (the sizing's d, a trip's load position)
or one none of its results depends on.  The command line warns of each (``ropemodel.cli._common.warn_unread``);
each command says what it reads (e.g. :func:`ropemodel.trips.reads`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ropemodel.scene import Scene


def unread(scene: Scene, reads: Iterable[str], chosen: Mapping[str, str] | None = None) -> dict[str, str]:
    """The values given on top of the scene's file (``--set``, ``values=``, :meth:`Scene.with_values`) that a
    command does not use, each with why: those in ``chosen`` it sets itself (name → how), the others are not
    in ``reads``, the parameters its results are computed from.  A value the scene's effects do not use at
    all is the scene's own warning (``unused``), not named here."""
    chosen, reads = dict(chosen or {}), set(reads)
    out = {}
    for values in scene.overrides().values():
        for name in values:
            if name in scene.parameters and (name in chosen or name not in reads):
                out[name] = chosen.get(name, "none of its results depends on it")
    return out


def not_read(scene: Scene, reads: Iterable[str], command: str, chosen: Mapping[str, str] | None = None) -> list[str]:
    """One warning line for each value of :func:`unread`, naming the value, where it came from and ``command``.

    >>> from ropemodel.scene import load
    >>> scene = load("winch_start", values={"t_ramp": "8 s"}, emit=False)
    >>> not_read(scene, scene.built.inputs_of(), "run")
    ['t_ramp = 8 s (api) does not change what run computes: none of its results depends on it']
    """
    q = scene.built.quantities
    return [f"{name} = {q[name].show(scene.parameters[name])} ({scene.origin.get(name, 'api')}) does not change what "
            f"{command} computes: {why}" for name, why in unread(scene, reads, chosen).items()]
