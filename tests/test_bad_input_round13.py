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
