"""The bad inputs of the command-line fuzz (``tests/test_fuzz.py``): generated, deterministic.

Every case is a command line that must fail cleanly: a scene file with bad contents, a bad option,
a bad data file or a bad output path.  Each starts from a *base* invocation of its command that
succeeds (``test_fuzz.py`` checks it), and changes one thing, so the change is what fails.
Choices among many (which parameter gets which bad value) come from ``random.Random(SEED)``.

A case is a :class:`Case`: ``argv`` with ``{d}`` standing for the case's own directory, the files
to write there first (bytes, or ``DIR`` for a directory), and the exit statuses it may end with
(2: bad input; 1: no valid solution, or work that could not be completed).
"""

from __future__ import annotations

import io
import random
import tomllib
from dataclasses import dataclass, field
from importlib import resources

SEED = 20261123
DIR = object()     # a file entry that is a directory
INPUT, FAIL = frozenset({2}), frozenset({1})


@dataclass
class Case:
    command: str
    kind: str                     # scene, option, data, output, edge, ...
    what: str                     # short description (the test id)
    argv: list[str]
    files: dict = field(default_factory=dict)
    codes: frozenset = INPUT
    #: "fail": a clean failure with one of ``codes``; "sound": exit 0 with a sound result, or a clean failure
    expect: str = "fail"
    #: words the error message must hold (e.g. the parameter or the flag it names)
    words: tuple = ()


def builtin(name: str) -> str:
    return resources.files("ropemodel.data").joinpath(f"{name}.toml").read_text()


#: command → (base scene, argv after the scene, files the base needs); each base succeeds.
#: the rotations of the Li et al. drive (mu = 0.25, EA = 50 kN) rounded to 1e-4 deg, as an encoder would give them
CAPSTAN_DATA = (b"F_T [N],delta_alpha [deg]\n0,0\n10,0.0314\n20,0.0691\n40,0.1464\n60,0.2238\n80,0.3786\n"
                b"100,0.5336\n")
BASES = {
    "run": ("krauze2025_fig9", [], {}),
    "solve": ("krauze2025_fig9", ["--given", "dF_up=1000mm", "--find", "q_lw"], {}),
    "size": ("winch_sizing_fig9", [], {}),
    "curve": ("capstan_li_experiment", ["--to", "100N", "-n", "5"], {}),
    "identify": ("capstan_li_experiment", ["{d}/data.csv"], {"data.csv": CAPSTAN_DATA}),
    "simulate": ("winch_start", [], {}),
    "sweep": ("krauze2025_fig9", ["--vary", "alpha_u=5deg:20deg:3", "-o", "{d}/out.csv"], {}),
    "sensitivity": ("krauze2025_fig9", ["--outputs", "F_C_up"], {}),
    "trip": ("trip_fig9", [], {}),
    "report": ("krauze2025_fig9", ["-o", "{d}/report.html"], {}),
    # a new command: its base here gets every scene case; its own options in _fuzz_cli.option_cases
}
#: scenes run also through 'run', so that every model's tables and numerics are fuzzed
EXTRA_RUN_SCENES = ("sheave_thirion", "capstan_li_experiment", "koepe_example")


def base_case(command: str, scene_text: str | bytes | None = None, scene_path: str = "{d}/scene.toml",
              extra=(), files=None, argv=None) -> tuple[list[str], dict]:
    """argv and files of ``command``'s base invocation with the scene replaced (text) and ``extra``
    options appended; ``argv`` replaces the options after the scene."""
    name, rest, base_files = BASES[command]
    text = builtin(name) if scene_text is None else scene_text
    out = {**base_files, **(files or {})}
    if scene_path == "{d}/scene.toml":
        out["scene.toml"] = text.encode() if isinstance(text, str) else text
    return [command, scene_path, *(rest if argv is None else argv), *extra], out


# ---------------------------------------------------------------- scene text edits

def set_value(text: str, table: str, key: str, raw: str) -> str:
    """``text`` with ``key = raw`` in ``[table]`` (replacing a line of that key, else added)."""
    lines, current, done = text.splitlines(), None, False
    for i, line in enumerate(lines):
        s = line.strip()
        if s.startswith("[") and not s.startswith("[["):
            current = s.strip("[] ")
        elif current == table and s.split("=", 1)[0].strip() == key and "=" in s:
            lines[i], done = f"{key} = {raw}", True
            break
    if not done:
        header = next((i for i, line in enumerate(lines) if line.strip() == f"[{table}]"), None)
        if header is None:
            lines += [f"[{table}]", f"{key} = {raw}"]
        else:
            lines.insert(header + 1, f"{key} = {raw}")
    return "\n".join(lines) + "\n"


def drop_key(text: str, table: str, key: str) -> str:
    lines, current, out = text.splitlines(), None, []
    for line in lines:
        s = line.strip()
        if s.startswith("["):
            current = s.strip("[] ")
        if current == table and "=" in s and s.split("=", 1)[0].strip() == key:
            continue
        out.append(line)
    return "\n".join(out) + "\n"


def _quantities(scene_name: str):
    import ropemodel as rm

    return rm.load_scene(scene_name, emit=False).built.quantities


