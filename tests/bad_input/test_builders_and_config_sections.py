"""Configs handed to a builder are checked as loaded ones are: Drake's own config sections,
nested configs of the wrong type, a text field outside its declared choices, a controller
section as written, and a config or object a script changed after loading; a bad setting
stops a trial, sweep or transfer world before anything runs."""

import dataclasses

import pytest

import tegrasp_drake as T
from tegrasp_drake import MakeGraspStation
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, object_pose
from tests.bad_input.probes import assert_one_line_error, refusal, run_cli

DRAKE_SECTION_PROBES = [  # (--set assignment, words the one error line holds)
    ("plant_config.contact_model=foo", "field 'plant_config.contact_model' must be one of"),
    ("simulator_config.integration_scheme=bogus",
     "field 'simulator_config.integration_scheme' must be one of"),
    ("plant_config.contact_surface_representation=sphere",
     "field 'plant_config.contact_surface_representation' must be one of 'triangle'"),
    ("plant_config.discrete_contact_approximation=exact",
     "field 'plant_config.discrete_contact_approximation' must be one of"),
    # Drake's names this station cannot run: refused at load, not a trial that reads no
    # taxel (point contact makes no pressure field) or stops in Drake (strict hydroelastic,
    # TAMSI, which has no ball constraint for the 2F-85's five-bar)
    ("plant_config.contact_model=point", "must be one of 'hydroelastic_with_fallback' (the "
                                         "taxels read the pads' hydroelastic pressure field"),
    ("plant_config.contact_model=hydroelastic",
     "must be one of 'hydroelastic_with_fallback'"),
    ("plant_config.discrete_contact_approximation=tamsi",
     "must be one of 'sap', 'similar', 'lagged' (the SAP solver's"),
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
    # in the package's words, not Drake's ("Expected a <class 'str'> value ...", "The fields
    # [...] were unknown to the schema")
    ("plant_config.contact_model=[1]", "field 'plant_config.contact_model' must be a string, "
                                       "got list [1]"),
    ("simulator_config.integration_scheme={a: 1}",
     "field 'simulator_config.integration_scheme' must be a string, got dict"),
    ("plant_config.time_stepp=0.001", "field 'plant_config.time_stepp': unknown field "
                                      "'plant_config.time_stepp' (known: "),
    ("plant_config=[1]", "field 'plant_config' must be a mapping of MultibodyPlantConfig "
                         "fields (time_step, "),
]

RELATED_FIELD_PROBES = [
    # a lift of 0 ran to the time limit in Lift (its share of the lift divides by it)
    ("grasp.lift_height=0", "field 'grasp.lift_height' must lie in [0.02, 0.3] m (a trial "
                             "counts the object held 2 cm above its rest)"),
    ("controller.lift_load.slip_band_hz=900.0", "field 'controller.lift_load.slip_band_hz' must lie below half"),
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


# Rule: a Drake config section (plant_config, simulator_config) that a scenario file gives as
# no mapping (a list, a text, a number, null) is refused in one line naming the file, the
# scenario and the field, and listing the section's fields, not in Drake's words ("YAML root
# was a <class 'list'> but should have been a dict").
@pytest.mark.parametrize("section, schema", [("plant_config", "MultibodyPlantConfig"),
                                             ("simulator_config", "SimulatorConfig")])
@pytest.mark.parametrize("value, described", [("[1, 2]", "list [1, 2]"), ("fast", "str 'fast'"),
                                              ("3", "int 3"), ("null", "None")])
def test_a_drake_section_that_is_no_mapping_is_refused_in_the_packages_words(
        tmp_path, section, schema, value, described):
    path = tmp_path / "s.yaml"
    path.write_text(f"s:\n  object: {{name: box}}\n  {section}: {value}\n")
    with pytest.raises(ConfigError) as refused:
        LoadScenario(path, "s")
    message = str(refused.value)
    assert "\n" not in message and "YAML root" not in message, message
    assert message.startswith(f"{path} [s]: field '{section}' must be a mapping of {schema} "
                              "fields ("), message
    assert message.endswith(f"got {described}"), message


def test_a_sweep_refuses_a_bad_drake_setting_up_front(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "heuristic",
                          "--attempts", "1", "--out", "sw", "--set",
                          "plant_config.contact_model=foo"], capfd)
    assert_one_line_error(code, text, "field 'plant_config.contact_model' must be one of")
    assert not (tmp_path / "sw").exists()


def test_a_transfer_world_with_a_bad_drake_setting_is_refused_up_front(tmp_path, monkeypatch,
                                                                        capfd):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "spec.yaml").write_text(
        "worlds:\n"
        "  ideal: {scenario: memorizing_world}\n"
        "  xovsim: {scenario: memorizing_world, overrides: [plant_config.contact_model=foo]}\n"
        "cells: {memorize_in: [ideal], run_in: [ideal, xovsim]}\n"
        "sweep: {controllers: [memorized], attempts: 1, base_seed: 600}\n")
    code, text = run_cli(["transfer", "spec.yaml", "--out", "tr"], capfd)
    assert_one_line_error(code, text, "worlds.xovsim",
                          "field 'plant_config.contact_model' must be one of")
    assert not (tmp_path / "tr").exists()


