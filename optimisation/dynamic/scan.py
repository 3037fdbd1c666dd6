"""A scan of the design box behind a "no design" verdict: every catalogue diameter × a grid of pretensions,
every check through every case, so that "no design" is not only the local verdict of IPOPT and the
least-violation problem (:mod:`optimisation.dynamic.diagnose`).

The box is the one the scene's machine declares (its manoeuvres' ``BOX``, a
:class:`~ropemodel.machines.base.DesignBox`; a winch's: :data:`ropemodel.machines.winch.manoeuvres.BOX`), by the
names of the design variables:

* the catalogue variable (the rope diameter): every catalogue diameter within the sizing bounds (the answer is a
  catalogue size; the continuous optimum lies between two of them);
* the grid variable (a winch's pretension): :data:`POINTS` values evenly from 0 to a top at which the static checks
  fail for every catalogue diameter (found by doubling from the declaration's ``top``, and checked there);
* the held variables (a winch's stroke): one value each, one every check only gains from, so that a point without a
  design there has none at any smaller value (the declaration says why).

Each point is judged as the NLP judges a design (its scaled margins, before the back-off): the static checks
(one vectorised call for the whole grid), then, where they hold, each case's checks on the NLP's integrator at
:data:`~optimisation.dynamic.start.DT_DENSE` — the cases the NLP integrates first, stopping at the first
case that fails.  Dynamic sizing scans before it starts the NLP
(:func:`optimisation.dynamic.design.continuous_optimum`), from the start outwards, to the first point that keeps
every check: a design exists, and the NLP has one more start (the first point tried on the shipped scene with a
4 s ramp, 0.35 CPU-s).  None keeps every check: the scan was complete, backs the "no design" verdict, and its
points that failed by least start the least-violation problem (:func:`optimisation.dynamic.diagnose.diagnose_dynamic`;
a whole scan with no design, 6 CPU-s on the test scene with a 2 s ramp: 178 of 1920 points keep the static checks,
most fail in the first case integrated).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from optimisation.dynamic.screen import least_margins
from optimisation.dynamic.start import DT_DENSE
from ropemodel.papers import en12385 as ropes
from ropemodel.units import factor

#: values of the grid variable (a winch's pretension) per catalogue diameter
POINTS = 64
#: doublings of F_top at most
DOUBLINGS = 12


@dataclass
class Scan:
    """What a scan of the design box did: its axes (``d`` [m], the catalogue variable's; ``grid``: the grid
    variable's values, ``held``: the held variables' values, both SI), how many points kept the static checks and
    were integrated (``unintegrable``: where the integrator failed), the designs it found (scaled, in the order
    tried; ``first``: it stopped at the first), the points that failed (``failed``: with the margin they failed by),
    the cases per point, the time step [s] and the CPU seconds it took; ``names``: the catalogue and the grid
    variable's names; ``quantities``: the design variables' declarations (their units and words)."""

    d: list[float]
    grid: list[float]
    held: dict
    cases: int
    dt: float
    names: tuple[str, str] = ("", "")
    quantities: dict = field(default_factory=dict, repr=False)
    static_ok: int = 0
    integrated: int = 0
    unintegrable: int = 0
    designs: list = field(default_factory=list)
    seconds: float = 0.0
    #: (the least scaled margin of the case that stopped it, scaled design) of each point integrated without a design
    failed: list = field(default_factory=list, repr=False)
    first: bool = False

    def least_violated(self, k: int) -> list[np.ndarray]:
        """The ``k`` points (scaled) that failed by the least margin in the case that stopped them: starts of the
        least-violation problem near its optimum."""
        return [x for _, x in sorted(self.failed, key=lambda f: -f[0])[:k]]

    @property
    def points(self) -> int:
        return len(self.d) * len(self.grid)

    def text(self) -> str:
        """One sentence: how fine the scan was and what it found (each variable by its name, in its display
        unit)."""
        step = self.grid[1] - self.grid[0] if len(self.grid) > 1 else 0.0
        name = self.names[1]
        unit, k = self._display(name)
        held = ", ".join(f"{h} = {v:g} {self._unit(h)}" for h, v in self.held.items())
        found = ("none keeps every check through the manoeuvres" if not self.designs else
                 "the first point found keeps every check" if self.first else f"{len(self.designs)} keep every check")
        return (f"a scan of the design box backs this: {len(self.d)} catalogue diameters "
                f"{self.d[0] * 1e3:g}-{self.d[-1] * 1e3:g} mm x {len(self.grid)} values of {name} 0-"
                f"{self.grid[-1] * k:.4g} {unit} (every {step * k:.4g} {unit}), {held} "
                f"(every check gains from more), {self.cases} cases (each manoeuvre at each place "
                f"of the load) on a {self.dt:g} s grid: {self.points} points, {self.static_ok} keep the static checks, "
                f"{found}{self._failed()}")

    def _unit(self, name: str) -> str:
        q = self.quantities.get(name)
        return q.unit if q is not None else "SI"

    def _display(self, name: str) -> tuple[str, float]:
        """(display unit, factor from SI) of design variable ``name``."""
        q = self.quantities.get(name)
        if q is None or not q.display:
            return self._unit(name), 1.0
        return q.display, factor(q.unit, q.display)

    def _failed(self) -> str:
        return f" ({self.unintegrable} could not be integrated to the NLP's tolerance)" if self.unintegrable else ""

    def to_dict(self) -> dict:
        catalogue, grid = self.names
        return {f"{catalogue} [m]": self.d, f"{grid} [{self._unit(grid)}]": self.grid,
                **{f"{h} [{self._unit(h)}]": v for h, v in self.held.items()}, "points": self.points,
                "cases": self.cases, "dt [s]": self.dt, "static_ok": self.static_ok, "integrated": self.integrated,
                "unintegrable": self.unintegrable,
                "designs_found": len(self.designs), "cpu_seconds": self.seconds}


def _static_ok(problem, X: np.ndarray, p) -> np.ndarray:
    """Whether each column of scaled designs ``X`` keeps every static check."""
    g = ca.Function("g_static", [problem.xs, problem.p], [problem.g_static])
    G = np.asarray(g.map(X.shape[1])(X, ca.repmat(ca.DM(p), 1, X.shape[1])))
    return np.all(G >= 0.0, axis=0)


def _point(problem, box, catalogue: float, grid: float) -> np.ndarray:
    """The scaled design with the catalogue and grid variables at these SI values, the held ones at theirs."""
    at = {**box.held, box.catalogue: catalogue, box.grid: grid}
    return np.array([at[v] for v in problem.variables]) / problem.x_scale


def _axes(problem, box, p):
    """The catalogue diameters in the box and the grid variable's axis, SI (see the module)."""
    lbx, ubx = problem.bounds()
    i = problem.variables.index(box.catalogue)
    lo, hi = lbx[i] * problem.x_scale[i], ubx[i] * problem.x_scale[i]
    d = [x for x in ropes.diameters() if lo - 1e-12 <= x <= hi + 1e-12]
    top = box.top(problem, _point(problem, box, d[-1], 0.0), p)
    for _ in range(DOUBLINGS):
        X = np.array([_point(problem, box, x, top) for x in d]).T
        if not _static_ok(problem, X, p).any():
            break
        top *= 2.0
    return d, [float(f) for f in np.linspace(0.0, top, POINTS)]


