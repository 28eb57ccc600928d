"""The sensitivity spec and its points: the one-factor ends, the Latin hypercube's strata,
the points as transfer worlds and cells, and one-line refusals of a bad spec."""

import dataclasses
import json
import textwrap
from pathlib import Path

import numpy as np
import pytest

from tegrasp_drake.rig.files import UserPathError
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.sensitivity.parameters import UNCERTAIN_PARAMETERS, parameter
from tegrasp_drake.sensitivity.study import (DEFAULT_POINT, LoadSensitivitySpec,
                                             SensitivitySpec, latin_hypercube, one_at_a_time,
                                             record_points, transfer_spec)
from tegrasp_drake.sweep.runner import SweepError

ROOT = Path(__file__).resolve().parents[2]
SMALL_SWEEP = """\
    sweep:
      objects: [box]
      controllers: [memorized]
      grid: [[0.0, 0.0], [0.01, 0.0]]
      attempts: 1
      base_seed: 600
    """


def write_spec(folder, text):
    path = Path(folder) / "sensitivity.yaml"
    path.write_text(textwrap.dedent(text))
    return path


def test_the_committed_spec_sweeps_every_parameter_on_the_paper_grid():
    spec = LoadSensitivitySpec(ROOT / "analysis" / "sensitivity.yaml")
    assert spec.parameters == UNCERTAIN_PARAMETERS
    assert spec.sweep.controllers == ("memorized", "open_loop", "heuristic", "taxel_aware")
    assert len(spec.sweep.objects) * len(spec.sweep.grid) * spec.sweep.attempts == 81


def test_one_at_a_time_moves_each_parameter_to_each_end_that_is_not_its_default():
    spec = SensitivitySpec()
    points = one_at_a_time(spec)
    assert points[0].name == DEFAULT_POINT and points[0].assignments() == ()
    moved = {(p.parameter, p.end): dict(p.values)[p.parameter] for p in points[1:]}
    for entry in UNCERTAIN_PARAMETERS:
        for end in ("low", "high"):
            value = getattr(entry, end)
            if value == entry.default:
                assert (entry.key, end) not in moved
            else:
                assert moved[entry.key, end] == value
    assert all(len(p.values) == 1 for p in points[1:])
    decimation = next(p for p in points if p.parameter == "tactile.capacitive.decimation")
    assert "tactile.sample_rate_hz=54.0" in decimation.assignments()


def test_the_latin_hypercube_puts_one_point_in_each_stratum_of_each_continuous_parameter():
    samples = 8
    spec = SensitivitySpec()
    points = latin_hypercube(spec, samples)
    assert points[0].name == DEFAULT_POINT and len(points) == samples + 1
    for k, entry in enumerate(spec.parameters):
        values = np.array([dict(p.values)[entry.key] for p in points[1:]])
        assert np.all((values >= entry.low) & (values <= entry.high))
        if entry.choices or entry.step:
            continue  # snapped onto the setting's own values
        u = (np.log(values / entry.low) / np.log(entry.high / entry.low) if entry.log_scale
             else (values - entry.low) / (entry.high - entry.low))
        strata = np.floor(np.clip(u, 0.0, 1.0 - 1e-9) * samples).astype(int)
        assert sorted(strata) == list(range(samples)), entry.key
    assert latin_hypercube(spec, samples) == points  # seeded by the sweep's base_seed


def test_each_point_is_a_world_memorizing_in_itself_or_at_the_defaults():
    spec = SensitivitySpec(parameters=(parameter("gripper.screw_efficiency"),))
    points = one_at_a_time(spec)
    own = transfer_spec(spec, points)
    assert own.cells == tuple((p.name, p.name) for p in points)
    assert own.worlds["gripper_screw_efficiency_low"].overrides == (
        "gripper.screw_efficiency=0.26",)
    shared = transfer_spec(SensitivitySpec(parameters=spec.parameters,
                                           events="default_point"), points)
    assert shared.cells == tuple((DEFAULT_POINT, p.name) for p in points)


