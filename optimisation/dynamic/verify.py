"""Every design checked by the hybrid simulator in every case: each of the four manoeuvres with the load at
every candidate position (an independent path).

The NLP integrates the smooth mode only, on its own grid; the hybrid simulator
(:func:`ropemodel.dynamics.simulate`, what ``ropemodel simulate`` runs) integrates the transient from
the scene's numbers with its own integrator, locates every event (slip, stick, the stroke's stops, a
slack element) by root finding, and switches modes.  A design keeps its checks through a manoeuvre when
the simulation stays in the smooth mode from start to end (no event at all) and every check's least
margin over the history (output every :data:`SIM_DT`) is at least 0.  The simulator runs at
``sim_rtol`` = :data:`SIM_RTOL` (its default 1e-8 leaves 3 N between it and the NLP's integration on the
Fig. 9 manoeuvres; 1e-10 leaves 0.2 N, well inside the NLP's back-off of 4.7 N).  Sampling every 1 ms
misses a peak between samples by at most |g''| dt²/8, 0.04 N for the Fig. 9 rope force.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from optimisation.dynamic.manoeuvres import declared, manoeuvre_scene, sides
from optimisation.dynamic.problem import BACKOFF
from optimisation.dynamic.start import DT_DENSE
from optimisation.problem import declaration
from ropemodel.dynamics import simulate

SIM_RTOL = 1e-10
SIM_DT = 1e-3
#: what judged a case (:attr:`Verdict.by`)
SIMULATED, INTEGRATED = "simulation", "the NLP's integration at the same mesh"
#: the largest difference (scaled: 0.05 % of the load's weight for a force, 5 mm of take-up) between the
#: simulator's and the NLP's integration's least margins in the simulated cases that lets :func:`verified` leave
#: the others to the integration: 50 times the integration's back-off :data:`~optimisation.dynamic.problem.BACKOFF`,
#: more than a hundred times what they differ by on the Fig. 9 manoeuvres (0.2 N of ~25 kN, at rtol 1e-10 both,
#: and up to 4 N from reading the integration every 0.01 s)
AGREE = 50 * BACKOFF
#: a case is left to the NLP's integration (:func:`verified`) only where every check keeps at least this scaled
#: margin there (0.5 % of the load's weight for a force, 5 cm of take-up): ten times :data:`AGREE`
EXEMPT = 10 * AGREE


@dataclass
class Verdict:
    """One case simulated at a design: the ``manoeuvre`` ("upward start"), the load's place ``x_m`` [m] and
    ``where`` (readable), whether the NLP integrated it (``in_nlp``); ``ok``; ``failures`` (readable); ``least``
    check → (least margin in the check's own unit, time [s]), ``sides`` check → the value and limit it compares
    there (SI) and ``scaled`` check → its least margin in the NLP's form and scale (comparable between checks);
    ``peaks`` (SI): what the machine's manoeuvres record of a simulation (``peaks(sim)``; a winch's F_C_max,
    F_S_min, take_up_max, dynamic_factor, t_F_C_max)."""

    manoeuvre: str
    x_m: float
    where: str
    in_nlp: bool
    ok: bool
    failures: list = field(default_factory=list)
    least: dict = field(default_factory=dict)
    scaled: dict = field(default_factory=dict)
    peaks: dict = field(default_factory=dict)
    sides: dict = field(default_factory=dict)
    #: peak → ``max`` or ``min``, which of two values is the worse (the machine's ``PEAKS``)
    worst: dict = field(default_factory=dict, repr=False)
    #: (effect, its modes) of each part of the simulated transient (empty: not simulated)
    parts: tuple = field(default=(), repr=False)
    #: what judged the case: :data:`SIMULATED` or :data:`INTEGRATED`
    by: str = SIMULATED

    def to_dict(self) -> dict:
        return {"manoeuvre": self.manoeuvre, "x_m": self.x_m, "where": self.where, "in_nlp": self.in_nlp,
                "ok": self.ok, "failures": self.failures, "judged_by": self.by,
                "least_margins": {k: {"margin": v, "t": t, **self.sides.get(k, {})}
                                  for k, (v, t) in self.least.items()},
                "peaks": self.peaks}


def simulation_scene(scene, manoeuvre, design: dict, values: dict | None = None):
    """The scene of one manoeuvre at ``design`` (SI), with the simulator at :data:`SIM_RTOL`, :data:`SIM_DT`."""
    sizing = declaration(scene)
    sc = manoeuvre_scene(scene, manoeuvre, design, tuple(sizing.VARIABLES) + tuple(sizing.D_OPTIONAL))
    if values:
        sc = sc.with_values(values)
    return dataclasses.replace(sc, numerics={**sc.numerics, "sim_rtol": SIM_RTOL, "sim_dt": SIM_DT})


def verify(problem, xs, values: dict | None = None, which=None) -> list[Verdict]:
    """Simulate every case of ``problem`` (each manoeuvre, the load at each candidate position; ``which``: these
    indices only) at scaled design ``xs`` (``values``: SI parameters that replace the scene's) and judge every
    check (:data:`~ropemodel.machines.winch.manoeuvres.CHECKS`)."""
    design = problem.to_si(xs)
    p = problem.p_of(values or {})
    a = {k: float(v) for k, v in problem.values(np.asarray(xs, float) * problem.x_scale, p).items()}
    which = range(len(problem.cases)) if which is None else which
    return [verdict(simulate(simulation_scene(problem.scene, problem.cases[i], design, values)), problem.cases[i], a,
                    problem.F_ref, i in problem.selected) for i in which]


def verdict(sim, manoeuvre, a: dict, F_ref: float, in_nlp: bool = True) -> Verdict:
    """The checks of one simulated case (``a``: the values the checks read, the machine's ``values``; ``F_ref``
    [N]: the NLP's scale of a force), on the series the machine's manoeuvres take from the simulation
    (``series(sim)``)."""
    h = sim.history
    out = Verdict(manoeuvre.label, manoeuvre.x_m, manoeuvre.where, in_nlp, True)
    machine = declared(sim.scene)
    for ev in sim.events:
        if ev.name in machine.EVENTS:     # an event that leaves the smooth mode
            out.failures.append(f"{ev.name} at t = {ev.t:.4f} s")
    smooth = sim.system.smooth_mode()
    for part in sim.system.parts:
        if part.column and (h[part.column] != smooth[part.effect]).any():
            out.failures.append(f"{part.column} leaves the {smooth[part.effect]} mode")
    t = h["t [s]"].to_numpy()
    o = machine.series(sim)
    for c in (c for c in machine.CHECKS if c.needs in o):
        name, series = c.name, np.asarray(c.margin(o, a), float).ravel()
        i = int(np.argmin(series))
        out.least[name] = (float(series[i]), float(t[i]))
        out.sides[name] = sides(machine, name, o, a, i)
        out.scaled[name] = float(np.min(np.asarray(c.nlp(o, a), float))) / (F_ref if c.unit == "N" else 1.0)
        if series[i] < 0:
            out.failures.append(f"{name} {series[i]:.6g} at t = {t[i]:.4f} s")
    out.peaks, out.worst = machine.peaks(sim), dict(machine.PEAKS)
    out.parts = tuple((part.effect, tuple(part.modes())) for part in sim.system.parts)
    out.ok = not out.failures
    return out


def to_simulate(integ: list[Verdict]) -> list[int]:
    """The cases (indices) the hybrid simulator judges in :func:`verified`, from ``integ`` (every case as the
    NLP integrates it, :func:`integrated`): every case where some check's least scaled margin is below
    :data:`EXEMPT`, and in each manoeuvre its least place (the case of the least scaled margin of any check), so
    that every manoeuvre's transient is simulated at least once and the agreement is measured in each."""
    def least(i: int) -> float:
        return min(integ[i].scaled.values(), default=-np.inf)

    out = {i for i in range(len(integ)) if least(i) < EXEMPT}
    for label in dict.fromkeys(v.manoeuvre for v in integ):
        out.add(min((i for i, v in enumerate(integ) if v.manoeuvre == label), key=least))
    return sorted(out)


def disagreement(simulated: list[Verdict], integ: list[Verdict]) -> float:
    """The largest difference (scaled) between the least margin of a check in a case as the hybrid simulator
    judges it and as the NLP integrates it (``integ``: the same cases, in the same order)."""
    return max((abs(s.scaled[c] - v.scaled[c]) for s, v in zip(simulated, integ) for c in s.scaled if c in v.scaled),
               default=np.inf)


def verified(problem, xs) -> list[Verdict]:
    """Every case of ``problem`` at scaled design ``xs`` judged, the cases within reach of a limit by the hybrid
    simulator (:func:`verify`), the others by the NLP's own integration at the same mesh and tolerance
    (:func:`integrated` every :data:`~optimisation.dynamic.start.DT_DENSE`: a check's least value between
    samples missed by at most |g''| dt²/8, 4 N for the Fig. 9 rope force, far inside :data:`EXEMPT`), each
    verdict saying which (``by``).

    Every case is integrated by the NLP's integrator first (a fraction of one simulation each: no events, no
    history).  The simulator then judges every case where some check's least scaled margin is within
    :data:`EXEMPT` of its limit, and each manoeuvre's least place (:func:`to_simulate`).  A case is left to
    the integration only when (1) every check keeps at least :data:`EXEMPT` there, (2) the two agree in every
    simulated case to within :data:`AGREE` on every check's least margin (one tenth of what the cases left out
    keep), and (3) every part of the transient that can leave its smooth mode is one a check keeps in it (the
    machine's ``CHECKED_MODES``: with the margins kept, the simulation stays in the smooth mode the NLP
    integrates).  Else every case is simulated.  The peaks (the machine's ``PEAKS``) of a case left to the
    integration are read from it (every DT_DENSE: a peak between samples missed by a few N).  A check's least place
    in a manoeuvre is not simulated for its own sake: where it keeps :data:`EXEMPT`, ten times the disagreement
    :data:`AGREE` the simulated cases must show, the integration decides it (measured on the three-segment route's
    catalogue design: 6 of its 36 cases simulated in 34 CPU-s, against 23 in 102 CPU-s when each check's least
    place was; 3 of the 6 are within EXEMPT)."""
    integ = integrated(problem, xs, DT_DENSE)
    first = to_simulate(integ)
    simulated = dict(zip(first, verify(problem, xs, which=first)))
    parts = next(iter(simulated.values())).parts if simulated else ()
    kept = set(getattr(declared(problem.scene), "CHECKED_MODES", ()))
    trusted = (disagreement(list(simulated.values()), [integ[i] for i in first]) <= AGREE
               and all(len(modes) == 1 or effect in kept for effect, modes in parts))
    rest = [i for i in range(len(problem.cases)) if i not in simulated]
    if not trusted:
        simulated.update(zip(rest, verify(problem, xs, which=rest)))
    return [simulated.get(i, integ[i]) for i in range(len(problem.cases))]


def integrated(problem, xs, dt: float) -> list[Verdict]:
    """Every case of ``problem`` at scaled design ``xs`` as the sizing NLP integrates it (its own integrator at
    its own mesh, read every ``dt`` [s] and at each phase's ends; no simulator, no events; the peaks the machine
    reads of an integration, ``integration_peaks``): the record
    of a design the answer reports but does not return, the continuous optimum, whose checks the NLP already
    holds between its grid points (:mod:`optimisation.dynamic.refine`) — the hybrid simulator verifies the
    catalogue design the answer returns, the same NLP's work one catalogue size up."""
    machine = declared(problem.scene)
    p = problem.p0
    a = {k: float(v) for k, v in problem.values(np.asarray(xs, float) * problem.x_scale, p).items()}
    out = []
    for i, (m, path) in enumerate(zip(problem.cases, problem.all_paths)):
        pp = problem.pp0(path, xs, p)
        t, o, _ = path.samples(pp, path.uniform_grid(pp, dt))
        # a tension's least over the elements (an inextensible rope has none: no tension to check through a manoeuvre)
        o = {k: np.min(np.atleast_2d(v), axis=0) for k, v in o.items() if np.size(v)}
        v = Verdict(m.label, m.x_m, m.where, i in problem.selected, True, by=INTEGRATED)
        for c in path.checks:
            series = np.asarray(c.margin(o, a), float).ravel()
            j = int(np.argmin(series))
            v.least[c.name] = (float(series[j]), float(t[j]))
            v.sides[c.name] = sides(machine, c.name, o, a, j)
            v.scaled[c.name] = float(np.min(np.asarray(c.nlp(o, a), float))) / (problem.F_ref if c.unit == "N" else 1.0)
            if series[j] < 0:
                v.failures.append(f"{c.name} {series[j]:.6g} at t = {t[j]:.4f} s")
        if (peaks_of := getattr(machine, "integration_peaks", None)) is not None:
            v.peaks, v.worst = peaks_of(problem, m, xs, p, t, o), dict(machine.PEAKS)
        v.ok = not v.failures
        out.append(v)
    return out


def all_ok(verdicts) -> bool:
    return all(v.ok for v in verdicts)


def by_manoeuvre(verdicts) -> list[dict]:
    """Each manoeuvre over every place of the load: ``ok``, where it is governed (``x_m`` [m], ``where``: the
    place of the least scaled margin of any check), each check's least margin with its instant and place and
    the value and limit it compares there (``least_margins``), the worst peaks (each of the machine's ``PEAKS``
    the largest or the least, with its ``x_m``), the ``failures`` (with their place) and every case
    (``positions``)."""
    out = []
    for label in dict.fromkeys(v.manoeuvre for v in verdicts):
        mine = [v for v in verdicts if v.manoeuvre == label]
        worst = min(mine, key=lambda v: min(v.scaled.values(), default=np.inf))
        least = {}
        for name in dict.fromkeys(k for v in mine for k in v.least):
            v = min((v for v in mine if name in v.least), key=lambda v: v.least[name][0])
            least[name] = {"margin": v.least[name][0], "t": v.least[name][1], "x_m": v.x_m, "where": v.where,
                           **v.sides.get(name, {})}
        peaks, seen = {}, [v for v in mine if v.peaks]       # those with peaks
        for key, pick in (seen[0].worst if seen else {}).items():
            v = pick(seen, key=lambda v: v.peaks[key])
            peaks[key], peaks[f"x_m_{key}"] = v.peaks[key], v.x_m
        out.append({"manoeuvre": label, "ok": all(v.ok for v in mine), "x_m": worst.x_m, "where": worst.where,
                    "least_margins": least, "peaks": peaks,
                    "failures": [f"{f} ({v.where})" for v in mine for f in v.failures],
                    "positions": [v.to_dict() for v in mine]})
    return out
