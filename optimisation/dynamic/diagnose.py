"""No design keeps every check through the manoeuvres: which checks conflict, and what would help.

The same questions as :mod:`optimisation.infeasibility` asks of the static problem, on the dynamic NLP
(with its Hessian of :attr:`~optimisation.dynamic.problem.DynamicSizingProblem.ipopt_options`), after a scan of the
design box (:func:`~optimisation.dynamic.scan.scan_box`) that looks for a design at every catalogue diameter and a
grid of pretensions, because both questions are local.  The scan finds one: it is returned as the design to solve
again from (a design the local solvers missed).  It finds none: the verdict says how fine the scan was
(``Diagnosis.backing``, ``Diagnosis.scan``), and

1. the least maximum violation, min t s.t. g_i(x) + t ≥ 0, from the least violated of the caller's design and the
   scan's points that failed by least: t* > 0 says no design exists; the checks with a nonzero multiplier there
   conflict (named with their manoeuvre and instant); t* = 0: a design between the scan's points;
2. in the user's terms: each scene parameter that relaxes a conflicting check (:data:`REMEDIES`, the
   static ones and the ramp time, which lowers every dynamic force) is freed alone, d anywhere in the
   catalogue's range, and the value at which a design just exists is found: "needs t_ramp >= 7.3 s" — by Newton on
   the least violation's active set (:mod:`optimisation.dynamic.remedy`), by IPOPT where that does not answer;
   each value verified: every check of the NLP holds there, between its grid points too
   (:func:`~optimisation.dynamic.remedy.between_points`).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from optimisation.dynamic.remedy import active_of, between_points, holding, newton_remedy
from optimisation.dynamic.scan import scan_box
from optimisation.infeasibility import REMEDIES as STATIC_REMEDIES
from optimisation.infeasibility import Diagnosis, remedy_text, shown_value
from ropemodel.errors import SolveError
from ropemodel.papers import en12385 as ropes

OPTS = {"ipopt.tol": 1e-9, "ipopt.print_level": 0, "print_time": False, "show_eval_warnings": False,
        "ipopt.sb": "yes", "ipopt.max_iter": 150}   # measured 22-105 iterations (see diagnose_dynamic)
TOL = 1e-7
#: the scan's points that failed by least tried as starts of the least-violation problem, besides the starts' end
STARTS = 4
#: the least-violation problem starts on the cases of the checks violated by at least this fraction of the worst
NEAR_WORST = 0.5
_RAMP = ("t_ramp", "min")
#: check → the parameters that relax it, and which way ("min": the least value that lets a design exist)
REMEDIES = {
    **STATIC_REMEDIES,
    "safety_margin": (_RAMP, *STATIC_REMEDIES["safety_margin"]),
    "safety_margin_S": (_RAMP, *STATIC_REMEDIES["safety_margin"]),
    "slip_margin_fwd": (_RAMP, ("mu_d", "min"), ("alpha_d", "min")),
    "slip_margin_back": (_RAMP, ("mu_d", "min"), ("alpha_d", "min")),
    "slack_margin": (_RAMP, *STATIC_REMEDIES["slack_margin"]),
    "taut_margin": (_RAMP, *STATIC_REMEDIES["slack_margin"]),
    "tension_margin": (_RAMP,),
}


def _base(constraint: str) -> str:
    name = constraint.split(" @ ")[0].split("[")[0]
    static = name.rsplit("_", 1)[0] if name.endswith(("_up", "_down")) else name
    return static if static in STATIC_REMEDIES and name not in REMEDIES else name


def _solver(problem, name, x, g, f):
    """IPOPT on (x, problem.p) with the objective ``f`` and constraints ``g`` ≥ 0; Hessian of the static
    part only, as the sizing NLP's."""
    lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", g.numel())
    n = problem.g_static.numel()
    lag = lam_f * f + ca.dot(lam_g[:n], g[:n])
    hess = ca.Function("hess_lag", [x, problem.p, lam_f, lam_g], [ca.triu(ca.hessian(lag, x)[0])],
                       ["x", "p", "lam_f", "lam_g"], ["hess"])
    return ca.nlpsol(name, "ipopt", {"x": x, "p": problem.p, "f": f, "g": g}, {**OPTS, "hess_lag": hess})


def _catalogue_bounds(problem):
    """The scaled bounds of the design: the catalogue's diameters, the box's held variables at their values (every
    check gains from more of them: :data:`~ropemodel.machines.base.DesignBox`; a winch's stroke: the smooth mode
    does not depend on it, so the least violation and the remedies are those of any stroke as long)."""
    lbx, ubx = problem.bounds((ropes.diameters()[0], ropes.diameters()[-1]))
    for name, value in problem.machine.manoeuvres.BOX.held.items():
        j = problem.variables.index(name)
        lbx[j] = ubx[j] = value / problem.x_scale[j]
    return lbx, ubx


