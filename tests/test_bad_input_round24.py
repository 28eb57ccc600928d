"""Bad inputs the fourteenth review found (round 24), one test per rule."""

import os
import subprocess
import sys

import pytest

PRECIOUS = "precious data\n"


# Rule: an LCM URL is checked from its text before LCM is given it: only the buses
# udpm:// and tcpq:// (and, for library code, memq://) are opened; file://, LCM's event-log
# provider, is refused without being opened, so checking it never creates or truncates the
# file it names (with ?mode=w, lcm.LCM(url) truncated it).
def test_a_file_lcm_url_is_refused_by_its_text_and_its_file_left_whole(tmp_path):
    from tegrasp_drake.hardware.config import lcm_url_problem, shared_lcm_url_problem
    precious = tmp_path / "precious.txt"
    precious.write_text(PRECIOUS)
    absent = tmp_path / "absent.lcmlog"
    for check in (lcm_url_problem, shared_lcm_url_problem):
        for url in (f"file://{precious}?mode=w", f"file://{absent}?mode=w"):
            problem = check(url)
            assert problem and "file://" in problem and "udpm://" in problem, problem
            assert "tcpq://" in problem, problem
    assert precious.read_text() == PRECIOUS
    assert not absent.exists()


def _hardware_config(tmp_path, url):
    """hw.yaml with arm.lcm_url `url`, or with no arm.lcm_url (its default) when None."""
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    config = HardwareStationConfig()
    text = hardware_config_to_yaml(config)
    line = f"  lcm_url: {config.arm.lcm_url}\n"
    assert line in text, text
    (tmp_path / "hw.yaml").write_text(
        text.replace(line, "" if url is None else f"  lcm_url: {url!r}\n"))


def _tegrasp(argv, cwd, environment=None):
    """(exit code, stderr) of `tegrasp ARGV` in its own process; an emulator that accepted
    the URL would run until stopped, so a run past the timeout fails the test."""
    done = subprocess.run([sys.executable, "-m", "tegrasp_drake", *argv], cwd=cwd,
                          env=environment, capture_output=True, text=True, timeout=60)
    return done.returncode, done.stderr


# Rule (the commands): `tegrasp hardware` (arm.lcm_url, or LCM_DEFAULT_URL as its default)
# and `tegrasp emulate` (--lcm-url, or LCM_DEFAULT_URL as its default) refuse a file:// URL
# in one line naming the field or variable and the providers accepted, and leave the file
# as it was.
@pytest.mark.parametrize("case", ["hardware", "hardware-variable", "emulate",
                                  "emulate-variable"])
def test_the_commands_refuse_a_file_lcm_url_and_leave_the_file_whole(tmp_path, case):
    precious = tmp_path / "precious.txt"
    precious.write_text(PRECIOUS)
    url = f"file://{precious}?mode=w"
    environment = dict(os.environ, PYTHONPATH=os.getcwd())
    if case.endswith("variable"):
        environment["LCM_DEFAULT_URL"] = url
    if case.startswith("hardware"):
        _hardware_config(tmp_path, None if case.endswith("variable") else url)
        argv = ["hardware", "--config", "hw.yaml", "--scenario-name", "box", "--set",
                "random_seed=690", "--log", "hw/run.lcmlog"]
        named = ("LCM_DEFAULT_URL" if case.endswith("variable")
                 else "hw.yaml: field 'arm.lcm_url'")
    else:
        argv = ["emulate", "jaco", "--scheduling", "normal"]
        if not case.endswith("variable"):
            argv += ["--lcm-url", url]
        named = "LCM_DEFAULT_URL" if case.endswith("variable") else "--lcm-url"
    code, text = _tegrasp(argv, tmp_path, environment)
    assert code == 1 and text.strip().count("\n") == 0, text
    for word in (named, "file://", "udpm://", "tcpq://"):
        assert word in text, text
    assert precious.read_text() == PRECIOUS
    assert not (tmp_path / "hw").exists()


# Rule: `-v` logs a command's steps on stderr (Python logging at INFO), `-vv` adds details
# (DEBUG), and neither changes stdout: `tegrasp hardware` says the devices it checked and
# that they came up, the run's start and end, the log and result it wrote, and, with
# --overwrite, the earlier run's log and result it replaced; `tegrasp emulate` says each
# device it raised and where, and that they stopped.
@pytest.mark.slow
def test_verbose_hardware_and_emulate_log_their_steps_on_stderr(tmp_path, ideal_grasp_log):
    from tegrasp_drake.commands.run_folder import result_path_beside_log
    from tegrasp_drake.emulators.emulator_process import EmulatedDevices, EmulatorProcess
    from tegrasp_drake.hardware.config import hardware_config_to_yaml
    trial = ideal_grasp_log("box").save(tmp_path / "box.npz")
    url = f"udpm://239.255.76.67:{7600 + (os.getpid() * 7) % 100}?ttl=0"
    log = tmp_path / "hw" / "run.lcmlog"
    log.parent.mkdir()
    log.write_text("the earlier run's log")
    result = result_path_beside_log(log)
    result.write_text("{}")
    with EmulatedDevices(lcm_url=url, trial=trial, scheduling="normal") as devices:
        (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(devices.config))
        done = subprocess.run(
            [sys.executable, "-m", "tegrasp_drake", "hardware", "-vv", "--config",
             str(tmp_path / "hw.yaml"), "--scenario-name", "box", "--set", "random_seed=691",
             "--config-set", "scheduling=normal", "--log", str(log), "--overwrite"],
            capture_output=True, text=True, timeout=300)
    assert done.returncode in (0, 2), done.stderr
    for words in (["devices checked", url, devices.config.gripper.port],
                  [f"gripper on {devices.config.gripper.port} (Modbus slave"],  # DEBUG
                  ["devices ready"], ["the run started"], ["the run ended"],
                  [f"wrote the log {log} and the result {result}"],
                  [f"replaced the earlier run's log {log} and result {result}"]):
        assert any(all(word in line for word in words)
                   for line in done.stderr.splitlines()), (words, done.stderr)
    assert "replaced" not in done.stdout and "the run started" not in done.stdout
    assert log.read_bytes() != b"the earlier run's log"
    replayed = subprocess.run([sys.executable, "-m", "tegrasp_drake", "replay", "-vv",
                               str(log)], capture_output=True, text=True, timeout=300)
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
    from tests.test_bad_input import run_cli
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
