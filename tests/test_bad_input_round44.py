"""Bad inputs the sixteenth hostile pass found, one test per rule; nothing is simulated."""

import contextlib
import errno

import pytest

from tests.test_bad_input import run_cli
from tests.test_bad_input_round14 import _FAKE_TRIALS

_SWEEP = ("sweep: {controllers: [memorized], attempts: 1, objects: [box], grid: [[0.0, 0.0]], "
          "base_seed: 640}\n")


def test_a_world_name_too_long_for_a_folder_is_refused_at_load(tmp_path, capfd):
    """A world's name names folders (its cells' twice): refused in one line before any
    folder is made, not an OSError after the events folder was."""
    name = "a" * 300
    spec = tmp_path / "t.yaml"
    spec.write_text(f"worlds: {{{name}: {{scenario: faithful_world}}}}\n"
                    f"cells: [[{name}, {name}]]\n" + _SWEEP)
    out = tmp_path / "out"
    code, text = run_cli(["transfer", str(spec), "--out", str(out), "--workers", "1",
                          "--no-progress", *_FAKE_TRIALS], capfd)
    assert code == 2, text
    assert "at most 64 characters" in text and "worlds.aaaa" in text
    assert len(text.strip().splitlines()) == 1 and "Traceback" not in text
    assert not (out / "events").exists()


@pytest.mark.parametrize("hook", ["..x:y", ".x:y", "x:", ":y", "x y:z", "x:y.z"])
def test_a_trial_function_not_module_colon_name_is_refused_in_one_line(tmp_path, capfd, hook):
    spec = tmp_path / "s.yaml"
    spec.write_text("controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                    "grid: [[0.0, 0.0]]\nbase_seed: 640\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--workers", "1", "--no-progress", "--trial-function", hook], capfd)
    assert code in (1, 2), text
    assert "trial function" in text and "Traceback" not in text and "internal error" not in text


def test_a_trial_function_module_that_raises_on_import_is_one_line(tmp_path, capfd,
                                                                    monkeypatch):
    (tmp_path / "bad_trials_module.py").write_text("raise RuntimeError('broken at import')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    from tegrasp_drake.commands.sweep import SweepError, resolve_trial_function
    with pytest.raises(SweepError, match="RuntimeError: broken at import"):
        resolve_trial_function("bad_trials_module:run")


@pytest.mark.parametrize("override", ["gripper={pad_friction: 1.0}", "gripper.pad_friction=1.0",
                                      " gripper.pad_friction =1.0"])
def test_a_sweep_override_of_a_swept_setting_or_its_section_is_refused(tmp_path, override):
    """A study whose every point ran the override's value would say its parameter changes
    nothing."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.pad_friction]\n"
                    "sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], "
                    f"attempts: 1, base_seed: 640, scenario_overrides: ['{override}']}}\n")
    with pytest.raises(ConfigError, match=r"scenario_overrides\[0\].*gripper.pad_friction"):
        LoadSensitivitySpec(spec)


@pytest.mark.parametrize("override", ["grasp.grip_force=25.0", "grasp={grip_force: 25.0}"])
def test_a_sweep_override_of_what_a_world_sets_is_refused(tmp_path, override):
    """The world named for 50 N ran (and recorded its events) at the sweep's 25 N."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds: {w50: {scenario: faithful_world, overrides: [grasp.grip_force=50.0]}}\n"
                    "cells: [[w50, w50]]\n"
                    "sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], "
                    f"attempts: 1, base_seed: 640, scenario_overrides: ['{override}']}}\n")
    with pytest.raises(ConfigError, match=r"scenario_overrides\[0\].*world 'w50'"):
        LoadTransferSpec(spec)


def test_a_sweep_override_beside_the_worlds_settings_is_kept(tmp_path):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec, world_scenario
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds: {w50: {scenario: faithful_world, overrides: [grasp.grip_force=50.0]}}\n"
                    "cells: [[w50, w50]]\n"
                    "sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], "
                    "attempts: 1, base_seed: 640, scenario_overrides: ['grasp.hold_s=4.0']}\n")
    scenario = world_scenario(LoadTransferSpec(spec), "w50", "box")
    assert scenario.grasp.grip_force == 50.0 and scenario.grasp.hold_s == 4.0


