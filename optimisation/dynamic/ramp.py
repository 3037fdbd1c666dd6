"""The shortest start and stop ramp that keeps a given design safe (``ropemodel size --dynamic --find t_ramp``).

The design (d, F_nwl, stroke: the scene's) is fixed; the drive's ramp time ``t_ramp`` (one value for start
and stop, the scene's ramp parameter) is the decision variable of an optimal-control problem:

    min t_ramp   s.t.  every check of :data:`~ropemodel.machines.winch.manoeuvres.CHECKS` ≥ 0 at every instant of
                       the four manoeuvres, t_ramp ≤ t_end,

the same constraints as dynamic sizing (:class:`~optimisation.dynamic.problem.DynamicSizingProblem`: every
manoeuvre with the load at every candidate position; the cases that govern a check at the scan's last
failing ramp are integrated, the others screened at the answer; the phases of each manoeuvre in scaled
time, so the ramp's end moves with t_ramp and the constraints' derivatives with respect to it are exact,
through the integrator).  A shorter ramp is harsher almost everywhere, but not
monotonically (the rope's own oscillation can meet a ramp's end in or out of phase), so the NLP is started
from a scan: t_ramp on a geometric grid of :data:`SCAN` values from :data:`T_LOW` to t_end, each judged by
its least margin on a dense grid; the NLP looks in the bracket between the last failing and the first safe
scanned value.  Its answer is refined as dynamic sizing's (the checks' exact local minima added to the
grid) and verified by the hybrid simulator; a ramp the simulator does not confirm is an error.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from optimisation.dynamic.problem import BACKOFF, DynamicSizingProblem
from optimisation.dynamic.refine import add_points, minima
from optimisation.dynamic.screen import all_margins, uncovered
from optimisation.dynamic.verify import by_manoeuvre, verify
from optimisation.problem import declaration, load_sizing
from ropemodel.errors import InputError, SolveError
from ropemodel.numerics.held import held_solver_output
from ropemodel.scene import Scene, SceneLike

#: the scene's ramp parameter
RAMP = "t_ramp"
#: shortest ramp scanned [s], and the number of scanned ramps
T_LOW = 0.2
SCAN = 16
OPTS: dict = {"ipopt.tol": 1e-10, "ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
              "ipopt.hessian_approximation": "limited-memory", "ipopt.constr_viol_tol": 1e-9,
              "ipopt.max_iter": 200, "show_eval_warnings": False}
MAX_ROUNDS = 6


@dataclass
class RampAnswer:
    """The shortest ramp [s] and what limits it (the active check, its manoeuvre, place and instant), the scan
    (t_ramp [s] → least scaled margin) and the simulator's verdicts at the answer (every case)."""

    t_ramp: float
    active: list = field(default_factory=list)
    scan: list = field(default_factory=list)
    verdicts: list = field(default_factory=list)
    design: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {"find": RAMP, RAMP: self.t_ramp, "design": self.design, "active": self.active,
                "scan": [{RAMP: t, "least_margin_scaled": m} for t, m in self.scan],
                "manoeuvres": by_manoeuvre(self.verdicts)}


def _design(scene) -> np.ndarray:
    variables = declaration(scene).VARIABLES
    missing = [k for k in variables if k not in scene.parameters or scene.origin.get(k) == "default"]
    if missing:
        raise InputError(f"--find {RAMP} keeps a given design: the scene must give {', '.join(missing)}")
    return np.array([scene.parameters[k] for k in variables], float)


def least_margin(problem, xs, p) -> tuple[float, str]:
    """The least scaled margin of every check (static, and through every case — each manoeuvre, the load at
    each candidate position — on a grid of step :data:`~optimisation.dynamic.start.DT_DENSE`) at scaled ``xs``,
    and the check's name."""
    n = problem.g_static.numel()
    g = np.asarray(problem.g_function(xs, p)).ravel()[:n] + 0.0
    i = int(np.argmin(g))
    least = (float(g[i]), problem.constraints[i])
    for k, margins in all_margins(problem, xs, p).items():
        for name, value in margins.items():
            least = min(least, (value, f"{name} @ {problem.cases[k].tag}"))
    return least