def _least_start(problem, p, candidates, lbx, ubx) -> np.ndarray:
    """Of the scaled designs ``candidates``, the one whose largest violation of the NLP's checks is least."""
    gfun = problem.g_function
    xs = [np.clip(np.asarray(x, float), lbx, np.where(np.isfinite(ubx), ubx, x)) for x in candidates]
    return min(xs, key=lambda x: -float(np.asarray(gfun(x, p)).min()))


def diagnose_dynamic(problem, x0, say=None, scan=None) -> tuple[Diagnosis, np.ndarray]:
    """Why ``problem`` (a :class:`~optimisation.dynamic.problem.DynamicSizingProblem`) has no design; and the
    (scaled) design of least maximum violation (a design, when the scan or the least violation finds one).

    First the scan of the design box (``scan``, when the caller has it: :func:`~optimisation.dynamic.scan.scan_box`);
    none found, the least-violation problem from the least violated of ``x0`` and the scan's points that failed by
    least (:data:`STARTS`), then each remedy (:func:`remedies`).  ``say`` is told which question is being asked
    (the command line's status line).  Measured on the test scene with a 2 s ramp, before: the least violation
    from where the starts ended 95 CPU-s, each remedy by IPOPT 83-498 CPU-s."""
    say = say or (lambda text: None)
    p = problem.p0
    lbx, ubx = _catalogue_bounds(problem)
    if scan is None:
        say("no design from the starts: a scan of the design box")
        scan = scan_box(problem, p)
    if scan.designs:
        return Diagnosis(True, 0.0, backing=scan.text(), scan=scan.to_dict()), scan.designs[0]
    say("no design in the scan: the least violation of the checks")
    x0 = _least_start(problem, p, [x0, *scan.least_violated(STARTS)], lbx, ubx)
    zz, r, sub = least_violation(problem, x0, lbx, ubx)
    n = len(problem.variables)
    t_star = float(zz[n])
    if t_star <= TOL:
        return Diagnosis(True, t_star, backing=scan.text(), scan=scan.to_dict()), zz[:n]
    lam_g, lam_x = (np.asarray(r[k]).ravel() for k in ("lam_g", "lam_x"))
    conflicting, bounds = active_of(sub, lam_g, lam_x, zz[:n], lbx, ubx)
    gz = np.asarray(problem.g_function(zz[:n], p)).ravel()
    margins = {c: float(v * s) for c, v, s in zip(problem.constraints, gz, problem.g_scale) if c in conflicting}
    needs = remedies(problem, conflicting, lbx, ubx, zz[:n], say, bounds)
    return Diagnosis(False, t_star, conflicting, {}, {}, margins, " through the manoeuvres", needs, scan.text(),
                     scan.to_dict()), zz[:n]


def least_violation(problem, x0, lbx, ubx):
    """min t s.t. g(x) + t ≥ 0 over every case ``problem`` integrates, from the scaled design ``x0``, by constraint
    generation (exchange method, Blankenship & Falk 1976): on the cases of the checks violated within
    :data:`NEAR_WORST` of the worst at ``x0``; at its optimum every case is evaluated and the cases of the checks
    violated by more than t* are added, until none is.  Then t* and its point are those of every case: no check
    is violated by more, and with fewer checks t* cannot be larger.  Returns (x and t, IPOPT's answer, the problem of
    the cases it ended on: its multipliers are of that problem's checks)."""
    p, n = problem.p0, len(problem.variables)
    g = np.asarray(problem.g_function(x0, p)).ravel()
    names = [c for c, v in zip(problem.constraints, g) if v < NEAR_WORST * min(g.min(), 0.0)]
    z = np.concatenate([x0, [max(0.0, -g.min())]])
    for _ in range(len(problem.selected) + 1):
        sub = holding(problem, names)
        t = ca.MX.sym("t")
        solver = _solver(sub, "minmax", ca.vertcat(sub.xs, t), sub.g_function(sub.xs, sub.p) + t, t)
        r = solver(x0=z, p=p, lbx=np.concatenate([lbx, [0.0]]), ubx=np.concatenate([ubx, [np.inf]]), lbg=0.0,
                   ubg=np.inf)
        z = np.asarray(r["x"]).ravel()
        g = np.asarray(problem.g_function(z[:n], p)).ravel()
        worse = [c for c, v in zip(problem.constraints, g) if v + z[n] < -TOL and c not in sub.constraints]
        if not worse:
            return z, r, sub
        names += worse
        z[n] = max(z[n], -g.min())
    raise SolveError("the least-violation problem did not settle on its cases; report it")


