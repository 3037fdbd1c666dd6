"""Bad options, data files and output paths of the command-line fuzz (see ``tests/_fuzz.py``)."""

from __future__ import annotations

import pandas as pd

from _fuzz import CAPSTAN_DATA, DIR, FAIL, Case, base_case, builtin, parquet_bytes, set_value

BIG = "1" * 400


def _opt(command: str, what: str, extra=(), argv=None, files=None, codes=None, scene=None, kind="option") -> Case:
    a, f = base_case(command, extra=extra, argv=argv, files=files, scene_path=scene or "{d}/scene.toml")
    return Case(command, kind, what, a, f, codes or frozenset({2}))


def option_cases() -> list[Case]:
    cases = [Case("(none)", "option", what, argv) for what, argv in (
        ("no command", []), ("unknown command", ["rn"]), ("unknown global option", ["--bogus", "run"]),
        ("only -q", ["-q"]), ("a scene but no command", ["example"]))]
    for command in ("run", "solve", "size", "curve", "identify", "simulate", "sweep", "sensitivity", "trip", "report"):
        cases += [_opt(command, what, extra) for what, extra in (
            ("unknown option", ["--bogus"]), ("--set without =", ["--set", "G_m"]),
            ("--set with no name", ["--set", "=3"]), ("--set with no value", ["--set", "G_m="]),
            ("--set an unknown name", ["--set", "G_mm=3kN"]), ("--set twice", ["--set", "mu=0.2", "--set", "mu=0.3"]),
            ("--set a 400-digit number", ["--set", f"mu={BIG}"]), ("--set nan", ["--set", "mu=nan"]),
            ("--set inf", ["--set", "mu=inf"]), ("--set a unit that is no unit", ["--set", "mu=0.2 furlong"]),
        )]
    cases += _run_solve_size() + _curve() + _identify_options() + _sweep_options() + _sensitivity_options()
    cases += [_opt("trip", what, extra, scene=scene) for what, extra, scene in (
        ("--direction unknown", ["--direction", "sideways"], None), ("a capstan scene", [], "capstan_li_experiment"),
        ("a sheave scene", [], "sheave_thirion"))]
    cases += [_opt("report", what, argv=argv) for what, argv in (
        ("nothing to write", []), ("-o and --pdf the same file", ["-o", "{d}/r.pdf", "--pdf", "{d}/r.pdf"]),
        ("--discrete unknown", ["-o", "{d}/r.html", "--discrete", "best"]))]
    cases.append(_opt("simulate", "a scene without dynamics", scene="example"))
    cases.append(_opt("simulate", "--set t_end bare", ["--set", "t_end=2"]))
    tiny = set_value(builtin("winch_start"), "numerics", "sim_rtol", "1e-300")
    cases.append(Case("simulate", "scene", "[numerics] sim_rtol = 1e-300", *base_case("simulate", tiny)))
    cases.append(_opt("simulate", "--set t_end negative", ["--set", "t_end=-2s"]))
    return cases


