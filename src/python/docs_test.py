"""The Python shown in README.md and docs/python.md runs as written (sizes shrunk, as the CLI's
doc test shrinks them: 20 000 particles become 1 000, t = 0.5 s becomes 0.05 s)."""

import re

import pytest


def python_blocks(path):
    return re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.S)


def shrunk(code):
    return code.replace("20_000", "1_000").replace("advance_to(0.5)", "advance_to(0.05)")


@pytest.mark.parametrize("document", ["README.md", "docs/python.md"])
def test_the_first_example_runs(repo, document, capsys):
    blocks = python_blocks(repo / document)
    assert blocks, f"{document} shows no Python"
    namespace = {}
    exec(compile(shrunk(blocks[0]), f"{document} (first python block)", "exec"), namespace)
    sim = namespace["sim"]
    assert sim.time == pytest.approx(0.05, abs=1e-7)
    assert namespace["x"].shape == (sim.particle_count, 3)


def test_the_scene_examples_run(repo, tmp_path, monkeypatch):
    """docs/python.md's Scenes block, its placeholders filled in."""
    monkeypatch.chdir(repo)
    block = next(b for b in python_blocks(repo / "docs" / "python.md") if "from_json" in b)
    text = (repo / "scenes" / "dam_break.json").read_text()  # no meshes beside it
    code = block.replace('{"container": {...}, "blocks": [...]}',
                         '{"container": {"min": [0, 0, 0], "max": [1, 1, 1]}, '
                         '"blocks": [{"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}]}')
    namespace = {"weir": __import__("weir"), "text": text}
    exec(compile(code, "docs/python.md (scenes)", "exec"), namespace)
    assert namespace["scene"].duration == 1
