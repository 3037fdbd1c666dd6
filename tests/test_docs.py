"""The documentation's reference tables are generated from the registry (the committed pages must equal them),
the shortest scenes and the run output it shows work as shown, and the README stays short (issue 26)."""

import re
from pathlib import Path

from _docs_text import README, section

from ropemodel.docs import files, render, update

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "docs" / "scenes.md"          # the site's scene reference


def test_every_generated_block_matches_the_registry():
    """Every file holding a generated block (README.md, docs/**/*.md) holds what the code generates now."""
    found = files(ROOT)
    assert SITE in found and ROOT / "docs" / "machines" / "winch.md" in found
    for path in found:
        text = path.read_text(encoding="utf-8")
        assert update(text) == text, f"{path.relative_to(ROOT)} drifted from the code: run python -m ropemodel.docs"


def test_the_readme_fits_on_a_screen_or_two():
    """Issue 26: a README of at most 250 lines, its links all reaching a file of the repository."""
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 250
    links = [t.partition("#")[0] for t in re.findall(r"\]\(([^)\s]+)\)", text) if not re.match(r"^[a-z]+:|^#", t)]
    assert links and not [t for t in links if not (ROOT / t).exists()], links


def test_site_tables_match_the_registry():
    """The site's scene reference holds every generated table, each as the registry has it now."""
    text = SITE.read_text(encoding="utf-8")
    assert update(text) == text, "docs/scenes.md tables drifted from the code: run python -m ropemodel.docs"
    for name in render():
        assert f"<!-- generated: {name} -->" in text, name


def _block(text: str, name: str) -> list[list[str]]:
    """Rows (cells) of the Markdown table in block ``name``, header and rule left out."""
    body = text.split(f"<!-- generated: {name} -->\n")[1].split(f"<!-- end: {name} -->")[0]
    return [[c.strip() for c in line.strip("|").split(" | ")] for line in body.strip().splitlines()[2:]]


def test_site_parameter_tables_are_the_quantities():
    """Read back, each parameter row of the site is its Quantity: every declared parameter some variant's
    model asks for (each variant built here; a route's per-segment L_1, alpha_1, ... are the route
    variant's, listed in its variants table), with its display unit, valid range and default."""
    from ropemodel.core.model import Model
    from ropemodel.effects import REGISTRY, all_quantities

    text = SITE.read_text(encoding="utf-8")
    for model, effects in REGISTRY.items():
        q = all_quantities(model)
        asked = {n for e, spec in effects.items() for v in spec.variants for n in Model(model, {e: v}).parameters}
        rows = {r[0].strip("`"): r for r in _block(text, f"parameters-{model}")}
        assert set(rows) == asked & set(q), model
        for name, (_, unit, meaning, default, valid, _usual) in rows.items():
            assert unit == ("-" if q[name].display_unit in ("1", "") else q[name].display_unit), name
            assert meaning == q[name].description and valid.startswith(q[name].range_text()), name
            d = q[name].default
            assert (default == "required") if d is None else default.startswith(q[name].show(d)), name


def _shortest_scenes():
    text = section("The shortest scene for each command")
    return [b for b in re.findall(r"```toml\n(.*?)```", text, re.S) if b.startswith("# ropemodel ")]


def test_the_shortest_scenes_work(tmp_path):
    """Every 'shortest scene' the scene reference shows loads without a warning and does its command's job."""
    import warnings

    import ropemodel as rm
    from optimisation.design import size
    from optimisation.problem import load_sizing

    blocks = _shortest_scenes()
    assert len(blocks) >= 4
    for i, block in enumerate(blocks):
        f = tmp_path / f"s{i}.toml"
        f.write_text(block, encoding="utf-8")
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            if block.startswith("# ropemodel size"):
                assert size(load_sizing(f), with_sensitivities=False).feasible
            elif block.startswith("# ropemodel simulate"):
                from ropemodel.dynamics import simulate

                assert simulate(rm.load_scene(f)).summary["t_end"] > 0
            else:
                assert rm.run(rm.load_scene(f)).values


def test_the_run_output_shown_is_what_ropemodel_run_prints(capsys):
    """The block the winch page shows under "The built-in example" is the command's output today, to the byte."""
    from ropemodel.cli import main

    block = re.search(r"<!-- generated: run-example -->\n```text\n(.*?)\n```\n<!-- end: run-example -->",
                      section("The built-in example: Krauze et al. (2025), Fig. 9"), re.S)
    assert block, "the built-in example's run block is not marked <!-- generated: run-example -->"
    assert main(["run"]) == 0
    assert capsys.readouterr().out == block[1] + "\n"