def _keeps(problem, xs, p, a_of, order) -> float | None:
    """The least scaled margin of the first case in which scaled design ``xs`` fails a check (stops there), 0.0
    when it keeps every check through every case; None when the integrator fails there (cvodes cannot meet its
    tolerance: no design the NLP could solve from)."""
    a = a_of(xs)
    for i in order:
        try:
            least = min(least_margins(problem, problem.all_paths[i], xs, p, a).values())
        except RuntimeError:
            return None
        if least < 0.0:
            return least
    return 0.0


def _order(problem, box, X: np.ndarray, points: np.ndarray, near) -> np.ndarray:
    """``points`` (columns of ``X``) nearest the scaled design ``near`` first, by grid steps of the catalogue and the
    grid variable (as given when ``near`` is None)."""
    if near is None:
        return points
    steps = []
    for name in (box.catalogue, box.grid):
        i = problem.variables.index(name)
        axis = np.unique(X[i])
        steps.append(np.abs(np.searchsorted(axis, X[i, points]) - np.searchsorted(axis, near[i])))
    return points[np.argsort(steps[0] + steps[1], kind="stable")]


def scan_box(problem, p=None, first: bool = False, near=None) -> Scan:
    """Scan the design box of ``problem`` (a :class:`~optimisation.dynamic.problem.DynamicSizingProblem`) at
    parameters ``p``: every check at every point (see the module); ``first``: stop at the first design found, enough
    to know a design exists; ``near`` (a scaled design): the points nearest it on the grid first (else the lightest
    first: diameters up, then the grid variable up)."""
    t0 = time.process_time()
    p = problem.p0 if p is None else np.asarray(p, float)
    box = problem.machine.manoeuvres.BOX
    d, grid = _axes(problem, box, p)
    quantities = problem.scene.built.quantities
    scan = Scan(d, grid, dict(box.held), len(problem.cases), DT_DENSE, (box.catalogue, box.grid),
                {k: quantities[k] for k in problem.variables if k in quantities}, first=first)
    X = np.array([_point(problem, box, x, f) for x in d for f in grid]).T
    ok = _static_ok(problem, X, p)
    scan.static_ok = int(ok.sum())
    order = list(problem.selected) + [i for i in range(len(problem.cases)) if i not in problem.selected]

    def a_of(xs):
        return {k: float(v) for k, v in problem.values(xs * problem.x_scale, p).items()}

    for j in _order(problem, box, X, np.flatnonzero(ok), near):
        scan.integrated += 1
        least = _keeps(problem, X[:, j], p, a_of, order)
        scan.unintegrable += least is None
        if least is not None and least < 0.0:
            scan.failed.append((least, X[:, j].copy()))
        elif least is not None:
            scan.designs.append(X[:, j].copy())
            if first:
                break
    scan.seconds = time.process_time() - t0
    return scan
