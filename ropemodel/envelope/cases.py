"""Load cases: where the load is and which manoeuvre the haulage makes, for the worst case of every output.

A winch's forces depend on where the load is (on a route of segments, through the inclination of the
load's segment; the least tension along the winding rope also through its place on the route) and, with
the ramps' inertia (``inertia = "rigid"``), on the haulage's acceleration.  A scene that leaves the load's
place out (``x_m``) or the acceleration (``a_h``) asks for every place and every manoeuvre: each output is
then taken at its own worst (:mod:`ropemodel.envelope.worst`).

Places (docs/physics.md §4).  The forces depend on the load's segment only through its inclination, so one
place per segment would do for them; the least tension of the winding rope also depends on where on its
segment the load is, and it is least with the load at an end of its segment.  The places are therefore the
return-sheave end of each segment j (x_m = L_1 + … + L_j, the load on segment j) and the drive (x_m = 0,
the load on segment 1): n + 1 places for n segments.  On the paper's straight route only the least tension
depends on the place: the drive and the return sheave.  Each place's x_m follows the segments' lengths, so
a sweep or a derivative over L_i moves it.

Manoeuvres (rigid-body inertia, :class:`ropemodel.effects.winch.RigidInertia`): steady motion (a_h = 0);
with ``t_ramp`` a start and a stop anywhere on the route, at the peak acceleration ±k v_pj/t_ramp of the
scene's ramp shape (k = 1 for the linear ramp, π/2 for the cosine one); with ``a_e`` an emergency stop at
−a_e.  Each case holds for both directions of travel: the outputs ``*_up`` are the upward haulage's, the
``*_down`` the downward's, at the same place and acceleration in their own direction of travel.

Survey scale (n in the thousands): each case evaluates the whole model, whose cost grows with n, so the
cases cost O(n²).  :func:`load_cases` lists every place (the envelope of a result evaluates them all in one
vectorised call); an NLP keeps only the places that can govern, found without the model
(:mod:`ropemodel.envelope.prune`); a pruned list is a list of :class:`LoadCase` like it, and every consumer
takes any list.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ropemodel.effects.winch_route import segment_lengths

if TYPE_CHECKING:
    from ropemodel.scene import Scene

#: the manoeuvres, in the order the cases list them
MANOEUVRES = ("steady", "start", "stop", "emergency stop")
#: the inputs a load case sets, and what each means when the scene leaves it open
CASE_INPUTS = ("x_m", "a_h")
OPEN = {"x_m": "every place", "a_h": "every manoeuvre"}
#: the parameters the manoeuvres' accelerations are computed from (besides the segments' lengths)
CASE_READS = ("v_pj", "t_ramp", "a_e")


@dataclass(frozen=True)
class LoadCase:
    """One place of the load and one manoeuvre.

    Attributes
    ----------
    joint: the load at the end of the route's first ``joint`` segments, x_m = L_1 + … + L_joint (0: at the
        drive; on a straight route 1 is the return sheave); None: the scene pins x_m (or has none).
    segment: the load's segment (1 = at the drive), None on a straight route or when x_m is pinned.
    manoeuvre: one of :data:`MANOEUVRES`, or None when the scene pins a_h (or has no inertia).
    ramp: the peak acceleration of the ramp per v_pj/t_ramp (1 for a linear ramp).
    """

    joint: int | None
    segment: int | None
    manoeuvre: str | None
    ramp: float = 1.0

    def values(self, params: Mapping, ends: list | None = None) -> dict:
        """The inputs this case sets, from ``params`` (SI floats, or CasADi symbols): ``x_m`` and ``a_h``.
        ``ends``: :func:`joint_ends` of ``params``, when many cases are evaluated (else computed here)."""
        out = {}
        if self.joint is not None:
            out["x_m"] = (ends or joint_ends(params))[self.joint]
        if self.manoeuvre is not None:
            out["a_h"] = _acceleration(params, self.manoeuvre, self.ramp)
        return out

    def key(self, inputs=CASE_INPUTS) -> tuple:
        """What tells this case from others in ``inputs`` (its place for ``x_m``, its manoeuvre for ``a_h``)."""
        return (self.joint if "x_m" in inputs else None, self.manoeuvre if "a_h" in inputs else None)

    def place(self, params: Mapping, ends: list | None = None) -> str:
        """``segment 2, x_m = 1300 m`` (numbers from ``params``; ``ends`` as in :meth:`values`)."""
        if self.joint is None:
            return ""
        x = f"x_m = {float((ends or joint_ends(params))[self.joint]):g} m"
        return x if self.segment is None else f"segment {self.segment}, {x}"

    def name(self) -> str:
        """The case in words, without numbers: ``segment 2 (its return-sheave end), start``."""
        if self.joint is None:
            place = ""
        elif self.segment is None:
            place = "at the drive" if self.joint == 0 else "at the return sheave"
        else:
            place = f"segment {self.segment} ({'at the drive' if self.joint == 0 else 'its return-sheave end'})"
        return ", ".join(p for p in (place, self.manoeuvre or "") if p)

    def label(self, params: Mapping, inputs=CASE_INPUTS, ends: list | None = None) -> str:
        """The place and the manoeuvre as text: ``segment 2, x_m = 1300 m, start`` (of ``inputs`` only; ``ends``
        as in :meth:`values`)."""
        parts = (self.place(params, ends) if "x_m" in inputs else "", (self.manoeuvre or "") if "a_h" in inputs else "")
        return ", ".join(p for p in parts if p)


def joint_ends(params: Mapping) -> list:
    """[0, L_1, L_1 + L_2, …, L_u]: where each place of the load is, x_m of joint k at index k (summed in order,
    so that each equals the sum a case of one place computes); [0, L_u] on the straight route."""
    out = [0.0]
    for length in segment_lengths(params) or [params["L_u"]]:
        out.append(out[-1] + length)
    return out


def _acceleration(params: Mapping, manoeuvre: str, ramp: float):
    if manoeuvre == "steady":
        return 0.0
    if manoeuvre == "emergency stop":
        return -params["a_e"]
    a = ramp * params["v_pj"] / params["t_ramp"]
    return a if manoeuvre == "start" else -a


#: the effects that give a winch's static forces its ramps: the whole-trip profile and the rigid-body inertia
RAMPS = {"dynamics": "trip", "inertia": "rigid"}


def with_ramps(scene: Scene) -> Scene:
    """The scene with the starts and stops its ``t_ramp`` implies (:data:`RAMPS`): a winch scene that gives
    ``t_ramp`` for no transient of its own (or asks for whole trips) gets the ramps' rigid-body inertia, so
    that its worst case includes them (``size`` has always done so).  Any other scene is returned as it is."""
    if scene.model != "winch" or scene.effects.get("inertia") == "rigid":
        return scene
    if "t_ramp" in scene.unused or scene.effects.get("dynamics") == "trip":
        dynamics = scene.effects.get("dynamics", "none")
        return scene.with_effects({**RAMPS, "dynamics": "trip" if dynamics == "none" else dynamics})
    return scene


def ramp_peak(scene) -> float:
    """The largest acceleration of the scene's ramp shape per v_pj/t_ramp [-]: max df/ds over its pieces
    (1 for the linear ramp, π/2 for the cosine one), sampled finely and at every piece's ends and middle."""
    from ropemodel.effects.base import REGISTRY

    shape: Any = REGISTRY[scene.model]["ramp"].variants[scene.effects.get("ramp", "linear")]()
    peak = 0.0
    for piece in shape.pieces(scene.parameters):
        s = np.linspace(float(piece.s0), float(piece.s1), 2001)
        peak = max(peak, float(np.max(np.asarray(piece.df(s), dtype=float) * np.ones_like(s))))
    return peak


