"""Errors: bad scenes raise tem.SceneError with `tem check`'s message; bad checkpoints and
directories RuntimeError; bad indices IndexError."""
import json

import pytest

import tem
from conftest import run_tem, scene_path

BAD = scene_path("tests/scenes/bad")


def tem_check_problems(path):
    """The problem lines `tem check` prints (stderr), without its closing count."""
    result = run_tem("check", path)
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert lines[-1].endswith("problem" if len(lines) == 2 else "problems")
    return lines[:-1]


@pytest.mark.parametrize("name, json_path, reason", [
    ("negative_density.json", "bodies[0].density", "must be a positive number, got -2"),
    ("unknown_key_typo.json", "bodies[0].shape",
     "unknown key 'radus' (did you mean 'radius'?)"),
    ("missing_radius.json", "bodies[0].shape", "missing required key 'radius'"),
    ("syntax_error.json", None, "syntax error"),
])
def test_bad_scene_file_raises_scene_error_like_tem_check(name, json_path, reason):
    path = BAD / name
    with pytest.raises(tem.SceneError) as info:
        tem.Simulation(path)
    message = str(info.value)
    assert isinstance(info.value, ValueError)
    assert message.startswith(f"{path}: ")
    if json_path:
        assert f": {json_path}: " in message
    assert reason in message
    assert message.splitlines() == tem_check_problems(path)


def test_every_problem_of_a_scene_is_in_the_message():
    path = BAD / "several_problems.json"
    with pytest.raises(tem.SceneError) as info:
        tem.Simulation(str(path))
    lines = str(info.value).splitlines()
    assert len(lines) == 10
    assert lines == tem_check_problems(path)


def test_bad_geometry_raises_scene_error():
    path = scene_path("tests/scenes/bad_geometry/coplanar_points.json")
    with pytest.raises(tem.SceneError) as info:
        tem.Simulation(path)
    assert str(info.value).splitlines() == tem_check_problems(path)


def coin(**shape):
    return {"bodies": [{"name": "coin", "position": [0, 0, 0],
                        "shape": {"type": "prism", "sides": 6, "height": 0.1, **shape}}]}


def test_bad_dict_names_the_dict_the_path_and_the_reason(tmp_path):
    scene = coin(radius=-0.15)
    with pytest.raises(tem.SceneError) as info:
        tem.Simulation.from_dict(scene)
    assert str(info.value) == \
        "<dict>: bodies[0].shape.radius: must be a positive number, got -0.15"
    # The same scene as a file: the same problem, under the file's name.
    path = tmp_path / "negative_radius.json"
    path.write_text(json.dumps(scene))
    assert tem_check_problems(path) == \
        [f"{path}: bodies[0].shape.radius: must be a positive number, got -0.15"]
    with pytest.raises(ValueError, match=r"<dict>: bodies\[0\]\.shape: unknown key 'radus'"):
        tem.Simulation.from_dict(coin(radus=0.15, radius=0.15))
    with pytest.raises(tem.SceneError, match=r"^scene\.txt: bodies\[0\]\.shape: missing"):
        tem.Simulation.from_json(json.dumps(coin()), origin="scene.txt")
    with pytest.raises(tem.SceneError, match="NaN is not valid JSON"):
        tem.Simulation.from_dict(coin(radius=float("nan")))
    with pytest.raises(TypeError, match="not JSON serializable"):
        tem.Simulation.from_dict(coin(radius=object()))


def test_missing_file_raises_scene_error(tmp_path):
    with pytest.raises(tem.SceneError, match="no such file"):
        tem.Simulation(tmp_path / "none.json")


def test_bad_checkpoints_raise_runtime_error(tmp_path):
    pile = scene_path("tests/scenes/small_pile.json")
    with pytest.raises(RuntimeError, match="no checkpoint"):
        tem.Simulation.resume(pile, tmp_path / "none.bin")
    garbage = tmp_path / "garbage.bin"
    garbage.write_bytes(b"not a checkpoint at all")
    with pytest.raises(RuntimeError, match="not a TEM checkpoint"):
        tem.Simulation.resume(pile, garbage)
    other = tem.Simulation(scene_path("tests/scenes/drop_box.json"))
    other.write_checkpoint(tmp_path / "box.bin")
    with pytest.raises(RuntimeError, match="another scene"):
        tem.Simulation.resume(pile, tmp_path / "box.bin")
    assert not isinstance(RuntimeError(), ValueError)  # not to be mistaken for SceneError


def test_unwritable_places_raise_runtime_error(tmp_path):
    sim = tem.Simulation(scene_path("tests/scenes/drop_box.json"))
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    with pytest.raises(RuntimeError, match="cannot be created"):
        sim.record(a_file / "out")
    with pytest.raises(RuntimeError, match="cannot be written"):
        sim.write_checkpoint(a_file / "checkpoint.bin")
    assert not sim.recording
    sim.step(3)  # the failures left the simulation usable
    assert sim.step_count == 3


def test_warnings_are_tem_checks():
    path = scene_path("tests/scenes/overlapping_start.json")
    sim = tem.Simulation(path)
    result = run_tem("check", path)
    assert result.returncode == 0
    assert [f"{path}: warning: {w}" for w in sim.warnings] == result.stderr.strip().splitlines()
    assert len(sim.warnings) == 2 and "overlap" in sim.warnings[0]


def test_stepping_past_the_duration_warns_before_it_starts():
    sim = tem.Simulation.from_dict({
        "time_step": 1e-3, "duration": 0.01,
        "bodies": [{"name": "a", "shape": {"type": "box", "size": [1, 1, 1]},
                    "position": [0, 0, 0]}]})
    assert sim.total_steps == 10
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sim.step(10)  # up to the duration: no warning
    with pytest.warns(RuntimeWarning, match=r"step\(5\) goes past the scene's duration "
                                            r"\(10 steps; now at step 10"):
        sim.step(5)
    assert sim.step_count == 15  # the steps go on, as a program may need
    # Warnings made errors: the call is refused before any step is taken.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(RuntimeWarning, match=r"step\(1000000000000\)"):
            sim.step(10**12)
    assert sim.step_count == 15


def test_record_returns_the_earlier_runs_files_it_removed(tmp_path):
    box = scene_path("tests/scenes/drop_box.json")
    first = tem.Simulation(box)
    assert first.record(tmp_path / "out", contacts=True) == []
    first.step(10)
    first.finish_recording()
    second = tem.Simulation(box)
    assert second.record(tmp_path / "out") == ["contacts.csv"]
    second.finish_recording()
    assert not (tmp_path / "out" / "contacts.csv").exists()
