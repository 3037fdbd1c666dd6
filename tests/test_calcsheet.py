"""The calculation sheet (``ropemodel report SCENE --format json``) and the formulas the page prints.

Truths: Python's ``math`` evaluating each sheet expression from its own inputs against the value the
compiled model computed (a second evaluation, by another engine, of what the page claims); CasADi's
own evaluation of random expressions against the printed Python; the paper's equations as printed
(Krauze et al. 2025, eq. (1)-(23); Hajduk 1992, eq. (19)) against the printed Unicode.
"""

from __future__ import annotations

import functools
import json
import math
import random
import re
import tomllib
from importlib import resources

import casadi as ca
import pytest

from ropemodel.cli import main
from ropemodel.scene import builtin_scenes


@functools.cache
def sheet_of(name: str) -> dict:
    """The sheet of a built-in scene, written as JSON text and read back (standard JSON only)."""
    from ropemodel.reports import load
    from ropemodel.reports.sheet import sheet

    text = json.dumps(sheet(load(name)), allow_nan=False)
    return json.loads(text)


def recompute(text: str, inputs: dict) -> float:
    """What a checker does with an expression of the sheet: Python's math, the inputs in SI."""
    return float(eval(text, {"math": math}, {k: float(v) for k, v in inputs.items()}))


@pytest.mark.parametrize("name", builtin_scenes())
def test_every_python_expression_of_the_sheet_recovers_its_value(name):
    """Each closed equation recomputed by Python's math from its inputs gives its value to 1e-9; each implicit
    one's governing equation holds at its value (both sides to 1e-9); each numerical one (an integration, an
    error estimate) names its method, and an integration its tolerance."""
    entries = sheet_of(name)["equations"]
    assert entries
    kinds = set()
    for e in entries:
        kinds.add(e["kind"])
        value = float(e["value"])
        if e["kind"] == "closed":
            got = recompute(e["python"], e["inputs"])
            assert got == pytest.approx(value, rel=1e-9, abs=1e-12), (e["name"], e["python"], got, value)
            assert e["formula"].split(" = ", 1)[0]            # "symbol = expression"
        elif e["kind"] == "implicit":
            scope = {**e["inputs"], re.sub(r"^(lambda)$", r"\1_", e["name"]): value}
            lhs, rhs = recompute(e["equation"]["lhs"], scope), recompute(e["equation"]["rhs"], scope)
            assert lhs == pytest.approx(rhs, rel=1e-9, abs=1e-9), (e["name"], lhs, rhs)
            assert e["python"] is None and e["method"]
        else:
            assert e["kind"] == "numerical" and e["python"] is None and e["formula"] == ""
            assert e["method"]
            assert e["tolerance"] is None or (e["tolerance"] > 0 and f"rtol = {e['tolerance']:g}" in e["method"])
    assert "closed" in kinds


def test_the_sheet_holds_every_equation_the_page_shows():
    """The page's equations section (one numbers line per equation) and the sheet name the same quantities."""
    from test_report import page_of

    for name in ("example", "sheave_hajduk_fig5", "capstan_li_experiment", "winch_sizing_fig9"):
        html = page_of(name).split('<section id="equations">', 1)[1].split("</section>", 1)[0]
        shown = re.findall(r'<div class="numbers"><span class="name">([^<]+)</span>', html)
        assert shown == [e["name"] for e in sheet_of(name)["equations"]], name


# the paper's equations as printed (Krauze et al. 2025, eq. (1)-(23)), in its symbols and order
FIG9_FORMULAS = {
    "G_ml": "G_ml = G_m sin α_u",                               # eq. (1)
    "G_l": "G_l = G_l1 + G_l2",                                 # eq. (2)
    "G_l1": "G_l1 = q_l (L_u − L_ul) sin α_u",                  # eq. (3)
    "G_mo": "G_mo = G_m cos α_u",                               # eq. (5)
    "T_m": "T_m = μ_pm G_m cos α_u",                            # eq. (7)
    "T_l2": "T_l2 = μ_pl2 q_l L_ul cos α_u",                    # eq. (9)
    "F_S_up": "F_S,up = 0.5 F_nwl + G_ls − T_ls",               # eq. (12), upward
    "F_C_up": "F_C,up = 0.5 F_nwl + G_lmC + T_m + T_l",         # eq. (13), upward
    "F_C_down": "F_C,down = 0.5 F_nwl + G_lmC − (T_m + T_l)",   # eq. (13), downward
    "dF_C_up": "ΔF_C,up = q_lw F_C,up",                         # eq. (19)
    "dF_up": "ΔF_up = ΔF_CS,up + ΔF_nwl",                       # eq. (23)
}


