"""Bad inputs found by the sixth hostile pass: every output is checked by one function before
the work, every read is bounded, damaged logs are damaged, no empty value the user gave is
replaced by a built-in one, and the Python API checks what it is given."""

import os
import pathlib

import pytest

from tests.test_bad_input import run_cli


def _one_error_line(text: str) -> list[str]:
    return [line for line in text.splitlines() if "error:" in line]


@pytest.fixture
def fifo(tmp_path) -> pathlib.Path:
    path = tmp_path / "pipe.html"
    os.mkfifo(path)
    return path


@pytest.mark.parametrize("argv_of", [
    lambda p: ["trial", "--controller", "open_loop", "--out", str(p.parent / "o"),
               "--html", str(p)],
    lambda p: ["plot", "trial", str(p.parent / "missing.npz"), "--out",
               str(p.with_suffix(".png"))],
])
def test_an_output_on_a_fifo_is_refused_naming_its_option(tmp_path, argv_of, capfd):
    path = tmp_path / "pipe.html"
    argv = argv_of(path)
    os.mkfifo(argv[-1])
    code, text = run_cli(argv, capfd)
    assert code not in (0, 70)
    errors = _one_error_line(text)
    assert len(errors) == 1 and argv[-2] in errors[0] and "named pipe" in errors[0], text
    assert pathlib.Path(argv[-1]).exists() and not pathlib.Path(argv[-1]).is_file()


@pytest.mark.parametrize("option, name", [("--html", "h.html")])
def test_an_output_in_proc_is_refused_before_the_run(tmp_path, option, name, capfd):
    code, text = run_cli(["trial", "--controller", "open_loop", "--out", str(tmp_path / "o"),
                          option, f"/proc/{name}"], capfd)
    assert code not in (0, 70)
    errors = _one_error_line(text)
    assert len(errors) == 1 and option in errors[0] and "/proc" in errors[0], text
    assert not (tmp_path / "o").exists()


def test_output_file_problem_refuses_devices_and_proc_and_accepts_a_new_file(tmp_path):
    from tegrasp_drake.rig.files import output_file_problem
    assert "device" in output_file_problem("/dev/null")
    assert "/proc" in output_file_problem("/proc/self/x.html")
    assert "folder" in output_file_problem(tmp_path)
    assert output_file_problem(tmp_path / "new" / "replay.html") is None
    (tmp_path / "plain").write_text("x")
    assert "not a folder" in output_file_problem(tmp_path / "plain" / "replay.html")


@pytest.mark.parametrize("trial", ["/dev/zero", "fifo"])
def test_emulate_myrio_refuses_a_trial_that_is_not_a_file_before_reading(tmp_path, trial,
                                                                         capfd):
    if trial == "fifo":
        trial = str(tmp_path / "t.npz")
        os.mkfifo(trial)
    code, text = run_cli(["emulate", "--scheduling", "normal", "myrio", "--trial", trial,
                          "--lcm-url", "udpm://239.255.76.67:8716?ttl=0"], capfd)
    assert code == 1
    errors = _one_error_line(text)
    assert len(errors) == 1 and trial in errors[0] and "not a file" in errors[0], text


def test_every_npz_reader_refuses_a_device_before_reading():
    from tegrasp_drake.rig.npz_headers import NpzHeaderError, checked_npz_arrays
    with pytest.raises(NpzHeaderError, match="not a regular file"):
        checked_npz_arrays("/dev/zero", ("t",), max_bytes=10)


@pytest.mark.parametrize("assignment", ["object.size=[]", "object.shape=''", "object.color=[]",
                                        "object.file=''"])
def test_an_empty_value_the_user_gives_is_refused_not_read_as_unset(assignment):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    field = assignment.split("=")[0]
    with pytest.raises(ConfigError, match=f"field '{field}' is empty: give a value, or leave"):
        LoadScenario(name="box", overrides=[assignment])


def test_a_stored_scenario_reads_back_as_a_scenario_file(tmp_path):
    from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
    stored = scenario_to_yaml(LoadScenario(name="box"))
    assert "file:" not in stored  # empty "not set" fields are left out of the text
    path = tmp_path / "s.yaml"
    path.write_text("x:\n" + "".join(f"  {line}\n" for line in stored.splitlines()))
    assert LoadScenario(path, name="x").object.size == LoadScenario(name="box").object.size