def _outside(q) -> list[str]:
    """TOML values of ``q`` outside its valid range (in its SI unit)."""
    unit = "" if q.dimensionless else f" {q.unit}"
    out = []
    if q.low > -float("inf"):
        out.append(q.low - max(1.0, abs(q.low)) if not q.low_open else q.low)
    if q.high < float("inf"):
        out.append(q.high + max(1.0, abs(q.high)) if not q.high_open else q.high)
    return [f"{v!r}" if not unit else f'"{v!r}{unit}"' for v in out]


def bad_values(q) -> list[tuple[str, str, frozenset]]:
    """(label, TOML value, exit codes) of values ``q`` must refuse."""
    unit = "" if q.dimensionless else f" {q.unit}"
    vals = [("boolean", "true", INPUT), ("array", "[1, 2]", INPUT), ("inline table", "{ a = 1 }", INPUT),
            ("date", "1979-05-27", INPUT), ("text", '"abc"', INPUT), ("empty text", '""', INPUT),
            ("400-digit integer", "1" * 400, INPUT), ("nan", "nan", INPUT), ("inf", "inf", INPUT),
            ("-inf", "-inf", INPUT), ("nan with unit", f'"nan{unit}"', INPUT),
            ("overflowing text", f'"1e999{unit}"', INPUT), ("unknown unit", '"3 furlong"', INPUT),
            ("unit first", f'"{unit.strip() or "kN"} 3"', INPUT), ("two numbers", f'"3 4{unit}"', INPUT)]
    if not q.dimensionless:
        vals += [("bare number", "300", INPUT), ("bare text number", '"300"', INPUT)]
        vals.append(("wrong dimension", '"3 s"' if "s" not in q.unit.split("/")[0] else '"3 kg"', INPUT))
    else:
        vals.append(("unit on a pure number", '"3 kN"', INPUT))
    vals += [(f"outside the valid range ({v})", v, INPUT) for v in _outside(q)]
    if getattr(q, "unlimited", False):   # inf says "unlimited" there (e.g. the tensioner's stroke)
        vals = [v for v in vals if v[0] != "inf"]
    return vals


def scene_file_cases() -> list[Case]:
    """Whole-file problems, for every command."""
    cases = []
    contents = {
        "binary": bytes(range(256)) * 4, "empty": b"", "only a comment": b"# nothing\n",
        "Latin-1 text": "[scene]\nname = \"caf\xe9\"\n".encode("latin-1"),
        "UTF-16": "[scene]\nname = \"x\"\n".encode("utf-16"),
        "NUL in text": b"[scene]\nname = \"a\x00b\"\n",
        "TOML: unclosed table": b"[scene\nname = 1\n", "TOML: bare key no value": b"[parameters]\nG_m =\n",
        "TOML: duplicate key": b"[scene]\nname = \"a\"\nname = \"b\"\n",
        "TOML: duplicate table": b"[scene]\n[scene]\n", "TOML: unterminated string": b"[scene]\nname = \"a\n",
        "TOML: invalid escape": b'[scene]\nname = "\\q"\n', "TOML: value without key": b"= 3\n",
        "TOML: a number as the whole file": b"3\n", "TOML: huge nesting": b"a = " + b"[" * 5000 + b"]" * 5000,
    }
    for command in BASES:
        for what, data in contents.items():
            argv, files = base_case(command, data)
            cases.append(Case(command, "scene", f"file {what}", argv, files))
        for what, path, files in (("missing file", "{d}/nothere.toml", {}),
                                  ("a directory", "{d}/adir.toml", {"adir.toml": DIR}),
                                  ("under a regular file", "{d}/afile/scene.toml", {"afile": b"x"}),
                                  ("unknown built-in name", "krauze2025_fig10", {})):
            argv, base_files = base_case(command, scene_path=path)
            cases.append(Case(command, "scene", f"file {what}", argv, {**base_files, **files}))
    return cases


def scene_structure_cases() -> list[Case]:
    """Tables and keys of the wrong kind, unknown names, bad [numerics] — every command."""
    edits = [
        ("scene table is a number", lambda t: "scene = 3\n" + _without_table(t, "scene")),
        ("parameters table is text", lambda t: 'parameters = "x"\n' + _without_table(t, "parameters")),
        ("effects table is an array", lambda t: "effects = [1]\n" + _without_table(t, "effects")),
        ("numerics table is a number", lambda t: "numerics = 1.5\n" + _without_table(t, "numerics")),
        ("route is a number", lambda t: "route = 2\n" + t),
        ("model = 3", lambda t: set_value(t, "scene", "model", "3")),
        ("model = unknown", lambda t: set_value(t, "scene", "model", '"winhc"')),
        ("model = a table", lambda t: set_value(t, "scene", "model", "{ a = 1 }")),
        ("name = 5", lambda t: set_value(t, "scene", "name", "5")),
        ("unknown [scene] key", lambda t: set_value(t, "scene", "nmae", '"x"')),
        ("unknown table", lambda t: t + "\n[paramaters]\nx = 1\n"),
        ("unknown parameter", lambda t: set_value(t, "parameters", "alpa_u", '"16 deg"')),
        ("unknown effect", lambda t: set_value(t, "effects", "elongaton", '"none"')),
        ("unknown variant", lambda t: _first_effect(t, '"off"')),
        ("variant = 3", lambda t: _first_effect(t, "3")),
        ("variant = true", lambda t: _first_effect(t, "true")),
        ("variant = an array", lambda t: _first_effect(t, '["a"]')),
        ("an effect under [parameters]", lambda t: set_value(t, "parameters", "lining", '"rigid"')),
        ("unknown numerics option", lambda t: set_value(t, "numerics", "rtoll", "1e-6")),
        ("output given that disagrees", lambda t: t),   # replaced per model below
        ("a parameter left out", lambda t: t),           # replaced per scene below
    ]
    cases = []
    for command in BASES:
        name = BASES[command][0]
        text = builtin(name)
        for what, edit in edits:
            if what == "output given that disagrees":
                new = _disagreeing_output(name, text)
            elif what == "a parameter left out":
                new = drop_key(text, "parameters", _required(name))
            else:
                new = edit(text)
            if new == text:
                continue
            argv, files = base_case(command, new)
            cases.append(Case(command, "scene", what, argv, files))
    return cases


