"""An object's (or world's) name names folders: it must be letters, digits and the like, not
empty, not too long for a folder, not one of the events folder's own subfolders, and a user's
own object needs its own name; each is refused at load in one line."""

import pytest

import tegrasp_drake as T
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tests.bad_input.probes import (FAKE_TRIALS, SEEDED_SWEEP, assert_one_line_error, refusal,
                                    run_cli)

OWN_CYLINDER = ["--set", "object.shape=cylinder", "--set", "object.size=[0.04,0.1]",
                "--set", "object.mass=0.12", "--set", "object.friction=0.6"]


@pytest.mark.parametrize("command", [["trial"], ["record-events"]])
def test_your_own_object_needs_its_own_name(command, capfd):
    code, text = run_cli([*command, *OWN_CYLINDER], capfd)
    assert_one_line_error(code, text, "field 'object.name'", "needs its own name",
                          "not the built-in 'box'")


def test_an_empty_object_name_is_refused_not_taken_as_none(capfd):
    code, text = run_cli(["replay", "run.lcmlog", "--object", ""], capfd)
    assert code == 2 and "--object '' is empty" in text and "Traceback" not in text


# Rule: an object's name given to a public function names a folder, as a scenario's
# object.name does: record_events declares OBJECT_NAME on its argument, checked at the call,
# so '' or '../x' is refused before an ideal grasp is simulated (load_memorized_events says
# so in its own words, with what to record instead).
@pytest.mark.parametrize("name", ["", "../x", "a b"])
def test_an_object_name_argument_is_refused_unless_it_names_a_folder(tmp_path, name):
    scenario = LoadScenario(overrides=["random_seed=633"])
    with pytest.raises(ValueError, match="argument 'object_name' must be letters, digits"):
        T.record_events(name, scenario)  # at once: no ideal grasp simulated


# Rule: an object's name is bounded where it is declared (rig/objects.OBJECT_NAME_PATTERN):
# it names a folder and is part of file names, so 300 characters are refused at load, not
# after minutes of simulation when the folder cannot be made.
def test_an_object_name_longer_than_a_folder_name_should_be_is_refused_at_load():
    own = ["object.shape=box", "object.size=[0.04, 0.04, 0.1]", "object.mass=0.1",
           "object.friction=0.5"]
    with pytest.raises(ConfigError) as refused:  # its --set echoes make it long: no _refused
        LoadScenario(overrides=["object.name=" + "a" * 300, *own])
    assert "\n" not in str(refused.value)
    assert "field 'object.name'" in str(refused.value)
    assert "at most 64 characters" in str(refused.value)
    assert LoadScenario(overrides=["object.name=" + "a" * 64, *own]).object.name == "a" * 64
    with pytest.raises(ValueError, match="at most 64 characters"):
        T.record_events("a" * 65, LoadScenario(overrides=["random_seed=633"]))


# Rule: one object-name rule (rig/objects.object_name_problem) wherever a name becomes a path:
# a folder name (with the suffixes of the files made of it) fits 255 bytes, and the events
# folder's own subfolders are no object's name.
_OWN_OBJECT = ["object.shape=box", "object.size=[0.04,0.04,0.1]", "object.mass=0.1",
               "object.friction=0.5"]


@pytest.mark.parametrize("name", ["ensemble", "corrective", "prismatic", "a" * 300])
def test_an_object_name_that_cannot_be_its_own_folder_is_refused(name):
    refusal(lambda: T.LoadScenario(name="box", overrides=[f"object.name={name}"] + _OWN_OBJECT),
             "'object.name'")


def test_the_reserved_names_are_the_events_folders_own_subfolders():
    from tegrasp_drake.control.controller_registry import CONTROLLERS
    from tegrasp_drake.recording.corrective_events import CORRECTIVE_FOLDER
    from tegrasp_drake.recording.ensemble_events import ENSEMBLE_FOLDER
    from tegrasp_drake.rig.objects import EVENTS_SUBFOLDERS
    from tegrasp_drake.robotiq.hand_models import GRIPPER_MODELS
    from tegrasp_drake.simulation.gripper_hands import gripper_hand
    folders = {entry.config.events_folder for entry in CONTROLLERS}
    folders |= {gripper_hand(model).events_folder for model in GRIPPER_MODELS}
    folders |= {CORRECTIVE_FOLDER, ENSEMBLE_FOLDER}
    assert folders - {None, ""} <= set(EVENTS_SUBFOLDERS)


def test_events_of_an_object_named_ensemble_cannot_replace_the_ensemble_folders_index(tmp_path):
    import dataclasses
    import shutil
    from tegrasp_drake.events import load_memorized_events, save_memorized_events
    from tegrasp_drake.rig import paths
    events_dir = tmp_path / "events"
    shutil.copytree(paths.package_events_dir() / "ensemble", events_dir / "ensemble")
    box = load_memorized_events(paths.package_events_dir(), "box").values()
    with pytest.raises(ValueError, match="object_name"):
        save_memorized_events(events_dir, [dataclasses.replace(e, object_name="ensemble")
                                           for e in box], keep_other_objects=True)
    assert (events_dir / "ensemble" / "index.json").is_file()


def test_a_sweep_object_name_follows_the_object_name_rule(tmp_path):
    path = tmp_path / "spec.yaml"
    path.write_text("objects: [ensemble]\ncontrollers: [open_loop]\nuser_objects:\n  ensemble: "
                    "{shape: box, size: [0.04, 0.04, 0.1], mass: 0.1, friction: 0.5}\n")
    refusal(lambda: T.LoadSweepSpec(path), "user_objects", "ensemble")


def test_a_world_name_too_long_for_a_folder_is_refused_at_load(tmp_path, capfd):
    """A world's name names folders (its cells' twice): refused in one line before any
    folder is made, not an OSError after the events folder was."""
    name = "a" * 300
    spec = tmp_path / "t.yaml"
    spec.write_text(f"worlds: {{{name}: {{scenario: faithful_world}}}}\n"
                    f"cells: [[{name}, {name}]]\n" + SEEDED_SWEEP)
    out = tmp_path / "out"
    code, text = run_cli(["transfer", str(spec), "--out", str(out), "--workers", "1",
                          "--no-progress", *FAKE_TRIALS], capfd)
    assert code == 2, text
    assert "at most 64 characters" in text and "worlds.aaaa" in text
    assert len(text.strip().splitlines()) == 1 and "Traceback" not in text
    assert not (out / "events").exists()
