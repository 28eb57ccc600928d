"""What a command writes to the terminal when the terminal fails it: a closed output pipe, a
full disk behind stdout or stderr, a progress bar or a log record that cannot be drawn, an
unwritable matplotlib folder, a viewer with no standard input. The command ends in one line
(or quietly, for a closed pipe) with its exit code, and a failed bar never stops the run.
Verbose logging (-v, -vv) says what each command read, ran and wrote, on stderr."""

import errno
import io
import os
import pathlib
import subprocess
import sys
import tempfile
import types

import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands import output_streams
from tegrasp_drake.commands.progress import SimulatedTimeBar
from tegrasp_drake.commands.viewer_args import wait_for_viewer
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.scenario import LoadScenario
from tests import killed_runs
from tests.bad_input.probes import (RefusingTerminal, logs_and_prints, parser_of_one_command,
                                    run_cli, tegrasp_in_child_process, verbose_command)
from tests.cheap_contact import CHEAP_CONTACT


def _closed_pipe_stream() -> io.TextIOWrapper:
    """A buffered text stream on a pipe whose reader has gone (`tegrasp ... | head`)."""
    read, write = os.pipe()
    os.close(read)
    return io.TextIOWrapper(io.BufferedWriter(io.FileIO(write, "w"), buffer_size=1 << 16),
                            encoding="utf-8")


@pytest.mark.parametrize("argv, closed", [
    (["--help"], "stdout"),
    (["sweep", "--help"], "stdout"),
    (["trial", "--no-such-option"], "stderr"),  # argparse's usage error
])
def test_a_closed_output_pipe_ends_the_command_quietly(monkeypatch, argv, closed):
    stream = _closed_pipe_stream()
    monkeypatch.setattr(cli.sys, closed, stream)
    other = "stderr" if closed == "stdout" else "stdout"
    monkeypatch.setattr(cli.sys, other, io.StringIO())
    try:
        assert cli.main(argv) == cli.EXIT_CLOSED_PIPE
        stream.flush()  # what Python does at exit: nothing left to report
    finally:
        stream.close()
    assert "Traceback" not in getattr(cli.sys, other).getvalue()


# Rule: the environment is told in one line at the error boundary, never as an internal error
# or another library's lines: an output stream the system refuses to write, a deleted current
# folder, a locale whose encoding is not UTF-8, an unwritable matplotlib folder.
def _full_stream():
    """A text stream on /dev/full, whose every write fails with ENOSPC."""
    return open("/dev/full", "w", encoding="utf-8")

needs_dev_full = pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full")


def _main_writing_to_a_full_disk(monkeypatch, argv) -> tuple[int, list[str]]:
    """(exit code, stderr's lines) of cli.main(argv) with stdout on /dev/full."""
    stream, errors = _full_stream(), io.StringIO()
    monkeypatch.setattr(cli.sys, "stdout", stream)
    monkeypatch.setattr(cli.sys, "stderr", errors)
    try:
        code = cli.main(argv)
    finally:
        stream.close()
    return code, errors.getvalue().splitlines()

FULL_DISK_LINE = "tegrasp: error: cannot write to standard output: No space left on device"


@needs_dev_full
def test_help_to_a_full_disk_is_one_line(monkeypatch):
    assert _main_writing_to_a_full_disk(monkeypatch, ["--help"]) == (cli.EXIT_ERROR,
                                                                     [FULL_DISK_LINE])


@needs_dev_full
def test_a_command_writing_to_a_full_disk_is_refused_in_one_line(monkeypatch):
    monkeypatch.setattr(cli, "build_parser",
                        lambda: parser_of_one_command(lambda args: print("x" * 100_000)))
    assert _main_writing_to_a_full_disk(monkeypatch, ["say"]) == (cli.EXIT_ERROR,
                                                                  [FULL_DISK_LINE])


# Rule: a standard output the shell closed (`>&-`; Python's sys.stdout is None) loses what
# the command writes, as a full disk does, and is told as one: one line, EXIT_ERROR.
CLOSED_STDOUT_LINE = ("tegrasp: error: cannot write to standard output: it is closed; send "
                      "it to a file, or to /dev/null to discard it")


def test_a_command_writing_to_a_closed_stdout_is_refused_in_one_line(monkeypatch):
    monkeypatch.setattr(cli, "build_parser",
                        lambda: parser_of_one_command(lambda args: print("plan")))
    errors = io.StringIO()
    monkeypatch.setattr(cli.sys, "stdout", None)
    monkeypatch.setattr(cli.sys, "stderr", errors)
    assert cli.main(["say"]) == cli.EXIT_ERROR
    assert errors.getvalue().splitlines() == [CLOSED_STDOUT_LINE]


