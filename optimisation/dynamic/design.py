"""The whole dynamic sizing answer: continuous optimum, catalogue design, each manoeuvre's peaks, where
the load governs it and its active instant, the returned design verified by the hybrid simulator — or why
no design exists.

Steps of :func:`size_dynamic`: the transient made from the scene
(:func:`~optimisation.dynamic.transient.transient_scene`); the static optimum (:mod:`optimisation.design`);
the static design with the dynamic factors its own transient shows
(:func:`~optimisation.dynamic.start.factored_start`, the start); the cases that govern a check there
(:mod:`optimisation.dynamic.screen`); the scan of the design box from the start outwards to its first design
(:mod:`optimisation.dynamic.scan`; none: no design, :mod:`optimisation.dynamic.diagnose` says why and what would
help); the dynamic NLP on a refined time grid, with every case that comes
within the back-off at its optimum (:func:`~optimisation.dynamic.refine.solve_refined`); the rope's
elements per span chosen from the force tolerance ``mesh_tol``, and the NLP solved again there with each
check backed off by the Richardson estimate of its discretisation error
(:func:`~optimisation.dynamic.mesh.converge`); the next catalogue size up with F_nwl and stroke
re-optimised through the transients, rounded up as the static sizing rounds; that catalogue design
simulated in every case, every manoeuvre with the load at every candidate position
(:func:`~optimisation.dynamic.verify.verify`).  A design the simulator does not confirm is an error
(:class:`~ropemodel.errors.SolveError`), never a result.  The continuous optimum, reported beside it but not
returned, is read through the manoeuvres by the NLP's own integration at its final mesh
(:func:`~optimisation.dynamic.verify.integrated`): simulating it too cost as much as verifying the catalogue
design (12 more simulations on the shipped scene, a third of the sizing's time) and checked nothing the
catalogue design's simulation does not — the same NLP, its same integration and mesh, one catalogue size
up.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from optimisation.design import Design, rounded_up, solve_best
from optimisation.dynamic.diagnose import diagnose_dynamic
from optimisation.dynamic.manoeuvres import declared
from optimisation.dynamic.mesh import converge, segments_of
from optimisation.dynamic.problem import DynamicSizingProblem
from optimisation.dynamic.refine import Refinement, solve_refined
from optimisation.dynamic.scan import scan_box
from optimisation.dynamic.start import DT_DENSE, factored_start, fallback_starts
from optimisation.dynamic.transient import transient_effects_of
from optimisation.dynamic.verify import by_manoeuvre, integrated, verified
from optimisation.infeasibility import diagnose
from optimisation.problem import SizingProblem, load_sizing
from ropemodel.errors import SolveError
from ropemodel.numerics.held import held_solver_output
from ropemodel.papers import en12385 as ropes
from ropemodel.scene import Scene, SceneLike


#: what the continuous optimum's record through the manoeuvres comes from (``--json``'s ``continuous``)
CONTINUOUS_FROM = ("the sizing NLP's own integration at its final mesh, every 0.01 s (not simulated: the hybrid "
                   "simulator verifies the catalogue design, the one returned)")


@dataclass
class DynamicDesign(Design):
    """:class:`~optimisation.design.Design` with the manoeuvres: ``manoeuvres`` (per manoeuvre at the
    catalogue design, over every place of the load: where it is governed, the worst peaks, each check's least
    margin with its instant and place, every case; :func:`~optimisation.dynamic.verify.by_manoeuvre`),
    ``nlp_cases`` (the manoeuvres and places the NLP integrated), ``static`` (the static optimum, SI),
    ``refinement`` (what the grid refinement did), ``seconds`` (static and dynamic solve times, s, this
    run); ``defaults`` (parameter → why its default) and ``transient`` (effect → (variant, chosen by the
    scene)) of the transient it sized through; ``mesh`` (the rope's elements per span, the tolerance, each
    check's estimated discretisation error and back-off, :func:`mesh_record`); ``slip_factors`` (the static
    and the dynamic slip factor, each with where its value comes from)."""

    manoeuvres: list = field(default_factory=list)
    manoeuvres_continuous: list = field(default_factory=list)
    nlp_cases: list = field(default_factory=list)
    static: dict | None = None
    refinement: dict = field(default_factory=dict)
    seconds: dict = field(default_factory=dict)
    defaults: dict = field(default_factory=dict)
    transient: dict = field(default_factory=dict)
    mesh: dict = field(default_factory=dict)
    slip_factors: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        out = super().to_dict()
        out["sizing"] = "dynamic"
        out["defaults"] = self.defaults
        out["transient"] = {e: {"variant": v, "chosen": chosen} for e, (v, chosen) in self.transient.items()}
        out["manoeuvres"] = self.manoeuvres
        out["nlp_cases"] = self.nlp_cases
        if out.get("continuous") is not None:
            out["continuous"]["manoeuvres"] = self.manoeuvres_continuous
            out["continuous"]["manoeuvres_from"] = CONTINUOUS_FROM
        out["active_instants"] = [a for a in self.active if " @ " in a and ", t = " in a]
        out["static"] = self.static
        out["refinement"] = self.refinement
        out["seconds"] = self.seconds
        out["mesh"] = self.mesh
        out["slip_factors"] = self.slip_factors
        return out


def _checked(problem, xs, what: str, how=None) -> list:
    """The verdicts at ``xs`` in every case, of the hybrid simulator (:func:`verify`) or, ``how`` =
    :func:`integrated`, of the NLP's own integration at :data:`DT_DENSE`; a failure is an error."""
    verdicts = verified(problem, xs) if how is None else how(problem, xs, DT_DENSE)
    bad = [f"{v.manoeuvre} at {v.where}: " + "; ".join(v.failures) for v in verdicts if not v.ok]
    if bad:
        by = "the hybrid simulator" if how is None else "the NLP's own integration"
        raise SolveError(f"the {what} design fails in {by} (" + " | ".join(bad) + "); the NLP's "
                         "checks did not hold between its grid points or in a case it left out; report it")
    return verdicts


