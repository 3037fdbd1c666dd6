"""Tornado chart of the Fig. 9 example: which inputs move the rope forces, the stroke and the power.

Local elasticities ∂ln y/∂ln p (automatic differentiation of the compiled
model, :func:`ropemodel.sensitivities.elasticities`) of the winding and
unwinding rope forces, the tensioner stroke and the drive power, upward
travel, at the Fig. 9 point of Krauze et al. (2025).  A second method checks
them: each input is changed by ±10 % and the output recomputed; the
linearised change ``(1.1^e − 1)`` is printed next to the real one (they part
where the output is nonlinear in the input, e.g. the inclination).

``python studies/tornado.py [--fast]`` writes ``elasticities.csv``,
``plus_minus_10.csv`` and ``tornado.png`` into ``studies/out/tornado/``.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from ropemodel.studykit import cli, output_dir

ROOT = Path(__file__).resolve().parents[1]
NAME = "tornado"
OUTPUTS = ["F_C_up", "F_S_up", "dF_up", "N_p_up"]


def main(out_dir=None, fast: bool = False) -> pd.DataFrame:
    import ropemodel as rm
    from ropemodel.sensitivities import elasticities, table, tornado

    out = output_dir(__file__, out_dir)
    scene = rm.load_scene()
    frame = elasticities(scene, outputs=OUTPUTS)
    frame.to_csv(out / "elasticities.csv", index=False)
    fig_title = "Krauze et al. 2025, Fig. 9: elasticities ∂ln y/∂ln p (upward travel)"
    tornado(frame, OUTPUTS, path=out / f"{NAME}.png", title=fig_title)
    if not fast:
        (ROOT / "studies" / "figures").mkdir(exist_ok=True)
        tornado(frame, OUTPUTS, path=ROOT / "studies" / "figures" / f"{NAME}.png", title=fig_title)

    # second method: +-10 % steps, recomputed
    problem = rm.Problem(scene)
    base = problem.solve()
    rows = []
    moved = frame[frame["defined"] & (frame["elasticity"] != 0.0)]
    for par in dict.fromkeys(moved["parameter"]):
        for step in (-0.1, 0.1):
            try:
                res = problem.solve({par: scene.parameters[par] * (1 + step)})
            except rm.InputError:  # e.g. eta = 1.1: outside its range, no such machine
                continue
            for r in moved[moved["parameter"] == par].itertuples():
                rows.append({"output": r.output, "parameter": par, "step": step, "elasticity": r.elasticity,
                             "linearised_change": (1 + step) ** r.elasticity - 1,
                             "actual_change": res[r.output] / base[r.output] - 1})
    steps = pd.DataFrame(rows)
    steps.to_csv(out / "plus_minus_10.csv", index=False)
    print(table(frame))
    worst = steps.assign(gap=(steps["linearised_change"] - steps["actual_change"]).abs()).nlargest(3, "gap")
    print("\nlargest gaps between the elasticity's prediction and a recomputed ±10 % step:")
    print(worst[["output", "parameter", "step", "linearised_change", "actual_change"]].to_string(index=False))
    return frame


if __name__ == "__main__":
    cli(main, __doc__, show=lambda df: f"{len(df)} elasticities written")
