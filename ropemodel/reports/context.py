"""What a report knows about its scene: the scene, and each analysis computed once, when a section asks.

An analysis that fails (a :class:`~ropemodel.errors.RopeModelError`: no valid solution, an
infeasible design, a transient the scene cannot run) fails every section that asks for it with
the same error; the page shows the error in those sections (see :mod:`ropemodel.reports.build`).
"""

from __future__ import annotations

import functools
from datetime import datetime, UTC

from ropemodel.errors import RopeModelError, SolveError
from ropemodel.scene import Scene, SceneLike
from ropemodel.machines import machine_of


def once(fn):
    """A read-only property computed on first use; its value, or the RopeModelError it raised, is kept."""
    name = fn.__name__

    @functools.wraps(fn)
    def get(self):
        kept = self.__dict__.setdefault("_once", {})
        if name not in kept:
            try:
                kept[name] = (True, fn(self))
            except RopeModelError as exc:
                kept[name] = (False, exc)
        ok, value = kept[name]
        if not ok:
            raise value
        return value

    return property(get)


def sizes(scene: Scene) -> bool:
    """True for a scene the report sizes: its machine declares a sizing, and the sizing says the report sizes the
    scene (its ``reported``: a winch with a catalogue rope, ``rope`` not ``"given"``; a Koepe without a transient,
    since sizing through one simulates every trial design: ``ropemodel size`` does it)."""
    sizing = getattr(machine_of(scene), "sizing", None)
    return sizing is not None and sizing.reported(scene)


class Context:
    """The scene of a report and its analyses.

    Attributes
    ----------
    scene: the scene as loaded (a sizing scene as sizing reads it: design checks on).
    sizing: True when the report sizes the scene (:func:`sizes`).
    method: how sizing picks the catalogue diameter (``optimisation.design``).
    created: when the report was made (UTC).
    """

    def __init__(self, scene: Scene, sizing: bool | None = None, method: str | None = None,
                 created: datetime | None = None):
        self.scene = scene
        self.sizing = sizes(scene) if sizing is None else sizing
        self.method = method
        self.created = created or datetime.now(UTC).replace(microsecond=0)

    @once
    def design(self):
        """The sizing (``optimisation.design.Design``) of a sizing scene, else None; through the four manoeuvres
        (``optimisation.dynamic.DynamicDesign``) when the scene asks for it (``[numerics] sizing = "dynamic"``)."""
        if not self.sizing:
            return None
        if self.scene.numerics.get("sizing") == "dynamic":
            from optimisation.dynamic import size_dynamic

            return size_dynamic(self.scene)
        from optimisation.design import DEFAULT_DISCRETE, size

        return size(self.scene, method=self.method or DEFAULT_DISCRETE, with_sensitivities=False)

    @once
    def point(self) -> Scene:
        """The scene whose values the results, equations and checks are at: the scene itself when it
        gives every parameter, else (a sizing scene that leaves the design to the sizing) the scene
        at the recommended design."""
        if not self.scene.absent:
            return self.scene
        design = self.design
        if design is None or not design.feasible:
            raise SolveError(f"the scene leaves {', '.join(self.scene.absent)} to the sizing, and the sizing "
                             "found no design: there are no values to report (see the sizing section)")
        values = dict(design.design)
        if design.least_drum is not None:
            values["D"] = design.least_drum
        return self.scene.with_values(values, origin="sizing")

    @property
    def at_design(self) -> bool:
        """True when :attr:`point` is the recommended design rather than the scene's own values."""
        return bool(self.scene.absent)

    @once
    def result(self):
        """The forward solve (:class:`~ropemodel.result.Result`) at :attr:`point`: each result at its worst over
        the load's places and the manoeuvres the scene leaves open (:func:`ropemodel.envelope.run`)."""
        from ropemodel.envelope import run

        return run(self.point)

    @once
    def simulation(self):
        """The transient (``ropemodel.dynamics.simulate``) at :attr:`point`."""
        from ropemodel.dynamics import simulate

        return simulate(self.point)

    @once
    def trips(self) -> dict:
        """The whole trip up and down (``ropemodel.trips``) at :attr:`point`: direction → Trip."""
        from ropemodel.trips import prepare, trip

        scene = prepare(self.point)
        return {d: trip(scene, d) for d in ("up", "down")}

    @once
    def reads(self) -> frozenset[str]:
        """The parameters the report's numbers are computed from: every input of the equations it shows, and
        what each section that applies computes from beyond them (:attr:`Section.reads
        <ropemodel.reports.registry.Section.reads>`: a trip, the sizing, a transient)."""
        from ropemodel.reports.registry import sections

        out = set(self.scene.built.inputs_of())
        for s in sections():
            if s.reads is not None and s.applies(self):
                out |= s.reads(self)
        return frozenset(out)

    @property
    def quantities(self) -> dict:
        return self.scene.built.quantities


def load(scene: SceneLike, values: dict | None = None, origin: str = "--set", bare: str = "refuse",
         method: str | None = None) -> Context:
    """The context of a report on ``scene`` (a :class:`~ropemodel.scene.Scene`, a file or a built-in scene's
    name) with ``values`` on top: every problem of the file and of ``values`` in one
    :class:`~ropemodel.errors.InputError`.  A sizing scene (:func:`sizes`) is read as ``ropemodel size``
    reads it (d, F_nwl, stroke and, on a drum without a compliant lining, D may be left out; design
    checks on); any other scene must give every parameter."""
    from optimisation.problem import D_OPTIONAL, SIZED, prepare
    from ropemodel.scene import load as load_scene

    if isinstance(scene, Scene):
        read = scene.with_values(values, bare=bare, origin=origin) if values else scene
    else:
        read = load_scene(scene, optional=SIZED + D_OPTIONAL, emit=False, values=values, bare=bare, origin=origin)
    if sizes(read):
        return Context(prepare(read), True, method)
    if read.absent:   # what sizing may leave out, any other scene must give: the scene's own error list
        read = read.with_effects({})
    return Context(read, False, method)
