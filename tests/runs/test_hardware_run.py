"""The hardware run's LCM log writer keeps lcm-logger's words off the user's terminal and
quotes them, on one line, when it fails."""

import time

from tegrasp_drake.runs.hardware_run import BusLogWriter

URL = "udpm://239.255.76.67:7683?ttl=0"  # loopback only


def test_the_loggers_words_do_not_reach_the_terminal(tmp_path, capfd):
    writer = BusLogWriter(URL, tmp_path / "run.lcmlog")
    assert writer.close(linger=0.0) == 0
    captured = capfd.readouterr()
    assert "Logger exiting" not in captured.out + captured.err
    assert (captured.out, captured.err) == ("", "")


def test_a_logger_that_fails_is_named_with_what_it_said(tmp_path, capfd):
    try:  # it fails at once, or just after creating its file
        writer = BusLogWriter("udpm://239.255.76.67:notaport?ttl=0", tmp_path / "run.lcmlog")
    except RuntimeError as error:
        message = str(error)
    else:
        deadline = time.monotonic() + 10.0
        while writer.problem() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        message = writer.problem()
        writer.close(linger=0.0)
    assert message is not None and "\n" not in message and "lcm-logger" in message
    assert "notaport" in message  # lcm-logger's own reason
    captured = capfd.readouterr()
    assert "Logger exiting" not in captured.out + captured.err


def test_the_live_printout_names_the_rule_that_decided_each_transition():
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    from tegrasp_drake.runs.hardware_run import format_transition
    transition = Transition(t=1.25, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                            trigger=Trigger.MEMORIZED_EVENT, reason="the Reach-Load event matched",
                            code="reach_event")
    line = format_transition(transition)
    assert "Reach -> Load" in line and "memorized_event: reach_event" in line
    assert "the Reach-Load event matched" in line
    scripted = Transition(t=1.25, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                          trigger=Trigger.TIMER, reason="")
    assert ":" not in format_transition(scripted).split("(")[1]


def test_a_tactile_stream_restart_is_said_live_with_the_time():
    from tegrasp_drake.hardware.myrio.tactile_frame import RESTART_RUN, TactileFrameDecoder
    from tegrasp_drake.runs.hardware_run import RunReporter
    from tests.hardware.test_myrio_tactile_frame import make_frames

    decoder = TactileFrameDecoder()
    decoder.feed(b"".join(make_frames(100)))
    decoder.feed(b"".join(make_frames(RESTART_RUN + 2)))
    lines = []
    quiet = _Clock()
    quiet.t = 2.5
    RunReporter(diagram=None, station=quiet, grasp=quiet, drake_lcm=quiet, out=lines.append,
                boundaries=[decoder.boundary])(quiet)
    # The frames before the restart was taken were refused (said once, as every refusal),
    # then the restart itself.
    assert "skipped a message (repeated" in lines[0]
    assert lines[1].startswith("[   2.500 s] tactile: the stream restarted its sequence")
    assert len(lines) == 2


class _Clock:
    """A station with no faults, a grasp with no transitions and a bus, at a time the test
    sets (the monitor is called as Initialize then AdvanceTo call it)."""
    def __init__(self):
        self.t = 0.0

    def GetOutputPort(self, name):
        return self

    def Eval(self, context):
        return []

    def GetMyContextFromRoot(self, context):
        return context

    def transitions(self, context):
        return []

    def Publish(self, channel, data):
        pass

    def get_time(self):
        return self.t


def test_a_log_that_stops_is_said_once_however_often_the_monitor_looks():
    from pydrake.systems.framework import EventStatus, LeafSystem
    from tegrasp_drake.runs.hardware_run import RunReporter
    clock, lines = _Clock(), []
    reporter = RunReporter(diagram=LeafSystem(), station=clock, grasp=clock, drake_lcm=clock,
                           out=lines.append, log_problem=lambda: "the LCM log x stopped")
    for t in (0.0, 0.103, 0.25, 0.5):
        clock.t = t
        status = reporter(clock)
        assert status.severity() == EventStatus.Severity.kReachedTermination
    assert sum("FAULT" in line for line in lines) == 1
    assert reporter.log_fault == "the LCM log x stopped"


def test_a_log_file_removed_during_the_run_is_a_stopped_log(tmp_path):
    writer = BusLogWriter(URL, tmp_path / "run.lcmlog")
    try:
        assert writer.problem() is None
        (tmp_path / "run.lcmlog").unlink()
        problem = writer.problem()
    finally:
        assert writer.close(linger=0.0) == 0  # counted as nothing, not an error
    assert problem is not None and "removed" in problem and "run.lcmlog" in problem


def test_every_result_json_holds_the_keys_a_hardware_result_is_known_by(tmp_path):
    """hardware --overwrite tells an earlier run's result.json by HARDWARE_RESULT_KEYS: each
    must be a key of every HardwareRunResult's JSON form, logged or not."""
    from tegrasp_drake.runs.hardware_run import HARDWARE_RESULT_KEYS, HardwareRunResult
    for log_path in (None, tmp_path / "run.lcmlog"):
        result = HardwareRunResult(transitions=[], faults=(), sim_time=0.0, wall_time=0.0,
                                   log_path=log_path, log_messages=0, device_counters={})
        assert set(HARDWARE_RESULT_KEYS) <= set(result.as_dict()), result.as_dict().keys()
