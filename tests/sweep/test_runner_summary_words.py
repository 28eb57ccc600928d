"""The sweep's closing summary says one trial in the singular."""

from tegrasp_drake.sweep.runner import SweepSummary, summary_text


def test_one_trial_is_one_trial():
    summary = SweepSummary(out_dir="out", total=1, skipped=0, ran=1, errors=(), unfinished=(),
                           corrupt=(), backend="processes:1", wall_time_s=1.0)
    assert summary_text(summary).startswith("sweep: 1 trial, 0 already finished")
