"""The hold-creep benchmark's parts (benchmarks/hold_creep.py): its cells, its criterion and
a bad cell refused in one line."""

import argparse

import pytest

from benchmarks.hold_creep import DEFAULT_CELLS, main, parse_cell, quiet_grip_rate
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           ra_noise_std_mps2)


def test_the_default_cells_are_the_grid_the_first_the_scenarios_own():
    cells = [parse_cell(c) for c in DEFAULT_CELLS]
    assert len(cells) == 18 and len(set(cells)) == 18
    assert cells[0] == (1e-3, "polygon", 0)


def test_the_criterion_is_the_ramp_the_film_reads_at_its_noise():
    # (dF/dt) / (2 pi f_c m) = noise: the film's high-pass turns a ramp into a level.
    vibration = VibrationSensorConfig()
    level = quiet_grip_rate() / (2 * 3.141592653589793 * vibration.highpass_cutoff_hz
                                 * vibration.film.mode_mass_kg)
    assert level == pytest.approx(ra_noise_std_mps2(vibration))


@pytest.mark.parametrize("text", ["1e-3:polygon", "1e-3:quad:0", "fast:polygon:0"])
def test_a_bad_cell_is_refused_naming_it(text):
    with pytest.raises(argparse.ArgumentTypeError) as error:
        parse_cell(text)
    assert text in str(error.value) and "\n" not in str(error.value)


def test_a_rod_facet_out_of_range_is_a_usage_error(capsys):
    with pytest.raises(SystemExit):
        main(["--rod-facet", "0.5"])
    assert "--rod-facet 0.5" in capsys.readouterr().err
