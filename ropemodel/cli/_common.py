"""Helpers shared by the CLI commands: scene arguments, NAME=VALUE assignments, warnings."""

from __future__ import annotations

import sys

from ropemodel.errors import InputError, Problems


def parse_assignment(text: str, option: str) -> tuple[str, str]:
    """``NAME=VALUE`` → (name, value text).  The value keeps its unit; a bare number is accepted
    later only for a dimensionless quantity (never guessed as SI)."""
    if "=" not in text:
        raise InputError(f"{option} {text!r}: expected NAME=VALUE, e.g. {option} alpha_u=16deg")
    name, value = (s.strip() for s in text.split("=", 1))
    if not name or not value:
        raise InputError(f"{option} {text!r}: expected NAME=VALUE")
    return name, value


def assignments(items, option: str) -> dict[str, str]:
    """Every ``NAME=VALUE`` of a repeated option; all mistakes at once."""
    out, found = {}, Problems()
    for item in items or []:
        with found.collect():
            name, value = parse_assignment(item, option)
            if name in out:
                raise InputError(f"{option} {name} given twice")
            out[name] = value
    found.raise_if_any()
    return out


def name_list(items, option: str, example: str) -> list[str]:
    """The names of a comma-separated option, repeated or not (``--outputs F_C_up,dF_up --outputs N_p_up``);
    [] when the option is not given.  An empty list (``--outputs ''``), an empty item (``a,,b``) or a
    name given twice is refused naming the option; example: a valid value for the message."""
    items = [items] if isinstance(items, str) else list(items or [])
    out: list[str] = []
    found = Problems()
    for item in items:
        names = [n.strip() for n in item.split(",")]
        if not any(names):
            found.add(f"{option} {item!r} names nothing: give NAME[,NAME...], e.g. {option} {example}, "
                      f"or leave {option} out")
            continue
        if not all(names):
            found.add(f"{option} {item!r} has an empty name between its commas: e.g. {option} {example}")
        for n in filter(None, names):
            if n in out:
                found.add(f"{option} names {n} twice")
            else:
                out.append(n)
    found.raise_if_any()
    return out


def refuse_without(args, needs: str, *flags: str) -> None:
    """:class:`InputError` naming every flag of ``flags`` (attribute names of ``args``) that was given
    although it only acts with ``needs``."""
    given = [f for f in flags if getattr(args, f) not in (None, False, [])]
    if given:
        shown = ", ".join("--" + f.replace("_", "-") for f in given)
        raise InputError(f"{shown} {'acts' if len(given) == 1 else 'act'} only with {needs}: add {needs} or "
                         f"leave {shown} out")


def named(items, option: str, form: str) -> dict[str, str]:
    """``NAME=SPEC`` of a repeated option (``--vary``, ``--sobol``) → {name: spec}; a name given
    twice is refused.  form: what an item looks like, for the message (e.g. ``NAME=LOW:HIGH``)."""
    out = {}
    for item in items or []:
        if "=" not in item:
            raise InputError(f"{option} {item!r}: expected {form}")
        name, spec = (s.strip() for s in item.split("=", 1))
        if name in out:
            raise InputError(f"{option} {name} given twice")
        out[name] = spec
    return out


#: built-in scenes the help suggests, with what they are
EXAMPLES = {"example": "Fig. 9", "winch_sizing_fig9": "Fig. 9 with a catalogue rope", "winch_start": "a start-up",
            "trip_fig9": "Fig. 9 as a whole trip", "capstan_li_experiment": "Li et al.'s capstan drive"}


def add_scene_arguments(parser, optional: bool = True, example: str = "example") -> None:
    """The scene argument (``example``: a built-in scene this command takes, suggested in its help), ``--set``
    and ``--json``."""
    if optional:
        parser.add_argument("scene", nargs="?", help="scene TOML file (default: the built-in Fig. 9 example)")
    else:
        parser.add_argument("scene", help=f"scene TOML file, or the name of a built-in scene ('{example}' for "
                                          f"{EXAMPLES[example]})")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a parameter; a dimensional VALUE carries its unit, e.g. alpha_u=20deg")
    parser.add_argument("--json", action="store_true", help="print one JSON object in SI units")


def scene_from_args(args, optional=(), announce: bool = True):
    """Load the scene named on the command line and apply ``--set``; print its warnings on stderr."""
    from ropemodel.scene import load

    scene = load(args.scene, optional=optional, emit=False, values=assignments(args.set, "--set"),
                 bare="refuse", origin="--set")
    if announce:
        warn(scene.warnings)
    return scene