def test_the_page_prints_the_papers_equations_in_its_symbols():
    formulas = {e["name"]: e["formula"] for e in sheet_of("example")["equations"]}
    for name, printed in FIG9_FORMULAS.items():
        assert formulas[name] == printed


def test_margins_and_catalogue_read_as_their_definitions():
    formulas = {e["name"]: e["formula"] for e in sheet_of("winch_sizing_fig9")["equations"]}
    assert formulas["safety_margin_up"] == "m_safety,up = F_min / (n_rope F_C,up) − 1"
    assert formulas["slip_margin_down"] == "m_slip,down = F_S,down traction_down / (n_slip F_C,down) − 1"
    assert formulas["drum_margin"] == "m_drum = D / ((D/d)_min d) − 1"
    assert formulas["F_min"] == "F_min = K d² R_r"                 # EN 12385-4
    assert formulas["q_l"] == "q_l = g W d²"
    assert formulas["q_lw"] == "q_lw = L_u / (E C d²)"
    ropes = tomllib.loads(resources.files("ropemodel.data").joinpath("ropes.toml").read_text())
    assert formulas["rope_K"] == f"K = {ropes['constructions']['6x36-IWRC']['K']}"      # the class's factor
    assert formulas["N_p_down"] == "N_p,down = max(P_drum,down, 0) / η + min(P_drum,down, 0) η"


def test_an_iteration_shows_the_equation_it_solves():
    """Hajduk (1992) eq. (19), ln(S/S_0) + S Q (1 − e^(−α/(λω))) = μα, for the closed form (Newton in ln s);
    the ODE and the capstan's rotation show no formula, their method and tolerance instead."""
    sheave = {e["name"]: e for e in sheet_of("sheave_hajduk_fig5")["equations"]}
    assert sheave["S"]["kind"] == "implicit"
    assert sheave["S"]["formula"] == "ln(S / S_0) + S Q (1 − e^(−α / max(λ ω, α / 700 + 10^(−30)))) = μ α"
    assert "Newton" in sheave["S"]["method"]
    thirion = {e["name"]: e for e in sheet_of("sheave_thirion")["equations"]}
    rtol = tomllib.loads(resources.files("ropemodel.data").joinpath("sheave_thirion.toml").read_text())["numerics"]
    assert thirion["S"]["kind"] == "numerical" and thirion["S"]["tolerance"] == rtol["rtol"]
    capstan = {e["name"]: e for e in sheet_of("capstan_li_experiment")["equations"]}
    assert capstan["delta"]["kind"] == "numerical" and "Dormand–Prince" in capstan["delta"]["method"]


def _every_model():
    from ropemodel.core.model import Model
    from ropemodel.effects import effects_of

    for model in ("winch", "sheave", "capstan"):
        for effect, spec in effects_of(model).items():
            for variant in spec.variants:
                for options in ({}, {"method": "ode"}):
                    yield Model(model, {effect: variant}, options)


def test_every_equation_of_every_variant_can_be_shown():
    """A formula printed from its expression, or (no closed form) the method that computes it."""
    from ropemodel.core.formulas import shown

    kinds = set()
    for m in _every_model():
        for eq in m.equations:
            s = shown(m, eq)
            kinds.add(s.kind)
            assert (s.formula and (s.python or s.lhs)) or (s.kind == "numerical" and s.method), (m.effects, eq)
    assert kinds == {"closed", "implicit", "numerical"}


# ------------------------------------------------------------------------------------------ the printer

