"""No feasible design: which checks conflict, and by how much.

An IPOPT "local infeasibility" says nothing about why.  Three small NLPs on the
same (scaled) margins g_i(x) >= 0 answer it:

1. **least maximum violation**: min t s.t. g_i(x) + t >= 0 ∀i, t >= 0.  t* > 0
   proves (locally) that no design meets every check; the checks with a nonzero
   multiplier at this point are the ones that conflict (only they hold t* up).
2. **one check relaxed at a time**: for each conflicting check i,
   min s s.t. g_i + s >= 0, g_j >= 0 (j ≠ i): how far check i alone must give
   (in the margin's own unit) for a design to exist — or "cannot" when relaxing it
   alone does not help.
3. **elastic L1**: min Σ s_i s.t. g_i + s_i >= 0, s >= 0: the least total relaxation;
   its nonzero slacks are reported too.
4. **in the user's terms**: for each conflicting check, the scene parameters that relax it
   (:data:`REMEDIES`) are freed one at a time, and the NLP finds the value that just lets a design
   exist: "needs D >= 1.26 m", "needs n_rope <= 4.1".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from optimisation.problem import SizingProblem
from ropemodel.papers import en12385 as ropes

#: check → the scene parameters that relax it, and in which direction ("min": the least value that lets
#: a design exist is asked for; "max": the largest)
REMEDIES = {
    "safety_margin": (("n_rope", "max"), ("rope_grade", "min")),
    "slip_margin": (("n_slip", "max"), ("mu_d", "min"), ("alpha_d", "min")),
    "slack_margin": (("F_S_min", "max"),),
    "taut_margin": (("F_S_min", "max"),),
    "sheave_margin": (("F_S_min", "max"),),
    "drum_margin": (("D", "min"), ("D_ratio_min", "max")),
}
OPTS: dict[str, Any] = {"ipopt.tol": 1e-10, "ipopt.print_level": 0, "print_time": False, "show_eval_warnings": False,
                        "calc_lam_p": False, "ipopt.sb": "yes", "ipopt.max_iter": 1000}
TOL = 1e-7


@dataclass
class Diagnosis:
    """Why no design exists (margins in their own SI units; negative = short by)."""

    feasible: bool
    max_violation: float                     # t* (scaled)
    conflicting: list[str] = field(default_factory=list)
    alone: dict[str, float | None] = field(default_factory=dict)   # check -> relaxation needed (SI), None = cannot
    elastic: dict[str, float] = field(default_factory=dict)        # nonzero L1 slacks (SI)
    margins_at_least_violation: dict[str, float] = field(default_factory=dict)
    where: str = ""
    needs: list[str] = field(default_factory=list)    # "needs D >= 1.26 m": what would make a design exist
    backing: str = ""                                 # what backs the verdict beyond the local solvers (a scan)
    scan: dict = field(default_factory=dict)          # that scan's axes and counts
    x_least: Any = None                               # the design (scaled) of least maximum violation

    def text(self, units: dict[str, str]) -> str:
        if self.feasible:
            return "a design meeting every check exists"
        lines = [f"no design meets every check{self.where}: " + (
            "these checks conflict: " + ", ".join(self.conflicting) if self.conflicting else   # none with a multiplier
            "these checks cannot hold: " + ", ".join(self.elastic))]                         # above 1e-6: the relaxed
        if self.backing:
            lines.append(f"  {self.backing}")
        if self.needs:
            lines.append("  each of these alone makes a design exist: " + "; ".join(self.needs))
        for c in self.conflicting:
            r = self.alone.get(c)
            lines.append(f"  {c}: " + ("relaxing it alone is not enough" if r is None else
                                      f"must give {_amount(r, units.get(c, '1'))} (alone) for a design to exist"))
        if self.elastic:
            lines.append("  least total relaxation: " + ", ".join(f"{k} by {_amount(v, units.get(k, '1'))}"
                                                                 for k, v in self.elastic.items()))
        return "\n".join(lines)


def _amount(value: float, unit: str) -> str:
    return f"{value:.6g}" if unit == "1" else f"{value:.6g} {unit}"


def _bounds(problem, d_range, fix_d):
    lbx, ubx = problem.bounds(d_range)
    if fix_d is not None:
        lbx[0] = ubx[0] = fix_d / problem.x_scale[0]
    return lbx, ubx


def diagnose(problem: SizingProblem, p=None, d_range=None, fix_d: float | None = None, x0=None) -> Diagnosis:
    """Diagnose the checks of ``problem`` (at parameters ``p``; d within ``d_range`` or fixed at ``fix_d``)."""
    p = problem.p0 if p is None else np.asarray(p, dtype=float)
    lbx, ubx = _bounds(problem, d_range, fix_d)
    x0 = problem.x0() if x0 is None else np.asarray(x0, dtype=float)
    x0 = np.clip(x0, lbx, np.where(np.isfinite(ubx), ubx, x0))
    ng = problem.g.numel()
    # at the scene's parameters, the NLP with them folded in (a route's sums are numbers, as IPOPT solved it)
    folded = problem.at_scene["g"] if np.array_equal(p, problem.p0) else problem.g
    gfun = ca.Function("g", [problem.xs, problem.p], [folded])
    n = len(problem.variables)
    xs = ca.MX.sym("x", n)
    g = gfun(xs, problem.p)

    # 1. least maximum violation
    t = ca.MX.sym("t")
    s1 = ca.nlpsol("minmax", "ipopt", {"x": ca.vertcat(xs, t), "p": problem.p, "f": t, "g": g + t}, OPTS)
    g0 = np.asarray(gfun(x0, p)).ravel()
    r1 = s1(x0=np.concatenate([x0, [max(0.0, -g0.min())]]), p=p, lbx=np.concatenate([lbx, [0.0]]),
            ubx=np.concatenate([ubx, [np.inf]]), lbg=0.0, ubg=np.inf)
    z1 = np.asarray(r1["x"]).ravel()
    t_star = float(z1[n])
    lam = np.abs(np.asarray(r1["lam_g"]).ravel())
    gz = np.asarray(gfun(z1[:n], p)).ravel()
    if t_star <= TOL:
        return Diagnosis(True, t_star)
    conflicting = [c for c, m in zip(problem.constraints, lam) if m > 1e-6]
    margins = {c: float(v * s) for c, v, s in zip(problem.constraints, gz, problem.g_scale)}

    # 2. one check relaxed at a time
    alone = {}
    s = ca.MX.sym("s")
    for c in conflicting:
        i = problem.constraints.index(c)
        e = np.zeros(ng)
        e[i] = 1.0
        solver = ca.nlpsol("alone", "ipopt", {"x": ca.vertcat(xs, s), "p": problem.p, "f": s,
                                              "g": g + s * ca.DM(e)}, OPTS)
        r = solver(x0=z1, p=p, lbx=np.concatenate([lbx, [0.0]]), ubx=np.concatenate([ubx, [np.inf]]),
                   lbg=0.0, ubg=np.inf)
        z = np.asarray(r["x"]).ravel()
        gg = np.asarray(gfun(z[:n], p)).ravel() + z[n] * e
        ok = solver.stats()["success"] and np.all(gg >= -1e-7)
        alone[c] = float(z[n] * problem.g_scale[i]) if ok else None

    # 3. elastic L1 relaxation
    sl = ca.MX.sym("sl", ng)
    s3 = ca.nlpsol("elastic", "ipopt", {"x": ca.vertcat(xs, sl), "p": problem.p, "f": ca.sum1(sl),
                                        "g": g + sl}, OPTS)
    r3 = s3(x0=np.concatenate([z1[:n], np.maximum(0.0, -gz)]), p=p, lbx=np.concatenate([lbx, np.zeros(ng)]),
            ubx=np.concatenate([ubx, np.full(ng, np.inf)]), lbg=0.0, ubg=np.inf)
    z3 = np.asarray(r3["x"]).ravel()
    elastic = {c: float(z3[n + i] * problem.g_scale[i]) for i, c in enumerate(problem.constraints)
               if z3[n + i] > 1e-6}
    where = f" at d = {fix_d * 1e3:g} mm" if fix_d is not None else ""
    needs = remedies(problem, conflicting, p, lbx, ubx, z1[:n])
    return Diagnosis(False, t_star, conflicting, alone, elastic, margins, where, needs, x_least=z1[:n])


def remedies(problem: SizingProblem, conflicting, p, lbx, ubx, x0) -> list[str]:
    """"NAME >= value" for each scene parameter that relaxes a conflicting check (:data:`REMEDIES`): the
    parameter is freed (within its valid range) and, for each catalogue diameter in turn (d fixed: the
    design must be a catalogue rope), the NLP finds the value at which a design just exists; the best
    over the catalogue is named."""
    q = problem.scene.built.quantities
    gfun = ca.Function("g", [problem.xs, problem.p], [problem.g])
    out, done = [], set()
    checks = [c.split(" @ ")[0] for c in conflicting]
    bases = list(dict.fromkeys(c.rsplit("_", 1)[0] if c.endswith(("_up", "_down")) else c for c in checks))
    for base in bases:
        for name, sense in getattr(problem, "remedies", REMEDIES).get(base, ()):
            if name not in problem.params or (name, sense) in done:     # a parameter two checks share: once
                continue
            done.add((name, sense))
            found = []
            free = _freeing(problem, gfun, problem.params.index(name), sense, q[name], p)   # one NLP, d in bounds
            for d in _diameters(lbx, ubx, problem):
                lo, hi = lbx.copy(), ubx.copy()
                lo[0] = hi[0] = d / problem.x_scale[0]
                found.append(free(lo, hi, np.array([lo[0], *x0[1:]])))
            found = [v for v in found if v is not None]
            value = (min(found) if sense == "min" else max(found)) if found else None
            if value is not None:
                out.append(remedy_text(name, sense, value, q[name]))
    return out


def remedy_text(name: str, sense: str, value: float, quantity) -> str:
    """"NAME >= value unit" ("min") or "NAME <= value unit" ("max"), the SI ``value`` in the quantity's display
    unit to four significant digits, rounded away from the infeasible side."""
    shown = _safe_round(quantity.to_display(value), up=sense == "min")
    return f"{name} {'>=' if sense == 'min' else '<='} {shown:.4g}{quantity.unit_text}"


def shown_value(sense: str, value: float, quantity) -> float:
    """The SI value :func:`remedy_text` shows for the SI ``value`` (four significant digits in the display unit,
    rounded away from the infeasible side)."""
    shown = float(f"{_safe_round(quantity.to_display(value), up=sense == 'min'):.4g}")
    return shown / quantity.to_display(1.0)


def _diameters(lbx, ubx, problem) -> list[float]:
    """The catalogue diameters [m] within the bounds of d (one fixed diameter if d is fixed)."""
    lo, hi = lbx[0] * problem.x_scale[0], ubx[0] * problem.x_scale[0]
    return [d for d in ropes.diameters() if lo - 1e-12 <= d <= hi + 1e-12]


def _safe_round(x: float, up: bool) -> float:
    """``x`` to four significant digits, rounded away from the infeasible side."""
    if x == 0 or not math.isfinite(x):
        return x
    step = 10.0 ** (math.floor(math.log10(abs(x))) - 3)
    return (math.ceil(x / step) if up else math.floor(x / step)) * step


def freeing(problem: SizingProblem, i: int, t: ca.MX) -> ca.MX:
    """The scaled constraints g of ``problem`` at the scene's parameters ``p0`` but the i-th, which is ``t``
    [SI], the others folded in as :attr:`~optimisation.problem.SizingProblem.at_scene` folds them (a route's
    sums over segments are numbers): what the remedies solve, each evaluation no longer a pass over the route.
    A parameter a route's places follow (a segment's length) is not folded: g through the whole model then."""
    name = problem.params[i]
    if not problem.nlp_model.is_a("SXFunction") or (problem.scene.route and name.startswith("L_")):
        whole = ca.Function("g", [problem.xs, problem.p], [problem.g])
        return whole(problem.xs, ca.vertcat(problem.p[:i], t, problem.p[i + 1:]))
    x, ts = ca.SX.sym("x", problem.nlp_model.size1_in("x")), ca.SX.sym("t")
    pv = ca.SX(ca.DM(problem.p0))
    pv[i] = ts
    c = ca.SX.sym("c", problem.nlp_model.size1_in("c"))
    model = ca.Function("nlp_model_free", [x, ts, c], problem.nlp_model.call([x, pv, c]), ["x", "t", "c"],
                        problem.nlp_model.name_out())

    def case(cv) -> ca.Function:
        return ca.Function("nlp_case", [x, ts], model.call([x, ts, ca.DM(ca.evalf(cv))]), ["x", "t"],
                           model.name_out())

    args = problem.known_values(ca.DM(problem.p0), problem.xs * ca.DM(problem.x_scale))
    args = {k: float(v) if isinstance(v, ca.DM) else v for k, v in args.items()}
    args[name] = t
    made = problem.make_constraints(case, args, problem.p, t=t)[1]
    return ca.vertcat(*made) / ca.DM(problem.g_scale)


def _freeing(problem, gfun, i, sense, quantity, p):
    """A function of the design's bounds and start: the least (``"min"``) or largest (``"max"``) value of
    parameter i with a feasible design within them, or None.  The NLP is built once and solved for each
    catalogue diameter (fixed through the bounds)."""
    t, n = ca.MX.sym("t"), len(problem.variables)
    scale = abs(p[i]) or 1.0
    if np.array_equal(p, problem.p0):     # the other parameters folded in (a route's sums are numbers)
        g_free = ca.Function("g_free", [problem.xs, t], [freeing(problem, i, t * scale)])
        g = g_free(xs := ca.MX.sym("x", n), t)

        def g_at(zz):      # the same arithmetic as gfun at p with p_i = t (folded), not a pass over the route
            return g_free(zz[:n], zz[n])
    else:
        xs = ca.MX.sym("x", n)
        g = gfun(xs, ca.vertcat(*[t * scale if j == i else problem.p[j] for j in range(len(p))]))

        def g_at(zz):
            return gfun(zz[:n], np.where(np.arange(len(p)) == i, zz[n] * scale, p))
    z = ca.vertcat(xs, t)
    solver = ca.nlpsol("free", "ipopt", {"x": z, "p": problem.p, "f": t if sense == "min" else -t, "g": g}, OPTS)
    lo = quantity.low / scale if math.isfinite(quantity.low) else -np.inf
    hi = quantity.high / scale if math.isfinite(quantity.high) else np.inf

    def free(lbx, ubx, x0):
        r = solver(x0=np.concatenate([x0, [1.0]]), p=p, lbx=np.concatenate([lbx, [lo]]),
                   ubx=np.concatenate([ubx, [hi]]), lbg=0.0, ubg=np.inf)
        zz = np.asarray(r["x"]).ravel()
        g = np.asarray(g_at(zz)).ravel()
        if not solver.stats()["success"] or g.min() < -1e-7 or not quantity.in_range(zz[n] * scale):
            return None
        return float(zz[n] * scale)
    return free
