"""The sensor-block benchmark's parts run and report (their values are machine dependent)."""

import math

from benchmarks.sensor_blocks import slip_band_tick_us, with_sensor_block
from tegrasp_drake.scenario.scenario import LoadScenario


def test_variants_differ_only_in_the_sensor_block_of_the_memorized_controller():
    scenario = LoadScenario(name="box")
    per_sample = with_sensor_block(scenario, 0.0)
    assert per_sample.controller.name == "memorized"
    assert per_sample.controller.sensor_block_s == 0.0
    assert with_sensor_block(scenario, 0.01).controller.sensor_block_s == 0.01
    assert scenario.controller.sensor_block_s == 0.0  # the caller's scenario is untouched


def test_slip_band_tick_is_measured_both_ways():
    for block in (1, 10):
        value = slip_band_tick_us(block, repeats=1)
        assert math.isfinite(value) and value > 0.0