def _without_table(text: str, table: str) -> str:
    out, skip = [], False
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("["):
            skip = s.strip("[] ") == table
        if not skip:
            out.append(line)
    return "\n".join(out) + "\n"


def _first_effect(text: str, raw: str) -> str:
    data = tomllib.loads(text)
    effect = next(iter(data.get("effects", {})), None)
    return set_value(text, "effects", effect, raw) if effect else text


def _required(scene_name: str) -> str:
    data = tomllib.loads(builtin(scene_name))
    q = _quantities(scene_name)
    return next(k for k in data["parameters"] if q[k].default is None)


def _disagreeing_output(scene_name: str, text: str) -> str:
    model = tomllib.loads(text).get("scene", {}).get("model", "winch")
    key, raw = {"winch": ("F_C_up", '"1 kN"'), "capstan": ("K", '"1 N/m"'), "sheave": ("S", '"1 N"')}[model]
    return set_value(text, "parameters", key, raw)


def scene_value_cases(rng: random.Random) -> list[Case]:
    """Every kind of bad value, each on a parameter drawn at random, for every command and every
    model's scene; every [numerics] option with values of the wrong kind."""
    cases = []
    targets = [(c, BASES[c][0]) for c in BASES] + [("run", s) for s in EXTRA_RUN_SCENES]
    for command, name in targets:
        text = builtin(name)
        data = tomllib.loads(text)
        q = _quantities(name)
        keys = sorted(data["parameters"])
        dimensional = [k for k in keys if not q[k].dimensionless]
        for key in keys:   # every parameter once, with a value outside its range or a bad kind
            label, raw, codes = rng.choice(bad_values(q[key]))
            new = set_value(text, "parameters", key, raw)
            argv, files = _scene_argv(command, name, new)
            cases.append(Case(command, "scene", f"{name}: {key} = {label}", argv, files, codes))
        kinds = {label: (raw, codes) for k in dimensional[:1] for label, raw, codes in bad_values(q[k])}
        for label in kinds:   # every kind of bad value once, on a parameter drawn at random
            key = rng.choice(dimensional if label in ("bare number", "bare text number", "wrong dimension")
                             else keys)
            options = {lb: (r, c) for lb, r, c in bad_values(q[key])}
            if label not in options:   # e.g. inf, which an unlimited quantity takes
                continue
            raw, codes = options[label]
            new = set_value(text, "parameters", key, raw)
            argv, files = _scene_argv(command, name, new)
            cases.append(Case(command, "scene", f"{name}: {key} = {label} (drawn)", argv, files, codes))
        for option in sorted(_numerics(data)):
            for label, raw in (("text", '"many"'), ("boolean", "true"), ("negative", "-3"), ("zero", "0"),
                               ("fraction", "2.5"), ("huge", "1" * 400), ("nan", "nan"), ("array", "[8]")):
                if label == "fraction" and option not in WHOLE_NUMBERS:
                    continue
                new = set_value(text, "numerics", option, raw)
                argv, files = _scene_argv(command, name, new)
                cases.append(Case(command, "scene", f"{name}: [numerics] {option} = {label}", argv, files))
    return cases


#: [numerics] options that count something: 2.5 is refused there (elsewhere it may be a valid value)
WHOLE_NUMBERS = ("points", "steps", "segments")


def _numerics(data: dict) -> list[str]:
    from ropemodel.effects import numerics_of

    return list(numerics_of(data.get("scene", {}).get("model", "winch")))


def _scene_argv(command: str, scene_name: str, text: str):
    if command == "run" and scene_name != BASES["run"][0]:
        return ["run", "{d}/scene.toml"], {"scene.toml": text.encode()}
    return base_case(command, text)


def data_file(rows: str | bytes) -> bytes:
    return rows.encode() if isinstance(rows, str) else rows


def parquet_bytes(frame) -> bytes:
    buf = io.BytesIO()
    frame.to_parquet(buf, index=False)
    return buf.getvalue()