def _run_solve_size() -> list[Case]:
    cases = [_opt("run", what, extra) for what, extra in (
        ("--set a bare dimensional number", ["--set", "G_m=300"]),
        ("--set an output", ["--set", "F_C_up=100kN"]), ("--set an effect", ["--set", "lining=rigid"]),
        ("--set a wrong dimension", ["--set", "alpha_u=16kN"]), ("--set overflow", ["--set", "G_m=1e999kN"]),
        ("--set outside the range", ["--set", "alpha_u=90deg"]), ("--set a 400-digit G_m", ["--set", f"G_m={BIG}kN"]),
        ("--set beyond the route", ["--set", "L_ul=2000m"]), ("--json and bad --set", ["--json", "--set", "G_m=x"]),
    )]
    solve = [("no --given, no --find", []),
             ("--find twice", ["--given", "dF_up=1000mm", "--find", "q_lw", "--find", "q_lw"]),
             ("--find listed twice", ["--given", "dF_up=1000mm", "--find", "q_lw,q_lw"]),
             ("--find unknown", ["--given", "dF_up=1000mm", "--find", "q_lww"]),
             ("--find an output", ["--given", "dF_up=1000mm", "--find", "F_C_up"]),
             ("--given bare", ["--given", "dF_up=1000", "--find", "q_lw"]),
             ("--given unknown", ["--given", "dF_upp=1000mm", "--find", "q_lw"]),
             ("--given a parameter", ["--given", "G_m=300kN", "--find", "q_lw"]),
             ("--given without --find", ["--given", "dF_up=1000mm"]), ("--find without --given", ["--find", "q_lw"]),
             ("--given twice", ["--given", "dF_up=1000mm", "--given", "dF_up=900mm", "--find", "q_lw"]),
             ("--given without =", ["--given", "dF_up", "--find", "q_lw"]),
             ("--given nan", ["--given", "dF_up=nan mm", "--find", "q_lw"]),
             ("--given wrong unit", ["--given", "dF_up=1000kN", "--find", "q_lw"]),
             ("two --find, one --given", ["--given", "dF_up=1000mm", "--find", "q_lw", "--find", "G_m"]),
             ("--given unreachable", ["--given", "dF_up=-1e9mm", "--find", "q_lw"]),
             ("--given a 400-digit value", ["--given", f"dF_up={BIG}mm", "--find", "q_lw"])]
    cases += [_opt("solve", what, argv=argv, codes=FAIL if "unreachable" in what else None) for what, argv in solve]
    cases += [_opt("size", what, extra, scene=scene) for what, extra, scene in (
        ("--discrete unknown", ["--discrete", "best"], None), ("a capstan scene", [], "capstan_li_experiment"),
        ("--set d bare", ["--set", "d=42"], None), ("--set n_rope < 1", ["--set", "n_rope=0.5"], None),
        ("--set eta > 1", ["--set", "eta=1.5"], None), ("--set D negative", ["--set", "D=-1m"], None),
        ("--discrete given twice", ["--discrete", "bonmin", "--discrete", "nope"], None),
    )]
    return cases


def _curve() -> list[Case]:
    rows = (("--to bare", ["--to", "100"]), ("--to negative", ["--to", "-5N"]), ("--to zero", ["--to", "0N"]),
            ("--to overflow", ["--to", "1e999N"]), ("--to nan", ["--to", "nan N"]), ("--to inf", ["--to", "inf N"]),
            ("--to wrong unit", ["--to", "100m"]), ("--to text", ["--to", "lots"]), ("--to empty", ["--to", ""]),
            ("--to 400 digits", ["--to", f"{BIG}N"]), ("--to unwraps", ["--to", "1e6N"]),
            ("--from above --to", ["--from", "200N", "--to", "100N"]),
            ("--from negative", ["--from", "-1N", "--to", "100N"]),
            ("--from bare", ["--from", "5", "--to", "100N"]), ("-n 0", ["--to", "100N", "-n", "0"]),
            ("-n 1", ["--to", "100N", "-n", "1"]), ("-n -5", ["--to", "100N", "-n", "-5"]),
            ("-n a fraction", ["--to", "100N", "-n", "2.5"]), ("-n text", ["--to", "100N", "-n", "many"]),
            ("-n 1e11", ["--to", "100N", "-n", "100000000000"]), ("-n 400 digits", ["--to", "100N", "-n", BIG]),
            ("--to missing", ["-n", "5"]), ("--json and -o", ["--to", "100N", "--json", "-o", "{d}/c.csv"]))
    cases = [_opt("curve", what, argv=argv) for what, argv in rows]
    cases.append(_opt("curve", "a winch scene", scene="example"))
    return cases