def add_at_argument(parser) -> None:
    """``--at NAME=VALUE``: one point (the load's place, the acceleration) instead of the worst case."""
    parser.add_argument("--at", action="append", metavar="NAME=VALUE", default=[],
                        help="one point instead of the worst case: the load's place x_m (e.g. x_m=1300m) or the "
                             "haulage's acceleration a_h (with the ramps' inertia); repeat for both")


def pinned(scene, items):
    """The scene with the case inputs of ``--at`` set (each must be one the scene's results depend on)."""
    from ropemodel.envelope import CASE_INPUTS

    values, found = assignments(items, "--at"), Problems()
    for name in values:
        if name not in CASE_INPUTS:
            found.add(f"--at {name}: --at takes the load's place x_m or the acceleration a_h; set other "
                      f"parameters with --set {name}=...")
        elif name not in scene.built.parameters:
            found.add(f"--at {name}: this scene's results do not depend on {name} "
                      + ("(a straight route without design checks: the forces are the same wherever the load is)"
                         if name == "x_m" else "(no ramps' inertia: set [effects] inertia = \"rigid\")"))
    found.raise_if_any()
    return scene.with_values(values, bare="refuse", origin="--at") if values else scene


def worst_case_scene(args):
    """The scene of the command line as the worst case takes it: its starts and stops switched on where it
    gives ``t_ramp`` (:func:`ropemodel.envelope.with_ramps`), its warnings printed, ``--at`` applied."""
    from ropemodel.envelope import with_ramps

    scene = with_ramps(scene_from_args(args, announce=False))
    warn(scene.warnings)
    return pinned(scene, getattr(args, "at", []))


def sizing_scene_from_args(args, dynamic: bool | None = False, declared_ok: bool = False):
    """The scene of a sizing command (``size``, ``sweep --sizing``, ``sensitivity --sizing``) as sizing reads it:
    no starting design needed (d, F_nwl, stroke, and D on a rigid drum), design checks on; its warnings on
    stderr.  ``dynamic``: sized through its transients, with the transient dynamic sizing builds (None: when
    ``--dynamic`` is given or the scene says ``[numerics] sizing = "dynamic"``, as ``size`` decides).
    ``declared_ok``: a machine whose sizing is a :class:`~ropemodel.machines.sizing.Declaration` (an integer
    enumerated, one NLP each) is accepted (``size``); else refused."""
    from optimisation.problem import D_OPTIONAL, SIZED, prepare, reads
    from ropemodel.machines import machine_of
    from ropemodel.machines.sizing import declared

    given = scene_from_args(args, optional=SIZED + D_OPTIONAL, announce=False)
    if dynamic is None:
        dynamic = bool(getattr(args, "dynamic", False)) or given.numerics.get("sizing") == "dynamic"
    if not declared_ok and declared(given) is not None:
        raise InputError(f"--sizing sizes at every point a machine sized in one NLP; a {given.model} is sized by "
                         f"`ropemodel size` (its sizing at many points is not built yet)")
    if dynamic and declared(given) is not None and getattr(machine_of(given), "manoeuvres", None) is None:
        raise InputError(f"--dynamic sizes a machine through the manoeuvres it declares, and a {given.model} declares "
                         f"none; `ropemodel size` without --dynamic sizes it through the transients its sizing "
                         f"simulates (a scene with dynamics = \"braking\")")
    try:
        scene = prepare(given)
    except InputError as exc:             # a dynamic sizing names what its transient lacks in the same error
        if not dynamic:
            raise
        from optimisation.dynamic.transient import missing

        raise InputError(problems=[*exc.problems, *missing(given)]) from None
    warn(scene.warnings)
    if dynamic:
        from optimisation.dynamic.transient import reads as dynamic_reads
        from optimisation.dynamic.transient import transient_scene

        scene = transient_scene(scene)
        warn_unread(scene, "the dynamic sizing", *dynamic_reads(scene))
    else:
        warn_unread(scene, "the sizing", *reads(scene))
    return scene


def warn_unread(scene, command: str, reads=None, chosen=None) -> None:
    """Warn of each value given on top of the scene's file (``--set``) that ``command`` does not use:
    ``chosen`` (name → how) it sets itself, the rest are not among ``reads`` (default: the parameters every
    output of the scene's static model is computed from, and those its worst case reads:
    :func:`ropemodel.envelope.reads`)."""
    from ropemodel.envelope import reads as case_reads
    from ropemodel.unread import not_read

    reads = scene.built.inputs_of() if reads is None else set(reads)
    warn(not_read(scene, reads | case_reads(scene), command, chosen))


def warn(lines) -> None:
    """Each line as ``warning: ...`` on stderr."""
    for line in lines:
        print(f"warning: {line}", file=sys.stderr)
