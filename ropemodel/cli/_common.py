"""Helpers shared by the CLI commands."""

from __future__ import annotations

from ropemodel.errors import InputError
from ropemodel.scene import load


def parse_assignment(text: str, option: str) -> tuple[str, object]:
    """``NAME=VALUE`` → (name, value); the value is a float if it reads as one, else a unit string."""
    if "=" not in text:
        raise InputError(f"{option} {text!r}: expected NAME=VALUE, e.g. {option} alpha_u=16deg")
    name, value = (s.strip() for s in text.split("=", 1))
    if not name or not value:
        raise InputError(f"{option} {text!r}: expected NAME=VALUE")
    try:
        return name, float(value)
    except ValueError:
        return name, value


def assignments(items, option: str) -> dict[str, object]:
    out = {}
    for item in items or []:
        name, value = parse_assignment(item, option)
        if name in out:
            raise InputError(f"{option} {name} given twice")
        out[name] = value
    return out


def add_scene_arguments(parser, optional: bool = True) -> None:
    if optional:
        parser.add_argument("scene", nargs="?", help="scene TOML file (default: the built-in Fig. 9 example)")
    else:
        parser.add_argument("scene", help="scene TOML file, or the name of a built-in scene ('example' for Fig. 9)")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE", default=[],
                        help="override a parameter; VALUE is SI or carries a unit, e.g. alpha_u=20deg")
    parser.add_argument("--json", action="store_true", help="print one JSON object in SI units")


def scene_from_args(args):
    """Load the scene named on the command line and apply ``--set``."""
    scene = load(args.scene)
    values = assignments(args.set, "--set")
    return scene.with_values(values) if values else scene