def _identify_options() -> list[Case]:
    rows = (("--sigma 0", ["--sigma", "0deg"]), ("--sigma negative", ["--sigma", "-0.01deg"]),
            ("--sigma nan", ["--sigma", "nan deg"]), ("--sigma inf", ["--sigma", "inf deg"]),
            ("--sigma bare", ["--sigma", "0.01"]), ("--sigma wrong unit", ["--sigma", "1kN"]),
            ("--sigma text", ["--sigma", "small"]), ("--sigma 400 digits", ["--sigma", f"{BIG}deg"]),
            ("--sigma empty", ["--sigma", ""]), ("--fit unknown", ["--fit", "mu,EAA"]),
            ("--fit twice", ["--fit", "mu,mu"]),
            ("--fit empty", ["--fit", ""]), ("--fit commas", ["--fit", ",,"]), ("--fit R", ["--fit", "R"]),
            ("--fit as many as the points", ["--fit", "mu,EA,F_p,L"]))
    few = {"data.csv": b"F_T [N],delta_alpha [deg]\n10,0.0314\n20,0.0691\n40,0.1464\n60,0.2238\n"}
    cases = [_opt("identify", what, extra, files=few if "as many" in what else None) for what, extra in rows]
    cases.append(_opt("identify", "a winch scene", scene="example"))
    cases.append(_opt("identify", "no data file", argv=[]))
    return cases


def _sweep_options() -> list[Case]:
    out = ["-o", "{d}/out.csv"]
    vary = ["--vary", "alpha_u=5deg:20deg:3"]
    rows = (("--vary without =", ["--vary", "alpha_u"] + out),
            ("--vary bare angles", ["--vary", "alpha_u=0:45:10"] + out),
            ("--vary N = 0", ["--vary", "alpha_u=0deg:45deg:0"] + out),
            ("--vary N < 0", ["--vary", "alpha_u=0deg:45deg:-1"] + out),
            ("--vary N fraction", ["--vary", "alpha_u=0deg:45deg:2.5"] + out),
            ("--vary 1e11 points", ["--vary", "alpha_u=0deg:45deg:100000000000"] + out),
            ("--vary N 400 digits", ["--vary", f"alpha_u=0deg:45deg:{BIG}"] + out),
            ("--vary 1e12-point product",
             ["--vary", "alpha_u=0deg:45deg:1000000", "--vary", "G_m=1kN:2kN:1000000"] + out),
            ("--vary two parts", ["--vary", "alpha_u=0deg:45deg"] + out),
            ("--vary four parts", ["--vary", "alpha_u=0deg:1deg:2deg:3"] + out),
            ("--vary unknown", ["--vary", "alpha_uu=0deg:45deg:3"] + out), ("--vary twice", vary + vary + out),
            ("--vary outside the range", ["--vary", "alpha_u=80deg:100deg:3"] + out),
            ("--vary an output", ["--vary", "F_C_up=1kN:2kN:3"] + out),
            ("--vary empty list", ["--vary", "alpha_u=,"] + out),
            ("--vary nan", ["--vary", "alpha_u=nan deg,1deg"] + out),
            ("--vary bare list", ["--vary", "G_m=300,400"] + out),
            ("neither --vary nor --points", out), ("no -o", vary),
            ("--chunk-size 0", vary + out + ["--chunk-size", "0"]),
            ("--chunk-size -1", vary + out + ["--chunk-size", "-1"]),
            ("--chunk-size text", vary + out + ["--chunk-size", "big"]),
            ("--chunk-size 400 digits", vary + out + ["--chunk-size", BIG]),
            ("--threads 0", vary + out + ["--threads", "0"]), ("--threads -1", vary + out + ["--threads", "-1"]),
            ("--threads 2.5", vary + out + ["--threads", "2.5"]),
            ("--threads 400 digits", vary + out + ["--threads", BIG]),
            ("--backend unknown", vary + out + ["--backend", "gpu"]),
            ("--outputs unknown", vary + out + ["--outputs", "F_C_upp"]),
            ("--outputs a parameter", vary + out + ["--outputs", "G_m"]),
            ("--given unknown", vary + out + ["--given", "foo"]),
            ("--find without --given", vary + out + ["--find", "q_lw"]),
            ("--given without --find", ["--vary", "dF_up=900mm:1000mm:3"] + out + ["--given", "dF_up"]),
            ("--find twice", ["--vary", "dF_up=900mm:1000mm:3"] + out + ["--given", "dF_up", "--find", "q_lw,q_lw"]),
            ("--sizing with --given", vary + out + ["--sizing", "--given", "dF_up"]),
            ("--sizing on a scene that cannot size", vary + out + ["--sizing"]))
    return [_opt("sweep", what, argv=argv) for what, argv in rows]