def test_a_dry_run_sweep_with_its_stdout_closed_is_refused_in_one_line(tmp_path):
    done = subprocess.run(["sh", "-c", '"$@" >&-', "sh", sys.executable, "-m", "tegrasp_drake",
                           "sweep", "--dry-run", "--out", str(tmp_path / "sweep")],
                          stderr=subprocess.PIPE, text=True, env=killed_runs.environment(),
                          timeout=300)
    assert (done.returncode, done.stderr.splitlines()) == (cli.EXIT_ERROR,
                                                           [CLOSED_STDOUT_LINE])


# Rule: a standard error the shell closed (`2>&-`; Python's sys.stderr is None) is a stream
# whose writes fail: what is said there is lost, never printed on stdout, and a refusal keeps
# its documented exit code (2 for a command line that does not parse or a spec refused).
def _refusing(code):
    def command(args):
        print("tegrasp: error: refused", file=sys.stderr)
        return code
    return command


@pytest.mark.parametrize("code", [cli.EXIT_ERROR, 2])
def test_a_refusal_said_on_a_closed_stderr_keeps_its_code_and_prints_nothing(monkeypatch,
                                                                             code):
    monkeypatch.setattr(cli, "build_parser", lambda: parser_of_one_command(_refusing(code)))
    printed = io.StringIO()
    monkeypatch.setattr(cli.sys, "stdout", printed)
    monkeypatch.setattr(cli.sys, "stderr", None)
    assert cli.main(["say"]) == code
    assert printed.getvalue() == ""


def test_a_command_line_that_does_not_parse_with_stderr_closed_exits_2(tmp_path):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [nope]\n")
    for argv in (["trial", "--bogus"], ["sweep", "--spec", str(spec), "--dry-run"]):
        done = subprocess.run(["sh", "-c", '"$@" 2>&-', "sh", sys.executable, "-m",
                               "tegrasp_drake", *argv], stdout=subprocess.PIPE, text=True,
                              env=killed_runs.environment(), timeout=300)
        assert (done.returncode, done.stdout) == (2, ""), argv


def test_an_unwritable_matplotlib_folder_adds_no_lines(tmp_path):
    env = {"HOME": "/proc", "TEGRASP_EVENTS_DIR": "", "XDG_DATA_HOME": "",
           "XDG_CONFIG_HOME": "", "XDG_CACHE_HOME": "", "MPLCONFIGDIR": ""}
    done = tegrasp_in_child_process(["record-events", "--object", "box"], **env)
    assert done.returncode == 1
    assert len(done.stderr.splitlines()) == 1, done.stderr
    assert "/proc" in done.stderr and "matplotlib" not in done.stderr.lower()


# Rule: MPLCONFIGDIR naming what is no folder to write (a file) is said in the package's one
# warning line and swapped for a temporary folder before matplotlib is imported, which would
# otherwise warn in two lines of its own.
def test_an_mplconfigdir_that_is_a_file_is_one_warning_line(tmp_path, monkeypatch, capsys):
    from tegrasp_drake.commands.process_environment import private_matplotlib_config
    a_file = tmp_path / "afile"
    a_file.write_text("")
    monkeypatch.setenv("MPLCONFIGDIR", str(a_file))
    private_matplotlib_config()
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("tegrasp: warning: MPLCONFIGDIR="), lines
    assert str(a_file) in lines[0] and os.path.isdir(os.environ["MPLCONFIGDIR"])


# Rule: a home folder that does not exist is not made to find out whether matplotlib can
# write under it: matplotlib's folders go to the temporary folder, and the home stays absent.
def test_a_missing_home_folder_is_not_made(tmp_path, monkeypatch):
    from tegrasp_drake.commands.process_environment import private_matplotlib_config
    home = tmp_path / "nohome"
    monkeypatch.setenv("HOME", str(home))
    for variable in ("XDG_CONFIG_HOME", "XDG_CACHE_HOME", "MPLCONFIGDIR"):
        monkeypatch.delenv(variable, raising=False)
    private_matplotlib_config()
    assert not os.path.lexists(home)
    assert os.environ["MPLCONFIGDIR"].startswith(tempfile.gettempdir())


