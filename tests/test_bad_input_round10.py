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


# Rule: a trial log's arrays are finite, every one a reader may draw or judge (not only the
# tactile signals), and a plot's preconditions are said in one line: the Avoid figure of a
# controller without an Avoid reaction is "no Avoid transition", not an internal error.
def test_trial_log_arrays_and_the_avoid_plots_precondition(tmp_path):
    import json

    import numpy as np

    from tegrasp_drake.cli import main
    from tegrasp_drake.scenario.trial_log_file import FORMAT_VERSION, TrialLogError
    from tests.test_bad_input import _trial_log
    for name, shape in (("object_state", (11, 13)), ("arm_q", (11, 6)),
                        ("gripper_status", (11, 8))):
        path = _trial_log(tmp_path / f"{name}.npz", **{name: np.full(shape, np.nan)})
        with pytest.raises(TrialLogError, match=rf"\['{name}'\] hold NaN or infinite"):
            T.load_trial_log(path)
    path = _trial_log(tmp_path / "open_loop.npz")
    with np.load(path) as stored:
        arrays = {key: stored[key] for key in stored.files if key != "meta"}
    scenario = T.with_controller(T.LoadScenario(name="box"), "open_loop")
    meta = {"format_version": FORMAT_VERSION, "scenario": T.scenario_to_yaml(scenario),
            "controller": "open_loop", "transitions": []}
    np.savez_compressed(path, meta=np.array(json.dumps(meta)), **arrays)
    with pytest.raises(SystemExit) as refused:
        main(["plot", "avoid", str(path), "--out", str(tmp_path / "a.png")])
    assert "no Avoid transition" in str(refused.value.code), refused.value.code


# Rule: an error is one bounded line that echoes values cut to about 80 characters, and its
# reason is the true one: a file of many plain values is not said to expand aliases.
def test_error_text_is_bounded_and_names_the_true_reason(tmp_path):
    import json
    import shutil

    from tegrasp_drake.events.event_file import MemorizedEventError
    from tegrasp_drake.rig import paths
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("prismatic", "ensemble", "corrective"))
    path = folder / "box" / "load_lift.json"
    event = json.loads(path.read_text())
    event["scenario"] = "default:\n  object: !!python/object/apply:os.system ['true']\n"
    path.write_text(json.dumps(event))
    with pytest.raises(MemorizedEventError) as refused:
        T.load_memorized_events(folder, "box")
    message = str(refused.value)
    assert "scenario" in message and "\n" not in message and len(message) < 600, message
    assert len(str(MemorizedEventError(path, "x" * 5000))) < 1200
    many = tmp_path / "many.yaml"
    many.write_text("".join(f"s{k}: {{random_seed: 1}}\n" for k in range(30_000)))
    _refused(lambda: T.LoadScenario(many, name="s7"), "holds more than 100000 values")
    aliased = tmp_path / "aliased.yaml"
    aliased.write_text("a: &a [" + ", ".join(["1"] * 1000) + "]\n"
                       + "b: [" + ", ".join(["*a"] * 200) + "]\n")
    _refused(lambda: T.LoadScenario(aliased, name="a"), "aliases expand to more than")


# Rule: an environment variable or option value is checked before a library is handed it:
# a backend matplotlib does not know, an output encoding that cannot hold a name the user
# gave, an LCM URL option LCM would ignore, a fault time beyond any hardware run.
def test_environment_and_option_values_are_checked_before_a_library_gets_them(tmp_path):
    import io
    import os
    import subprocess
    import sys

    from tegrasp_drake.cli import main
    from tegrasp_drake.commands.output_streams import guarded_output
    from tegrasp_drake.hardware.config import lcm_url_problem
    environment = dict(os.environ, MPLBACKEND="banana")
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake", "plot", "events", "--out",
                           str(tmp_path / "x.png")], env=environment, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 1, done.stderr
    assert done.stderr.strip().count("\n") == 0 and "MPLBACKEND='banana'" in done.stderr
    ascii_out = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    saved = sys.stdout
    sys.stdout = ascii_out
    try:
        with guarded_output():
            print("wrote o/été_ü.png")
    finally:
        sys.stdout = saved
    ascii_out.flush()
    assert ascii_out.buffer.getvalue() == b"wrote o/\\xe9t\\xe9_\\xfc.png\n"
    for option in ("ttl=zero", "ttl=0&recv_buf_size=lots"):
        problem = lcm_url_problem(f"udpm://239.255.76.67:8793?{option}")
        assert problem and "Invalid value for" in problem, problem
    assert lcm_url_problem("udpm://239.255.76.67:8793?ttl=0") is None
    for fault in ("14@1e9", "14@601", "14@-1"):
        with pytest.raises(SystemExit) as refused:
            main(["emulate", "robotiq", "--inject-fault", fault, "--scheduling", "normal",
                  "--lcm-url", "udpm://239.255.76.67:8793?ttl=0"])
        assert "must lie in [0, 600] s" in str(refused.value.code), refused.value.code
