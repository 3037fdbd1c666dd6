"""Elasticities by AD against finite differences and closed forms; zero handling; CLI."""

import json
import math
from importlib import resources

import pytest

import ropemodel as rm
from ropemodel.cli import main as cli
from ropemodel.sensitivities import elasticities, table

SCENES = sorted(p.name for p in resources.files("ropemodel.data").iterdir() if p.name.endswith(".toml")
                and p.name != "ropes.toml")


def fd_elasticities(problem, x, par, outputs, h=1e-5):
    """Central differences of ln y in ln p for each of ``outputs`` on single evaluations (no range check:
    eta = 1 may step past 1), Richardson-extrapolated from steps h and h/2 so the O(h^2) truncation error
    goes (outputs near zero, e.g. a slip margin, have elasticities of order 100 and large curvature).
    A factor a rule set gives from ``par`` (a safety factor from the suspended length) follows it."""

    def at(value):
        point = {**x, par: value}
        point.update(problem.scene.rule_values(point, [par]))
        return problem.function(**point)

    def central(step):
        up, dn = at(x[par] * (1 + step)), at(x[par] * (1 - step))
        return {o: (math.log(abs(float(up[o]))) - math.log(abs(float(dn[o])))) / (math.log1p(step) - math.log1p(-step))
                for o in outputs}

    half, full = central(h / 2), central(h)
    return {o: (4 * half[o] - full[o]) / 3 for o in outputs}


def fd_worst(scene, par, outputs, h=1e-5):
    """As :func:`fd_elasticities`, of each output's worst over the scene's load cases (each case's place and
    acceleration follow the parameters), evaluated without range checks."""
    from ropemodel.envelope import envelope, load_cases, with_ramps

    scene = with_ramps(scene)
    problem, cases = rm.Problem(scene), load_cases(scene)
    p0 = problem.inputs()[par]

    def central(step):
        up, dn = (envelope(problem, cases, {par: p0 * (1 + f * step)}).values() for f in (1, -1))
        return {o: (math.log(abs(up[o])) - math.log(abs(dn[o]))) / (math.log1p(step) - math.log1p(-step))
                for o in outputs}

    half, full = central(h / 2), central(h)
    return {o: (4 * half[o] - full[o]) / 3 for o in outputs}


def _scene(name):
    return rm.load_scene(str(resources.files("ropemodel.data").joinpath(name)))


@pytest.mark.parametrize("name", SCENES)
def test_elasticities_match_finite_differences_on_every_builtin_scene(name):
    scene = _scene(name)
    problem = rm.Problem(scene)
    x = problem.inputs()
    frame = elasticities(scene)
    y = problem.solve(x)
    # at a single point, or the same in every load case: differences at the scene's point; at the worst over
    # the load cases: differences of the worst (the governing case changes within the step only at a tie,
    # where the worst has no derivative)
    same = frame["where"].isin(["", "the same in every case"])
    rows = [r for r in frame[frame["defined"] & same].itertuples() if abs(y[r.output]) >= 1e-9 * max(1.0, abs(r.y))]
    worst = list(frame[frame["defined"] & ~same].itertuples())
    fd = {par: fd_elasticities(problem, x, par, sorted({r.output for r in rows if r.parameter == par}))
          for par in {r.parameter for r in rows}}
    fd_w = {par: fd_worst(scene, par, sorted({r.output for r in worst if r.parameter == par}))
            for par in {r.parameter for r in worst}}
    for r in worst:
        assert r.elasticity == pytest.approx(fd_w[r.parameter][r.output], abs=2e-6, rel=1e-7), (r.output, r.parameter)
    for r in rows:
        # FD error after extrapolation: O(h^4) truncation and rounding ~ 1e-16/h of ln y
        assert r.elasticity == pytest.approx(fd[r.parameter][r.output], abs=2e-6, rel=1e-7), (r.output, r.parameter)
    assert len(rows) + len(worst) > 10