def _margins(problem, xs, manoeuvres) -> dict:
    """The static checks' margins (the static model) and each check's least margin through each manoeuvre
    over every place of the load (the simulator's histories), in their own units."""
    out = {k: v for k, v in problem.margins(xs).items() if k in problem.static_constraints}
    for m in manoeuvres:
        out.update({f"{name} @ {m['manoeuvre']}": least["margin"] for name, least in m["least_margins"].items()})
    return out


def _active(sol, problem, catalogue: bool) -> list[str]:
    bounds = [f"{problem.variables[i]} {side} bound" for i, side in sol.active_bounds if not (catalogue and i == 0)]
    return list(sol.active) + bounds + (["d (catalogue size)"] if catalogue else [])


def _static(scene):
    """The static optimum (scaled solution, problem, seconds)."""
    static = SizingProblem(scene)
    t0 = time.perf_counter()
    sol = solve_best(static)
    return static, sol, time.perf_counter() - t0


def continuous_optimum(problem, static_xs, record: Refinement | None = None, say=None):
    """The continuous dynamic optimum from the static optimum ``static_xs`` (scaled): (problem on its refined
    grid, solution, None), or (problem, None, the diagnosis) when no design exists.

    First the scan of the design box (:func:`~optimisation.dynamic.scan.scan_box`) from the start, the static
    design with the factors its transient shows (:func:`factored_start`), outwards, to the first design it finds.
    It finds one: IPOPT from the start, then from the scan's design and from the static design with the flat
    factor (:func:`fallback_starts`).  It finds none: the least-violation problem and the remedies
    (:func:`decided`), with no start of the NLP (measured on the test scene with a 2 s ramp: IPOPT from the two
    starts to their iteration limit took 356 CPU-s, the scan 6; when the least violation finds a design the scan
    missed between its points, the NLP is solved from there)."""
    say = say or (lambda text: None)
    start = factored_start(problem, static_xs)
    problem = problem.screened(start)
    scan = scan_box(problem, first=True, near=start)
    if not scan.designs:
        return decided(problem, start, record, say, scan)
    problem, sol = solve_refined(problem, start, record=record, screen=False,
                                 others=(scan.designs[0], *fallback_starts(problem, static_xs)))
    return (problem, sol, None) if sol.feasible else decided(problem, sol.xs, record, say, scan)