def _sensitivity_options() -> list[Case]:
    s = ["--sobol", "alpha_u=10deg:20deg"]
    rows = (("--outputs unknown", ["--outputs", "F_C_upp"]), ("--parameters unknown", ["--parameters", "G_mm"]),
            ("--outputs a parameter", ["--outputs", "G_m"]), ("--parameters an output", ["--parameters", "F_C_up"]),
            ("--sobol without =", ["--sobol", "alpha_u"]), ("--sobol bare", ["--sobol", "alpha_u=10:20"]),
            ("--sobol reversed", ["--sobol", "alpha_u=20deg:10deg"]),
            ("--sobol empty range", ["--sobol", "alpha_u=10deg:10deg"]),
            ("--sobol outside the range", ["--sobol", "alpha_u=10deg:100deg"]),
            ("--sobol unknown", ["--sobol", "G_mm=1kN:2kN"]),
            ("--sobol three parts", ["--sobol", "alpha_u=1deg:2deg:3deg"]),
            ("--sobol nan", ["--sobol", "alpha_u=nan deg:2deg"]),
            ("--sobol an output", ["--sobol", "F_C_up=1kN:2kN"]), ("--sobol twice", s + s),
            ("--samples 0", s + ["--samples", "0"]), ("--samples 1", s + ["--samples", "1"]),
            ("--samples 2", s + ["--samples", "2"]), ("--samples 3", s + ["--samples", "3"]),
            ("--samples 1000", s + ["--samples", "1000"]), ("--samples -8", s + ["--samples", "-8"]),
            ("--samples 2**40", s + ["--samples", str(2 ** 40)]), ("--samples 400 digits", s + ["--samples", BIG]),
            ("--samples text", s + ["--samples", "many"]), ("--seed -1", s + ["--seed", "-1"]),
            ("--seed 400 digits", s + ["--seed", BIG]), ("--seed text", s + ["--seed", "x"]),
            ("--sizing without --sobol", ["--sizing"]), ("--sobol with --plot", s + ["--plot", "{d}/t.png"]),
            ("--sizing on a scene that cannot size", s + ["--sizing", "--samples", "4"]))
    return [_opt("sensitivity", what, argv=["--outputs", "F_C_up", *argv] if "--outputs" not in argv
                 and "--parameters" not in argv else argv) for what, argv in rows]


# ---------------------------------------------------------------- data files

POINTS = {
    "empty": b"", "header only": b"alpha_u [deg]\n", "ragged": b"alpha_u [deg],G_m [kN]\n10,300\n12\n14,300,5\n",
    "binary": bytes(range(256)) * 8, "Latin-1": "alpha_u [\xb0]\n10\n".encode("latin-1"),
    "UTF-16": "alpha_u [deg]\n10\n".encode("utf-16"), "booleans": b"alpha_u [deg]\ntrue\nfalse\n",
    "mixed booleans": b"alpha_u [deg]\n10\ntrue\n", "NaN": b"alpha_u [deg]\n10\nnan\n",
    "empty cell": b"alpha_u [deg],mu_pm\n10,\n",
    "inf": b"alpha_u [deg]\ninf\n", "text": b"alpha_u [deg]\nsteep\n", "no unit": b"alpha_u\n10\n",
    "wrong unit": b"alpha_u [kN]\n10\n", "unknown unit": b"alpha_u [furlong]\n10\n",
    "unknown column": b"alpha_uu [deg]\n10\n",
    "duplicate column": b"alpha_u [deg],alpha_u [rad]\n10,0.1\n", "only outputs": b"F_C_up [kN]\n100\n",
    "400-digit number": b"G_m [kN]\n" + BIG.encode() + b"\n", "outside the range": b"alpha_u [deg]\n95\n",
    "broken label": b"alpha_u [deg\n10\n", "unclosed quote": b'"alpha_u [deg]\n10\n', "only commas": b",,,\n,,,\n",
}


