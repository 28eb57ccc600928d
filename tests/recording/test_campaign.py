"""An event-recording campaign's run logs (recording/campaign.py, log_dir): a log that cannot
be written there (a full disk, a log_dir that cannot be made) never turns the finished
recording into an exception or a loss. Every run is still simulated once and cut, the events
are combined, and the campaign ends in LogNotWritten carrying them, with the first log it
could not write and why; nothing half-written stays in log_dir."""

import errno
import types

import numpy as np
import pytest

from tests.bad_input.probes import memorized_events
from tegrasp_drake.recording import campaign
from tegrasp_drake.scenario.trial_log_file import LogNotWritten
from tests.fake_trials import small_trial_log

RUNS = [campaign.CampaignRun("run0", types.SimpleNamespace(random_seed=1_000_000)),
        campaign.CampaignRun("run1", types.SimpleNamespace(random_seed=1_000_001)),
        campaign.CampaignRun("run2", types.SimpleNamespace(random_seed=1_000_002),
                             role="held_out")]


@pytest.fixture
def simulated(monkeypatch):
    """The runs' labels as each is simulated (a small log, no physics), each cut into the
    probes' events (seeded by the run)."""
    labels = []
    small_log = small_trial_log()  # made before a test replaces np.savez_compressed

    def ideal_grasp(scenario, *, duration, progress):
        labels.append(RUNS[scenario.random_seed - 1_000_000].label)
        return small_log, 0.0

    def cut(log, run, times, **options):
        return {e.transition: e for e in memorized_events(seed=run.scenario.random_seed)}

    monkeypatch.setattr(campaign, "run_ideal_grasp", ideal_grasp)
    monkeypatch.setattr(campaign, "cut_events", cut)
    return labels


def _record(log_dir):
    return campaign.record_campaign(RUNS, lambda log, scenario: {}, object_name="mine",
                                    nominal_object=None, note="test", log_dir=log_dir)


def _events_of_templates() -> dict:
    return campaign.combine_runs([{e.transition: e for e in memorized_events(seed=seed)}
                                  for seed in (1_000_000, 1_000_001)], note="test")


def _assert_same_events(got: dict, expected: dict) -> None:
    assert list(got) == list(expected)
    for transition, event in expected.items():
        np.testing.assert_allclose(got[transition].sa, event.sa, rtol=1e-12)
        np.testing.assert_allclose(got[transition].ra, event.ra, rtol=1e-12)


def test_a_log_dir_that_cannot_be_made_keeps_the_recording(tmp_path, simulated):
    (tmp_path / "notes").write_text("a file where log_dir's folder would be")
    log_dir = tmp_path / "notes" / "logs"
    with pytest.raises(LogNotWritten) as unwritten:
        _record(log_dir)
    assert simulated == ["run0", "run1", "run2"]  # each run once, the campaign to its end
    assert unwritten.value.path == str(log_dir / "run0.npz")
    assert unwritten.value.reason == "Not a directory"
    _assert_same_events(unwritten.value.result, _events_of_templates())


def test_a_full_disk_keeps_the_recording_and_leaves_no_half_written_log(tmp_path, simulated,
                                                                        monkeypatch):
    def disk_full(stream, **arrays):
        stream.write(b"PK\x03\x04 a part of the archive")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(np, "savez_compressed", disk_full)
    with pytest.raises(LogNotWritten) as unwritten:
        _record(tmp_path)
    assert simulated == ["run0", "run1", "run2"]
    assert unwritten.value.path == str(tmp_path / "run0.npz")
    assert unwritten.value.reason == "No space left on device"
    _assert_same_events(unwritten.value.result, _events_of_templates())
    assert list(tmp_path.iterdir()) == []



def test_a_corrective_recording_on_a_full_disk_carries_its_one_event(tmp_path, monkeypatch):
    import dataclasses
    from tegrasp_drake.recording import corrective_events

    small_log = small_trial_log()  # made before np.savez_compressed is replaced below

    def ideal_grasp(scenario, *, duration, progress):  # a small log, no physics
        return small_log, 0.0

    def cut(log, run, times, **options):  # the probes' first event, as hold_avoid's
        (transition,) = times
        return {transition: dataclasses.replace(memorized_events(seed=len(run.label))[0],
                                                transition=transition)}

    def disk_full(stream, **arrays):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(campaign, "run_ideal_grasp", ideal_grasp)
    monkeypatch.setattr(campaign, "cut_events", cut)
    monkeypatch.setattr(corrective_events, "corrective_event_time", lambda *args: 1.0)
    monkeypatch.setattr(np, "savez_compressed", disk_full)
    with pytest.raises(LogNotWritten) as unwritten:
        corrective_events.record_corrective_events("box", "hold_avoid", log_dir=tmp_path)
    event = unwritten.value.result
    assert event.transition == "hold_avoid" and event.object_name == "mine"
    assert unwritten.value.reason == "No space left on device"
    assert list(tmp_path.iterdir()) == []