@pytest.fixture
def listener():
    """A local TCP service on a free port that is not a Dask scheduler: `silent` accepts and
    says nothing; `garbage` sends 0xff bytes (a frame length of 2**64 - 1) and hangs up."""
    import socket
    import threading
    servers, held = [], []

    def start(kind):
        server = socket.socket()
        server.bind(("127.0.0.1", 0))
        server.listen(8)
        servers.append(server)

        def serve():
            while True:
                try:
                    connection, _ = server.accept()
                except OSError:
                    return
                if kind == "silent":
                    held.append(connection)
                    continue
                with contextlib.suppress(OSError):
                    connection.sendall(b"\xff" * 4096)
                connection.close()
        threading.Thread(target=serve, daemon=True).start()
        return f"tcp://127.0.0.1:{server.getsockname()[1]}"
    yield start
    for connection in [*servers, *held]:
        connection.close()


@pytest.mark.parametrize("kind", ["silent", "garbage"])
def test_a_scheduler_address_that_is_not_a_dask_scheduler_is_one_error(listener, monkeypatch,
                                                                       kind):
    """A silent peer held the Client past distributed's timeout (forever); garbage was exit
    70 from inside distributed's frame reader. The wall-time bound is shortened here only so
    the test takes seconds."""
    pytest.importorskip("distributed")
    from tegrasp_drake.sweep import runner
    monkeypatch.setattr(runner, "DASK_ANSWER_BOUND_S", 3.0)
    with pytest.raises(runner.SweepError, match="Dask scheduler"):
        runner.connect_scheduler(listener(kind))


