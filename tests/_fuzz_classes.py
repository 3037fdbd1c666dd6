"""The classes of inputs a second, independent fuzz found mishandled (issue 22), each a generated family here.

* output paths: a name or path too long for the file system (5000 characters; a 250-byte name; a folder
  name too long), a NUL, a read-only file in the way, a place that refuses files, for every output of
  every command; a disk that fills while the output is written (a file-size limit in a real process);
* inputs outside their physical domain where the scene does not use them, and magnitudes of 1e308 with a
  unit (the edges of every domain are generated in ``_fuzz_edges``);
* work without bounds: a transient of 10^6 s or at sim_dt = 1e-9 s, a Sobol study of 2^20 samples, sizing
  on a route of many short segments — each refused above its budget, naming ``--no-limit``;
* empty and contradictory flags, data with no information, a rope slack at rest;
* a UTF-8 byte-order mark in a scene, a points file and identification data (accepted);
* messages that must name the actual fix;
* valid inputs that were refused (dynamic sizing with the capstan drum contact, with mu_d = 5; sizing
  sensitivities of the README's shortest sizing scene; sizing on a short route of segments);
* the classes again on the Koepe hoist (``model = "koepe"``).
"""

from __future__ import annotations

from _fuzz import CAPSTAN_DATA, FAIL, INPUT, Case, base_case, builtin, drop_key, set_value

SOUND = frozenset({0})
LONG = "a" * 5000
#: every command that writes a file: (command, its output option, suffix, argv before it, base scene or None)
OUTPUTS = (("curve", "-o", ".csv", ["--to", "100N", "-n", "5"], None), ("simulate", "-o", ".csv", [], None),
           ("trip", "-o", ".csv", [], None),
           ("sweep", "-o", ".csv", ["--vary", "alpha_u=5deg:20deg:3"], None),
           ("sweep", "-o", ".csv", ["--vary", "G_m=400kN,467kN", "--sizing"], "winch_sizing_fig9"),
           ("report", "-o", ".html", [], None), ("report", "--pdf", ".pdf", [], None),
           ("sensitivity", "--plot", ".png", ["--outputs", "F_C_up"], None))


def _out(command, option, path, before, scene, what, files=None, codes=INPUT, words=()) -> Case:
    argv, f = base_case(command, scene_text=builtin(scene) if scene else None, argv=[*before, option, path],
                        files=files)
    return Case(command, "output", f"{option} {what}" + (" (--sizing)" if "--sizing" in before else ""), argv, f,
                codes, words=words)


def output_path_cases() -> list[Case]:
    cases = []
    for command, option, suffix, before, scene in OUTPUTS:
        for what, path, files, words in (
                ("5000 characters", LONG + suffix, {}, ("characters", "File name too long")),
                ("a folder name too long", "{d}/" + "f" * 300 + "/o" + suffix, {}, ("File name too long",)),
                ("a 250-byte name", "{d}/" + "n" * 246 + suffix, {}, ("bytes long",)),
                ("a NUL in the name", "{d}/o\x00" + suffix, {}, ("NUL",)),
                ("a read-only file in the way", "{d}/ro" + suffix, {"ro" + suffix: b"old"}, ("read-only",)),
                ("a place that refuses files", "/sys/ropemodel-fuzz" + suffix, {}, ("cannot write",))):
            case = _out(command, option, path, before, scene, what, files, words=words)
            if what.startswith("a read-only"):
                case.kind = "output read-only"     # the test makes the file read-only before running
            cases.append(case)
    return cases


def disk_full_cases() -> list[Case]:
    """The disk fills while the output is written: a real process with RLIMIT_FSIZE (exit 1, one line, nothing
    left beside the inputs)."""
    return [_out(command, option, "{d}/full" + suffix, before, scene, "on a disk that fills", codes=FAIL,
                 words=("cannot write",)) for command, option, suffix, before, scene in OUTPUTS]


