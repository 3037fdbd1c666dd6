"""Every flag of every command, alone at the edges of its values and in pairs, read from the parser itself.

:func:`ropemodel.cli.build_parser` lists each command's options; each gets odd values from what the parser
knows of it (a whole number: 0, -1, 2^63, a fraction, text; a choice: each choice and one that is not; a
text value: empty, commas only, a NUL, 5000 characters), and every pair of a command's options is tried
with a valid use of each (:data:`GOOD`).  A flag alone must give a sound result or fail cleanly; a pair
must give a sound result or fail cleanly naming one of its two flags (a contradiction is refused by
name).  A new option fails :func:`missing_good` until :data:`GOOD` says how it is used, and is then
fuzzed with the rest.
"""

from __future__ import annotations

import argparse
import itertools

from _fuzz import INPUT, Case, base_case, builtin

SOUND = frozenset({0, 1, 2})
#: argv of a valid use of each option on the command's base scene (or on the scene named third), or None
#: for an option the base invocation already uses.  An entry whose second item is True replaces the base's
#: options after the scene (it needs others), with the files it needs.
POINTS = {"p.csv": b"alpha_u [deg]\n10\n12\n"}
SIZING = ["--vary", "G_m=400kN,467kN", "--sizing", "-o", "{d}/z.csv"]
DYNAMIC_SIZING = ["--vary", "G_m=460kN,467kN", "--sizing", "--dynamic", "-o", "{d}/z.csv"]
COMMON = {"set": (["--set", "mu_pl=0.06"], False, None), "json": (["--json"], False, None),
          "quiet": (["-q"], False, None), "no_limit": (["--no-limit"], False, None)}
GOOD = {
    "run": {"worst": (["--worst"], False, "route_segments"), "at": (["--at", "x_m=100m"], False, "route_segments")},
    "solve": {"given": None, "find": None, "at": (["--at", "x_m=100m"], False, "route_segments")},
    "size": {"discrete": (["--discrete", "bonmin"], False, None), "dynamic": (["--dynamic"], False, "dynamic"),
             "find": (["--dynamic", "--find", "t_ramp"], False, "dynamic")},
    "curve": {"set": (["--set", "R=80mm"], False, None),      # a capstan scene: none of the winch's names
              "to": None, "n": None, "start": (["--from", "10N"], False, None), "display": (["--display"], False, None),
              "output": (["-o", "{d}/c.csv"], False, None)},
    "identify": {"set": (["--set", "R=80mm"], False, None),
                 "data": None, "fit": (["--fit", "mu"], False, None), "sigma": (["--sigma", "0.01deg"], False, None)},
    "simulate": {"output": (["-o", "{d}/h.csv"], False, None)},
    "sweep": {"vary": None, "output": None, "points": (["--points", "{d}/p.csv", "-o", "{d}/out.csv"], True, None),
              "outputs": (["--outputs", "F_C_up"], False, None),
              "given": (["--vary", "F_C_up=180kN:200kN:3", "--given", "F_C_up", "--find", "G_m", "-o", "{d}/g.csv"],
                        True, None),
              "find": (["--vary", "dF_up=900mm:1000mm:3", "--given", "dF_up", "--find", "q_lw", "-o", "{d}/f.csv"],
                       True, None),
              "chunk_size": (["--chunk-size", "2"], False, None), "threads": (["--threads", "1"], False, None),
              "backend": (["--backend", "casadi"], False, None), "si": (["--si"], False, None),
              "mark_failures": (["--mark-failures"], False, None), "restart": (["--restart"], False, None),
              "sizing": (SIZING, True, "winch_sizing_fig9"), "cold": ([*SIZING, "--cold"], True, "winch_sizing_fig9"),
              "dynamic": (DYNAMIC_SIZING, True, "dynamic"), "no_progress": (["--no-progress"], False, None)},
    "sensitivity": {"scene": None, "outputs": None, "at": (["--at", "x_m=100m"], False, "route_segments"),
                    "parameters": (["--parameters", "G_m"], False, None),
                    "plot": (["--plot", "{d}/t.png"], False, None),
                    "sobol": (["--sobol", "G_m=400kN:467kN", "--samples", "8"], False, None),
                    "samples": (["--sobol", "G_m=400kN:467kN", "--samples", "16"], False, None),
                    "seed": (["--sobol", "G_m=400kN:467kN", "--samples", "8", "--seed", "7"], False, None),
                    "sizing": (["--sizing", "--sobol", "G_m=400kN:467kN", "--samples", "4"], True,
                               "winch_sizing_fig9")},
    "trip": {"direction": (["--direction", "down"], False, None), "output": (["-o", "{d}/t.csv"], False, None)},
    "report": {"output": None, "pdf": (["--pdf", "{d}/r.pdf"], False, None),
               "discrete": (["--discrete", "next-size-up"], False, None),
               "format": (["--format", "json", "-o", "{d}/calc.json"], True, None)},
}
SKIP = ("help", "scene", "_main")


