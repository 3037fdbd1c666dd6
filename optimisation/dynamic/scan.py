"""A scan of the design box behind a "no design" verdict: every catalogue diameter × a grid of pretensions,
every check through every case, so that "no design" is not only the local verdict of IPOPT and the
least-violation problem (:mod:`optimisation.dynamic.diagnose`).

The box and why it is enough, for the design variables the problem declares
(:data:`optimisation.problem.VARIABLES`, the winch's d, F_nwl, stroke), by their place in x:

* the first (d): every catalogue diameter within the sizing bounds (the answer is a catalogue size; the
  continuous optimum lies between two of them);
* the second (the pretension F_nwl): :data:`POINTS` values evenly from 0 to a top at which the static checks
  fail for every catalogue diameter (found by doubling from the thickest rope's F_min / n_rope, and checked
  there);
* the third (the stroke): one value, :data:`HELD` (m).  The smooth mode does not depend on the stroke (only the
  stroke's stops, events that leave it, do) and every check grows with it (the stroke checks are
  stroke − z ≥ 0, eq. (23)), so a point without a design at this stroke has none at any shorter one.

Each point is judged as the NLP judges a design (its scaled margins, before the back-off): the static checks
(one vectorised call for the whole grid), then, where they hold, each case's checks on the NLP's integrator at
:data:`~optimisation.dynamic.start.DT_DENSE` — the cases the NLP integrates first, stopping at the first
case that fails.  A point that keeps every check is a design the local solvers missed: the dynamic NLP is
solved again from the lightest such point (:func:`optimisation.dynamic.diagnose.diagnose_dynamic`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from optimisation.dynamic.screen import least_margins
from optimisation.dynamic.start import DT_DENSE
from optimisation.problem import VARIABLES
from ropemodel.papers import en12385 as ropes
from ropemodel.units import factor

#: values of the second design variable (the pretension) per catalogue diameter
POINTS = 64
#: the third design variable (the stroke, m) at every scan point (see the module: the checks only gain from it)
HELD = 100.0
#: doublings of F_top at most
DOUBLINGS = 12


@dataclass
class Scan:
    """What a scan of the design box did: its axes (``d`` [m]; ``grid``: the second design variable's values,
    ``held``: the third's value, both SI), how many points kept the static checks and were integrated
    (``unintegrable``: where the integrator failed), the designs it found (scaled, lightest first), the cases per
    point, the time step [s] and the CPU seconds it took; ``quantities``: the design variables' declarations
    (their units and words)."""

    d: list[float]
    grid: list[float]
    held: float
    cases: int
    dt: float
    quantities: dict = field(default_factory=dict, repr=False)
    static_ok: int = 0
    integrated: int = 0
    unintegrable: int = 0
    designs: list = field(default_factory=list)
    seconds: float = 0.0

    @property
    def points(self) -> int:
        return len(self.d) * len(self.grid)

    def text(self) -> str:
        """One sentence: how fine the scan was and what it found (each variable by its name, in its display
        unit)."""
        step = self.grid[1] - self.grid[0] if len(self.grid) > 1 else 0.0
        name, held = VARIABLES[1], VARIABLES[2]
        unit, k = self._display(name)
        found = (f"{len(self.designs)} keep every check" if self.designs else "none keeps every check through the "
                 "manoeuvres")
        return (f"a scan of the design box backs this: {len(self.d)} catalogue diameters "
                f"{self.d[0] * 1e3:g}-{self.d[-1] * 1e3:g} mm x {len(self.grid)} values of {name} 0-"
                f"{self.grid[-1] * k:.4g} {unit} (every {step * k:.4g} {unit}), {held} = {self.held:g} "
                f"{self._unit(held)} (every check gains from more), {self.cases} cases (each manoeuvre at each place "
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
        return {f"{VARIABLES[0]} [m]": self.d, f"{VARIABLES[1]} [{self._unit(VARIABLES[1])}]": self.grid,
                f"{VARIABLES[2]} [{self._unit(VARIABLES[2])}]": self.held, "points": self.points,
                "cases": self.cases, "dt [s]": self.dt, "static_ok": self.static_ok, "integrated": self.integrated,
                "unintegrable": self.unintegrable,
                "designs_found": len(self.designs), "cpu_seconds": self.seconds}


def _static_ok(problem, X: np.ndarray, p) -> np.ndarray:
    """Whether each column of scaled designs ``X`` keeps every static check."""
    g = ca.Function("g_static", [problem.xs, problem.p], [problem.g_static])
    G = np.asarray(g.map(X.shape[1])(X, ca.repmat(ca.DM(p), 1, X.shape[1])))
    return np.all(G >= 0.0, axis=0)


def _axes(problem, p):
    """The catalogue diameters in the box and the second design variable's axis, SI (see the module)."""
    lbx, ubx = problem.bounds()
    lo, hi = lbx[0] * problem.x_scale[0], ubx[0] * problem.x_scale[0]
    d = [x for x in ropes.diameters() if lo - 1e-12 <= x <= hi + 1e-12]
    top = problem.evaluate(np.array([d[-1], 0.0, HELD]) / problem.x_scale, p)["F_min"] / \
        p[problem.params.index("n_rope")]
    for _ in range(DOUBLINGS):
        X = np.array([[x, top, HELD] for x in d]).T / problem.x_scale[:, None]
        if not _static_ok(problem, X, p).any():
            break
        top *= 2.0
    return d, [float(f) for f in np.linspace(0.0, top, POINTS)]


def _keeps(problem, xs, p, a_of, order) -> bool | None:
    """Whether scaled design ``xs`` keeps every check through every case (stops at the first that fails); None
    when the integrator fails there (cvodes cannot meet its tolerance: no design the NLP could solve from)."""
    a = a_of(xs)
    for i in order:
        try:
            least = min(least_margins(problem, problem.all_paths[i], xs, p, a).values())
        except RuntimeError:
            return None
        if least < 0.0:
            return False
    return True


def scan_box(problem, p=None) -> Scan:
    """Scan the design box of ``problem`` (a :class:`~optimisation.dynamic.problem.DynamicSizingProblem`) at
    parameters ``p``: every check at every point (see the module)."""
    t0 = time.process_time()
    p = problem.p0 if p is None else np.asarray(p, float)
    d, grid = _axes(problem, p)
    quantities = problem.scene.built.quantities
    scan = Scan(d, grid, HELD, len(problem.cases), DT_DENSE, {k: quantities[k] for k in VARIABLES if k in quantities})
    X = np.array([[x, f, HELD] for x in d for f in grid]).T / problem.x_scale[:, None]
    ok = _static_ok(problem, X, p)
    scan.static_ok = int(ok.sum())
    order = list(problem.selected) + [i for i in range(len(problem.cases)) if i not in problem.selected]

    def a_of(xs):
        return {k: float(v) for k, v in problem.values(xs * problem.x_scale, p).items()}

    for j in np.flatnonzero(ok):
        scan.integrated += 1
        keeps = _keeps(problem, X[:, j], p, a_of, order)
        scan.unintegrable += keeps is None
        if keeps:
            scan.designs.append(X[:, j].copy())
    scan.seconds = time.process_time() - t0
    return scan
