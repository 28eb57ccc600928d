"""Bad inputs a hostile tester found past the first disciplines, each as the class it belongs
to: Drake's own config sections checked like ours, list lengths, a null the user writes,
fields that relate (grasp height, filters against their rates), files that are not regular,
a run folder two runs share, outputs that would overwrite the run's own files. Each stops
with one line naming the input and what to do, a non-zero exit, and nothing lost."""

import dataclasses
import hashlib
import pathlib

import pytest

from test_bad_input import assert_one_line_error, run_cli
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario


def _write(name, text):
    return lambda folder: (folder / name).write_text(text)


DRAKE_SECTION_PROBES = [  # (--set assignment, words the one error line holds)
    ("plant_config.contact_model=foo", "field 'plant_config.contact_model' must be one of"),
    ("simulator_config.integration_scheme=bogus",
     "field 'simulator_config.integration_scheme' must be one of"),
    ("plant_config.contact_surface_representation=sphere",
     "field 'plant_config.contact_surface_representation' must be one of 'triangle'"),
    ("plant_config.discrete_contact_approximation=exact",
     "field 'plant_config.discrete_contact_approximation' must be one of"),
    ("plant_config.penetration_allowance=-1.0",
     "field 'plant_config.penetration_allowance' must lie in (0, "),
    ("plant_config.stiction_tolerance=0.0", "field 'plant_config.stiction_tolerance' must lie in"),
    ("plant_config.sap_near_rigid_threshold=-3.0",
     "field 'plant_config.sap_near_rigid_threshold' must lie in [0, "),
    ("simulator_config.start_time=100.0", "field 'simulator_config.start_time' must lie in"),
    ("simulator_config.target_realtime_rate=-1.0",
     "field 'simulator_config.target_realtime_rate' must lie in [0, "),
    ("simulator_config.max_step_size=0.0", "field 'simulator_config.max_step_size' must lie in"),
    ("simulator_config.accuracy=5.0", "field 'simulator_config.accuracy' must lie in (0, 1]"),
]

RELATED_FIELD_PROBES = [
    ("controller.slip_band_hz=900.0", "field 'controller.slip_band_hz' must lie below half"),
    ("grasp.grasp_height=0.5", "field 'grasp.grasp_height' must lie within the object's height"),
    ("object.mass=~", "field 'object.mass' is null"),
    ("object.friction=~", "field 'object.friction' is null"),
    ("object.color=[0.1,0.2,0.3]", "field 'object.color' must be [r, g, b, a]"),
    ("object.color=[2.0,0.0,0.0,1.0]", "field 'object.color[0]' must lie in [0, 1]"),
    ("object.file=mine.sdf", "field 'object.file' is for your own object"),
]


@pytest.mark.parametrize("assignment, words", DRAKE_SECTION_PROBES + RELATED_FIELD_PROBES,
                         ids=[p[0] for p in DRAKE_SECTION_PROBES + RELATED_FIELD_PROBES])
def test_a_bad_setting_stops_the_trial_with_one_line(assignment, words, tmp_path, monkeypatch,
                                                      capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["trial", "--set", assignment, "--out", "run"], capfd)
    assert_one_line_error(code, text, words, f"--set {assignment}")
    assert not (tmp_path / "run").exists()


def test_a_sweep_refuses_a_bad_drake_setting_up_front(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "heuristic",
                          "--attempts", "1", "--out", "sw", "--set",
                          "plant_config.contact_model=foo"], capfd)
    assert_one_line_error(code, text, "field 'plant_config.contact_model' must be one of")
    assert not (tmp_path / "sw").exists()


@pytest.mark.parametrize("change, words", [
    (lambda s: setattr(s.plant_config, "stiction_tolerance", 0.0),
     "field 'plant_config.stiction_tolerance' must lie in"),
    (lambda s: setattr(s.plant_config, "contact_model", "foo"),
     "field 'plant_config.contact_model' must be one of"),
    (lambda s: setattr(s.simulator_config, "start_time", 100.0),
     "field 'simulator_config.start_time' must lie in"),
    (lambda s: setattr(s, "object_offset", [0.0, 0.0, 0.0]),
     "field 'object_offset' must hold 2 numbers [m], got 3 elements"),
    (lambda s: setattr(s, "expected_object_xy", [0.7]),
     "field 'expected_object_xy' must hold 2 numbers"),
    (lambda s: setattr(s.disturbance, "hit_force_n", [0.0, 1.0]),
     "field 'disturbance.hit_force_n' must hold 3 numbers"),
    (lambda s: setattr(s.arm, "initial_gripper_xyz", [0.7, 0.0]),
     "field 'arm.initial_gripper_xyz' must hold 3 numbers"),
], ids=["stiction 0", "contact model", "start time", "offset of 3", "xy of 1", "hit of 2",
        "start xyz of 2"])
def test_the_builder_refuses_a_config_changed_after_loading(change, words):
    """A Scenario changed in Python is checked by the same validator when a builder gets it:
    a ConfigError, never Drake's abort (SystemExit) or numpy's broadcast error."""
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    scenario = LoadScenario()
    change(scenario)
    with pytest.raises(ConfigError, match=r"^MakeGraspDiagram: scenario: " + _escape(words)):
        MakeGraspDiagram(scenario)


def _escape(words):
    import re
    return re.escape(words)


def test_a_colour_on_a_built_in_object_is_honoured():
    scenario = LoadScenario(overrides=["object.color=[0.1,0.2,0.3,1.0]"])
    assert scenario.object.color == [0.1, 0.2, 0.3, 1.0]
    assert scenario.object.mass == LoadScenario().object.mass  # the rest is the built-in's


def test_a_high_pass_is_checked_against_the_rate_it_runs_at():
    """The film's charge amplifier is integrated at vibration.internal_rate_hz (20 kHz): a
    600 Hz corner is a valid filter there, even with RA sampled at 1 kHz. The accelerometer's
    high-pass runs on its 1 kHz samples: above 500 Hz it is refused."""
    assert LoadScenario(overrides=["vibration.highpass_cutoff_hz=600.0"])
    with pytest.raises(ConfigError, match="field 'vibration.highpass_cutoff_hz' must lie below "
                                          "500 Hz, half the vibration.sample_rate_hz"):
        LoadScenario(overrides=["vibration.highpass_cutoff_hz=600.0",
                                "vibration.transducer=accelerometer"])
