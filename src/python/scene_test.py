"""weir.Scene and weir.load_scene: the same scenes, and the same errors, as the weir command."""

import json
import pathlib

import pytest

import weir


def test_builtin_scenes_are_listed_and_load():
    names = weir.builtin_scenes()
    assert "dam_break" in names and "drop_into_pool" in names
    scene = weir.load_scene("dam_break")
    assert scene.name == "dam_break"
    assert scene.source == "<built-in dam_break>"
    assert weir.Scene.builtin("drop_into_pool").name == "drop_into_pool"


def test_file_json_text_and_dict_give_the_same_scene(repo):
    path = repo / "examples" / "showcase.json"
    from_file = weir.Scene.from_file(str(path))
    # The rock mesh is found beside the file, so the JSON text names the same folder.
    text = path.read_text()
    from_text = weir.Scene.from_json(text, source=str(path))
    from_dict = weir.Scene.from_dict(json.loads(text), source=str(path))
    from_path = weir.load_scene(pathlib.Path(path))
    assert from_file.name == "showcase"
    assert from_file.to_dict() == from_text.to_dict() == from_dict.to_dict() == \
        from_path.to_dict()
    assert from_file.to_dict()["particles"]["count"] == 20000


def test_a_bad_field_raises_scene_error_naming_field_value_and_what_is_allowed(tmp_path, cli):
    fields = {
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.5, 0.4]}],
        "particles": {"count": 1000, "smoothingRatio": 9},
    }
    with pytest.raises(weir.SceneError) as caught:
        weir.Scene.from_dict(fields)
    message = str(caught.value)
    assert "particles.smoothingRatio" in message and "9" in message
    assert isinstance(caught.value, ValueError)
    # The CLI says the same of the same file.
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(fields))
    with pytest.raises(weir.SceneError) as from_file:
        weir.load_scene(str(bad))
    done = cli("run", bad, "--backend", "cpu", "--out", tmp_path / "out", check=False)
    assert done.returncode == 1
    assert str(from_file.value) in done.stderr


def test_a_missing_file_and_a_misspelt_name_are_errors_like_the_clis(tmp_path, cli):
    with pytest.raises(weir.SceneError) as missing:
        weir.load_scene(str(tmp_path / "nothing.json"))
    assert "nothing.json" in str(missing.value)
    with pytest.raises(weir.SceneError) as misspelt:
        weir.load_scene("dambreak")
    assert "did you mean 'dam_break'" in str(misspelt.value)
    done = cli("run", "dambreak", "--out", tmp_path / "out", check=False)
    assert str(misspelt.value) in done.stderr


def test_json_that_is_not_json_names_the_source():
    with pytest.raises(weir.SceneError) as caught:
        weir.Scene.from_json('{"container": ', source="mine.json")
    assert "mine.json" in str(caught.value)


def test_overrides_merge_and_are_checked_again():
    scene = weir.load_scene("dam_break")
    changed = scene.with_overrides({"fluid": {"viscosity": 0.01}, "time": {"duration": 0.5}})
    fields = changed.to_dict()
    assert fields["fluid"]["viscosity"] == 0.01
    assert fields["fluid"]["preset"] == scene.to_dict()["fluid"]["preset"]  # merged, not replaced
    assert changed.duration == 0.5
    with pytest.raises(weir.SceneError) as caught:
        scene.with_overrides({"fluid": {"viscosity": -1}})
    assert "fluid.viscosity" in str(caught.value) and "-1" in str(caught.value)
    with pytest.raises(weir.SceneError):
        scene.with_overrides("[1, 2]")


def test_solver_and_model_are_set_by_name():
    scene = weir.load_scene("dam_break")
    assert scene.with_solver("dfsph").solver == "dfsph"
    assert scene.with_model("paper").model == "paper"
    with pytest.raises(ValueError) as caught:
        scene.with_solver("sph2000")
    assert "sph2000" in str(caught.value) and "dfsph" in str(caught.value)


def test_a_scene_of_another_type_is_a_type_error():
    with pytest.raises(TypeError):
        weir.load_scene(42)
