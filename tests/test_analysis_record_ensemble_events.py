"""analysis/record_ensemble_events.py on a logs folder it cannot write (a full disk): one
error line naming the log and the reason, exit 1, no events made from a partial
campaign, nothing half-written left; the logs are its first stage's only product, made in a process pool
(here a thread pool, so the test's stand-ins reach the workers)."""

import errno
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from tegrasp_drake.recording import campaign
from tests.fake_trials import small_trial_log
from tests.analysis_script import load_analysis_script


def _script():
    return load_analysis_script("record_ensemble_events")


def test_a_full_logs_folder_is_one_error_line_and_exit_1(tmp_path, monkeypatch, capsys):
    script = _script()
    simulated = []

    small_log = small_trial_log()  # made before np.savez_compressed is replaced below

    def ideal_grasp(scenario, *, duration, progress):  # a small log, no physics
        simulated.append(scenario.random_seed)
        return small_log, 0.0

    def disk_full(stream, **arrays):
        stream.write(b"PK\x03\x04 a part of the archive")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(campaign, "run_ideal_grasp", ideal_grasp)
    monkeypatch.setattr(np, "savez_compressed", disk_full)
    monkeypatch.setattr(script, "ProcessPoolExecutor", ThreadPoolExecutor)
    code = script.main([str(tmp_path / "logs"), "--runs", "2", "--template-runs", "1",
                        "--workers", "1", "--events", str(tmp_path / "events")])
    captured = capsys.readouterr()
    assert code == 1
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("record_ensemble_events: error: cannot write the run log ")
    assert "(No space left on device)" in lines[0] and "run0.npz" in lines[0], lines[0]
    assert simulated  # the failure came after a run was simulated, writing its log
    assert not (tmp_path / "events").exists()
    assert [path for path in (tmp_path / "logs").rglob("*") if path.is_file()] == []