# Rule: under an existing home folder nothing is made by the check either (matplotlib makes
# its own folder there when it needs it), and matplotlib's own folders are kept.
def test_an_existing_home_folder_is_used_and_left_as_it_was(tmp_path, monkeypatch):
    from tegrasp_drake.commands.process_environment import private_matplotlib_config
    monkeypatch.setenv("HOME", str(tmp_path))
    for variable in ("XDG_CONFIG_HOME", "XDG_CACHE_HOME", "MPLCONFIGDIR"):
        monkeypatch.delenv(variable, raising=False)
    private_matplotlib_config()
    assert "MPLCONFIGDIR" not in os.environ and os.listdir(tmp_path) == []


# Rule: a log record stderr refuses (-v on a full disk) is dropped, never Python logging's
# traceback ("--- Logging error ---"); the command ends as a full stdout ends it: one line,
# EXIT_ERROR. (The package logs only to stderr: there is no log-file option.)
class _StderrRefusingLogRecords:
    """A stderr whose disk is full for the log records only (it fills, then frees)."""

    def __init__(self):
        self.lines = []

    def write(self, text):
        if "INFO" in text:
            raise OSError(28, "No space left on device")
        self.lines.append(text)
        return len(text)

    def flush(self):
        pass

FULL_STDERR_LINE = "tegrasp: error: cannot write to standard error: No space left on device"


def test_a_log_record_stderr_refuses_ends_the_command_in_one_line(monkeypatch, capsys):
    import logging
    from tegrasp_drake import cli
    monkeypatch.setattr(logging.getLogger(), "handlers", [])  # the command line's own
    monkeypatch.setattr(cli, "build_parser", lambda: verbose_command(logs_and_prints))
    stderr = _StderrRefusingLogRecords()
    monkeypatch.setattr(sys, "stderr", stderr)
    assert cli.main(["say", "-v"]) == cli.EXIT_ERROR
    assert "".join(stderr.lines).splitlines() == [FULL_STDERR_LINE]
    assert capsys.readouterr().out == "said\n"


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full")
def test_verbose_logging_to_a_full_stderr_ends_with_the_error_code(tmp_path):
    script = ("import sys\nfrom tegrasp_drake import cli\n"
              "from tests.bad_input.probes import logs_and_prints, verbose_command\n"
              "cli.build_parser = lambda: verbose_command(logs_and_prints)\n"
              "sys.exit(cli.main(['say', '-v']))\n")
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-c", script], stdout=subprocess.PIPE,
                              stderr=full, text=True, env=killed_runs.environment(),
                              timeout=300)
    assert (done.returncode, done.stdout) == (1, "said\n")


# Rule: the progress bar is decoration: a terminal that refuses it (hung up: EIO; closed)
# while Drake's monitor draws it stops the bar, not the simulation; a refused write is
# remembered for the command's end (output_streams), as every failed write is.
@pytest.mark.parametrize("error, remembered", [
    (OSError(errno.EIO, "Input/output error"), True),  # a terminal hung up
    (OSError(errno.ENOSPC, "No space left on device"), True),
    (ValueError("I/O operation on closed file."), False),
    (BrokenPipeError(errno.EPIPE, "Broken pipe"), False),  # the command line ends quietly
])
@pytest.mark.parametrize("accepted", [0, 3])  # refused at the first draw, or mid-run
def test_a_progress_bar_that_cannot_be_drawn_does_not_stop_the_simulation(
        error, remembered, accepted, monkeypatch):
    scenario = LoadScenario(name="box", overrides=list(CHEAP_CONTACT))
    monkeypatch.setattr(sys, "stderr", RefusingTerminal(error, accepted))
    with output_streams.guarded_output():  # as the command line runs: the bar on its stderr
        with SimulatedTimeBar("ideal grasp", enabled=True) as progress:
            log, _ = run_ideal_grasp(scenario, duration=1.1, progress=progress)
        failures = output_streams.unwritable_output()
    assert log.t_ra[-1] > 1.09  # the whole 1.1 s simulated (5 draws of the bar)
    assert (failures is not None) == remembered, failures
    if remembered:
        assert failures[0] == output_streams.STANDARD_ERROR


# Rule: the progress bar is decoration in every run that draws it, a hardware run's monitor
# too: a line written above the bar (SimulatedTimeBar.write, a hardware run's `out`) when the
# terminal starts refusing stops the bar, as a refused draw does, and the line still reaches
# stdout; the run goes on.
@pytest.mark.parametrize("error", [OSError(5, "Input/output error"),
                                   OSError(28, "No space left on device"),
                                   ValueError("I/O operation on closed file.")])
