"""Bad inputs the thirteenth review found, one test per rule."""

import pytest

import tegrasp_drake as T
from tests.test_bad_input_round10 import _refused


# Rule: a range's low end is a physical low, not just "positive": a value a real fingertip,
# pad, object or amplifier cannot have is refused naming the field, while the committed
# values (and the slip recordings' slippery objects) still load.
@pytest.mark.parametrize("setting, field", [
    ("vibration.film.mode_frequency_hz=1e-9", "vibration.film.mode_frequency_hz"),
    ("vibration.film.mode_frequency_hz=1.0", "vibration.film.mode_frequency_hz"),
    ("vibration.film.mode_mass_kg=1e-9", "vibration.film.mode_mass_kg"),
    ("vibration.film.pad_contact_stiffness_n_per_m=1e-6",
     "vibration.film.pad_contact_stiffness_n_per_m"),
    ("vibration.film.feedback_capacitance_f=1e-20", "vibration.film.feedback_capacitance_f"),
    ("vibration.highpass_cutoff_hz=1e-9", "vibration.highpass_cutoff_hz"),
    ("vibration.slip_texture_period_m=1e-12", "vibration.slip_texture_period_m"),
    ("vibration.amplifier_swing_v=1e-6", "vibration.amplifier_swing_v"),
    ("vibration.internal_rate_hz=1.0", "vibration.internal_rate_hz"),
    ("object.friction=1e-12", "object.friction"),
    ("gripper.pad_friction=1e-9", "gripper.pad_friction"),
    ("tactile.capacitive.calibration_force_n=1e-9", "tactile.capacitive.calibration_force_n"),
    ("tactile.capacitive.minimum_gap_fraction=1e-9",
     "tactile.capacitive.minimum_gap_fraction"),
    ("grasp.grip_force=1.0", "grasp.grip_force"),
])
def test_a_physically_meaningless_small_value_is_refused(setting, field):
    _refused(lambda: T.LoadScenario(name="box", overrides=[setting]), f"'{field}'")


def test_the_slip_recordings_slippery_object_still_loads():
    assert T.LoadScenario(name="box", overrides=["object.friction=0.008"]).object.friction \
        == pytest.approx(0.008)


# Rule: a public dataclass names the type of each field, so its constructor's check (the
# public_dataclass decorator every public dataclass has) refuses a value of another type:
# a controller's systems and ports are Drake systems and output ports, not any object.
@pytest.fixture(scope="module")
def built_controller():
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    return MakeGraspDiagram(T.LoadScenario(name="box", controller="open_loop"),
                            log=False).controller


@pytest.mark.parametrize("field, value", [
    ("channels", "box"), ("detector", 5), ("state_machine", None), ("gripper_command", 1.0),
    ("arm_desired_state", "port"), ("mode", [0]), ("segments", "abc"),
])
def test_a_grasp_controller_refuses_a_field_of_another_type(built_controller, field, value):
    import dataclasses
    fields = {f.name: getattr(built_controller, f.name)
              for f in dataclasses.fields(built_controller)}
    T.GraspController(**fields)  # the built one's fields are taken
    fields[field] = value
    with pytest.raises(TypeError) as refused:
        T.GraspController(**fields)
    assert f"'{field}'" in str(refused.value) and "\n" not in str(refused.value)


# Rule: values are read as YAML 1.2 reads them (rig/core_schema_yaml.py): `yes`, `no`, `on`
# and `off` (any case) are text, which a true/false setting refuses saying to write true or
# false, in a file and in --set alike; a text setting keeps them as text.
@pytest.mark.parametrize("word", ["yes", "no", "on", "off", "Yes", "OFF", "y", "N"])
def test_a_yaml_11_boolean_word_is_refused_for_a_true_false_setting(tmp_path, word):
    path = tmp_path / "s.yaml"
    path.write_text(f"default: {{arm: {{tracker: {{continuous_joints: "
                    f"[{word}, false, false, true, true, true]}}}}}}\n")
    _refused(lambda: T.LoadScenario(path), "'arm.tracker.continuous_joints[0]'",
             "write true or false")
    setting = f"vibration.film.impact_enabled={word}"
    _refused(lambda: T.LoadScenario(name="box", overrides=[setting]),
             "'vibration.film.impact_enabled'", "write true or false")


