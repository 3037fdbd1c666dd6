"""The README's reference tables are generated from the registry: the committed README must equal them."""

from pathlib import Path

from ropemodel.docs import render, update

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_tables_match_the_registry():
    text = README.read_text(encoding="utf-8")
    assert update(text) == text, "README tables drifted from the code: run python -m ropemodel.docs README.md"
    for name in render():
        assert f"<!-- generated: {name} -->" in text, name


def _shortest_scenes():
    import re

    text = README.read_text(encoding="utf-8")
    return [b for b in re.findall(r"```toml\n(.*?)```", text, re.S) if b.startswith("# ropemodel ")]


def test_the_readmes_shortest_scenes_work(tmp_path):
    """Every 'shortest scene' the README shows loads without a warning and does its command's job."""
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


def test_the_readmes_run_output_is_what_ropemodel_run_prints(capsys):
    """The block the README shows under "The built-in example" is the command's output today, to the byte."""
    import re

    from ropemodel.cli import main

    block = re.search(r"<!-- generated: run-example -->\n```text\n(.*?)\n```\n<!-- end: run-example -->",
                      README.read_text(encoding="utf-8"), re.S)
    assert block, "the README's run block is not marked <!-- generated: run-example -->"
    assert main(["run"]) == 0
    assert capsys.readouterr().out == block[1] + "\n"