def shortest_ramp(scene: SceneLike) -> RampAnswer:
    """The shortest ``t_ramp`` [s] that keeps the scene's design safe through the four manoeuvres
    (``ropemodel size --dynamic --find t_ramp``).

    Parameters
    ----------
    scene : Scene or str or Path
        A winch sizing scene with a transient (as for :func:`optimisation.dynamic.size_dynamic`) that gives
        the design to keep: ``d`` [m], ``F_nwl`` [N] and ``stroke`` [m]. A TOML file or built-in name is
        read by :func:`optimisation.problem.load_sizing`.

    Returns
    -------
    RampAnswer
        ``t_ramp`` [s]; ``active``: the check, manoeuvre and instant that a shorter ramp would break;
        ``scan``: the scanned ramps [s] and their least scaled margins; ``verdicts``: the hybrid
        simulator's judgement of the four manoeuvres at the answer; ``to_dict()``: the ``--json`` output.

    Raises
    ------
    InputError
        The scene gives no design, or its transient has no ramp time.
    SolveError
        No ramp up to ``t_end`` keeps the design safe, the design is safe at the shortest ramp scanned
        (0.2 s), or the simulator does not confirm the answer.

    Examples
    --------
    Tens of seconds of work, so not run as a doctest (``tests/test_dynamic_sizing.py`` checks the answer on
    both sides)::

        answer = shortest_ramp("my_winch.toml")     # d, F_nwl and stroke given in the scene
        answer.t_ramp, answer.active                # s; e.g. ['slip_margin_fwd @ upward start, t = 3.1 s']
    """
    scene = load_sizing(scene, emit=False)
    with held_solver_output():
        return _shortest(scene)


def _shortest(scene: Scene) -> RampAnswer:
    x_si = _design(scene)
    problem = DynamicSizingProblem(scene)
    if RAMP not in problem.params:
        raise InputError(f"the scene's transient has no ramp time {RAMP}")
    xs = x_si / problem.x_scale
    t_end = scene.parameters["t_end"]
    judged = [(float(t), *least_margin(problem, xs, problem.p_of({RAMP: float(t)})))
              for t in np.geomspace(min(T_LOW, t_end / 2), t_end, SCAN)]
    scan = [(t, m) for t, m, _ in judged]
    if scan[-1][1] < 0:
        raise SolveError(f"no ramp up to t_end = {t_end:g} s keeps the design safe: {judged[-1][2]} fails even at "
                         f"t_ramp = t_end (a larger design, or a longer t_end)")
    k = next(i for i, (_, m) in enumerate(scan) if m >= BACKOFF)
    if k == 0:
        raise SolveError(f"the design is safe down to t_ramp = {scan[0][0]:g} s, the shortest ramp scanned")
    lo, hi = scan[k - 1][0], scan[k][0]
    t, active, problem = _solve(problem, xs, lo, hi)
    answer = RampAnswer(t, active, scan, design=dict(zip(problem.variables, map(float, x_si))))
    answer.verdicts = verify(problem, xs, {RAMP: t})
    bad = [f"{v.manoeuvre}: " + "; ".join(v.failures) for v in answer.verdicts if not v.ok]
    if bad:
        raise SolveError(f"the shortest ramp t_ramp = {t:.6g} s fails in the hybrid simulator (" + " | ".join(bad)
                         + "): the NLP's checks did not hold between its grid points; report it")
    return answer


def _solve(problem, xs, lo: float, hi: float):
    """min t_ramp in [lo, hi] with the design fixed, on grids refined until every exact local minimum of every
    check keeps half the back-off, with every case that comes within the back-off at the answer.  Returns
    (t_ramp [s], the active constraints, the final problem)."""
    t = hi
    problem = problem.screened(xs, problem.p_of({RAMP: lo}))
    for _ in range(MAX_ROUNDS):
        t = _nlp(problem, xs, lo, hi, t)
        p = problem.p_of({RAMP: t})
        found = minima(problem, xs, p)
        low = [m for m in found if m.value < 0.5 * BACKOFF]
        more = [] if low else uncovered(problem, xs, p, BACKOFF)
        if not low and not more:
            active = [f"{m.check} @ {problem.paths[m.path].manoeuvre.tag}, t = {m.t:.6g} s"
                      for m in sorted(found, key=lambda m: m.value) if m.value < 2 * BACKOFF]
            return t, active, problem
        problem = problem.refined(add_points(problem, problem.grids, low, p)) if low else \
            problem.with_cases([*problem.selected, *more])
    raise SolveError(f"the time grid and the cases of the shortest-ramp problem did not converge in {MAX_ROUNDS} "
                     f"refinements")


def _nlp(problem, xs, lo: float, hi: float, start: float):
    """IPOPT on min t s.t. g(xs, p(t)) ≥ 0 (every check; the dynamic ones with their back-off), t in [lo, hi]."""
    i = problem.params.index(RAMP)
    t = ca.MX.sym(RAMP)
    p = ca.vertcat(*[t if j == i else problem.p0[j] for j in range(len(problem.params))])
    g = problem.g_function(ca.DM(xs), p)
    nlp: dict = {"x": t, "f": t, "g": g}
    solver = ca.nlpsol("shortest_ramp", "ipopt", nlp, OPTS)
    r = solver(x0=start, lbx=lo, ubx=hi, lbg=0.0, ubg=np.inf)
    value = float(r["x"])
    gv = np.asarray(r["g"]).ravel()
    if not solver.stats()["success"] or gv.min() < -1e-9:
        raise SolveError(f"the shortest-ramp NLP did not converge between t_ramp = {lo:.4g} s and {hi:.4g} s "
                         f"({solver.stats()['return_status']})")
    return value