def test_a_line_above_a_refused_bar_stops_the_bar_not_the_run(error, monkeypatch, capsys):
    import sys
    from tegrasp_drake.commands import output_streams
    from tegrasp_drake.commands.progress import SimulatedTimeBar
    terminal = RefusingTerminal(error, accepted=10**6)
    monkeypatch.setattr(sys, "stderr", terminal)
    with output_streams.guarded_output():
        with SimulatedTimeBar("hardware", enabled=True) as progress:
            progress(1.0, 10.0)  # the bar is drawn
            terminal._accepted = 0  # the terminal hangs up
            progress.write("gripper active")
            progress(2.0, 10.0)
            progress.write("arm moving")
    assert capsys.readouterr().out.splitlines() == ["gripper active", "arm moving"]


# Rule: `-v` makes a command log its main steps at INFO through the package's logging, as
# `trial` does: for a sweep (and the sweeps of transfer and sensitivity), what it read from
# --out, what it will run and on what, and what it wrote.
def test_a_verbose_sweep_logs_what_it_read_ran_and_wrote(tmp_path, capfd, caplog):
    out = tmp_path / "out"
    code, text = run_cli(["sweep", "-v", "--objects", "box", "--controllers", "heuristic",
                          "--attempts", "1", "--workers", "1", "--out", str(out),
                          "--trial-function", "tests.fake_trials:fake_trial", "--no-progress"],
                         capfd)
    assert code == 0, text
    info = [record.getMessage() for record in caplog.records  # pytest holds the log
            if record.levelname == "INFO" and record.name.startswith("tegrasp_drake")]
    assert any(f"0 records read from {out}" in line for line in info), info
    assert any("running" in line and "processes:1" in line for line in info), info
    assert any("wrote" in line and str(out) in line for line in info), info


def test_a_verbose_plot_logs_what_it_read_and_wrote(tmp_path, capfd, caplog):
    from tegrasp_drake.rig.paths import package_events_dir
    events, out = package_events_dir(), tmp_path / "events.png"
    code, text = run_cli(["plot", "events", "-v", "--events", str(events), "--out", str(out)],
                         capfd)
    assert code == 0, text
    info = [record.getMessage() for record in caplog.records
            if record.levelname == "INFO" and record.name.startswith("tegrasp_drake")]
    assert any(f"reading {events}" in line and str(out) in line for line in info), info
    assert any(f"wrote {out}" in line for line in info), info


# Rule: `-v` logs a command's steps on stderr (Python logging at INFO), `-vv` adds details
# (DEBUG), and neither changes stdout: `tegrasp hardware` says the devices it checked and
# that they came up, the run's start and end, the log and result it wrote, and, with
# --overwrite, the earlier run's log and result it replaced; `tegrasp emulate` says each
# device it raised and where, and that they stopped.
@pytest.mark.slow
def test_verbose_hardware_and_emulate_log_their_steps_on_stderr(tmp_path, ideal_grasp_log):
    from tegrasp_drake.commands.hardware import failed_run_path
    from tegrasp_drake.commands.run_folder import result_path_beside_log
    from tegrasp_drake.emulators.emulator_process import EmulatedDevices, EmulatorProcess
    from tegrasp_drake.hardware.config import hardware_config_to_yaml
    from tests.loaded_host import tolerate_a_loaded_host
    from tests.runs.earlier_hardware_run import EARLIER_LOG, EARLIER_RESULT
    trial = ideal_grasp_log("box").save(tmp_path / "box.npz")
    url = f"udpm://239.255.76.67:{7600 + (os.getpid() * 7) % 100}?ttl=0"
    log = tmp_path / "hw" / "run.lcmlog"
    log.parent.mkdir()
    log.write_bytes(EARLIER_LOG)
    result = result_path_beside_log(log)
    result.write_text(EARLIER_RESULT)
    with EmulatedDevices(lcm_url=url, trial=trial) as devices:
        config = tolerate_a_loaded_host(devices.config)
        (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(config))
        done = subprocess.run(
            [sys.executable, "-m", "tegrasp_drake", "hardware", "-vv", "--config",
             str(tmp_path / "hw.yaml"), "--scenario-name", "box", "--set", "random_seed=691",
             "--log", str(log), "--overwrite"],
            capture_output=True, text=True, timeout=300)
    assert done.returncode in (0, 2), done.stderr
    # A loaded host can fail the run (a device's messages late): then the earlier run is kept
    # and this one's pair is written beside it, as `tegrasp hardware --overwrite` documents.
    failed = done.returncode == 2
    failed_log = failed_run_path(log)
    written = ([["the run failed", f"this run's are {failed_log} and "
                 f"{result_path_beside_log(failed_log)}"]] if failed else
               [[f"wrote the log {log} and the result {result}"],
                [f"replaced the earlier run's log {log} and result {result}"]])
    for words in [["devices checked", url, devices.config.gripper.port],
                  [f"gripper on {devices.config.gripper.port} (Modbus slave"],  # DEBUG
                  ["devices ready"], ["the run started"], ["the run ended"]] + written:
        assert any(all(word in line for word in words)
                   for line in done.stderr.splitlines()), (words, done.stderr)
    assert "replaced" not in done.stdout and "the run started" not in done.stdout
    assert (log.read_bytes() == EARLIER_LOG) == failed
    replayed = subprocess.run([sys.executable, "-m", "tegrasp_drake", "replay", "-vv",
                               str(failed_log if failed else log)],
                              capture_output=True, text=True, timeout=300)
    assert replayed.returncode == 0, replayed.stderr
    assert "the matcher's settings" in replayed.stderr, replayed.stderr  # DEBUG
    emulator_url = f"udpm://239.255.76.67:{7700 + (os.getpid() * 7) % 100}?ttl=0"
    with EmulatorProcess("jaco", "-vv", "--lcm-url", emulator_url, "--scheduling",
                         "normal") as jaco:
        jaco.stop()
    said = "\n".join(jaco.output)  # its stdout and stderr
    for words in (f"jaco up on {emulator_url}", f"the station's arm: lcm_url={emulator_url}",
                  "the devices stopped"):
        assert words in said, said


