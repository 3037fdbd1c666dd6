"""No design keeps every check through the manoeuvres: which checks conflict, and what would help.

The same questions as :mod:`optimisation.infeasibility` asks of the static problem, on the dynamic NLP
(with its Hessian of :attr:`~optimisation.dynamic.problem.DynamicSizingProblem.ipopt_options`):

1. the least maximum violation, min t s.t. g_i(x) + t ≥ 0: t* > 0 says no design exists; the checks
   with a nonzero multiplier there conflict (named with their manoeuvre and instant);
2. in the user's terms: each scene parameter that relaxes a conflicting check (:data:`REMEDIES`, the
   static ones and the ramp time, which lowers every dynamic force) is freed alone, d anywhere in the
   catalogue's range, and the NLP finds the value at which a design just exists: "needs t_ramp >= 7.3 s".

Both are local: before the verdict, a scan of the design box (:func:`~optimisation.dynamic.scan.scan_box`)
looks for a design at every catalogue diameter and a grid of pretensions.  None found: the verdict says how fine
the scan was (``Diagnosis.backing``, ``Diagnosis.scan``); one found: it is returned as the design to solve again
from (a design the local solvers missed).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from optimisation.dynamic.scan import scan_box
from optimisation.infeasibility import REMEDIES as STATIC_REMEDIES
from optimisation.infeasibility import Diagnosis, remedy_text
from ropemodel.papers import en12385 as ropes

OPTS = {"ipopt.tol": 1e-9, "ipopt.print_level": 0, "print_time": False, "show_eval_warnings": False,
        "ipopt.sb": "yes", "ipopt.max_iter": 150}   # measured 22-105 iterations (see diagnose_dynamic)
TOL = 1e-7
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
    lbx, ubx = problem.bounds((ropes.diameters()[0], ropes.diameters()[-1]))
    return lbx, ubx


def diagnose_dynamic(problem, x0, say=None) -> tuple[Diagnosis, np.ndarray]:
    """Why ``problem`` (a :class:`~optimisation.dynamic.problem.DynamicSizingProblem`) has no design; and the
    (scaled) design of least maximum violation (a design, when the diagnosis finds one feasible).

    Each question is an NLP through the four manoeuvres (measured on the test scene with a 2 s ramp: the
    least violation 33 iterations, 25 s; each parameter freed 22-105 iterations, 17-95 s): ``say`` is told
    which one is being asked (the command line's status line)."""
    say = say or (lambda text: None)
    say("no design from the starts: the least violation of the checks")
    p = problem.p0
    lbx, ubx = _catalogue_bounds(problem)
    x0 = np.clip(np.asarray(x0, float), lbx, np.where(np.isfinite(ubx), ubx, x0))
    gfun = problem.g_function
    t = ca.MX.sym("t")
    z = ca.vertcat(problem.xs, t)
    g = gfun(problem.xs, problem.p)
    s1 = _solver(problem, "minmax", z, g + t, t)
    g0 = np.asarray(gfun(x0, p)).ravel()
    r = s1(x0=np.concatenate([x0, [max(0.0, -g0.min())]]), p=p, lbx=np.concatenate([lbx, [0.0]]),
           ubx=np.concatenate([ubx, [np.inf]]), lbg=0.0, ubg=np.inf)
    zz = np.asarray(r["x"]).ravel()
    t_star = float(zz[3])
    if t_star <= TOL:
        return Diagnosis(True, t_star), zz[:3]
    say("no design from the least violation: a scan of the design box")
    scan = scan_box(problem, p)
    if scan.designs:
        return Diagnosis(True, t_star, backing=scan.text(), scan=scan.to_dict()), scan.designs[0]
    lam = np.abs(np.asarray(r["lam_g"]).ravel())
    conflicting = [c for c, value in zip(problem.constraints, lam) if value > 1e-6]
    gz = np.asarray(gfun(zz[:3], p)).ravel()
    margins = {c: float(v * s) for c, v, s in zip(problem.constraints, gz, problem.g_scale) if c in conflicting}
    needs = remedies(problem, conflicting, lbx, ubx, zz[:3], say)
    return Diagnosis(False, t_star, conflicting, {}, {}, margins, " through the manoeuvres", needs, scan.text(),
                     scan.to_dict()), zz[:3]


def remedies(problem, conflicting, lbx, ubx, x0, say=None) -> list[str]:
    """"NAME >= value" for each parameter that relaxes a conflicting check, d anywhere in the catalogue."""
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
        value = _free(problem, name, sense, q[name], lbx, ubx, x0)
        if value is not None:
            out.append(remedy_text(name, sense, value, q[name]))
    return out


def _free(problem, name, sense, quantity, lbx, ubx, x0):
    """The least (``"min"``) or largest (``"max"``) value of parameter ``name`` with a design, or None."""
    p = problem.p0
    i = problem.params.index(name)
    scale = abs(p[i]) or 1.0
    t = ca.MX.sym("t")
    pv = ca.vertcat(*[t * scale if j == i else problem.p[j] for j in range(len(p))])
    g = problem.g_function(problem.xs, pv)
    solver = _solver(problem, f"free_{name}", ca.vertcat(problem.xs, t), g, t if sense == "min" else -t)
    lo = quantity.low / scale if math.isfinite(quantity.low) else -np.inf
    hi = quantity.high / scale if math.isfinite(quantity.high) else np.inf
    if name == "t_ramp":            # the ramp must end before the transient does
        hi = min(hi, 0.999 * problem.scene.parameters["t_end"] / scale)
    r = solver(x0=np.concatenate([x0, [1.0]]), p=p, lbx=np.concatenate([lbx, [lo]]), ubx=np.concatenate([ubx, [hi]]),
               lbg=0.0, ubg=np.inf)
    zz = np.asarray(r["x"]).ravel()
    value = float(zz[3] * scale)
    gz = np.asarray(problem.g_function(zz[:3], problem.p_of({name: value}))).ravel()
    if not solver.stats()["success"] or gz.min() < -1e-7 or not quantity.in_range(value):
        return None
    return value

