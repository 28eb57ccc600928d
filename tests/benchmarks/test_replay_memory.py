"""The replay-memory benchmark writes a run log of the messages asked for and reports every
figure for it (their values are machine dependent)."""

import math

from benchmarks.replay_memory import run_replay_memory_benchmark, write_run_log
from tegrasp_drake.hardware.device_log_messages import TACTILE_CHANNEL
from tegrasp_drake.runs.hardware_log_reader import read_run_log


def test_the_generated_log_holds_the_tactile_messages_asked_for(tmp_path):
    log = read_run_log(write_run_log(tmp_path / "run.lcmlog", 4500))
    assert log.message_counts[TACTILE_CHANNEL] == 4500 and not log.damage
    assert len(log.transitions) == 5


def test_benchmark_reports_positive_figures(tmp_path):
    results = run_replay_memory_benchmark((300,), repeats=1, folder=tmp_path)
    assert set(results[300]) == {"imports_max_rss_mb", "read_bytes_per_message",
                                 "read_max_rss_mb", "read_wall_s", "log_mb"}
    assert all(math.isfinite(value) and value > 0.0 for value in results[300].values())