# Rule: `-vv` adds DEBUG details to `plot`'s INFO steps: what it read (the events of each
# folder, a trial log's samples).
def test_a_very_verbose_plot_logs_what_it_read_in_detail(tmp_path, capfd, caplog,
                                                         ideal_grasp_log):
    trial = ideal_grasp_log("box").save(tmp_path / "box.npz")
    for argv, words in ((["plot", "events", "-vv", "--out", str(tmp_path / "e.png")],
                         "memorized events from"),
                        (["plot", "signals", str(trial), "-vv", "--out",
                          str(tmp_path / "s.png")], "tactile samples")):
        caplog.clear()
        code, text = run_cli(argv, capfd)
        assert code == 0, text
        debug = [record.getMessage() for record in caplog.records
                 if record.levelname == "DEBUG" and record.name.startswith("tegrasp_drake")]
        assert any(words in line for line in debug), (argv, debug)


class _Viewer:
    def web_url(self):
        return "http://localhost:7000"


@pytest.mark.parametrize("stdin", [None, "hung up"])
def test_the_viewer_closes_when_there_is_no_standard_input_to_wait_on(monkeypatch, capsys,
                                                                      stdin):
    """`tegrasp trial --meshcat 0<&-` ran the trial, then stopped with exit 70 waiting for
    Enter on a standard input Python had set to None."""
    class HungUp:
        def readline(self):
            raise OSError(5, "Input/output error")
    monkeypatch.setattr(sys, "stdin", None if stdin is None else HungUp())
    wait_for_viewer(types.SimpleNamespace(meshcat=True), _Viewer())
    assert capsys.readouterr().err.count("\n") == 1


# Rule: a warning that names a user's file or value holding a control character (a file
# named with an escape sequence in a sweep's trials folder) shows it escaped, in one line:
# never a raw escape that drives the terminal, never a line break that splits the warning.
def test_a_warning_naming_a_file_with_control_characters_shows_them_escaped(tmp_path):
    from tests.bad_input.probes import tegrasp_in_child_process
    out = tmp_path / "out"
    out.joinpath("trials").mkdir(parents=True)
    out.joinpath("trials", "mine\x1b[31m\nred.json").write_text("x")
    done = tegrasp_in_child_process(
        ["sweep", "--objects", "box", "--controllers", "open_loop", "--attempts", "1",
         "--out", str(out), "--workers", "1", "--no-progress",
         "--trial-function", "tests.fake_trials:fake_trial"],
        PYTHONPATH=str(pathlib.Path(__file__).resolve().parents[2]))
    assert done.returncode == 0, done.stderr
    warnings = [line for line in done.stderr.splitlines() if "warning" in line]
    assert len(warnings) == 1, done.stderr
    assert "mine\\x1b[31m\\nred.json" in warnings[0], done.stderr
    assert "\x1b" not in done.stderr, repr(done.stderr)