def _random_expression(rng: random.Random, x: list, depth: int):
    """A random scalar SX expression of the symbols ``x``, each operation kept inside its domain."""
    if depth == 0 or rng.random() < 0.2:
        return rng.choice(x) if rng.random() < 0.8 else ca.SX(rng.choice([-2.5, -1.0, 0.5, 2.0, 9.80665]))
    a, b = _random_expression(rng, x, depth - 1), _random_expression(rng, x, depth - 1)
    ops = [lambda: a + b, lambda: a - b, lambda: a * b, lambda: a / (1 + b * b), lambda: -a,
           lambda: ca.sin(a), lambda: ca.exp(ca.sin(a)), lambda: ca.log(1 + a * a), lambda: ca.fmin(a, b),
           lambda: ca.fmax(a, b), lambda: ca.if_else(a <= b, a, b * 2), lambda: ca.expm1(ca.cos(a)),
           lambda: ca.log1p(b * b), lambda: a ** 2, lambda: ca.sqrt(1 + b * b), lambda: ca.fabs(a) * b,
           lambda: -(a - b) / (2 + ca.cos(b)), lambda: (-1.0) * a + (-b)]
    return rng.choice(ops)()


def test_the_printed_python_evaluates_as_casadi_does():
    """500 random expressions (sums, products, quotients, signs, functions, min/max, if_else): the Python text
    evaluated by math against CasADi's own evaluation of the expression."""
    from ropemodel.core.infix import python, tree

    rng = random.Random(24)
    names = ["a", "b", "lambda"]
    x = [ca.SX.sym(n) for n in names]
    f_in = ca.Function
    for _ in range(500):
        expr = _random_expression(rng, x, 4)
        values = [rng.uniform(-3.0, 3.0) for _ in x]
        truth = float(f_in("f", x, [expr])(*values))
        text = python(tree(expr))
        got = float(eval(text, {"math": math}, {"a": values[0], "b": values[1], "lambda_": values[2]}))
        assert got == pytest.approx(truth, rel=1e-12, abs=1e-12), (str(expr), text)


def test_the_printer_tidies_signs_and_shows_cases():
    from ropemodel.core.infix import python, tree, unicode

    a, b, c = (ca.SX.sym(n) for n in ("a", "b", "c"))
    assert unicode(tree(-(a * b) * (-1.0)), {}) == "a b"
    assert unicode(tree(-((c * a - b) / (c * a))), {}) == "b / (c a) − 1"      # (b − ca)/(ca) = b/(ca) − 1
    assert unicode(tree(a - (-1.0) * b), {}) == "a + b"
    assert unicode(tree(-ca.expm1(-a * b)), {"a": "μ", "b": "α"}) == "1 − e^(−μ α)"
    assert unicode(tree(ca.if_else(a <= b, 0, ca.if_else(c < a, a, b))), {}) == "{0 if a ≤ b; a if c < a; b otherwise}"
    assert unicode(tree((a + b) / 9.80665 * c), {}) == "(a + b) c / g"
    assert python(tree(ca.if_else(a <= b, a, b))) == "(a if a <= b else b)"


def test_the_printer_refuses_what_no_one_reads():
    from ropemodel.core.infix import TooLarge, tree

    x = ca.SX.sym("x")
    u = x
    for _ in range(12):                      # a Newton iteration unrolled: its tree doubles each step
        u = u - (u * u - x) / (2 * u)
    with pytest.raises(TooLarge):
        tree(u)


# ------------------------------------------------------------------------------------------ the command

def test_cli_writes_the_sheet(tmp_path, capsys):
    out = tmp_path / "calc.json"
    assert main(["report", "example", "--format", "json", "-o", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == f"wrote {out}"
    data = json.loads(out.read_text(encoding="utf-8"))
    assert data["scene"]["sha256"] and data["units"] == "SI" and data["at"] == "the scene's values"
    F_C = next(e for e in data["equations"] if e["name"] == "F_C_up")
    assert F_C["value"] == pytest.approx(190.95e3, abs=5.0)                # Krauze et al. 2025, Fig. 9
    assert F_C["cites"] == ["krauze2025"] and "Krauze" in data["references"]["krauze2025"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["calc.json"]


@pytest.mark.parametrize("args, words", [
    (["--format", "json"], "give -o"),
    (["--format", "json", "-o", "{d}/calc.html"], "must end in .json"),
    (["--format", "xml", "-o", "{d}/calc.xml"], "invalid choice"),
])
def test_cli_refuses_a_sheet_it_cannot_write(tmp_path, capsys, args, words):
    assert main(["report", "example", *[a.format(d=tmp_path) for a in args]]) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.strip().splitlines()) == 1, err