def domain_cases() -> list[Case]:
    """Values outside their domain where the scene does not use them; magnitudes of 1e308 with a unit."""
    cases = []
    unused = (("eta", "5"), ("v_pj", '"-5 m/s"'), ("mu_d", "-1"), ("stroke", '"-1 mm"'), ("n_rope", "0"),
              ("alpha_d", '"-3 deg"'), ("t_ramp", '"0 s"'))
    for key, raw in unused:
        argv, files = base_case("run", set_value(builtin("krauze2025_fig9"), "parameters", key, raw))
        cases.append(Case("run", "domain", f"unused {key} = {raw} outside its domain", argv, files, words=(key,)))
    route = set_value(builtin("route_segments"), "parameters", "alpha_u", '"95 deg"')
    cases.append(Case("trip", "domain", "unused alpha_u = 95 deg on a route of segments",
                      *base_case("trip", route), words=("alpha_u",)))
    beyond = set_value(builtin("krauze2025_fig9"), "parameters", "x_m", '"5000 m"')
    cases.append(Case("run", "domain", "unused x_m beyond a straight route", *base_case("run", beyond),
                      words=("x_m", "L_u")))
    for command in ("trip", "simulate"):
        for key, unit in (("t_ramp", "s"), ("v_pj", "m/s"), ("t_end", "s"), ("rope_damping", "s"), ("m_t", "kg")):
            argv, files = base_case(command, extra=["--set", f"{key}=1e308{unit}"])
            cases.append(Case(command, "domain", f"--set {key} = 1e308 {unit}", argv, files, words=(key,)))
    return cases


def route_scene(n: int, length: str) -> str:
    """The Fig. 9 sizing scene on a route of ``n`` segments of ``length`` each."""
    segments = "".join(f'[[route]]\nlength = "{length}"\ninclination = "{5 + i % 7} deg"\n' for i in range(n))
    head = builtin("winch_sizing_fig9").split("[parameters]")
    params = drop_key(drop_key("[parameters]" + head[1], "parameters", "L_u"), "parameters", "L_ul")
    return head[0].replace("[effects]", '[effects]\nroute = "segments"') + segments + params


def budget_cases() -> list[Case]:
    """Work above its budget, refused with the count and --no-limit."""
    dt = set_value(builtin("winch_start"), "numerics", "sim_dt", "1e-9")
    rows = [Case("simulate", "budget", "t_end = 1e6 s", *base_case("simulate", extra=["--set", "t_end=1e6s"]),
                 words=("history rows", "--no-limit")),
            Case("simulate", "budget", "sim_dt = 1e-9 s", *base_case("simulate", dt), words=("history rows",
                                                                                            "--no-limit")),
            Case("sensitivity", "budget", "--samples 2^20",
                 *base_case("sensitivity", argv=["--sobol", "G_m=400kN:467kN", "--samples", str(2**20)]),
                 words=("evaluations", "--no-limit")),
            # ``size`` itself sizes 1000 segments in seconds (constraint generation: its NLP holds a few places);
            # a sizing sweep checks every place in one NLP, each through the route: 51 x 50 is over the budget
            Case("sweep", "budget", "--sizing on a route of 50 segments of 1 m",
                 *base_case("sweep", route_scene(50, "1 m"),
                            argv=["--vary", "G_m=400kN,467kN", "--sizing", "-o", "{d}/o.csv"]),
                 words=("segment evaluations", "--no-limit"))]
    return rows