def points_cases() -> list[Case]:
    cases = []
    out = ["-o", "{d}/out.csv"]
    for what, data in POINTS.items():
        cases.append(_opt("sweep", f"points csv: {what}", argv=["--points", "{d}/p.csv", *out], files={"p.csv": data},
                          kind="data"))
    parquet = {"corrupt Parquet": b"PAR1" + bytes(range(200)) + b"PAR1", "truncated Parquet": None,
               "Parquet of booleans": parquet_bytes(pd.DataFrame({"alpha_u [deg]": [True, False]})),
               "Parquet of text": parquet_bytes(pd.DataFrame({"alpha_u [deg]": ["a", "b"]})),
               "Parquet with NaN": parquet_bytes(pd.DataFrame({"alpha_u [deg]": [10.0, float("nan")]})),
               "Parquet without rows": parquet_bytes(pd.DataFrame({"alpha_u [deg]": pd.Series([], dtype=float)})),
               "Parquet without a unit": parquet_bytes(pd.DataFrame({"alpha_u": [10.0]})),
               "CSV named .parquet": b"alpha_u [deg]\n10\n"}
    full = parquet_bytes(pd.DataFrame({"alpha_u [deg]": [10.0, 12.0]}))
    parquet["truncated Parquet"] = full[: len(full) // 2]
    for what, data in parquet.items():
        cases.append(_opt("sweep", f"points: {what}", argv=["--points", "{d}/p.parquet", *out],
                          files={"p.parquet": data}, kind="data"))
    for what, path, files in (("a directory", "{d}/pd.csv", {"pd.csv": DIR}), ("missing", "{d}/none.csv", {}),
                              ("unknown suffix", "{d}/p.xlsx", {"p.xlsx": b"alpha_u [deg]\n10\n"}),
                              ("no suffix", "{d}/p", {"p": b"alpha_u [deg]\n10\n"}),
                              ("with --vary too", "{d}/p.csv", {"p.csv": b"alpha_u [deg]\n10\n"})):
        extra = ["--vary", "G_m=300kN,400kN"] if "vary" in what else []
        cases.append(_opt("sweep", f"points file {what}", argv=["--points", path, *extra, *out], files=files,
                          kind="data"))
    return cases


DATA = {
    "empty": b"", "header only": b"F_T [N],delta_alpha [deg]\n",
    "ragged": b"F_T [N],delta_alpha [deg]\n10,0.9\n20\n40,3,1\n",
    "binary": bytes(range(256)) * 8,
    "Latin-1": "F_T [N],delta_alpha [\xb0]\n10,0.9\n20,1.7\n40,3.1\n".encode("latin-1"),
    "UTF-16": CAPSTAN_DATA.decode().encode("utf-16"), "corrupt Parquet bytes": b"PAR1" + bytes(range(200)) + b"PAR1",
    "booleans": b"F_T [N],delta_alpha [deg]\n10,true\n20,false\n40,true\n",
    "NaN": CAPSTAN_DATA + b"120,nan\n", "inf": CAPSTAN_DATA + b"inf,8\n", "empty cell": CAPSTAN_DATA + b"120,\n",
    "text": CAPSTAN_DATA + b"120,big\n", "negative load": CAPSTAN_DATA + b"-5,0.1\n",
    "load beyond the unwrap limit": CAPSTAN_DATA + b"100000,60\n",
    "no units": b"F_T,delta_alpha\n10,0.9\n20,1.7\n40,3.1\n",
    "no unit on F_T": b"F_T,delta_alpha [deg]\n10,0.9\n20,1.7\n40,3.1\n",
    "no unit on delta_alpha": b"F_T [N],delta_alpha\n10,0.016\n20,0.03\n40,0.054\n",
    "wrong unit": b"F_T [deg],delta_alpha [deg]\n10,0.9\n20,1.7\n40,3.1\n",
    "unknown unit": b"F_T [furlong],delta_alpha [deg]\n10,0.9\n",
    "no delta_alpha": b"F_T [N]\n10\n20\n", "no load": b"delta_alpha [deg]\n1\n2\n",
    "one point": b"F_T [N],delta_alpha [deg]\n10,0.9\n",
    "duplicate column": b"F_T [N],F_T [kN],delta_alpha [deg]\n10,0.01,0.9\n20,0.02,1.7\n40,0.04,3.1\n",
    "400-digit load": CAPSTAN_DATA + BIG.encode() + b",5\n", "rotations that fall with the load":
        b"F_T [N],delta_alpha [deg]\n10,6\n20,5\n40,4\n60,3\n80,2\n100,1\n",
    # (rotations all negative fail the same way, exit 1, but IPOPT takes ~30 s over the rotation integral there)
}


def data_cases() -> list[Case]:
    cases = []
    for what, data in DATA.items():
        codes = FAIL if what == "rotations that fall with the load" else None
        cases.append(_opt("identify", f"data: {what}", argv=["{d}/d.csv"], files={"d.csv": data}, codes=codes,
                          kind="data"))
    for what, path, files in (("a directory", "{d}/dd.csv", {"dd.csv": DIR}), ("missing", "{d}/none.csv", {}),
                              ("under a file", "{d}/f/d.csv", {"f": b"x"})):
        cases.append(_opt("identify", f"data file {what}", argv=[path], files=files, kind="data"))
    li_scene = __import__("_fuzz").builtin("capstan_li_experiment")
    torque = "\n".join(line for line in li_scene.splitlines()
                       if not line.startswith("F_T")).replace('load = "force"', 'load = "torque"')
    cases.append(Case("identify", "data", "data: torque without a unit", ["identify", "{d}/scene.toml", "{d}/d.csv"],
                      {"scene.toml": (torque + '\nT = "7.5 N*m"\n').encode(),
                       "d.csv": b"T,delta_alpha [deg]\n1.5,0.9\n3,1.7\n6,3.1\n"}))
    return cases


# ---------------------------------------------------------------- output paths

def output_cases() -> list[Case]:
    paths = (("a directory", "{d}/o.csv", {"o.csv": DIR}, None),
             ("under a regular file", "{d}/f/o.csv", {"f": b"x"}, None),
             ("in a missing directory", "{d}/no/such/o.csv", {}, None), ("unknown suffix", "{d}/o.xyz", {}, None),
             ("no suffix", "{d}/o", {}, None), ("empty name", "", {}, None),
             ("unwritable place", "/proc/ropemodel-fuzz.csv", {}, None))
    cases = []
    for what, path, files, codes in paths:
        cases.append(_opt("curve", f"-o {what}", ["-o", path], files=files, codes=codes, kind="output"))
        cases.append(_opt("simulate", f"-o {what}", ["-o", path], files=files, codes=codes, kind="output"))
        cases.append(_opt("sweep", f"-o {what}", argv=["--vary", "alpha_u=5deg:20deg:3", "-o", path], files=files,
                          codes=codes, kind="output"))
        cases.append(_opt("sweep", f"--sizing -o {what}", argv=["--vary", "G_m=400kN,467kN", "--sizing", "-o", path],
                          files=files, codes=codes, scene="winch_sizing_fig9", kind="output"))
        cases.append(_opt("trip", f"-o {what}", ["-o", path], files=files, codes=codes, kind="output"))
        html = path.replace(".csv", ".html") if path.endswith(".csv") else path
        cases.append(_opt("report", f"-o {what}", argv=["-o", html], codes=codes, kind="output",
                          files={k.replace(".csv", ".html"): v for k, v in files.items()}))
        pdf = path.replace(".csv", ".pdf") if path.endswith(".csv") else path
        cases.append(_opt("report", f"--pdf {what}", argv=["--pdf", pdf], codes=codes, kind="output",
                          files={k.replace(".csv", ".pdf"): v for k, v in files.items()}))
        png = path.replace(".csv", ".png") if path.endswith(".csv") else path
        cases.append(_opt("sensitivity", f"--plot {what}", ["--plot", png], codes=codes, kind="output",
                          files={k.replace(".csv", ".png"): v for k, v in files.items()}))
    for suffix in (".xyz", ".csv", ".txt", ".html"):
        cases.append(_opt("sensitivity", f"--plot suffix {suffix}", ["--plot", "{d}/t" + suffix], kind="output"))
    return cases
