"""Every list of a sweep, transfer or sensitivity spec is counted against its stated maximum before
anything is built from it (the cheap checks first), and every count field has a declared
range: a grid of millions of markers, a cell matrix of thousands of worlds or an attempt
count no sweep can make is refused in one line giving the count and the maximum, at once."""

import time

import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.sensitivity import study as sensitivity_study
from tegrasp_drake.sensitivity.parameters import UNCERTAIN_PARAMETERS
from tegrasp_drake.sweep import spec as sweep_spec
from tegrasp_drake.sweep.spec import (MAX_CONFIRMED_TRIALS, MAX_GRID_MARKERS, MAX_SWEEP_OBJECTS,
                                      SweepSpec, validate_spec)
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.transfer.matrix import MAX_CELLS, MAX_WORLDS, LoadTransferSpec


def _offsets(count):
    return [round(-0.2 + 0.4 * k / (count - 1), 7) for k in range(count)]


@pytest.fixture
def nothing_built(monkeypatch):
    """Fails a test in which a product grid is built."""
    def built(*args):
        raise AssertionError("the product grid was built")
    monkeypatch.setattr("tegrasp_drake.sweep.spec_file.product_grid", built)


def test_a_product_grid_past_the_maximum_is_refused_before_it_is_built(tmp_path,
                                                                       nothing_built):
    spec = tmp_path / "s.yaml"
    spec.write_text(f"objects: [box]\ngrid: {{normal_offsets_m: {_offsets(2000)}, "
                    f"stroke_offsets_m: {_offsets(2000)}}}\n")
    start = time.perf_counter()
    with pytest.raises(ConfigError) as refused:
        LoadSweepSpec(spec)
    assert time.perf_counter() - start < 5.0  # 33 s and 0.5 GB when the grid was built first
    assert str(refused.value) == (
        f"{spec}: field 'grid' holds 4000000 markers (2000 normal_offsets_m x 2000 "
        f"stroke_offsets_m); a sweep takes at most {MAX_GRID_MARKERS} markers: give fewer, "
        "or split the sweep into several")


def test_a_sensitivity_spec_naming_more_parameters_than_there_are_is_refused_before_any_is_read(
        tmp_path, monkeypatch):
    monkeypatch.setattr(sensitivity_study, "parameter",
                        lambda key: pytest.fail(f"parameter {key!r} was looked up"))
    most = len(UNCERTAIN_PARAMETERS)
    spec = tmp_path / "s.yaml"
    spec.write_text(f"parameters: {[entry.key for entry in UNCERTAIN_PARAMETERS] * 1000}\n"
                    .replace("'", ""))
    with pytest.raises(ConfigError) as refused:
        sensitivity_study.LoadSensitivitySpec(spec)
    assert str(refused.value) == (
        f"{spec}: field 'parameters' holds {most * 1000} parameters; a sensitivity spec takes "
        f"at most {most} parameters: give fewer, or split the sensitivity spec into several")


@pytest.mark.parametrize("text, field, count, items, most", [
    ("grid: " + str([[0.0, 0.0]] * (MAX_GRID_MARKERS + 1)) + "\n", "grid",
     MAX_GRID_MARKERS + 1, "markers", MAX_GRID_MARKERS),
    ("objects: " + str(["box"] * (MAX_SWEEP_OBJECTS + 1)).replace("'", "") + "\n", "objects",
     MAX_SWEEP_OBJECTS + 1, "objects", MAX_SWEEP_OBJECTS),
    ("controllers: " + str(["memorized"] * 99).replace("'", "") + "\n", "controllers", 99,
     "controllers", len(sweep_spec.CONTROLLER_NAMES)),
], ids=["grid-list", "objects", "controllers"])
def test_a_spec_list_past_its_maximum_is_refused_giving_count_and_maximum(
        tmp_path, text, field, count, items, most):
    spec = tmp_path / "s.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=f"field '{field}' holds {count} {items}; a sweep "
                                          f"takes at most {most} {items}"):
        LoadSweepSpec(spec)


def test_a_python_spec_past_a_maximum_is_refused_by_validate_spec():
    spec = SweepSpec(grid=tuple((0.0, k * 1e-6) for k in range(MAX_GRID_MARKERS + 1)))
    with pytest.raises(ConfigError, match=f"field 'grid' holds {MAX_GRID_MARKERS + 1} markers"):
        validate_spec(spec)


# Rule: a grid offset is judged by its declared range before it is used as a marker's
# identity (in micrometres): 1e308 m was an OverflowError traceback.
@pytest.mark.parametrize("grid", ["[[1e308, 0]]", "[[0, -1.0e+300]]",
                                  "{normal_offsets_m: [1e308], stroke_offsets_m: [0]}"])
def test_a_grid_offset_beyond_any_range_is_refused_in_its_range_words(tmp_path, grid):
    spec = tmp_path / "s.yaml"
    spec.write_text(f"objects: [box]\ngrid: {grid}\n")
    with pytest.raises(ConfigError, match=r"field 'grid\[0\]\[[01]\]' must lie in \[-0.2, 0.2\] m"):
        LoadSweepSpec(spec)


@pytest.mark.parametrize("attempts", ["100000000000000000000", str(MAX_CONFIRMED_TRIALS + 1)])
def test_an_attempt_count_no_sweep_can_make_is_refused_at_load(tmp_path, attempts):
    spec = tmp_path / "s.yaml"
    spec.write_text(f"objects: [box]\nattempts: {attempts}\n")
    with pytest.raises(ConfigError, match=f"field 'attempts' must lie in \\[1, "
                                          f"{MAX_CONFIRMED_TRIALS}\\]"):
        LoadSweepSpec(spec)


def _worlds(count):
    return ", ".join(f"w{k}: {{scenario: default}}" for k in range(count))


def test_a_transfer_cell_product_past_the_maximum_is_refused_before_it_is_listed(tmp_path):
    names = [f"w{k}" for k in range(300)]
    spec = tmp_path / "t.yaml"
    spec.write_text(f"worlds: {{{_worlds(300)}}}\ncells: {{memorize_in: {names}, run_in: "
                    f"{names}}}\n".replace("'", ""))
    start = time.perf_counter()
    with pytest.raises(ConfigError, match=f"field 'cells' holds 90000 cells \\(300 memorize_in "
                                          f"x 300 run_in\\); a transfer spec takes at most "
                                          f"{MAX_CELLS} cells"):
        LoadTransferSpec(spec)
    assert time.perf_counter() - start < 5.0  # 113 s when the cells were listed first


def test_transfer_worlds_past_the_maximum_are_refused(tmp_path):
    spec = tmp_path / "t.yaml"
    spec.write_text(f"worlds: {{{_worlds(MAX_WORLDS + 1)}}}\ncells: [[w0, w0]]\n")
    with pytest.raises(ConfigError, match=f"field 'worlds' holds {MAX_WORLDS + 1} worlds; a "
                                          f"transfer spec takes at most {MAX_WORLDS} worlds"):
        LoadTransferSpec(spec)