def test_a_null_scenario_entry_is_refused_naming_it(tmp_path, capfd):
    path = tmp_path / "s.yaml"
    path.write_text("x:\n")
    code, text = run_cli(["trial", "--scenario", str(path), "--scenario-name", "x",
                          "--out", str(tmp_path / "o")], capfd)
    assert code == 1
    errors = _one_error_line(text)
    assert len(errors) == 1 and "scenario 'x' is empty" in errors[0], text


def test_a_sweep_spec_that_is_an_empty_mapping_is_refused_like_an_empty_file(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sweep.spec_file import LoadSweepSpec
    for text in ("", "{}\n"):
        (tmp_path / "spec.yaml").write_text(text)
        with pytest.raises(ConfigError, match="the sweep spec is empty"):
            LoadSweepSpec(tmp_path / "spec.yaml")


def _reachable_dataclasses(*roots):
    import dataclasses
    import typing
    from tegrasp_drake.rig.ranges import _config_classes
    seen, pending = [], list(roots)
    while pending:
        cls = pending.pop()
        if cls in seen or not dataclasses.is_dataclass(cls):
            continue
        seen.append(cls)
        hints = typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            pending.extend(_config_classes(hints[field.name]))
    return seen


def test_every_timeout_refuses_zero_as_the_user_guide_says():
    import dataclasses
    from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_named
    from tegrasp_drake.hardware.config import HardwareStationConfig
    from tegrasp_drake.rig.ranges import range_of
    from tegrasp_drake.scenario.scenario import Scenario
    roots = [Scenario, HardwareStationConfig,
             *(type(controller_named(name)) for name in CONTROLLER_NAMES)]
    timeouts, zero_allowed = [], []
    for cls in _reachable_dataclasses(*roots):
        for field in dataclasses.fields(cls):
            declared = range_of(field)
            if "timeout" in field.name and declared is not None:
                timeouts.append(f"{cls.__name__}.{field.name}")
                if declared.low is not None and declared.low <= 0 and not declared.low_open:
                    zero_allowed.append(f"{cls.__name__}.{field.name}")
    assert len(timeouts) >= 4 and zero_allowed == []


@pytest.mark.parametrize("key", ["controller.load_event_timeout_s",
                                 "controller.re_reach.reach_event_timeout_s",
                                 "controller.place.event_timeout_s"])
def test_a_zero_controller_timeout_is_refused(key):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    with pytest.raises(ConfigError, match=f"field '{key}' must be positive"):
        LoadScenario(name="box", overrides=[f"{key}=0.0"])


@pytest.mark.parametrize("name, size, words", [("box", [0.1], "3 positive sizes"),
                                               ("thin_cylinder", [0.02, 0.1, 0.1],
                                                "2 positive sizes")])
def test_builders_recheck_an_object_a_script_changed(name, size, words):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    from tegrasp_drake.scenario.scenario import LoadScenario
    scenario = LoadScenario(name=name)
    scenario.object.size = size
    with pytest.raises(ConfigError, match=f"MakeGraspDiagram: scenario: field 'object.size' "
                                          f"must hold {words}"):
        MakeGraspDiagram(scenario)


def test_a_recheck_keeps_a_built_in_object_with_sizes_the_user_set_and_resolves_a_bare_one():
    from tegrasp_drake.scenario.scenario import LoadScenario, Scenario, rechecked
    loaded = LoadScenario(name="box", overrides=["object.size=[0.05,0.05,0.1]"])
    assert rechecked(loaded, "test").object.size == [0.05, 0.05, 0.1]
    assert rechecked(Scenario(), "test").object.size == LoadScenario(name="box").object.size


def test_record_result_refuses_what_is_not_a_trial_record():
    from tegrasp_drake.sweep.records import record_result
    with pytest.raises(ValueError, match="argument 'record' is not a sweep record"):
        record_result({"a": 1})
    with pytest.raises(ValueError, match="'result' is not a trial's result"):
        record_result({"status": "ok", "result": {"a": 1}})
    assert record_result({"status": "error", "result": None}) is None


def test_public_dataclasses_check_scalar_field_types_at_construction():
    import numpy as np
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(TypeError, match="TrialResult: field 'hold_success' must be bool, got str"):
        TrialResult(hold_success="yes")
    with pytest.raises(TypeError, match="ObjectConfig: field 'mass' must be"):
        ObjectConfig(mass="heavy")
    assert TrialResult(hold_success=np.bool_(True), seed=np.int64(3), hold_time_s=3).seed == 3