def options() -> dict[str, list[argparse.Action]]:
    """Each command's options, from the parser the command line builds."""
    from ropemodel.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return {name: [a for a in p._actions if a.dest not in SKIP and a.option_strings]
            for name, p in sub.choices.items()}


def good(command: str, dest: str):
    return {**COMMON, **GOOD.get(command, {})}.get(dest, "missing")


def missing_good() -> list[str]:
    """Options without a valid use in :data:`GOOD` (a new flag must say how it is used)."""
    return [f"{c} {a.option_strings[-1]}" for c, acts in options().items() for a in acts
            if good(c, a.dest) == "missing"]


def _scene_text(name: str | None):
    if name is None:
        return None
    if name == "dynamic":
        from _dynamic_scene import SCENE

        return SCENE.format(extra="")
    return builtin(name)


def odd_values(action) -> list[tuple[str, str]]:
    """(label, value) of values at the edges of what ``action`` takes."""
    if action.nargs == 0:
        return []
    if action.choices:
        return [(f"choice {c}", str(c)) for c in action.choices] + [("not a choice", "nope"), ("empty", "")]
    if action.type is int:
        return [("0", "0"), ("-1", "-1"), ("2^63", str(2**63)), ("a fraction", "1.5"), ("text", "many"),
                ("empty", "")]
    return [("empty", ""), ("commas only", ",,"), ("a space", " "), ("a NUL", "a\x00b"),
            ("5000 characters", "x" * 5000)]


def single_cases() -> list[Case]:
    """Each option alone: a valid use (sound), and odd values (sound or a clean failure)."""
    cases = []
    for command, actions in options().items():
        for action in actions:
            flag = action.option_strings[-1]
            entry = good(command, action.dest)
            if entry is not None and entry != "missing":
                argv, replace, scene = entry
                a, f = base_case(command, _scene_text(scene), argv=argv if replace else None,
                                 extra=() if replace else argv, files=POINTS)
                cases.append(Case(command, "flag", f"{flag} alone", a, f, SOUND, expect="sound"))
            for label, value in odd_values(action):
                a, f = base_case(command, extra=[flag, value])
                cases.append(Case(command, "flag", f"{flag} {label}", a, f, SOUND, expect="sound"))
    return cases


def pair_cases() -> list[Case]:
    """Every pair of a command's options, each used validly: a sound result, or a refusal naming one."""
    cases = []
    for command, actions in options().items():
        usable = [(a.option_strings[-1], good(command, a.dest)) for a in actions]
        usable = [(flag, e) for flag, e in usable if e not in (None, "missing")]
        for (fa, (a, ra, sa)), (fb, (b, rb, sb)) in itertools.combinations(usable, 2):
            if (ra and rb) or (sa and sb and sa != sb) or set(x for x in a if x.startswith("-")) & set(
                    x for x in b if x.startswith("-")):
                continue      # two replacements, two scenes, or one option twice: not a pair of uses
            replace = a if ra else b if rb else None
            extra = [x for x, r in ((a, ra), (b, rb)) if not r]
            argv, files = base_case(command, _scene_text(sa or sb), argv=replace,
                                    extra=[x for e in extra for x in e], files=POINTS)
            cases.append(Case(command, "flag pair", f"{fa} with {fb}", argv, files, SOUND | INPUT, expect="sound",
                              words=((fa, fb, *[x for x in a + b if "=" in x]),)))
    return cases