def decided(problem, x0, record: Refinement | None = None, say=None, scan=None):
    """The least-violation problem (:func:`diagnose_dynamic`, after ``scan`` of the design box, or a scan of its
    own) on ``problem`` from the scaled design ``x0``: (problem, None, the diagnosis) when no design exists, else the
    NLP solved again from the design it found: (problem, solution, None)."""
    diagnosis, x_least = diagnose_dynamic(problem, x0, say, scan)
    if not diagnosis.feasible:
        return problem, None, diagnosis
    problem, sol = solve_refined(problem, x_least, record=record)
    if not sol.feasible:
        raise SolveError("a design keeping every check through the manoeuvres exists (the least-violation problem "
                         "or the scan of the design box found one), but the sizing NLP did not converge from it; "
                         "report it")
    return problem, sol, None


def size_dynamic(scene: SceneLike, with_sensitivities: bool = False,
                 progress: Callable[[str], None] | None = None) -> DynamicDesign:
    """Size the winch of ``scene`` through its start-up and braking in both directions
    (``ropemodel size --dynamic``): the lightest catalogue rope, then the least pretension, then the least
    stroke such that every design check of Krauze et al. (2025) holds at every instant of four simulated
    manoeuvres (start and stop, up and down) with the load anywhere on the route (the ends and the middle of
    every segment), the returned (catalogue) design verified by the hybrid simulator.

    Parameters
    ----------
    scene : Scene or str or Path
        A winch sizing scene (catalogue rope) on a straight route or a route of segments, with the drive's
        ramp time ``t_ramp`` [s]; the transient (rope model, tensioner, drum friction from the lining, how
        long each manoeuvre is followed) is made from it where it does not say
        (:func:`~optimisation.dynamic.transient.transient_scene`).  A TOML file or built-in name is read by
        :func:`optimisation.problem.load_sizing`.
    with_sensitivities : bool
        Also compute ∂x*/∂p of the continuous optimum (:mod:`optimisation.dynamic.sensitivity`).
    progress : callable, optional
        Called with a short text at each step (the command line's status line).

    Returns
    -------
    DynamicDesign
        As :func:`optimisation.design.size`'s :class:`~optimisation.design.Design` (``design``,
        ``continuous``: d [m], F_nwl [N], stroke [m]; ``active``; ``margins``), plus ``static`` (the static
        optimum, SI), ``manoeuvres`` (per manoeuvre over every place of the load: where it is governed, the
        worst peaks F_C_max [N], F_S_min [N], take_up_max [m], dynamic factor [-], each check's least margin
        with its instant [s] and place, every place's own verdict), ``nlp_cases``, ``defaults``,
        ``transient`` and ``seconds``. When no design exists: ``feasible`` is False, ``message`` and
        ``diagnosis`` name the conflicting checks with their manoeuvre, place and instant, and what alone
        would make a design exist.

    Raises
    ------
    InputError
        The scene cannot be sized dynamically (no ramp time, a rope without a catalogue, bad values): every
        missing item named at once.
    SolveError
        A design the hybrid simulator does not confirm (never returned as a result).

    Examples
    --------
    Minutes of work (the manoeuvres integrated inside IPOPT), so not run as a doctest; the test scene of
    ``tests/_dynamic_scene.py``::

        design = size_dynamic("my_winch.toml")
        design.design["d"], design.continuous["d"], design.static["d"]    # m: catalogue, dynamic, static
        [(m["peaks"]["F_C_max"], m["where"]) for m in design.manoeuvres]  # N, and where the load governs
    """
    scene = load_sizing(scene, emit=False)
    with held_solver_output():
        return _size(scene, with_sensitivities, progress or (lambda text: None))


