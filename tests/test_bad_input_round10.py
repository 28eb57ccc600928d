"""Bad inputs the tenth review found, one test per rule."""

import dataclasses

import pytest

import tegrasp_drake as T
from tegrasp_drake.rig.typed_yaml import ConfigError


def _refused(call, *words) -> str:
    """The one-line ConfigError of `call()`, which names each of `words`."""
    with pytest.raises(ConfigError) as refused:
        call()
    message = str(refused.value)
    assert "\n" not in message and len(message) < 400, message
    for word in words:
        assert word in message, message
    return message


def _scenario_with(field: str, value) -> T.Scenario:
    scenario = T.LoadScenario(name="box")
    setattr(scenario, field, value)
    return scenario


# Rule: a builder checks a config it is given against its dataclass's type hints, nested
# configs included: a mapping, None or a name where a config belongs is refused naming the
# field, and a config built in Python is checked as a loaded one is (ranges too).
@pytest.mark.parametrize("field, value, builder", [
    ("object", {"name": "box", "mass": -1}, "MakeStation"),
    ("object", None, "MakeStation"),
    ("object", "box", "MakeStation"),
    ("station", "sim", "MakeStation"),
    ("vibration", None, "MakeStation"),
    ("grasp", None, "grasp_plan"),
])
def test_a_builder_refuses_a_nested_config_of_the_wrong_type(field, value, builder):
    scenario = _scenario_with(field, value)
    _refused(lambda: getattr(T, builder)(scenario), builder, f"'{field}'", "must be")


def test_a_config_built_in_python_is_checked_for_nested_types_and_ranges():
    _refused(lambda: T.Scenario(object={"name": "box"}), "Scenario", "'object'", "ObjectConfig")
    _refused(lambda: T.MemorizedControllerConfig(re_reach={"opened_m": 0.2}), "'re_reach'",
             "ReReachConfig")
    _refused(lambda: T.HardwareStationConfig(gripper={"port": "/dev/null"}), "'gripper'")
    _refused(lambda: T.SweepSpec(randomisation={"placement_xy_bound_m": 0.002},
                                 objects=("box",), controllers=("open_loop",),
                                 grid=((0.0, 0.0),), attempts=1), "'randomisation'")
    controller = T.MemorizedControllerConfig()
    controller.re_reach = {"opened_m": 0.2}  # set after building
    _refused(lambda: T.MakeGraspDiagram(_scenario_with("controller", controller)),
             "MakeGraspDiagram", "controller.re_reach")
    scenario = T.LoadScenario(name="box")
    scenario.controller = dataclasses.replace(scenario.controller)
    scenario.controller.re_reach.opened_m = 0.2  # the right type, out of its range
    _refused(lambda: T.MakeGraspDiagram(scenario), "re_reach.opened_m")


# Rule: the public value classes check their fields' types when built, as the guide says.
def test_the_public_value_classes_refuse_fields_of_the_wrong_type():
    _refused(lambda: T.Transition(t=1.0, from_mode="Reach", to_mode="Load", trigger="timer",
                                  reason="x"), "Transition", "'from_mode'", "Mode")
    _refused(lambda: T.TrialLog(*([None] * 13), meta={}), "TrialLog", "'t_sa'")
    _refused(lambda: T.TrialResult(final_mode="Done"), "TrialResult", "'final_mode'")
    _refused(lambda: T.TrialResult(transitions=({"t": 1.0},)), "transitions[0]", "Transition")


# Rule: a configuration file without a field (empty, comments only, `{}`, a lone tag) is a
# mistake, not a request for every default: the hardware config as scenario files and specs.
@pytest.mark.parametrize("text", ["", "# my robot\n", "{}\n", "!Scenario {}\n",
                                  "!HardwareStationConfig {}\n"])
def test_a_hardware_config_without_fields_is_refused(tmp_path, text):
    path = tmp_path / "hardware.yaml"
    path.write_text(text)
    _refused(lambda: T.LoadHardwareConfig(path), str(path), "is empty")
    spec = tmp_path / "spec.yaml"
    spec.write_text(text)
    _refused(lambda: T.LoadSweepSpec(spec), str(spec), "is empty")


# Rule: the sweep API's records, reports and folders are bounded as the CLI's are: a
# hand-edited record is one line, trial ids that name no record are refused, an empty
# folder argument is not the current folder.
def test_sweep_records_reports_and_folders_at_the_api(tmp_path, monkeypatch):
    from tests.fake_trials import fake_trial
    record = {"status": "ok", "result": fake_trial({"pair_id": "p", "seed": 600,
                                                    "well_placed": True,
                                                    "controller": "memorized"})}
    assert T.record_result(record).hold_success in (True, False)
    for transitions in ([{"t": "soon"}], "Reach", [None]):
        record["result"]["transitions"] = transitions
        with pytest.raises(ValueError, match="not a trial result's JSON form") as refused:
            T.record_result(record)
        assert "\n" not in str(refused.value)
    spec = T.SweepSpec(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),),
                       attempts=1)
    summary = T.run_sweep(spec, fake_trial, tmp_path / "sweep", workers=1, progress=False)
    assert summary.ran == 1
    with pytest.raises(ValueError, match="'trial_ids' names no trial recorded"):
        T.write_reports(tmp_path / "sweep", trial_ids=["nope"])
    assert T.write_reports(tmp_path / "sweep", trial_ids=list(summary.trial_ids))
    monkeypatch.chdir(tmp_path)
    for empty in ("", " "):
        with pytest.raises(OSError, match="is empty; give a folder"):
            T.run_sweep(spec, fake_trial, empty, workers=1, progress=False)
    assert not (tmp_path / "trials").exists()

