"""A hardware run's LCM log whose receive times (the LCM event timestamps lcm-logger writes)
cannot be one run's: a jump of years, or time going back, with every message's own contents
intact. The replay reads such a log as damaged (what was read, what is wrong; exit code 3),
and still takes the small swaps and the silent wait for the devices that real runs show."""

import lcm
import numpy as np

from tegrasp_drake.events import save_memorized_events
from tegrasp_drake.events.synthetic import synthetic_grasp
from tegrasp_drake.hardware.device_log_messages import RUN_INFO_CHANNEL, TACTILE_CHANNEL
from tegrasp_drake.lcmtypes import lcmt_tegrasp_run_info
from tegrasp_drake.runs.hardware_log_reader import read_run_log
from tests.runs.test_hardware_log_reader import EVENTS, GRASP, tactile_message
from tests.test_bad_input import run_cli

START_US = 1_796_070_992_580_719  # a hardware log's first receive time (lcm-logger's clock)
WAIT_US = 300_000_000  # the run's info, then 300 s of silence while the devices come up
SWAP_US = 156  # the largest step back measured in hardware logs (two messages swapped)


def _run_log(path, receive_times):
    """A run's log from the synthetic grasp at 1 kHz: TEGRASP_RUN_INFO, then the tactile
    messages, written with lcm.EventLog at `receive_times(k)` [us] for message k (k = 0 the
    run's info). The messages' own times run forward whatever the receive times do."""
    trial = synthetic_grasp(GRASP)
    info = lcmt_tegrasp_run_info()
    info.controller, info.object_name, info.versions_json = "memorized", "box", "{}"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(receive_times(0), RUN_INFO_CHANNEL, info.encode())
    for k, t in enumerate(trial.t_ra):
        sa = trial.sa[min(np.searchsorted(trial.t_sa, t, side="right") - 1, len(trial.sa) - 1)]
        log.write_event(receive_times(k + 1), TACTILE_CHANNEL,
                        tactile_message(t, sa, trial.ra[k]).encode())
    log.close()
    return path


def _real_run_times(k):
    """Receive times as a real run's: the wait for the devices after the run's info, 1 ms
    ticks, and one pair of messages swapped by SWAP_US."""
    if k == 0:
        return START_US
    return START_US + WAIT_US + 1000 * k - (SWAP_US + 1000 if k == 1001 else 0)


# Rule: the receive times run forward (lcm-logger writes messages in the order it receives
# them; two that arrive together may swap by less than MAX_RECEIVE_STEP_BACK_US) and never
# jump further than a run's bus can be silent (MAX_RECEIVE_GAP_US); a log breaking this is
# damaged, and says where.
def test_a_31_year_jump_in_the_receive_times_is_damage(tmp_path):
    jump = 10**15  # hostile pass 14's: added to every receive time from one message on
    path = _run_log(tmp_path / "jump.lcmlog",
                    lambda k: _real_run_times(k) + (jump if k >= 3000 else 0))
    log = read_run_log(path)
    assert len(log.damage) == 1, log.damage
    damage = log.damage[0]
    assert "receive times" in damage and "forward" in damage and "31.7 years" in damage
    assert "between messages 3000 and 3001" in damage, damage
    text = log.damage_text()
    assert str(path) in text and "\n" not in text
    assert len(log.tactile["t"]) == log.message_counts[TACTILE_CHANNEL]  # contents kept


def test_receive_times_going_back_seconds_are_damage(tmp_path):
    # a log joined to a copy of its end: the receive times go back 5 s at message 2501, while
    # the messages' own times run on
    path = _run_log(tmp_path / "back.lcmlog",
                    lambda k: _real_run_times(k) - (5_000_000 if k >= 2500 else 0))
    damage = read_run_log(path).damage
    assert len(damage) == 1, damage
    assert "go back" in damage[0] and "by 5 s" in damage[0], damage
    assert "between messages 2500 and 2501" in damage[0], damage


def test_replay_exits_3_naming_a_jump_in_the_receive_times(tmp_path, capfd):
    save_memorized_events(tmp_path / "events", EVENTS.values())
    path = _run_log(tmp_path / "jump.lcmlog",
                    lambda k: _real_run_times(k) + (10**15 if k >= 3000 else 0))
    code, text = run_cli(["replay", str(path), "--events", str(tmp_path / "events")], capfd)
    assert code == 3, text
    assert "Traceback" not in text
    warnings = [line for line in text.splitlines() if line.startswith("tegrasp: warning:")]
    assert len(warnings) == 1 and "damaged log" in warnings[0], text
    assert "receive times" in warnings[0] and "jump forward" in warnings[0], text