def flag_cases() -> list[Case]:
    """The empty and contradictory flags of the issue, and data with no information."""
    out = ["-o", "{d}/out.csv"]
    vary = ["--vary", "alpha_u=5deg:20deg:3"]
    rows = (("sweep", "--vary with an empty item", ["--vary", "alpha_u=5deg,,10deg", *out], None, ("--vary",)),
            ("sweep", "--outputs ''", [*vary, *out, "--outputs", ""], None, ("--outputs",)),
            ("sweep", "--outputs ',,'", [*vary, *out, "--outputs", ",,"], None, ("--outputs",)),
            ("sensitivity", "--parameters ','", ["--parameters", ","], None, ("--parameters",)),
            ("sweep", "--given NAME=VALUE and --vary NAME",
             ["--vary", "F_C_up=100kN:200kN:3", "--given", "F_C_up=150kN", "--find", "G_m", *out], None,
             ("--given", "--vary")),
            ("sweep", "--find NAME and --vary NAME", ["--vary", "G_m=400kN,467kN", "--given", "F_C_up=190kN",
                                                      "--find", "G_m", *out], None, ("--find",)),
            ("sweep", "--outputs NAME and --vary NAME", [*vary, *out, "--outputs", "alpha_u"], None, ("--outputs",)),
            ("sweep", "--cold without --sizing", [*vary, *out, "--cold"], None, ("--cold",)),
            ("sweep", "--dynamic without --sizing", [*vary, *out, "--dynamic"], None, ("--sizing",)),
            ("solve", "--find ''", ["--given", "dF_up=1000mm", "--find", ""], None, ("--find",)),
            ("size", "--find ''", ["--find", ""], None, ("--find",)),
            ("sensitivity", "--samples without --sobol", ["--samples", "8"], None, ("--samples",)),
            ("identify", "--fit ''", ["{d}/data.csv", "--fit", ""], None, ("--fit",)),
            ("sweep", "--chunk-size with --sizing", ["--vary", "G_m=400kN,467kN", "--sizing", "--chunk-size", "8",
                                                     *out], "winch_sizing_fig9", ("--chunk-size",)))
    cases = [Case(c, "flags", what, *base_case(c, scene_text=builtin(s) if s else None, argv=argv),
                  words=words) for c, what, argv, s, words in rows]
    repeated = b"F_T [N],delta_alpha [deg]\n40,0.1464\n40,0.1464\n40,0.1464\n40,0.1464\n"
    zeros = b"F_T [N],delta_alpha [deg]\n0,0\n0,0\n0,0\n"
    for what, data in (("only one row, repeated", repeated), ("only rows at no load", zeros)):
        cases.append(Case("identify", "flags", f"data: {what}", *base_case("identify", files={"data.csv": data}),
                          words=("distinct load",)))
    for scene in ("winch_start", "trip_fig9"):
        cases.append(Case("simulate", "flags", f"{scene}: F_nwl = 0, slack at rest",
                          ["simulate", scene, "--set", "F_nwl=0kN"], {}, words=("slack",)))
    return cases


BOM = b"\xef\xbb\xbf"


def bom_cases() -> list[Case]:
    """A UTF-8 byte-order mark (Windows editors) before a scene, a points file and identification data."""
    scene = BOM + builtin("krauze2025_fig9").encode()
    return [Case("run", "bom", "a scene with a BOM", *base_case("run", scene), SOUND, expect="sound"),
            Case("sweep", "bom", "a points file with a BOM",
                 *base_case("sweep", argv=["--points", "{d}/p.csv", "-o", "{d}/out.csv"],
                            files={"p.csv": BOM + b"alpha_u [deg]\n10\n12\n"}), SOUND, expect="sound"),
            Case("identify", "bom", "identification data with a BOM",
                 *base_case("identify", files={"data.csv": BOM + CAPSTAN_DATA}), SOUND, expect="sound")]


def message_cases() -> list[Case]:
    """Messages that must name the actual fix (and not the wrong one)."""
    capstan = builtin("winch_start_capstan").replace('lining = "rigid"', "").replace('D = "2.5 m"', "")
    rope = ('rope = "6x36-IWRC"',)
    rows = [Case("size", "message", "a scene without a rope construction",
                 *base_case("size", builtin("krauze2025_fig9")), words=rope),
            Case("size", "message", "--dynamic on a scene without a rope construction",
                 *base_case("size", builtin("winch_start"), extra=["--dynamic"]), words=rope),
            Case("sweep", "message", "--sizing on a scene without a rope construction",
                 *base_case("sweep", argv=["--vary", "G_m=400kN,467kN", "--sizing", "-o", "{d}/o.csv"]), words=rope),
            Case("sensitivity", "message", "--sizing on a scene without a rope construction",
                 *base_case("sensitivity", argv=["--sizing", "--sobol", "G_m=400kN:467kN", "--samples", "4"]),
                 words=rope),
            Case("curve", "message", "L = 0 from F_T = 0", *base_case("curve", extra=["--set", "L=0mm"]),
                 words=("L = 0",)),
            Case("simulate", "message", "drum_contact = capstan without a lining", *base_case("simulate", capstan),
                 words=("drum_contact = 'capstan' needs a friction drum",))]
    return rows


