"""Bad inputs the fifteenth hostile pass found in sweep records: a record whose checksum was
recomputed after a hand edit is refused by what it holds, one test per rule."""

import pytest

from tegrasp_drake.sweep.records import load_records, record_path
from tegrasp_drake.sweep.runner import run_sweep
from tegrasp_drake.sweep.spec import RandomisationConfig, SweepSpec
from tests.fake_trials import fake_trial
from tests.test_bad_input_round27 import forge_record

# Two markers, so that one trial is well placed and one is not.
SPEC = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1,
                 grid=((0.0, 0.0), (0.01, 0.0)), base_seed=620)
WELL_PLACED, MISPLACED = "memorized/box/m00/a0", "memorized/box/m10/a0"


def _forge(folder, trial_id, edit):
    """SPEC's record of `trial_id`, hand-edited with `edit` (forge_record)."""
    return forge_record(folder, SPEC, trial_id, edit)


def _trial(**fields):
    return lambda record: record["trial"].update(fields)


def _perturbation(**fields):
    return lambda record: record["trial"]["perturbation"].update(fields)


def _seeds(seed):
    def edit(record):
        record["trial"]["seed"] = seed
        record["result"]["seed"] = seed
    return edit


def _assert_corrupt_and_run_again(folder, path, words):
    loaded = load_records(folder)
    assert path not in {record_path(folder, t) for t in loaded.records}
    assert words in loaded.corrupt[path] and "'trial'" in loaded.corrupt[path], loaded.corrupt
    summary = run_sweep(SPEC, fake_trial, folder, workers=1, progress=False)
    assert (summary.ran, summary.corrupt) == (1, (str(path),))
    assert list(path.parent.glob(f"{path.name}.corrupt-*"))  # kept aside, not lost
    assert load_records(folder).corrupt == {}


# Rule: a record's trial is one the sweep makes: each field within the range declared beside
# it (the perturbation within what the randomisation bounds can draw, attempts from 0), its
# ids made of its object, marker and attempt, well placed exactly at the (0, 0) marker, and
# its seed the one its base seed and scene give; any other is corrupt and its trial runs again.
@pytest.mark.parametrize("trial_id, edit, words", [
    (MISPLACED, _perturbation(mass_scale=-1.0), "perturbation.mass_scale"),
    (MISPLACED, _perturbation(mass_scale=5.0), "perturbation.mass_scale"),
    (MISPLACED, _perturbation(friction_scale=0.0), "perturbation.friction_scale"),
    (MISPLACED, _perturbation(dx_m=0.3), "perturbation.dx_m"),
    (MISPLACED, _trial(attempt=-3), "attempt"),
    (MISPLACED, _trial(pair_id="../../x"), "pair_id"),
    (MISPLACED, _trial(marker="../m10"), "marker"),
    (MISPLACED, _trial(well_placed=True), "well_placed"),
    (WELL_PLACED, _trial(marker_dx_m=0.01), "well_placed"),
    (MISPLACED, _seeds(7), "seed"),
    (MISPLACED, _trial(base_seed=9999), "seed"),
    (MISPLACED, _trial(perturbation={"dx_m": 0.0}), "perturbation"),
], ids=["negative-mass", "mass-x5", "no-friction", "jitter-30cm", "attempt", "pair-id",
        "marker", "well-placed", "marker-moved", "seed", "base-seed", "perturbation-fields"])
def test_a_record_whose_trial_no_sweep_makes_is_corrupt_and_runs_again(
        tmp_path, trial_id, edit, words):
    path = _forge(tmp_path, trial_id, edit)
    _assert_corrupt_and_run_again(tmp_path, path, words)


def _rebased(base_seed):
    """A forger's edit: another base seed, the seed it gives the scene recomputed, the
    perturbation (what the trial ran with) kept."""
    def edit(record):
        from tegrasp_drake.sweep.spec import scene_seeds
        trial = record["trial"]
        _, seed = scene_seeds(base_seed, trial["object_name"],
                              (trial["marker_dx_m"], trial["marker_dy_m"]), trial["attempt"])
        trial.update(base_seed=base_seed, seed=seed)
        record["result"]["seed"] = seed
    return edit


def _nudged(field, by):
    return lambda record: record["trial"]["perturbation"].update(
        {field: record["trial"]["perturbation"][field] + by})


def _flipped(field):
    return lambda record: record["trial"]["perturbation"].update(
        {field: -record["trial"]["perturbation"][field]})


