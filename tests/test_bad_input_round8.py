"""Bad inputs found by the eighth hostile pass, one test per rule."""

import argparse
import io
import os
import signal
import subprocess
import sys

import pytest

from tegrasp_drake import cli
from tests import killed_runs
from tests.test_bad_input import assert_one_line_error, run_cli


# Rule: every YAML the package reads (scenario files, --set values, sweep, sensitivity and
# transfer specs) reads numbers as YAML 1.2's core schema does (rig/core_schema_yaml.py):
# YAML 1.1's base-60, binary and `_` forms are text, refused by a numeric field in one line.
@pytest.mark.parametrize("override, field", [
    ("placement.yaw_deg=1:30", "placement.yaw_deg"),
    ("random_seed=0b101", "random_seed"),
    ("random_seed=1_000", "random_seed"),
])
def test_a_yaml_11_only_number_in_a_set_value_is_refused(override, field, capfd):
    code, text = run_cli(["trial", "--set", override], capfd)
    assert_one_line_error(code, text, f"field '{field}' must be", "YAML 1.2")


def test_a_leading_zero_is_decimal_and_0x_hexadecimal():
    from tegrasp_drake.scenario.scenario import LoadScenario
    assert LoadScenario(name="box", overrides=["random_seed=017"]).random_seed == 17
    assert LoadScenario(name="box", overrides=["random_seed=0x10"]).random_seed == 16