def test_an_inproc_scheduler_address_is_refused_by_its_form(tmp_path, capfd):
    spec = tmp_path / "s.yaml"
    spec.write_text("controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                    "grid: [[0.0, 0.0]]\nbase_seed: 640\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--workers", "1", "--scheduler", "inproc://x", *_FAKE_TRIALS], capfd)
    assert code == 1 and "--scheduler 'inproc://x' is not a scheduler address" in text, text


def test_a_world_events_folder_that_cannot_be_made_is_one_line(tmp_path, capfd):
    """OUT/events a link to a folder no world's folder can be made in (/proc): refused in one
    line before anything is recorded, not exit 70 from mkdir."""
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds: {w: {scenario: faithful_world}}\ncells: [[w, w]]\n" + _SWEEP)
    out = tmp_path / "out"
    out.mkdir()
    (out / "events").symlink_to("/proc")
    code, text = run_cli(["transfer", str(spec), "--out", str(out), "--workers", "1",
                          "--no-progress", *_FAKE_TRIALS], capfd)
    assert code == 1, text
    assert "events/w" in text and "internal error" not in text
    assert len(text.strip().splitlines()) == 1


def _full_disk(*args, **kwargs):
    """rig.files.staged_file on a file system with no room left."""
    raise OSError(errno.ENOSPC, "No space left on device")


def test_a_finished_transfer_rerun_on_a_full_disk_is_one_line_and_keeps_its_reports(
        tmp_path, capfd, monkeypatch):
    """A rerun with nothing left to run rewrites only its reports: on a full disk that was exit
    70 (world.json rewritten unchanged) and a 0-byte table1.md (written in place)."""
    from tegrasp_drake.events.events_folder import load_memorized_events
    from tegrasp_drake.recording import paper_events
    from tegrasp_drake.rig import files, paths
    monkeypatch.setattr(paper_events, "record_events", lambda name, scenario=None, **_:
                        load_memorized_events(paths.package_events_dir(), name))
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds: {w: {scenario: faithful_world}}\ncells: [[w, w]]\n" + _SWEEP)
    out = tmp_path / "out"
    argv = ["transfer", str(spec), "--out", str(out), "--workers", "1", "--no-progress",
            *_FAKE_TRIALS]
    code, text = run_cli(argv, capfd)
    assert code == 0, text
    reports = sorted(out.glob("transfer.*"))
    assert any(report.name == "transfer.md" for report in reports)
    before = {report: report.read_bytes() for report in reports}
    world = out / "events" / "w" / "world.json"
    world_before = world.stat().st_mtime_ns

    monkeypatch.setattr(files, "staged_file", _full_disk)
    code, text = run_cli(argv, capfd)
    assert code == 1, text
    assert "No space left on device" in text and "internal error" not in text
    assert len([line for line in text.splitlines() if "error" in line]) == 1, text
    assert "transfer.md" in text  # the first write of the rerun: world.json is kept as it is
    assert {report: report.read_bytes() for report in reports} == before
    assert world.stat().st_mtime_ns == world_before


def test_a_finished_sweep_rerun_on_a_full_disk_is_one_line_and_keeps_its_reports(
        tmp_path, capfd, monkeypatch):
    """The Markdown, CSV and JSON reports were written in place: a full disk left a 0-byte
    table1.md where the earlier one was, and exit 70."""
    from tegrasp_drake.rig import files
    spec = tmp_path / "s.yaml"
    spec.write_text("controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                    "grid: [[0.0, 0.0]]\nbase_seed: 640\n")
    out = tmp_path / "out"
    argv = ["sweep", "--spec", str(spec), "--out", str(out), "--workers", "1",
            "--no-progress", "--trial-function", "tests.fake_trials:fake_trial"]
    code, text = run_cli(argv, capfd)
    assert code == 0, text
    reports = sorted(path for path in out.iterdir() if path.suffix in (".md", ".csv", ".json"))
    assert {"table1.md", "table1.csv", "statistics.json"} <= {path.name for path in reports}
    before = {report: report.read_bytes() for report in reports}

    monkeypatch.setattr(files, "staged_file", _full_disk)
    code, text = run_cli(argv, capfd)
    assert code == 1, text
    assert "No space left on device" in text and "internal error" not in text
    assert {report: report.read_bytes() for report in reports} == before


@pytest.mark.parametrize("command", ["sweep", "transfer", "sensitivity"])
def test_a_runner_option_refused_is_bad_input_as_for_every_command(tmp_path, capfd, command):
    """An --out that is a file: exit 1, as `tegrasp trial` and `plot` give (the table: bad
    input, a file that cannot be written); a spec refused stays 2."""
    taken = tmp_path / "a_file"
    taken.write_text("")
    spec = tmp_path / "spec.yaml"
    spec.write_text({"sweep": "controllers: [memorized]\nattempts: 1\nobjects: [box]\n"
                              "grid: [[0.0, 0.0]]\nbase_seed: 640\n",
                     "transfer": "worlds: {w: {scenario: faithful_world}}\ncells: [[w, w]]\n"
                                 + _SWEEP,
                     "sensitivity": "parameters: [gripper.pad_friction]\n" + _SWEEP}[command])
    spec_argument = ["--spec", str(spec)] if command == "sweep" else [str(spec)]
    for out, code in ((taken, 1), (tmp_path / "out", 1)):
        workers = "1" if out == taken else "0"
        status, text = run_cli([command, *spec_argument, "--out", str(out), "--workers",
                                workers, "--no-progress", *_FAKE_TRIALS], capfd)
        assert status == code, text
        assert len(text.strip().splitlines()) == 1, text


def test_a_transition_built_in_python_with_a_code_of_no_rule_is_refused():
    """The JSON reader refused it; a Transition built by hand (the API) did not."""
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    from tegrasp_drake.rig.typed_yaml import ConfigError
    with pytest.raises(ConfigError, match="names no rule"):
        Transition(t=1.0, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                   trigger=Trigger.MEMORIZED_EVENT, reason="", code="bogus_rule")
    Transition(t=1.0, from_mode=Mode.REACH, to_mode=Mode.LOAD,
               trigger=Trigger.MEMORIZED_EVENT, reason="", code="reach_event")
