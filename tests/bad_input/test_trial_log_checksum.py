"""A trial log is read only as its trial wrote it: TrialLog.save stores the SHA-256 of its
metadata and arrays (meta 'checksum'); every reader (load_trial_log: `tegrasp plot`, the
emulated myRIO, the sweeps' and recordings' readers) refuses a log whose contents give another
checksum in one line naming the file and saying to run the trial again; one that holds none
(an earlier version's) saying to delete it or run the trial again to replace it."""

import json

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import (TactileRecordingError,
                                                    load_tactile_recording,
                                                    save_tactile_recording)
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.scenario.trial_log_file import (CHECKSUM_FIELD, TrialLogError,
                                                   load_trial_log, trial_log_checksum)
from tests.bad_input.probes import (assert_one_line_error, one_line_of, run_cli,
                                    trial_log_with)
from tests.trial_log_contents import read_trial_log_contents

BOX_SIZE = "size: [0.045, 0.045, 0.11]"  # the box's, in its scenario's YAML


@pytest.fixture
def saved_log(tmp_path):
    """A log TrialLog.save wrote, storing the box's whole scenario (its size among it)."""
    box = scenario_to_yaml(LoadScenario(name="box"))
    assert BOX_SIZE in box
    log = load_trial_log(trial_log_with(tmp_path / "made.npz", {"scenario": box}))
    return log.save(tmp_path / "trial.npz")


def _edited_by_hand(path, change_meta=None, **arrays):
    """`path`'s log with its metadata or arrays changed and written back as a user would (no
    checksum made again)."""
    contents = read_trial_log_contents(path)
    meta = json.loads(str(contents["meta"]))
    if change_meta is not None:
        change_meta(meta)
    contents.update(arrays, meta=np.array(json.dumps(meta)))
    np.savez_compressed(path, **contents)
    return path


def _bigger_box(meta):
    meta["scenario"] = meta["scenario"].replace(BOX_SIZE, "size: [0.045, 0.045, 0.2]")


def test_a_saved_trial_log_stores_the_checksum_of_what_it_holds(saved_log):
    contents = read_trial_log_contents(saved_log)
    meta = json.loads(str(contents["meta"]))
    assert meta[CHECKSUM_FIELD] == trial_log_checksum(meta, contents)
    assert load_trial_log(saved_log).meta[CHECKSUM_FIELD] == meta[CHECKSUM_FIELD]


@pytest.mark.parametrize("edit", [
    lambda path: _edited_by_hand(path, _bigger_box),
    lambda path: _edited_by_hand(path, lambda meta: meta.update(grip_force=100.0)),
    lambda path: _edited_by_hand(path, taxels=read_trial_log_contents(path)["taxels"] * 1.01),
    lambda path: _edited_by_hand(path, t_sa=read_trial_log_contents(path)["t_sa"]
                                 .astype(np.float32)),  # another dtype, the same values
], ids=["object size", "grip force", "taxels", "dtype"])
def test_a_trial_log_edited_after_it_was_written_is_refused_by_every_reader(
        edit, saved_log, tmp_path, capfd):
    edit(saved_log)
    expected = f"trial log '{saved_log}' was changed after it was written"
    with pytest.raises(TrialLogError, match="was changed after it was written") as refused:
        load_trial_log(saved_log)
    assert str(refused.value).startswith(expected)
    assert str(refused.value).endswith("run the trial again to remake it")
    with pytest.raises(TactileRecordingError, match="was changed after it was written"):
        load_tactile_recording(saved_log)
    code, text = run_cli(["plot", "trial", str(saved_log), "--out",
                          str(tmp_path / "t.png")], capfd)
    assert_one_line_error(code, text, expected, "run the trial again")
    assert not (tmp_path / "t.png").exists()
    code, text = run_cli(["emulate", "myrio", "--trial", str(saved_log), "--scheduling",
                          "normal"], capfd)
    assert_one_line_error(code, text, expected)


def test_a_trial_log_without_a_checksum_is_refused_saying_to_delete_or_remake_it(saved_log):
    _edited_by_hand(saved_log, lambda meta: meta.pop(CHECKSUM_FIELD))
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(saved_log)
    assert_unchecksummed_refusal(one_line_of(refused.value), saved_log)


def test_a_reused_log_without_a_checksum_is_refused_saying_to_delete_it(saved_log, monkeypatch):
    """A campaign keeps its runs' logs (LOGS_DIR/<label>.npz) and reads one there instead of
    simulating: an earlier version's log is refused there with the words that get past it."""
    from tegrasp_drake.recording import campaign
    _edited_by_hand(saved_log, lambda meta: meta.pop(CHECKSUM_FIELD))
    monkeypatch.setattr(campaign, "run_ideal_grasp",
                        lambda *a, **k: pytest.fail("the reused log was simulated again"))
    run = campaign.CampaignRun("trial", LoadScenario(name="box"))
    with pytest.raises(TrialLogError) as refused:
        campaign.simulate_run(run, log_path=campaign.run_log_path(saved_log.parent, run))
    assert_unchecksummed_refusal(one_line_of(refused.value), saved_log)


def assert_unchecksummed_refusal(text: str, path) -> None:
    assert text.startswith(f"trial log '{path}' was written by an earlier version of the "
                           "package, without a checksum (meta 'checksum')"), text
    assert f"delete '{path}'" in text and "run the trial again to replace it" in text, text


def test_a_loaded_log_saved_again_carries_the_checksum_of_its_new_contents(saved_log, tmp_path):
    log = load_trial_log(saved_log)
    log.meta["campaign_run"] = "run1"  # as a recording campaign marks the logs it keeps
    again = load_trial_log(log.save(tmp_path / "again.npz"))
    assert again.meta["campaign_run"] == "run1"
    assert again.meta[CHECKSUM_FIELD] != log.meta[CHECKSUM_FIELD]


def test_a_trial_log_stripped_of_its_metadata_is_not_replayed(saved_log, tmp_path, capfd):
    contents = read_trial_log_contents(saved_log)
    stripped = tmp_path / "stripped.npz"
    np.savez(stripped, **{name: array for name, array in contents.items() if name != "meta"})
    with pytest.raises(TactileRecordingError, match=r"holds a trial log's arrays \(true_taxels, "
                                                    r"channels, .*\) but not its metadata"):
        load_tactile_recording(stripped)
    code, text = run_cli(["emulate", "myrio", "--trial", str(stripped), "--scheduling",
                          "normal"], capfd)
    assert_one_line_error(code, text, str(stripped), "but not its metadata")


def test_the_myrio_emulator_command_replays_trial_logs_not_bare_recordings(saved_log, tmp_path,
                                                                            capfd):
    log = load_tactile_recording(saved_log)
    bare = save_tactile_recording(tmp_path / "bare.npz", log)
    assert load_tactile_recording(bare).duration == log.duration  # the Python API reads it
    code, text = run_cli(["emulate", "myrio", "--trial", str(bare), "--scheduling",
                          "normal"], capfd)
    assert_one_line_error(code, text, str(bare), "holds no trial metadata ('meta'), so it is "
                          "not a trial log; give a trial.npz")