def test_inverse_problem_elasticities_match_finite_differences(fig9):
    problem = rm.Problem(fig9, given={"dF_up": "1000 mm"}, find=["G_m"])
    x = problem.inputs()
    frame = elasticities(fig9, given={"dF_up": "1000 mm"}, find=["G_m"], outputs=["G_m", "F_C_up"])
    for r in frame[frame["defined"]].itertuples():
        fd = fd_elasticities(problem, x, r.parameter, [r.output])[r.output]
        assert r.elasticity == pytest.approx(fd, abs=2e-6)
    # the load is inversely proportional to nothing simple, but the stroke enters linearly: e(G_m, dF_up) > 1
    e = frame.set_index(["output", "parameter"])["elasticity"]
    assert e["G_m", "dF_up"] > 1.0


def test_closed_form_elasticities(fig9):
    e = elasticities(fig9).set_index(["output", "parameter"])["elasticity"]
    assert e["N_p_up", "v_pj"] == pytest.approx(1.0, abs=1e-14)   # N_p_up = (F_C - F_S) v / eta (motoring)
    assert e["N_p_up", "eta"] == pytest.approx(-1.0, abs=1e-14)
    assert e["dF_up", "q_lw"] == pytest.approx(1.0, abs=1e-14)    # every elongation is q_lw * force
    p = fig9.parameters
    # eq. (13) upward: d ln F_C / d ln G_m = G_m (sin a + mu_pm cos a) / F_C
    F_C = rm.run(fig9)["F_C_up"]
    a = p["alpha_u"]
    assert e["F_C_up", "G_m"] == pytest.approx(p["G_m"] * (math.sin(a) + p["mu_pm"] * math.cos(a)) / F_C, rel=1e-13)
    # the two ropes' resistances cancel exactly in the stroke: reported 0, not 1e-18
    assert e["dF_up", "mu_pl"] == 0.0


def test_zero_output_is_marked_not_nan(fig9):
    scene = fig9.with_values({"L_ul": "1150 m"})   # point A at the drive: G_l1 = 0
    frame = elasticities(scene, outputs=["G_l1", "F_C_up"])
    g = frame[frame["output"] == "G_l1"]
    assert not g["defined"].any() and (g["note"] == "undefined: y = 0").all()
    assert g["elasticity"].isna().all()
    d = g.set_index("parameter")["dy_dp"]
    p = scene.parameters
    assert d["L_u"] == pytest.approx(p["q_l"] * math.sin(p["alpha_u"]) / 1e3, rel=1e-13)  # kN per m
    assert frame.loc[frame["defined"], "elasticity"].notna().all()
    assert "dG_l1/dL_u = 0.022051 kN/m" in table(frame)


def test_zero_parameter_is_marked(fig9):
    frame = elasticities(fig9.with_values({"F_nwl": 0.0}), outputs=["F_C_up"])
    r = frame.set_index("parameter").loc["F_nwl"]
    assert not r["defined"] and r["note"] == "undefined: p = 0" and r["dy_dp"] == pytest.approx(0.5, rel=1e-14)


def test_cli_table_json_and_plot(tmp_path, capsys):
    png = tmp_path / "t.png"
    assert cli(["sensitivity", "--outputs", "F_C_up,dF_up", "--plot", str(png)]) == 0
    text = capsys.readouterr().out
    assert text.splitlines()[0].startswith("d ln y / d ln p") and "F_C_up [kN]" in text
    assert png.stat().st_size > 5000 and png.read_bytes()[:4] == b"\x89PNG"
    assert cli(["sensitivity", "--set", "L_ul=1150m", "--outputs", "G_l1", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert all(r["elasticity"] is None and r["note"] == "undefined: y = 0" for r in rows)
    assert cli(["sensitivity", "--outputs", "F_C_upp"]) == 2
    assert "F_C_up" in capsys.readouterr().err
