"""Bad inputs found by the eighth hostile pass, one test per rule."""

import pytest

from tests.test_bad_input import assert_one_line_error, run_cli


# Rule: every YAML the package reads (scenario files, --set values, sweep, sensitivity and
# transfer specs) reads numbers as YAML 1.2's core schema does (rig/core_schema_yaml.py):
# YAML 1.1's base-60, binary and `_` forms are text, refused by a numeric field in one line.
@pytest.mark.parametrize("override, field", [
    ("placement.yaw_deg=1:30", "placement.yaw_deg"),
    ("random_seed=0b101", "random_seed"),
    ("random_seed=1_000", "random_seed"),
])
def test_a_yaml_11_only_number_in_a_set_value_is_refused(override, field, capfd):
    code, text = run_cli(["trial", "--set", override], capfd)
    assert_one_line_error(code, text, f"field '{field}' must be", "YAML 1.2")


def test_a_leading_zero_is_decimal_and_0x_hexadecimal():
    from tegrasp_drake.scenario.scenario import LoadScenario
    assert LoadScenario(name="box", overrides=["random_seed=017"]).random_seed == 17
    assert LoadScenario(name="box", overrides=["random_seed=0x10"]).random_seed == 16


def test_a_scenario_file_reads_base_60_as_text(tmp_path, capfd):
    (tmp_path / "s.yaml").write_text("s:\n  placement: {yaw_deg: 1:30}\n")
    code, text = run_cli(["trial", "--scenario", str(tmp_path / "s.yaml"),
                          "--scenario-name", "s", "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "field 'placement.yaw_deg' must be a finite number")


def test_a_sweep_spec_reads_base_60_as_text(tmp_path, capfd):
    (tmp_path / "spec.yaml").write_text("objects: [box]\nattempts: 1:00\n")
    code, text = run_cli(["sweep", "--spec", str(tmp_path / "spec.yaml"), "--workers", "1",
                          "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "attempts", "1:00")
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())