def test_true_and_false_are_still_read_and_a_text_setting_keeps_yes_as_text():
    scenario = T.LoadScenario(name="box", overrides=["vibration.film.impact_enabled=False",
                                                     "object.name=yes", "object.shape=box",
                                                     "object.size=[0.04,0.04,0.1]",
                                                     "object.mass=0.1", "object.friction=0.5"])
    assert scenario.vibration.film.impact_enabled is False and scenario.object.name == "yes"


# Rule: a command's refusal names its option, not the function argument it is bound to
# (`--events`, not run_trial_from_spec's events_dir), before any trial runs.
@pytest.mark.parametrize("controller", ["open_loop", "memorized"])
def test_tegrasp_sweep_names_its_events_option(tmp_path, capfd, controller):
    from tests.test_bad_input import run_cli
    missing = tmp_path / "MISSING"
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", controller,
                          "--base-seed", "640", "--attempts", "1", "--workers", "1",
                          "--out", str(tmp_path / "sw"), "--events", str(missing)], capfd)
    assert code == 1, text
    assert f"--events {missing}" in text and "events_dir" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert not (tmp_path / "sw").exists()


# Rule: the progress bar is decoration in every run that draws it, a hardware run's monitor
# too: a line written above the bar (SimulatedTimeBar.write, a hardware run's `out`) when the
# terminal starts refusing stops the bar, as a refused draw does, and the line still reaches
# stdout; the run goes on.
@pytest.mark.parametrize("error", [OSError(5, "Input/output error"),
                                   OSError(28, "No space left on device"),
                                   ValueError("I/O operation on closed file.")])
def test_a_line_above_a_refused_bar_stops_the_bar_not_the_run(error, monkeypatch, capsys):
    import sys
    from tegrasp_drake.commands import output_streams
    from tegrasp_drake.commands.progress import SimulatedTimeBar
    from tests.test_bad_input_round11 import _RefusingTerminal
    terminal = _RefusingTerminal(error, accepted=10**6)
    monkeypatch.setattr(sys, "stderr", terminal)
    with output_streams.guarded_output():
        with SimulatedTimeBar("hardware", enabled=True) as progress:
            progress(1.0, 10.0)  # the bar is drawn
            terminal._accepted = 0  # the terminal hangs up
            progress.write("gripper active")
            progress(2.0, 10.0)
            progress.write("arm moving")
    assert capsys.readouterr().out.splitlines() == ["gripper active", "arm moving"]


# Rule: what a scenario's fields must be to build is checked where it is loaded (validate),
# not found while building: a side grasp the JACO2 cannot reach, at which the carriage's
# impedance is taken (`station.arm: carriage`), is bad input naming the fields (exit 1).
CARRIAGE_OUT_OF_REACH = ["station.arm=carriage", "placement.expected_xy=[0.2,0.0]"]


def test_a_carriage_side_grasp_out_of_reach_is_refused_at_load():
    _refused(lambda: T.LoadScenario(name="box", overrides=CARRIAGE_OUT_OF_REACH),
             "'placement.expected_xy'", "reach")


def test_tegrasp_trial_says_a_carriage_side_grasp_out_of_reach_as_bad_input(tmp_path, capfd):
    from tests.test_bad_input import run_cli
    argv = ["trial", "--set", "random_seed=640", "--out", str(tmp_path / "o")]
    for setting in CARRIAGE_OUT_OF_REACH:
        argv += ["--set", setting]
    code, text = run_cli(argv, capfd)
    assert code == 1 and "placement.expected_xy" in text and "internal error" not in text, text


# Rule: a refusal names what the user set: events recorded into the user's folder that an
# environment variable chose (no --events) are refused naming that variable, before
# anything is simulated.
@pytest.mark.parametrize("variable, value", [("XDG_DATA_HOME", "/proc/x"),
                                             ("TEGRASP_EVENTS_DIR", "/proc/x/events")])
def test_an_unusable_events_folder_from_the_environment_is_named_by_its_variable(
        variable, value, monkeypatch, capfd):
    from tests.test_bad_input import run_cli
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    monkeypatch.setenv(variable, value)
    code, text = run_cli(["record-events", "--set", "random_seed=642", "--ensemble-runs", "0"],
                         capfd)
    assert code == 1, text
    assert f"{variable}=" in text and "--events" not in text.split(";")[0], text
    assert len(text.strip().splitlines()) == 1, text
