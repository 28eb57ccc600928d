"""Bad inputs the twelfth review found, one test per rule."""

import pytest

import tegrasp_drake as T
from tests.test_bad_input_round10 import _refused




# Rule: an empty text or list is a value only where the field declares what empty means
# (unset_fields) or where its default is itself empty; a field whose default is filled (an
# LCM bus, a port, the joints that wrap) refuses an empty one naming the field, rather than
# run on LCM's default bus or no device (rig/ranges.check_ranges, at load and at a public
# function). A list of a fixed length (one value per joint) holds that many in every config.
@pytest.mark.parametrize("text, field, words", [
    ("arm: {tracker: {continuous_joints: []}}\n", "arm.tracker.continuous_joints", "is empty"),
    ("arm: {tracker: {continuous_joints: [true]}}\n", "arm.tracker.continuous_joints",
     "must hold 6"),
    ('arm: {lcm_url: ""}\n', "arm.lcm_url", "is empty"),
    ("arm: {lcm_url: ''}\n", "arm.lcm_url", "is empty"),
    ('gripper: {port: ""}\n', "gripper.port", "is empty"),
    ("gripper: {port: ''}\n", "gripper.port", "is empty"),
    ('tactile: {port: ""}\n', "tactile.port", "is empty"),
    ("tactile: {port: ''}\n", "tactile.port", "is empty"),
])
def test_a_hardware_config_refuses_an_empty_or_short_value(tmp_path, text, field, words):
    path = tmp_path / "hardware.yaml"
    path.write_text(text)
    _refused(lambda: T.LoadHardwareConfig(path), str(path), f"field '{field}' {words}")


def test_an_empty_value_is_kept_where_the_field_declares_what_empty_means(tmp_path):
    path = tmp_path / "hardware.yaml"
    path.write_text('tactile: {port: /dev/ttyACM0, calibration_file: ""}\n')
    assert T.LoadHardwareConfig(path).tactile.calibration_file == ""
    _refused(lambda: T.LoadScenario(name="box", overrides=["object.shape=''"]),
             "'object.shape'")
    assert T.LoadScenario(name="box", overrides=[
        "controller.event_object_may_differ=[]"]).controller.event_object_may_differ == []


# Rule: one object-name rule (rig/objects.object_name_problem) wherever a name becomes a path:
# a folder name (with the suffixes of the files made of it) fits 255 bytes, and the events
# folder's own subfolders are no object's name.
_OWN_OBJECT = ["object.shape=box", "object.size=[0.04,0.04,0.1]", "object.mass=0.1",
               "object.friction=0.5"]


@pytest.mark.parametrize("name", ["ensemble", "corrective", "prismatic", "a" * 300])
def test_an_object_name_that_cannot_be_its_own_folder_is_refused(name):
    _refused(lambda: T.LoadScenario(name="box", overrides=[f"object.name={name}"] + _OWN_OBJECT),
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
    _refused(lambda: T.LoadSweepSpec(path), "user_objects", "ensemble")


# Rule: a run log's TEGRASP_RUN_INFO is checked as a whole when it is read: a controller
# the package lacks, an object name no folder can have or versions that are not JSON are
# refused naming the field, as a bad scenario in it is.
@pytest.mark.parametrize("field, value", [("controller", "bogus"),
                                          ("versions_json", "{not json"),
                                          ("versions_json", "[1, 2]"),
                                          ("object_name", "../../etc")])
def test_a_run_info_field_the_run_never_writes_is_refused(tmp_path, field, value):
    import lcm
    from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL
    from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info
    from tegrasp_drake.runs.hardware_log_reader import RunLogError, read_run_log
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name, info.versions_json = "memorized", "box", "{}"
    setattr(info, field, value)
    path = tmp_path / "run.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(0, RUN_INFO_CHANNEL, info.encode())
    log.close()
    with pytest.raises(RunLogError, match=f"'{field}'") as refused:
        read_run_log(path)
    assert "\n" not in str(refused.value)


# Rule: a Robotiq status whose gFLT holds a major fault (2F-85 manual: the fingers stop
# until the next activation) is a device fault, not an active gripper, whatever gSTA says;
# and the client keeps pymodbus's multi-line hex dumps of garbage replies off stderr (it
# counts those replies itself).
@pytest.mark.real_time
def test_a_gripper_reporting_a_major_fault_is_not_taken_as_active():
    import logging
    import time
    from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator, RobotiqEmulatorConfig
    from tegrasp_drake.hardware.robotiq.modbus_client import (
        RobotiqActivationError, RobotiqModbusClient, RobotiqModbusConfig)
    logging.getLogger("pymodbus").setLevel(logging.NOTSET)
    config = RobotiqEmulatorConfig(activation_duration=1.0)
    with RobotiqEmulator(config) as emulator:
        with RobotiqModbusClient(RobotiqModbusConfig(port=emulator.port,
                                                     activation_timeout=5.0)) as client:
            assert logging.getLogger("pymodbus").level == logging.CRITICAL
            time.sleep(0.3)  # the activation writes are answered; gSTA not yet 3
            emulator.inject_fault(0x0F)  # automatic release completed
            with pytest.raises(RobotiqActivationError, match="gFLT = 0x0F"):
                client.wait_until_active(8.0)


# Rule: a corrupt record in a sweep's folder is said, one line naming the file, before its
# trial runs again, and kept aside rather than overwritten.
def test_a_corrupt_sweep_record_is_said_and_kept_aside_before_its_trial_reruns(tmp_path, caplog):
    from tegrasp_drake.sweep.records import record_path
    from tegrasp_drake.sweep.runner import run_sweep
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    from tests.fake_trials import fake_trial
    spec = SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                     grid=((0.0, 0.0),))
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    damaged = record_path(tmp_path, expand_trials(spec)[0].trial_id)
    damaged.write_text('{"trunc')
    with caplog.at_level("WARNING", logger="tegrasp_drake.sweep.runner"):
        summary = run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    assert summary.ran == 1
    said = [r.getMessage() for r in caplog.records if str(damaged) in r.getMessage()]
    assert len(said) == 1 and "re-run" in said[0] and "\n" not in said[0]
    (kept,) = tmp_path.glob(f"**/{damaged.name}.corrupt-*")
    assert kept.read_text() == '{"trunc'