def _size(scene: Scene, with_sensitivities: bool, say: Callable[[str], None]) -> DynamicDesign:
    problem = DynamicSizingProblem(scene)
    design = DynamicDesign(problem.scene, False, units=dict(problem.units), defaults=dict(problem.scene.defaults),
                           transient=transient_effects_of(problem.scene), slip_factors=slip_factors(problem.scene))
    say("static optimum")
    static, ssol, t_static = _static(problem.scene)
    if not ssol.feasible:
        design.diagnosis = diagnose(static)
        design.message = "no static design exists, so no dynamic one: " + design.diagnosis.text(static.units)
        return design
    design.static = static.to_si(ssol.xs)
    say(f"dynamic optimum ({problem.machine.manoeuvres.TEXT['all']} inside the NLP)")
    t0 = time.perf_counter()
    record = Refinement()
    problem, sol, diagnosis = continuous_optimum(problem, ssol.xs, record, say)
    if diagnosis is None:
        say("mesh: the rope's discretisation error at the optimum")
        n_scene, t1 = segments_of(problem.scene), time.perf_counter()
        problem, sol, found = converge(problem, sol, record, say)
        design.mesh = mesh_record(problem, found, n_scene, time.perf_counter() - t1)
        if not sol.feasible:        # none on the finer mesh with the back-offs, or one the NLP missed
            problem, sol, diagnosis = decided(problem, sol.xs, record, say)
    design.refinement = record.to_dict()
    if diagnosis is not None:
        design.diagnosis = diagnosis
        design.message = diagnosis.text(problem.units)
        return design
    design.seconds = {"static": t_static, "dynamic": time.perf_counter() - t0,
                      "mesh": design.mesh.get("seconds", 0.0)}
    say("the continuous optimum through the manoeuvres, as the NLP integrates them")
    design.manoeuvres_continuous = by_manoeuvre(_checked(problem, sol.xs, "continuous", integrated))
    design.continuous = problem.to_si(sol.xs)
    design.active_continuous = _active(sol, problem, False)
    design.margins_continuous = _margins(problem, sol.xs, design.manoeuvres_continuous)
    design.lexicographic_ok = sol.lexicographic_ok
    if with_sensitivities:
        from optimisation.dynamic.sensitivity import sensitivities

        say("sensitivities of the optimum")
        design.sensitivities = sensitivities(problem, sol)
    say("catalogue size")
    return _catalogue(problem, sol, design, say)


