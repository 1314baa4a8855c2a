"""The module and `tem run` give the same results, bit for bit: hashes, files, checkpoints."""
import filecmp

import pytest

import tem
from conftest import run_tem, scene_path

PILE = scene_path("tests/scenes/small_pile.json")  # 40 coins, 400 steps, many contacts


def tem_run_hash(scene, out_dir):
    result = run_tem("run", scene, "--out", out_dir, "--hash")
    assert result.returncode == 0, result.stderr
    last = result.stdout.strip().splitlines()[-1]
    assert last.startswith("hash: ")
    return last.split()[1]


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "pile"
    return tem_run_hash(PILE, out), out


def test_python_steps_give_tem_runs_hash(cli_run):
    cli_hash, _ = cli_run
    sim = tem.Simulation(PILE)
    assert sim.state_hash() != cli_hash  # the start is not the end
    sim.step(sim.total_steps)
    assert sim.step_count == 400
    h = sim.state_hash()
    assert len(h) == 16 and int(h, 16) >= 0
    assert h == cli_hash


def test_hash_does_not_depend_on_how_the_steps_are_split(cli_run):
    cli_hash, _ = cli_run
    sim = tem.Simulation(PILE)
    for _ in range(37):
        sim.step()
    sim.step(100)
    sim.step(0)
    sim.step(sim.total_steps - sim.step_count)
    assert sim.state_hash() == cli_hash


def test_hash_of_a_scene_from_a_dict(cli_run, tmp_path):
    import json
    cli_hash, _ = cli_run
    sim = tem.Simulation.from_dict(json.loads(PILE.read_text()))
    sim.step(sim.total_steps)
    assert sim.state_hash() == cli_hash
    sim = tem.Simulation.from_json(PILE.read_text())
    sim.step(sim.total_steps)
    assert sim.state_hash() == cli_hash


def test_record_writes_tem_runs_files(cli_run, tmp_path):
    _, cli_dir = cli_run
    sim = tem.Simulation(PILE)
    out = tmp_path / "py"
    sim.record(out)
    assert sim.recording
    sim.step(sim.total_steps)
    sim.write_checkpoint(out / "checkpoint.bin")  # as `tem run` does at the end
    sim.finish_recording()
    assert not sim.recording
    names = ["bodies.csv", "energy.csv", "scene.json", "checkpoint.bin"]
    match, mismatch, errors = filecmp.cmpfiles(cli_dir, out, names, shallow=False)
    assert match == names, (mismatch, errors)


def test_record_with_contacts_writes_tem_runs_files(tmp_path):
    box = scene_path("tests/scenes/drop_box.json")
    cli_dir = tmp_path / "cli"
    result = run_tem("run", box, "--out", cli_dir, "--contacts")
    assert result.returncode == 0, result.stderr
    sim = tem.Simulation(box)
    sim.record(tmp_path / "py", contacts=True)
    sim.step(sim.total_steps)
    sim.write_checkpoint(tmp_path / "py" / "checkpoint.bin")
    sim.finish_recording()
    names = ["bodies.csv", "energy.csv", "contacts.csv", "scene.json", "checkpoint.bin"]
    match, mismatch, errors = filecmp.cmpfiles(cli_dir, tmp_path / "py", names, shallow=False)
    assert match == names, (mismatch, errors)
    assert len((cli_dir / "contacts.csv").read_text().splitlines()) > 5  # it did land


def test_resume_from_a_checkpoint_continues_bit_for_bit(cli_run, tmp_path):
    cli_hash, _ = cli_run
    sim = tem.Simulation(PILE)
    sim.step(150)
    checkpoint = tmp_path / "at150.bin"
    sim.write_checkpoint(checkpoint)
    at150 = sim.state_hash()
    sim.step(sim.total_steps - sim.step_count)
    assert sim.state_hash() == cli_hash  # the checkpoint did not disturb the run

    resumed = tem.Simulation.resume(PILE, checkpoint)
    assert resumed.step_count == 150
    assert resumed.time == pytest.approx(150 * resumed.time_step)
    assert resumed.state_hash() == at150
    resumed.step(resumed.total_steps - resumed.step_count)
    assert resumed.state_hash() == cli_hash


def test_resume_from_tem_runs_checkpoint(cli_run):
    cli_hash, cli_dir = cli_run
    resumed = tem.Simulation.resume(str(PILE), str(cli_dir / "checkpoint.bin"))
    assert resumed.step_count == resumed.total_steps
    assert resumed.state_hash() == cli_hash
