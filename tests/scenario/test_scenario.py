import pytest
from pydrake.common.yaml import yaml_load

from tegrasp_drake.rig import paths
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.rig.typed_yaml import ConfigError

SCENARIO_NAMES = sorted(yaml_load(filename=str(paths.scenarios_file())))


@pytest.mark.parametrize("name", SCENARIO_NAMES)
def test_every_named_scenario_loads(name):
    scenario = LoadScenario(name=name)
    assert scenario.object.shape in ("box", "cylinder", "file")


def test_override_changes_a_nested_field():
    scenario = LoadScenario(overrides=["object.name=thin_cylinder", "random_seed=7"])
    assert scenario.object.name == "thin_cylinder" and scenario.random_seed == 7


@pytest.mark.parametrize("overrides, message", [
    (["object.colour=[1,0,0,1]"], "unknown field 'object.colour'"),
    (["object.mass=heavy"], "field 'object.mass' must be a finite number"),
    (["grasp.hold_s=[3]"], "field 'grasp.hold_s' must be a finite number"),
    (["object.name=bowl"], "field 'object.name': 'bowl' is not a built-in object"),
    (["object.name=crate", "object.shape=box", "object.size=[0.09, 0.09, 0.1]",
      "object.mass=0.1", "object.friction=0.5"],
     "field 'object.size' makes the object 90.0 mm wide"),
    (["controller.name=magic"], "field 'controller.name': 'magic' is not one of"),
    (["controller.name=heuristic", "controller.matching.sa_threshold=0.5"],
     "field 'controller.matching.sa_threshold' is a setting of the memorized and taxel_aware"),
    (["disturbance.hit_force_n=[1, 2]"], "field 'disturbance.hit_force_n' must hold 3 numbers"),
    (["object.mass=-1"], "field 'object.mass' must be positive"),
    (["object.name=model", "object.shape=file", "object.file=/no/such/model.sdf", "object.size=[0.04,0.04,0.1]",
      "object.mass=0.1", "object.friction=0.5"], "model file '/no/such/model.sdf' does not exist"),
    (["plant_config.time_step=fast"], "field 'plant_config.time_step' must be a finite number"),
    (["tactile.transducer=piezo"], "field 'tactile.transducer' must be one of 'force', "
     "'capacitive'"),
    (["vibration.transducer=microphone"], "field 'vibration.transducer' must be one of 'film', "
     "'accelerometer'"),
    (["tactile.capacitive.minimum_gap_fraction=1.5"],
     "field 'tactile.capacitive.minimum_gap_fraction' must lie in"),
    (["tactile.capacitive.output=volts"], "field 'tactile.capacitive.output' must be one of "
     "'calibrated', 'counts'"),
    (["tactile.capacitive.decimation=100"], "field 'tactile.capacitive.decimation' must be "
     "one of 64, 128, 256"),
    (["tactile.transducer=capacitive", "tactile.capacitive.decimation=128"],
     "field 'tactile.sample_rate_hz' must be the AD7147's frame rate at "
     "tactile.capacitive.decimation 128, 54.3 Hz"),
    (["vibration.adc_input=usb"], "field 'vibration.adc_input' must be one of 'msp', 'mxp', "
     "'ideal'"),
    (["vibration.adc_noise_lsb=-1"], "field 'vibration.adc_noise_lsb' must be zero"),
    (["vibration.amplifier_swing_v=0"], "field 'vibration.amplifier_swing_v' must lie in "
     "[0.1, 15] V"),
    (["vibration.gripper_drive.orders=[1]"], "field 'vibration.gripper_drive.orders' must "
     "give one order per amplitude"),
    (["controller.lift_load.slip_vibration_sigmas=-2"], "field 'controller.lift_load.slip_vibration_sigmas' must "
     "be zero"),
])
def test_bad_input_names_the_field(overrides, message):
    with pytest.raises(ConfigError, match=message.replace("[", r"\[").replace("(", r"\(")):
        LoadScenario(overrides=overrides)


def test_fields_set_on_a_builtin_object_override_it():
    scenario = LoadScenario(overrides=["object.name=box", "object.mass=0.3"])
    assert scenario.object.mass == 0.3 and scenario.object.size == [0.045, 0.045, 0.110]


def test_missing_file_and_scenario_are_named(tmp_path):
    with pytest.raises(ConfigError, match="does not exist"):
        LoadScenario(tmp_path / "none.yaml")
    (tmp_path / "s.yaml").write_text("mine: {}\n")
    with pytest.raises(ConfigError, match="no scenario named 'default'.*mine"):
        LoadScenario(tmp_path / "s.yaml")


@pytest.mark.parametrize("decimation, rate_hz", [(64, 108.0), (128, 54.0), (256, 27.0)])
def test_capacitive_taxels_at_each_decimation_load_at_its_frame_rate(decimation, rate_hz):
    scenario = LoadScenario(overrides=[
        "tactile.transducer=capacitive", f"tactile.capacitive.decimation={decimation}",
        f"tactile.sample_rate_hz={rate_hz}"])
    assert scenario.tactile.capacitive.decimation == decimation


def test_capacitive_taxels_at_a_rate_the_ad7147_cannot_give_need_the_idealised_readout():
    at_1khz = ["tactile.transducer=capacitive", "tactile.sample_rate_hz=1000.0"]
    with pytest.raises(ConfigError, match="tactile.sample_rate_hz.*ad7147_timing=false"):
        LoadScenario(overrides=at_1khz)
    idealised = LoadScenario(overrides=at_1khz + ["tactile.capacitive.ad7147_timing=false"])
    assert idealised.tactile.sample_rate_hz == 1000.0


@pytest.mark.parametrize("controller", [None, "memorized", "EventMatcherConfig"])
def test_a_scenario_holding_no_controller_config_is_refused_naming_the_field(controller):
    from tegrasp_drake.events.event_matcher import EventMatcherConfig
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    scenario = LoadScenario(name="box")
    scenario.controller = EventMatcherConfig() if controller == "EventMatcherConfig" else controller
    with pytest.raises(ConfigError, match=r"field 'controller'"):
        MakeGraspDiagram(scenario)
