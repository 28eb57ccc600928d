"""The film's settings (simulation/pad_vibration_sensor.py): the film's mechanics in their
own section, and what relates the settings, checked by the class."""

import pytest

from tegrasp_drake.rig.ranges import check_ranges
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.simulation.drive_vibration import DriveVibrationConfig
from tegrasp_drake.simulation.pad_vibration_sensor import FilmConfig, VibrationSensorConfig
from tests.rig.test_api_boundary import assignment_error_in_a_fresh_interpreter


def test_the_films_mechanics_declare_their_units_and_ranges():
    with pytest.raises(ConfigError, match=r"field 'film.mode_mass_kg' must lie in \[0.001, 1\] kg"):
        check_ranges(VibrationSensorConfig(film=FilmConfig(mode_mass_kg=0.0)), "here")


@pytest.mark.parametrize("config, words", [
    (VibrationSensorConfig(transducer="piezo"),
     "field 'transducer' must be one of 'film', 'accelerometer'"),
    (VibrationSensorConfig(adc_input="usb"), "field 'adc_input' must be one of 'msp', 'mxp', "
     "'ideal'"),
    (VibrationSensorConfig(pad_force_source="usb"), "field 'pad_force_source' must be one of "
     "'contact_results', 'joint_forces'"),
])
def test_the_films_choices_are_declared_on_their_fields(config, words):
    with pytest.raises(ConfigError, match=words):
        check_ranges(config, "here")


@pytest.mark.parametrize("config, field, words", [
    (VibrationSensorConfig(film=FilmConfig(mode_frequency_hz=12_000.0)),
     "film.mode_frequency_hz", "must lie in [50, 10000) Hz"),
    (VibrationSensorConfig(transducer="accelerometer", highpass_cutoff_hz=600.0),
     "highpass_cutoff_hz", "below 500 Hz, half the vibration.sample_rate_hz"),
    (VibrationSensorConfig(gripper_drive=DriveVibrationConfig(amplitudes_mps2=[0.1, 0.1],
                                                              orders=[1.0])),
     "gripper_drive.orders", "one order per amplitude (2 amplitudes"),
])
def test_what_relates_the_films_settings_is_checked_by_its_class(config, field, words):
    found = config.problem()
    assert found[0] == field and words in found[1]


def test_the_default_film_fits():
    assert VibrationSensorConfig().problem() is None


def test_a_moved_film_setting_names_its_new_path_with_only_this_module_imported():
    out = assignment_error_in_a_fresh_interpreter(
        "tegrasp_drake.simulation.pad_vibration_sensor", "VibrationSensorConfig",
        "mode_mass_kg = 0.03")
    assert out == "VibrationSensorConfig has no field 'mode_mass_kg': it is now 'film.mode_mass_kg'"