def refused_valid_cases() -> list[Case]:
    """Valid inputs that were refused: each must now give a result (exit 0)."""
    from _dynamic_scene import SCENE

    dyn = SCENE.format(extra="")
    capstan = dyn.replace('tensioner = "constant_force"', 'tensioner = "constant_force"\ndrum_contact = "capstan"')
    shortest = _readme_block("# ropemodel size: no starting design")
    return [Case("size", "valid", "--dynamic with drum_contact = capstan",
                 *base_case("size", capstan, extra=["--dynamic"]), SOUND, expect="sound"),
            Case("size", "valid", "--dynamic with mu_d = 5", *base_case("size", dyn.replace("mu_d = 0.2", "mu_d = 5"),
                                                                         extra=["--dynamic"]), SOUND, expect="sound"),
            Case("sensitivity", "valid", "--sizing on the README's shortest sizing scene",
                 *base_case("sensitivity", shortest, argv=["--sizing", "--sobol", "G_m=400kN:467kN", "--samples", "4"]),
                 SOUND, expect="sound"),
            Case("sweep", "valid", "--sizing on the README's shortest sizing scene",
                 *base_case("sweep", shortest, argv=["--vary", "G_m=400kN,467kN", "--sizing", "-o", "{d}/o.csv"]),
                 SOUND, expect="sound"),
            Case("size", "valid", "a route of 5 segments of 1 m", *base_case("size", route_scene(5, "1 m")), SOUND,
                 expect="sound")]


def koepe_cases() -> list[Case]:
    """The classes on the Koepe hoist (``model = "koepe"``) through the commands that take it: output paths,
    1e308 with a unit (a rule set reads H: no rule value from a refused H), an unused value outside its
    domain, a Sobol study above its budget, empty flags, a byte-order mark."""
    text = builtin("koepe_example")
    out = ["-o", "{d}/o.csv"]
    rows = [("report", "-o 5000 characters", ["-o", LONG + ".html"], text, ("File name too long",)),
            ("sweep", "-o 5000 characters", ["--vary", "H=500m,900m", "-o", LONG + ".csv"], text,
             ("File name too long",)),
            ("sweep", "--outputs ''", ["--vary", "H=500m,900m", *out, "--outputs", ""], text, ("--outputs",)),
            ("sensitivity", "--samples 2^20", ["--sobol", "H=500m:900m", "--samples", str(2**20)], text,
             ("evaluations", "--no-limit")),
            ("run", "unused Q_R = 2 1/N outside its domain", [], set_value(text, "parameters", "Q_R", '"2 1/N"'),
             ("Q_R",))]
    rows += [("run", f"{key} = 1e308 {unit}", [], set_value(text, "parameters", key, f'"1e308 {unit}"'), (key,))
             for key, unit in (("H", "m"), ("m_payload", "kg"), ("v_max", "m/s"), ("F_r", "N"))]
    cases = [Case(c, "koepe", what, *base_case(c, scene, argv=argv), words=words)
             for c, what, argv, scene, words in rows]
    cases.append(Case("run", "koepe", "a Koepe scene with a BOM", *base_case("run", BOM + text.encode()), SOUND,
                      expect="sound"))
    return cases


def _readme_block(first_line: str) -> str:
    """The scene the documentation shows under "The shortest scene for each command" whose first line is
    ``first_line`` (the scene reference, docs/scenes.md)."""
    from _docs_text import section

    text = section("The shortest scene for each command")
    start = text.index(first_line)
    return text[text.index("\n", start) + 1:text.index("```", start)]


def issue_cases() -> list[Case]:
    return (output_path_cases() + domain_cases() + budget_cases() + flag_cases() + bom_cases() + message_cases()
            + refused_valid_cases() + koepe_cases())
