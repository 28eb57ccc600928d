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