def free(scene) -> tuple[str, ...]:
    """The case inputs the scene leaves free: ``x_m`` not given, ``a_h`` not given (with the ramps' inertia)."""
    params, model = scene.parameters, scene.built
    out = []
    if "x_m" in model.parameters and params.get("x_m", 0.0) == math.inf:
        out.append("x_m")
    if "a_h" in model.parameters and scene.origin.get("a_h") == "default":
        out.append("a_h")
    return tuple(out)


def load_cases(scene, pinned=()) -> list[LoadCase]:
    """Every place and manoeuvre the scene leaves open (see the module docstring); one case when it pins both.
    ``pinned``: case inputs to leave alone (e.g. ``x_m`` when a question solves for it)."""
    params, open_ = scene.parameters, [n for n in free(scene) if n not in pinned]
    places: list[tuple[int | None, int | None]] = [(None, None)]
    if "x_m" in open_:
        n = len(segment_lengths(params))
        segments: list[int | None] = [*range(1, n + 1), 1] if n else [None, None]
        places = list(zip([*range(1, n + 1), 0] if n else [1, 0], segments))
    manoeuvres: list[str | None] = [None]
    ramp = 1.0
    if "a_h" in open_:
        ramps = "t_ramp" in params and "v_pj" in params
        given = {"steady": True, "start": ramps, "stop": ramps, "emergency stop": params.get("a_e", 0.0) > 0.0}
        manoeuvres = [m for m in MANOEUVRES if given[m]]
        ramp = ramp_peak(scene) if ramps else 1.0
    return [LoadCase(j, seg, m, ramp) for j, seg in places for m in manoeuvres]


