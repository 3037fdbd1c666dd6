"""Simulate the transient of a scene: assemble it from the variants the scene picks and what its machine declares
(:class:`ropemodel.machines.Transient`), integrate it."""

from __future__ import annotations

from collections.abc import Mapping

from ropemodel.dynamics.assemble import build, declared
from ropemodel.dynamics.history import Simulation
from ropemodel.dynamics.hybrid import HybridIntegrator
from ropemodel.scene import SceneLike, as_scene

def simulate(scene: SceneLike, values: Mapping | None = None, progress: bool | None = None) -> Simulation:
    """Simulate the transient of a scene with a transient (``dynamics`` "start", "stop" or "trip").

    Parameters
    ----------
    scene : Scene or str or Path
        A scene of a machine with a transient whose ``dynamics`` effect makes one (a winch: "start", "stop"
        or "trip"; a Koepe hoist: "braking" or "start").
        A TOML scene file or a built-in scene's name is loaded first (:func:`ropemodel.load_scene`).
    values : dict, optional
        Scene parameters to override (SI numbers or strings with units).
    progress : bool, optional
        Show a status line while the model is built and a bar over the simulated time on stderr
        (default: when stderr is a terminal and not silenced; see :func:`ropemodel.progress.enabled`).

    Returns
    -------
    Simulation
        (or the machine's own result) ``history`` (DataFrame, SI, units in the column names: ``t [s]``,
        ``F_C [N]``, ...), ``summary``,
        ``events``.

    Raises
    ------
    InputError
        A scene without a transient, or one that cannot start (e.g. a slack rope).
    SolveError
        The integration fails or cannot meet its tolerance.

    Examples
    --------
    The 5 s start-up of the Fig. 9 haulage: the paper's static F_C_up = 190.95 kN, and the peak during
    the start 1.36 times that:

    >>> import ropemodel as rm
    >>> sim = simulate(rm.load_scene("winch_start"), progress=False)
    >>> round(sim.summary["F_C_static"] / 1e3, 2), round(sim.summary["dynamic_factor"], 2)
    (190.95, 1.36)
    """
    from ropemodel.progress import status

    scene = as_scene(scene)
    transient = declared(scene)
    if values:
        scene = scene.with_values(values)
    with status(f"simulating {scene.name}: building the transient", progress):
        system = build(scene)
        x0, mode = system.initial()
    atol = scene.numerics["sim_rtol"] * 1e-1 * max(transient.length(system), 1e-9)
    result = transient.result or Simulation
    return integrate(result(scene, system), system, x0, mode, atol, progress)


def integrate(sim, system, x0, mode, atol: float, progress: bool | None):
    """Run the hybrid integrator of ``system`` from ``(x0, mode)`` at the scene's ``[numerics]`` (sim_rtol,
    sim_dt, sim_integrator; ``atol`` in the state's units), its history within the work budget, recording
    into ``sim`` (a simulation of any model, with ``record`` and ``finish``) with a progress bar."""
    from ropemodel.progress import bar

    num = sim.scene.numerics
    integrator = HybridIntegrator(system, num["sim_rtol"], num["sim_dt"], num["sim_integrator"], atol)
    t_end = float(integrator.phases[-1].t1)
    _check_work(t_end, num["sim_dt"])
    with bar(t_end, "simulate", unit="s", flag=progress, bar_format="{l_bar}{bar}| {n:.1f}/{total:.1f} s") as shown:
        def record(times, X, out, mode):
            sim.record(times, X, out, mode)
            shown.update(max(0.0, min(float(times[-1]), t_end) - shown.n))

        events = integrator.run(x0, mode, record)
    sim.finish(events)
    return sim


#: the fewest columns a history has (time, speeds, forces, take-up, modes): a lower bound of its memory
HISTORY_COLUMNS = 10


def _check_work(t_end: float, dt: float) -> None:
    """The history's rows t_end/sim_dt against the work budget, and against memory whatever the budget."""
    from ropemodel import budget
    from ropemodel.sweeps.files import check_size

    rows = t_end / dt + 1
    budget.check("history", rows, f"a transient of {t_end:.6g} s at [numerics] sim_dt = {dt:g} s",
                 "take a larger sim_dt, or shorten t_end (a trip: its route or t_ramp)")
    check_size(int(min(rows, 2**62)), HISTORY_COLUMNS, what="a transient's history is kept in memory")
