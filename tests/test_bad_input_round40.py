"""Bad inputs the fortieth review found: a text setting's choices are declared on its field
and checked wherever a config is handed to a public builder, not only where it is loaded."""

import dataclasses

import pytest

from tegrasp_drake import ConfigError, LoadScenario, MakeGraspStation
from tegrasp_drake.scenario.scenario import object_pose


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