def reads(scene: Scene) -> set[str]:
    """What the worst case of ``scene`` is computed from besides its equations' inputs: the parameters the open
    manoeuvres' accelerations come from (``v_pj``, ``t_ramp``, ``a_e``) and the open case inputs themselves
    (given, each pins its case: ``x_m`` one place, ``a_h`` one manoeuvre).  Every command that takes the worst
    case reads ``scene.built.inputs_of() | reads(scene)`` (:mod:`ropemodel.unread`)."""
    open_ = free(scene)
    ramps = {k for k in CASE_READS if k in scene.parameters} if "a_h" in open_ else set()
    return ramps | set(open_)


def depends_on(function, outputs, inputs=CASE_INPUTS, follows=None) -> dict[str, tuple[str, ...]]:
    """Output → the case inputs among ``inputs`` it depends on, from ``function``'s structure (a CasADi
    Function with named inputs and outputs); ``follows``: inputs computed per case (a long route's numbers,
    :attr:`ropemodel.core.model.Model.derived`) → the case inputs each follows, counted as theirs."""
    names = set(function.name_in())
    through = {k: [n for n, f in (follows or {}).items() if k in f and n in names] for k in inputs}
    ins = [k for k in inputs if k in names or through[k]]

    def uses(name: str, o: str) -> bool:
        return bool(function.sparsity_jac(function.index_in(name), function.index_out(o)).nnz())

    return {o: tuple(k for k in ins if (k in names and uses(k, o)) or any(uses(n, o) for n in through[k]))
            for o in outputs}


def distinct(cases: list[LoadCase], inputs) -> list[int]:
    """Indices of the first case of each distinct place (if ``x_m`` is in ``inputs``) and manoeuvre (if
    ``a_h`` is): where an output that depends on only these inputs takes each of its values."""
    seen: dict = {}
    for i, c in enumerate(cases):
        seen.setdefault(c.key(inputs), i)
    return list(seen.values())


def describe(cases: list[LoadCase], params: Mapping) -> str:
    """``4 places x 3 manoeuvres (steady, start, stop)`` of a list of cases."""
    places = list(dict.fromkeys(c.joint for c in cases))
    kinds = list(dict.fromkeys(c.manoeuvre for c in cases))
    text = []
    if places != [None]:
        text.append(f"{len(places)} places of the load")
    if kinds != [None]:
        text.append(f"{len(kinds)} manoeuvres ({', '.join(str(k) for k in kinds)})")
    return " x ".join(text) or "one point"