def test_a_folder_of_another_sampling_is_refused(tmp_path):
    spec = SensitivitySpec()
    record_points(spec, latin_hypercube(spec, 2), tmp_path)
    record_points(spec, latin_hypercube(spec, 2), tmp_path)  # the same points: resumed
    other = SensitivitySpec(sweep=spec.sweep.__class__(base_seed=601))
    with pytest.raises(SweepError,
                       match=r"another sensitivity study: .*seed 0, this study.s .*seed 601;"):
        record_points(other, latin_hypercube(other, 2), tmp_path)


def test_the_events_seed_reaches_the_worlds_and_a_folder_of_another_is_refused(tmp_path):
    """A spec's events_seed is its transfer's (the seed its events are recorded at); a folder
    recorded at another is another study, and one whose points.json was written before the
    field was recorded at the default."""
    spec = LoadSensitivitySpec(write_spec(tmp_path, "parameters: [gripper.screw_efficiency]\n"
                                          "events_seed: 650\n"
                                          + textwrap.dedent(SMALL_SWEEP)))
    points = one_at_a_time(spec)
    assert transfer_spec(spec, points).events_seed == 650
    record_points(spec, points, tmp_path / "seeded")
    record_points(spec, points, tmp_path / "seeded")  # the same seed: resumed
    default = dataclasses.replace(spec, events_seed=0)
    with pytest.raises(SweepError, match=r"another sensitivity study: events recorded at "
                                         r"events_seed 650 in the folder, not 0;"):
        record_points(default, points, tmp_path / "seeded")
    older = tmp_path / "older" / "points.json"
    record_points(default, points, older.parent)
    written = json.loads(older.read_text())
    del written["study"]["events_seed"]  # as written before the field
    older.write_text(json.dumps(written))
    record_points(default, points, older.parent)
    with pytest.raises(SweepError, match="events_seed 0 in the folder, not 650"):
        record_points(spec, points, older.parent)


def test_a_points_file_that_is_a_device_is_refused_as_one(tmp_path):
    (tmp_path / "points.json").symlink_to("/dev/null")  # reads empty, as a truncated file would
    with pytest.raises(UserPathError, match=r"points.json: is a device, not a file; give "):
        record_points(SensitivitySpec(), latin_hypercube(SensitivitySpec(), 2), tmp_path)


@pytest.mark.parametrize("text, words", [
    ("parameters: [gripper.pad_length]\n",
     "field 'parameters[0]': 'gripper.pad_length' is not an uncertain parameter"),
    ("parameters: []\n", "field 'parameters' must be a list"),
    ("parameters: [gripper.screw_efficiency, gripper_screw_efficiency]\n",
     "field 'parameters[1]'"),
    ("events: everywhere\n", "field 'events' must be one of each_point, default_point"),
    ("events_seed: -3\n", "field 'events_seed' must lie in [0, 4294967295]"),
    ("events_seed: '650'\n", "field 'events_seed' must be a whole number"),
    ("points: 3\n", "unknown field 'points'"),
    ("sweep: {attempts: 0}\n", "field 'attempts'"),
    ("sweep: {scenario_overrides: [gripper.screw_efficiency=0.9]}\n",
     "gripper.screw_efficiency"),
    ("- a list\n", "must be a mapping"),
    ("sweep: {scenario_overrides: [tactile.sample_rate_hz=108.0]}\n",
     "field 'sweep.scenario_overrides[0]': 'tactile.sample_rate_hz' is set by the study"),
])
def test_a_bad_spec_is_refused_in_one_line_naming_file_and_field(tmp_path, text, words):
    path = write_spec(tmp_path, text)
    with pytest.raises(ConfigError) as error:
        LoadSensitivitySpec(path)
    message = str(error.value)
    assert words in message and str(path) in message and "\n" not in message


def test_a_latin_hypercube_of_no_points_is_refused():
    with pytest.raises(ConfigError, match="--latin-hypercube must be a whole number"):
        latin_hypercube(SensitivitySpec(), 0)