def test_a_scenario_file_reads_base_60_as_text(tmp_path, capfd):
    (tmp_path / "s.yaml").write_text("s:\n  placement: {yaw_deg: 1:30}\n")
    code, text = run_cli(["trial", "--scenario", str(tmp_path / "s.yaml"),
                          "--scenario-name", "s", "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "field 'placement.yaw_deg' must be a finite number")


def test_a_sweep_spec_reads_base_60_as_text(tmp_path, capfd):
    (tmp_path / "spec.yaml").write_text("objects: [box]\nattempts: 1:00\n")
    code, text = run_cli(["sweep", "--spec", str(tmp_path / "spec.yaml"), "--workers", "1",
                          "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "attempts", "1:00")
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


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


def _parser_of_one_command(func):
    """A command line whose one command `say` runs `func`."""
    parser = argparse.ArgumentParser(prog="tegrasp")
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("say").set_defaults(func=func)
    return parser


@needs_dev_full
def test_a_command_writing_to_a_full_disk_is_refused_in_one_line(monkeypatch):
    monkeypatch.setattr(cli, "build_parser",
                        lambda: _parser_of_one_command(lambda args: print("x" * 100_000)))
    assert _main_writing_to_a_full_disk(monkeypatch, ["say"]) == (cli.EXIT_ERROR,
                                                                  [FULL_DISK_LINE])


def test_a_deleted_current_folder_is_named(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.rig.files import folder_problem, output_file_problem
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()
    for problem in (output_file_problem("f.png"), folder_problem("o")):
        assert "the current folder no longer exists; cd to one that does" in problem
    code, text = run_cli(["plot", "trial", str(tmp_path / "trial.npz"), "--out", "f.png"],
                         capfd)
    assert_one_line_error(code, text, "current folder no longer exists")


def _tegrasp(argv, **environment):
    """`python -m tegrasp_drake ARGV` in a child process with `environment` changed."""
    env = {**os.environ, **environment}
    return subprocess.run([sys.executable, "-m", "tegrasp_drake", *argv], env=env,
                          capture_output=True, text=True, timeout=600)


def test_a_locale_without_utf8_runs_the_command_in_utf8_mode():
    done = _tegrasp(["trial", "--help"], LC_ALL="C", LANG="C", PYTHONUTF8="0")
    assert done.returncode == 0, done.stderr
    assert "--out" in done.stdout and done.stderr == ""


def test_an_unwritable_matplotlib_folder_adds_no_lines(tmp_path):
    env = {"HOME": "/proc", "TEGRASP_EVENTS_DIR": "", "XDG_DATA_HOME": "",
           "XDG_CONFIG_HOME": "", "XDG_CACHE_HOME": "", "MPLCONFIGDIR": ""}
    done = _tegrasp(["record-events", "--object", "box"], **env)
    assert done.returncode == 1
    assert len(done.stderr.splitlines()) == 1, done.stderr
    assert "/proc" in done.stderr and "matplotlib" not in done.stderr.lower()


# Rule: a public function's number takes the range its command-line or scenario twin takes,
# from the same declaration.
def test_the_api_rates_noise_and_duration_share_the_command_lines_ranges():
    from tegrasp_drake.commands.hardware import MAX_DURATION_S
    from tegrasp_drake.control.grasp_controller import RA_NOISE_RANGE, SAMPLE_RATE_RANGE
    from tegrasp_drake.rig.ranges import HARDWARE_RUN_DURATION, field_range
    from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
    from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig
    assert SAMPLE_RATE_RANGE == field_range(TactileSensorConfig, "sample_rate_hz")
    assert SAMPLE_RATE_RANGE == field_range(VibrationSensorConfig, "sample_rate_hz")
    assert RA_NOISE_RANGE == field_range(VibrationSensorConfig, "noise_std_mps2")
    assert MAX_DURATION_S == HARDWARE_RUN_DURATION.high


def test_a_huge_sample_rate_is_refused_before_anything_is_built():
    from pydrake.systems.framework import DiagramBuilder
    from pydrake.systems.primitives import ConstantVectorSource
    from tegrasp_drake import AddGraspController, LoadScenario, grasp_plan
    scenario = LoadScenario(name="box")
    with pytest.raises(ValueError, match=r"sample_rates_hz.*must lie in \[16, 20000\] Hz"):
        AddGraspController(DiagramBuilder(), controller=scenario.controller,
                           plan=grasp_plan(scenario), station=ConstantVectorSource([0.0]),
                           arm=scenario.arm, sample_rates_hz=(1e12, 1e12))


def test_a_hardware_run_longer_than_the_command_lines_cap_is_refused():
    from tegrasp_drake import LoadScenario, run_on_hardware
    with pytest.raises(ValueError, match=r"duration.*must lie in \(0, 600\] s"):
        run_on_hardware(LoadScenario(name="box"), duration=1e9)


# Rule: every catchable terminating signal stops a run as Ctrl-C does (its staging removed);
# a run killed past its handlers leaves a staging folder the next run into its folder removes.
@pytest.mark.parametrize("name", ["SIGQUIT", "SIGUSR1", "SIGUSR2", "SIGALRM"])
def test_a_terminating_signal_removes_the_runs_staging(name, tmp_path, monkeypatch, capfd):
    from tegrasp_drake.commands.run_folder import STAGING_PREFIX, staged_run

    def stage_and_signal(args):
        with staged_run(tmp_path):
            os.kill(os.getpid(), signal.Signals[name])
            raise AssertionError("the signal did not stop the run")

    monkeypatch.setattr(cli, "build_parser", lambda: _parser_of_one_command(stage_and_signal))
    code, text = run_cli(["say"], capfd)
    assert code == 128 + signal.Signals[name].value
    assert text.strip() == f"tegrasp: interrupted ({name}); the run's unfinished files were removed"
    assert not list(tmp_path.glob(f"{STAGING_PREFIX}*"))


def test_the_staging_of_a_killed_run_is_removed_by_the_next_run(tmp_path):
    from tegrasp_drake.commands.run_folder import STAGING_PREFIX, RunFolderError, staged_run
    killed = subprocess.run(
        [sys.executable, "-c", "import os, signal, sys\n"
         "from tegrasp_drake.commands.run_folder import staged_run\n"
         "with staged_run(sys.argv[1]):\n    os.kill(os.getpid(), signal.SIGKILL)\n",
         str(tmp_path)], env=killed_runs.environment(), timeout=300)
    assert killed.returncode == -signal.SIGKILL
    (left,) = tmp_path.glob(f"{STAGING_PREFIX}*")
    with staged_run(tmp_path) as stage:
        assert not left.exists() and stage.is_dir()
        with pytest.raises(RunFolderError, match="another run is writing there now"):
            with staged_run(tmp_path):
                pass
        assert stage.is_dir()  # a live run's staging is never touched
    assert not list(tmp_path.glob(f"{STAGING_PREFIX}*"))


# Rule: no output of any command goes inside the installed package, which pip deletes.
def test_output_inside_the_installed_package_is_refused(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.rig import files
    package = (tmp_path / "site-packages" / "tegrasp_drake").resolve()
    (package / "events").mkdir(parents=True)
    monkeypatch.setattr(files, "installed_package_dir", lambda: package)
    assert "pip deletes" in files.folder_problem(package / "events" / "mine")
    assert "pip deletes" in files.output_file_problem(package / "f.png")
    assert files.folder_problem(tmp_path / "mine") is None
    code, text = run_cli(["trial", "--out", str(package / "events" / "mine")], capfd)
    assert_one_line_error(code, text, "is inside the installed package", "outside it")
    assert not (package / "events" / "mine").exists()


def test_a_source_checkout_is_not_an_installed_package():
    from tegrasp_drake.rig.files import installed_package_dir
    assert installed_package_dir() is None  # the tests run from the checkout


# Rule: a save of nothing is refused, as the command line never makes one.
def test_saving_no_events_is_refused(tmp_path):
    from tegrasp_drake import save_memorized_events
    with pytest.raises(ValueError, match="no events given; there is nothing to save"):
        save_memorized_events(tmp_path / "ev", [])
    assert not (tmp_path / "ev").exists()


# Rule: a study whose trials read events its worlds' recording does not make (the paper's
# and the taxel_aware ensemble are made; here the ensemble's folder is renamed) is refused
# before anything is recorded or written, naming the folder.
def test_a_sensitivity_study_of_events_no_recording_makes_is_refused_before_recording(
        tmp_path, capfd, monkeypatch):
    from tegrasp_drake.control.controller_config import TaxelAwareControllerConfig
    monkeypatch.setattr(TaxelAwareControllerConfig, "events_folder", "unrecorded")
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.pad_friction]\nsweep:\n  objects: [box]\n"
                    "  controllers: [taxel_aware]\n  grid: [[0.0, 0.0]]\n  attempts: 1\n")
    code, text = run_cli(["sensitivity", str(spec), "--out", str(tmp_path / "o"),
                          "--workers", "1"], capfd)
    assert_one_line_error(code, text, "taxel_aware", "unrecorded (no index.json)",
                          "record these there first or drop the controller")
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").rglob("*"))