def _catalogue(problem, sol, design: DynamicDesign, say) -> DynamicDesign:
    """The next catalogue size up with F_nwl and stroke re-optimised (and rounded up), verified."""
    if design.continuous is None:
        raise ValueError("the catalogue design needs the continuous optimum")
    d_star = design.continuous["d"]
    for dk in [d for d in ropes.diameters() if d >= d_star - 1e-9]:
        x0 = np.array([dk / problem.x_scale[0], *sol.xs[1:]])
        prob, dsol = solve_refined(problem, x0, fix_d=dk, warm=(problem, sol))
        if dsol.feasible and design.mesh.get("segments"):       # its own estimate, at this design
            t0 = time.perf_counter()
            prob, dsol, found = converge(prob, dsol, say=say, fix_d=dk, coarsest=design.mesh["segments_scene"])
            design.mesh["catalogue"] = {**found.to_dict(), "seconds": time.perf_counter() - t0} if found else None
        if not dsol.feasible:
            continue
        xs = rounded_up(prob, dsol.xs)
        say(f"verifying d = {dk * 1e3:g} mm by simulation")
        design.manoeuvres = by_manoeuvre(_checked(prob, xs, "catalogue"))
        design.nlp_cases = [prob.cases[i].to_dict() | {"manoeuvre": prob.cases[i].label} for i in prob.selected]
        design.feasible = True
        design.design = prob.to_si(xs)
        design.active = _active(dsol, prob, True)
        design.margins = _margins(prob, xs, design.manoeuvres)
        values = prob.evaluate(xs)
        design.power = {k: values[k] for k in ("N_p_up", "N_p_down") if k in values}
        if prob.least_drum:
            design.least_drum = values["D"]
        design.message = (f"design found; every check holds through {prob.machine.manoeuvres.TEXT['all']} "
                          "(verified by simulation where a check comes near its limit)")
        return design
    design.message = (f"no catalogue diameter from {d_star * 1e3:.4g} mm up keeps every check through the "
                      f"manoeuvres (the largest is {ropes.diameters()[-1] * 1e3:g} mm)")
    why_no_size(problem, d_star, design)
    return design


def why_no_size(problem, d_star: float, design: DynamicDesign) -> None:
    """Add to ``design.message`` what fails when the next catalogue size up fails the static checks alone
    (measured: winch_sizing_voigt with a 4 s ramp, continuous d = 52.96 mm under the drum's limit
    D / D_ratio_min = 53.33 mm, so 54 mm and up fail D / d >= 30 whatever the pretension and stroke)."""
    above = [d for d in ropes.diameters() if d >= d_star - 1e-9]
    if not above:
        return
    static = SizingProblem(problem.scene)
    diag = diagnose(static, fix_d=above[0])
    if not diag.feasible:
        design.diagnosis = diag
        design.message += (f"; the next size up, {above[0] * 1e3:g} mm, already fails the static checks: "
                           + diag.text(static.units))


def mesh_record(problem, found, n_scene: int, seconds: float) -> dict:
    """What the mesh control did (``--json``'s ``mesh``): the scene's and the chosen elements per span, the
    tolerance [N], each check's estimated discretisation error and its back-off in the NLP (the largest over the
    cases; ``cases``: each estimated case's own, with the margin, the unsafe part and how much worse a coarser
    mesh judged it), in the check's unit (N or m; the back-off adds the integration's), the observed orders,
    each mesh tried, the seconds."""
    if found is None:
        return {"segments_scene": None, "segments": None, "note": "the transient's rope has no elements to refine"}
    check = problem.machine.manoeuvres.CHECK
    index = {case.tag: i for i, case in enumerate(problem.cases)}

    def si(c: str, tag: str) -> float:
        return problem.backoff(c, index[tag]) * (problem.F_ref if check[c].unit == "N" else 1.0)

    out = found.to_dict()
    for entry in out["cases"]:
        entry["backoff"] = si(entry["check"], entry["case"])
    backed = [(tag, c) for tag, by in problem.backoffs.items() for c in by] + list(found.cases)
    largest: dict[str, float] = {}
    for tag, c in backed:           # every check the optimum's NLP backs off its own way, in any case
        largest[c] = max(largest.get(c, 0.0), si(c, tag))
    return {**out, "segments_scene": n_scene, "at": "the continuous optimum", "seconds": seconds,
            "backoffs": largest}


def slip_factors(scene) -> dict:
    """The slip factors of ``scene`` (value, the check it applies to and where it comes from), as its machine's
    manoeuvres declare them (``SLIP_FACTORS``, the static one first) — {} where the scene carries no static one
    (no lining's slip checks)."""
    out = {}
    for name, what in declared(scene).SLIP_FACTORS:
        if name in scene.parameters:
            out[name] = {"value": scene.parameters[name], "check": what, "basis": scene.basis(name)}
    first = declared(scene).SLIP_FACTORS[0][0]
    return out if first in out else {}