@pytest.mark.parametrize("change, words", [
    (lambda s: setattr(s.plant_config, "stiction_tolerance", 0.0),
     "field 'plant_config.stiction_tolerance' must lie in"),
    (lambda s: setattr(s.plant_config, "contact_model", "foo"),
     "field 'plant_config.contact_model' must be one of"),
    (lambda s: setattr(s.simulator_config, "start_time", 100.0),
     "field 'simulator_config.start_time' must lie in"),
    (lambda s: setattr(s.placement, "offset", [0.0, 0.0, 0.0]),
     "field 'placement.offset' must hold 2 numbers [m], got 3 elements"),
    (lambda s: setattr(s.placement, "expected_xy", [0.7]),
     "field 'placement.expected_xy' must hold 2 numbers"),
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


def test_builders_recheck_an_object_a_script_made_deeper_than_the_hand_takes():
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
    from tegrasp_drake.scenario.scenario import LoadScenario
    scenario = LoadScenario(name="box")
    scenario.object.size = [0.3, 0.045, 0.11]
    with pytest.raises(ConfigError, match="MakeGraspDiagram: scenario: field 'object.size' "
                                          "makes the object 300.0 mm deep along the approach, "
                                          "more than the 85.0 mm"):
        MakeGraspDiagram(scenario)


def test_a_recheck_keeps_a_built_in_object_with_sizes_the_user_set_and_resolves_a_bare_one():
    from tegrasp_drake.scenario.scenario import LoadScenario, Scenario, rechecked
    loaded = LoadScenario(name="box", overrides=["object.size=[0.05,0.05,0.1]"])
    assert rechecked(loaded, "test").object.size == [0.05, 0.05, 0.1]
    assert rechecked(Scenario(), "test").object.size == LoadScenario(name="box").object.size


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
    refusal(lambda: getattr(T, builder)(scenario), builder, f"'{field}'", "must be")


def test_a_config_built_in_python_is_checked_for_nested_types_and_ranges():
    refusal(lambda: T.Scenario(object={"name": "box"}), "Scenario", "'object'", "ObjectConfig")
    refusal(lambda: T.MemorizedControllerConfig(re_reach={"opened_m": 0.2}), "'re_reach'",
             "ReReachConfig")
    refusal(lambda: T.HardwareStationConfig(gripper={"port": "/dev/null"}), "'gripper'")
    refusal(lambda: T.SweepSpec(randomisation={"placement_xy_bound_m": 0.002},
                                 objects=("box",), controllers=("open_loop",),
                                 grid=((0.0, 0.0),), attempts=1), "'randomisation'")
    controller = T.MemorizedControllerConfig()
    controller.re_reach = {"opened_m": 0.2}  # set after building
    refusal(lambda: T.MakeGraspDiagram(_scenario_with("controller", controller)),
             "MakeGraspDiagram", "controller.re_reach")
    scenario = T.LoadScenario(name="box")
    scenario.controller = dataclasses.replace(scenario.controller)
    scenario.controller.re_reach.opened_m = 0.2  # the right type, out of its range
    refusal(lambda: T.MakeGraspDiagram(scenario), "re_reach.opened_m")


# Rule: a choice of controller (`--controller`, LoadScenario(controller=...)) replaces the
# scenario's controller tag and drops the other controllers' settings only after the section
# as written is checked: its form (a mapping, a known tag) and each setting against the
# controller that has it, type and range, as a load without the choice checks them.
@pytest.mark.parametrize("text, overrides, words", [
    ("default: {object: {name: box}, controller: memorized}\n", [],
     "field 'controller' must be a mapping of fields, got str 'memorized'"),
    ("default: {object: {name: box}, controller: !Bogus {}}\n", [],
     "field 'controller': unknown tag !Bogus"),
    ("default: {}\n", ["controller.matching.sa_threshold=abc"],
     "field 'controller.matching.sa_threshold' must be a finite number"),
    ("default: {}\n", ["controller.re_reach.max_re_reaches=-1"],
     "field 'controller.re_reach.max_re_reaches' must be zero or positive"),
    ("default: {}\n", ["controller.update_period_s=0.0"],
     "field 'controller.update_period_s' must be positive"),
])
def test_a_choice_of_controller_checks_the_controller_section_as_written(
        tmp_path, text, overrides, words):
    path = tmp_path / "s.yaml"
    path.write_text(text)
    for controller in ("open_loop", "heuristic"):
        refusal(lambda: LoadScenario(path, overrides=overrides, controller=controller),
                 str(path), words)
    ignored = []
    LoadScenario(overrides=["controller.matching.sa_threshold=0.5"], controller="heuristic",
                 on_ignored=ignored.extend)  # a good setting of another controller: dropped
    assert ignored == ["matching.sa_threshold"]


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


def _sections(scenario):
    return dict(plant_config=scenario.plant_config, arm=scenario.arm, gripper=scenario.gripper,
                object=scenario.object, X_WO=object_pose(scenario), tactile=scenario.tactile,
                vibration=scenario.vibration, disturbance=scenario.disturbance,
                random_seed=scenario.random_seed, grasp_height=scenario.grasp.grasp_height,
                contact_geometry=scenario.contact_geometry)


# Rule: MakeGraspStation refuses a config section holding a text value that is not one of the
# field's choices, as LoadScenario does, naming the argument's field and the allowed values
# (accepted before, or a bare KeyError).
@pytest.mark.parametrize("section, field, value, allowed", [
    ("tactile", "transducer", "rr", "'force', 'capacitive'"),
    ("vibration", "transducer", "rr", "'film', 'accelerometer'"),
    ("vibration", "pad_force_source", "rr", "'contact_results', 'joint_forces'"),
    ("vibration", "adc_input", "rr", "'msp', 'mxp', 'ideal'"),
    ("contact_geometry", "table", "rr", "'box', 'half_space'"),
    ("contact_geometry", "box_triangles", 18, "24, 12"),
    ("gripper", "model", "rr", "'linkage', 'prismatic'"),
])
def test_make_grasp_station_refuses_a_value_outside_a_fields_choices(section, field, value,
                                                                     allowed):
    arguments = _sections(LoadScenario())
    arguments[section] = dataclasses.replace(arguments[section], **{field: value})
    with pytest.raises(ConfigError, match=f"MakeGraspStation: argument '{section}': field "
                                          f"'{field}' must be one of {allowed}"):
        MakeGraspStation(**arguments)


# Rule: the capacitive taxels' output and decimation are refused by the builder as by the loader.
@pytest.mark.parametrize("field, value, allowed", [
    ("output", "volts", "'calibrated', 'counts'"),
    ("decimation", 100, "64, 128, 256"),
])
def test_make_grasp_station_refuses_a_capacitive_setting_outside_its_choices(field, value,
                                                                            allowed):
    arguments = _sections(LoadScenario())
    tactile = arguments["tactile"]
    arguments["tactile"] = dataclasses.replace(
        tactile, capacitive=dataclasses.replace(tactile.capacitive, **{field: value}))
    with pytest.raises(ConfigError, match=f"field 'capacitive.{field}' must be one of "
                                          f"{allowed}"):
        MakeGraspStation(**arguments)


@pytest.mark.parametrize("controller", ["open_loop", "heuristic"])
def test_events_given_to_a_controller_that_reads_none_are_refused(controller):
    """Memorized events handed to a controller that never reads them would be dropped without a
    word: the diagram built would not be the run the caller meant."""
    events = T.load_controller_events(LoadScenario())
    scenario = LoadScenario(controller=controller)
    with pytest.raises(ValueError, match=rf"^AddGraspController: events: the {controller} "
                                         "controller reads no memorized events; leave events"):
        T.MakeGraspDiagram(scenario, events=events, log=False)
    with pytest.raises(ValueError, match=r"^AddGraspController: corrective_events: the "
                                         "controller's memorized_corrective.events names none"):
        T.MakeGraspDiagram(scenario, corrective_events=events, log=False)


def _add_box_controller(**given):
    """AddGraspController on the box's station, with the box scenario's arguments but `given`."""
    from pydrake.systems.framework import DiagramBuilder
    scenario = LoadScenario(name="box")
    builder = DiagramBuilder()
    station = builder.AddNamedSystem("station", T.MakeStation(scenario))
    arguments = dict(controller=scenario.controller, plan=T.grasp_plan(scenario),
                     station=station, arm=scenario.arm,
                     sample_rates_hz=T.sample_rates_hz(scenario),
                     events=T.load_controller_events(scenario))
    arguments.update(given)
    return T.AddGraspController(builder, **arguments)


def test_a_grasp_controller_refuses_another_objects_events():
    """The box's plan matched against the thin cylinder's templates is not the box's grasp
    (load_controller_events refuses such events by the object's name too)."""
    _add_box_controller()  # the box's own events are taken
    cylinder = T.load_controller_events(LoadScenario(name="thin_cylinder"))
    with pytest.raises(ValueError, match=r"^AddGraspController: events\['reach_load'\] was "
                                         "felt on 'thin_cylinder', but the plan grasps 'box'"):
        _add_box_controller(events=cylinder)


def test_a_grasp_controller_refuses_rates_its_station_does_not_deliver():
    """Windows read at 1 kHz from a 108 Hz SA output would span a tenth of the events' time."""
    with pytest.raises(ValueError, match=r"^AddGraspController: sample_rates_hz \(1000, 1000\) "
                                         r"Hz: the station samples SA at 108 Hz and RA at "
                                         "1000 Hz"):
        _add_box_controller(sample_rates_hz=(1000.0, 1000.0))