def remedies(problem, conflicting, lbx, ubx, x0, say=None, bounds=None) -> list[str]:
    """"NAME >= value" for each parameter that relaxes a conflicting check, d anywhere in the catalogue: by Newton
    on the least-violation optimum's active set (``conflicting`` and ``bounds``, at ``x0``;
    :func:`~optimisation.dynamic.remedy.newton_remedy`), by IPOPT (:func:`free_by_ipopt`) where that does not
    give the answer."""
    q = problem.scene.built.quantities
    names: dict[str, str] = {}     # parameter → "min" or "max", the first check that names it decides
    for base in dict.fromkeys(_base(c) for c in conflicting):
        for name, sense in REMEDIES.get(base, ()):
            if name in problem.params:
                names.setdefault(name, sense)
    out = []
    for k, (name, sense) in enumerate(names.items()):
        if say is not None:
            say(f"no design: the {'least' if sense == 'min' else 'largest'} {name} with a design "
                f"({k + 1} of {len(names)})")
        found = remedy(problem, name, sense, q[name], (conflicting, bounds or {}, x0), (lbx, ubx))
        if found is not None:
            out.append(remedy_text(name, sense, found[0], q[name]))
    return out


def remedy(problem, name, sense, quantity, least, box):
    """(the least (``sense`` "min") or largest ("max") value [SI] of parameter ``name`` with a design, the scaled
    design there) or None: by Newton on the least-violation optimum's active set (``least``: its active checks,
    active bounds and design; :func:`~optimisation.dynamic.remedy.newton_remedy`), by IPOPT
    (:func:`free_by_ipopt`) where that does not give the answer; every check holding between the grid points too
    at the value the answer shows (:func:`~optimisation.dynamic.remedy.between_points`).  ``box``: (lbx, ubx), the
    design's scaled bounds."""
    conflicting, bounds, x0 = least
    lbx, ubx = box
    lo, hi = _range(problem, name, quantity)
    scale = abs(problem.p0[problem.params.index(name)]) or 1.0

    def solve(grid):
        found = newton_remedy(grid, name, sense, x0, conflicting, bounds, (lbx, ubx, lo / scale, hi / scale),
                              lambda value, x: _holds(grid, name, sense, value, x, quantity))
        return found if found is not None else free_by_ipopt(grid, name, sense, quantity, lbx, ubx, x0)

    return between_points(problem, solve, lambda grid, value: grid.p_of({name: shown_value(sense, value, quantity)}))


def _range(problem, name, quantity) -> tuple[float, float]:
    """The valid range [SI] of parameter ``name`` as a remedy (the ramp must end before the transient does)."""
    lo = quantity.low if math.isfinite(quantity.low) else -np.inf
    hi = quantity.high if math.isfinite(quantity.high) else np.inf
    if name == "t_ramp":
        hi = min(hi, 0.999 * problem.scene.parameters["t_end"])
    return lo, hi


def _holds(problem, name, sense, value, x, quantity) -> bool:
    """Whether a design ``x`` (scaled) keeps every check of ``problem`` with parameter ``name`` at the value its
    remedy's text shows for ``value`` [SI] (four digits, rounded away from the infeasible side; the scene's rules
    applied), and that value is in the parameter's valid range."""
    shown = shown_value(sense, value, quantity)
    gz = np.asarray(problem.g_function(x, problem.p_of({name: shown}))).ravel()
    return bool(gz.min() >= -TOL and quantity.in_range(shown))


def free_by_ipopt(problem, name, sense, quantity, lbx, ubx, x0):
    """(the least (``"min"``) or largest (``"max"``) value [SI] of parameter ``name`` with a design, the scaled design
    there) by IPOPT from the scaled design ``x0`` and the parameter's value, verified (:func:`_holds`), or None."""
    p = problem.p0
    i = problem.params.index(name)
    scale = abs(p[i]) or 1.0
    t = ca.MX.sym("t")
    pv = ca.vertcat(*[t * scale if j == i else problem.p[j] for j in range(len(p))])
    g = problem.g_function(problem.xs, pv)
    solver = _solver(problem, f"free_{name}", ca.vertcat(problem.xs, t), g, t if sense == "min" else -t)
    lo, hi = _range(problem, name, quantity)
    r = solver(x0=np.concatenate([x0, [p[i] / scale]]), p=p, lbx=np.concatenate([lbx, [lo / scale]]),
               ubx=np.concatenate([ubx, [hi / scale]]), lbg=0.0, ubg=np.inf)
    zz = np.asarray(r["x"]).ravel()
    x, value = zz[:-1], float(zz[-1] * scale)
    return (value, x) if solver.stats()["success"] and _holds(problem, name, sense, value, x, quantity) else None