# Rule: a record's perturbation is its seed's draw (the seed's uniforms under one set of
# randomisation bounds): a base seed changed and its seed recomputed, or a draw edited, is
# corrupt and its trial runs again.
@pytest.mark.parametrize("edit, words", [
    (_rebased(621), "perturbation."),
    (_nudged("dy_m", 1e-6), "perturbation.d"),  # dx and dy share a bound: one is named
    (_flipped("yaw_rad"), "perturbation.yaw_rad"),
], ids=["base-seed-recomputed", "jitter-nudged", "yaw-flipped"])
def test_a_record_whose_perturbation_is_not_its_seeds_draw_is_corrupt_and_runs_again(
        tmp_path, edit, words):
    path = _forge(tmp_path, MISPLACED, edit)
    _assert_corrupt_and_run_again(tmp_path, path, words)


def test_a_plot_of_a_record_whose_perturbation_is_not_its_seeds_draw_is_refused_in_one_line(
        tmp_path, monkeypatch, capfd):
    from tests.test_bad_input import assert_one_line_error, run_cli
    _forge(tmp_path / "sweep", MISPLACED, _rebased(621))
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["plot", "latency", "sweep", "--out", "latency.png"], capfd)
    assert_one_line_error(code, text, "memorized.box.m10.a0.json", "perturbation.")
    assert not (tmp_path / "latency.png").exists()


@pytest.mark.parametrize("randomisation", [
    RandomisationConfig(), RandomisationConfig(0.0, 0.0, 0.0, 0.0),
    RandomisationConfig(0.05, 180.0, 0.999999, 1e-12)], ids=["default", "none", "extremes"])
def test_the_draws_of_any_randomisation_bounds_are_read(randomisation):
    from tegrasp_drake.sweep.spec import expand_trials, trial_problem
    spec = SweepSpec(base_seed=620, attempts=2, randomisation=randomisation)
    assert [t.trial_id for t in expand_trials(spec) if trial_problem(t.to_dict())] == []


def test_the_trials_a_sweep_makes_are_read():
    from tegrasp_drake.sweep.spec import expand_trials, trial_problem
    spec = SweepSpec(base_seed=620, attempts=2)  # the paper's objects, grid and controllers
    assert [t.trial_id for t in expand_trials(spec) if trial_problem(t.to_dict())] == []


def _result(**fields):
    return lambda record: record["result"].update(fields)


def _events(**identity):
    return lambda record: record.update(events=identity)


# Rule: a record's result is where its trial put the object (the marker moved by the jitter),
# and its events identity is a SHA-256 and a folder (or null), as a sweep writes it.
@pytest.mark.parametrize("edit, words", [
    (_result(offset_m=[0.19, -0.19]), "offset_m"),
    (_result(offset_m=[0.01, 0.0]), "offset_m"),  # the marker, without its jitter
    (_events(folder="/etc", sha256="zz"), "events.sha256"),
    (_events(folder="", sha256="0" * 64), "events.folder"),
], ids=["offset-far", "offset-without-jitter", "events-digest", "events-folder-empty"])
def test_a_record_whose_result_is_not_its_trials_is_corrupt_and_runs_again(
        tmp_path, edit, words):
    path = _forge(tmp_path, MISPLACED, edit)
    loaded = load_records(tmp_path)
    assert words in loaded.corrupt[path], loaded.corrupt
    summary = run_sweep(SPEC, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.corrupt) == (1, (str(path),))



# Rule: a result's real-time factor is its simulated time over its wall time, as run_trial
# writes it; a factor of 1e300 on a 8 s trial that took 2 s is refused.
@pytest.mark.parametrize("data, words", [
    ({"sim_time_s": 8.0, "wall_time_s": 2.0, "real_time_factor": 1e300}, "sim_time_s / wall"),
    ({"sim_time_s": 8.0, "wall_time_s": 2.0, "real_time_factor": 0.0}, "sim_time_s / wall"),
    ({"sim_time_s": 8.0, "wall_time_s": 0.0, "real_time_factor": 3.0}, "wall_time_s' is 0"),
])
def test_a_real_time_factor_not_simulated_over_wall_time_is_refused(data, words):
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ValueError, match=words):
        TrialResult.from_dict(data)



# Rule: a sweep trial runs at most the longest scenario time limit (a grasp script within
# its limit plus the time for corrections); a record of a longer run is corrupt.
def test_a_record_of_a_run_longer_than_any_sweep_trial_is_corrupt(tmp_path):
    path = _forge(tmp_path, MISPLACED, _result(sim_time_s=1e12))
    loaded = load_records(tmp_path)
    assert "sim_time_s" in loaded.corrupt[path], loaded.corrupt
