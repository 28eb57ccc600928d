"""Trial log files (scenario/trial_log_file.py): TrialLog.save writes through a temporary file
beside the log and a rename; the next save of that log removes what a save of it killed past
its handlers (SIGKILL) left beside it, and nothing else."""

from tests.commands.test_run_folder import _ended_process_id
from tests.fake_trials import small_trial_log
from tests.killed_runs import killed_before_rename

_SAVE_A_LOG = """
from tegrasp_drake.scenario.trial_log_file import load_trial_log
load_trial_log({source!r}).save({path!r})
"""


def test_a_log_save_removes_what_a_killed_save_of_that_log_left(tmp_path):
    target = tmp_path / "run0.npz"
    source = tmp_path.parent / f"{tmp_path.name}-source.npz"
    small_trial_log().save(source)
    killed_before_rename(_SAVE_A_LOG.format(source=str(source), path=str(target)))
    left = sorted(tmp_path.iterdir())
    assert len(left) == 1 and not target.exists(), left  # the killed save's temporary file
    dead = _ended_process_id()
    kept = {tmp_path / f".run1.npz.abcd1234.{dead}.staging": b"PK\x03\x04",  # another log's
            tmp_path / f".run0.npz.abcd1234.{dead}.staging": b"my notes"}  # not a zip
    for path, data in kept.items():
        path.write_bytes(data)
    small_trial_log().save(target)
    assert sorted(tmp_path.iterdir()) == sorted([target, *kept])
