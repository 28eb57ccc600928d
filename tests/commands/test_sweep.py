"""The `sweep` sub-command: options, bad input, reports, benchmark."""

import argparse
import json
from statistics import median as statistics_median

import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands import sweep as command
from tegrasp_drake.sweep.records import load_records
from tegrasp_drake.rig.paths import package_events_dir


def sweep_main(argv) -> int:
    """`tegrasp sweep ARGV` run in this process through the command line's entry."""
    return cli.main(["sweep", *argv])

FAKE = ["--trial-function", "tests.fake_trials:fake_trial", "--no-progress"]


def test_register_adds_the_sweep_subcommand():
    parser = argparse.ArgumentParser(prog="tegrasp")
    command.register(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(["sweep", "--objects", "box", "--workers", "2"])
    assert args.func is command.run
    assert (args.objects, args.workers, args.out) == (["box"], 2, "results/sweep")
    assert args.trial_function == "tegrasp_drake.sweep.trial_function:run_trial_from_spec"


def test_sweep_writes_records_and_reports(tmp_path, capsys):
    out = tmp_path / "out"
    code = sweep_main(["--objects", "box", "--controllers", "memorized", "heuristic",
                         "--attempts", "1", "--workers", "2", "--base-seed", "3",
                         "--out", str(out), *FAKE])
    assert code == 0
    records = load_records(out).records
    assert len(records) == 18
    assert {r["trial"]["base_seed"] for r in records.values()} == {3}
    for name in ("table1.md", "table1.csv", "statistics.md", "statistics.json",
                 "success_maps.png"):
        assert (out / name).is_file(), name
    stdout = capsys.readouterr().out
    assert "sweep: 18 trials, 0 already finished, 18 run now on processes:2" in stdout
    assert "heuristic thresholds" in (out / "table1.md").read_text()


def test_spec_file_with_command_line_overrides(tmp_path):
    spec = tmp_path / "grid.yaml"
    spec.write_text("objects: [thin_cylinder]\ncontrollers: [open_loop]\nattempts: 3\n"
                    "grid: [[0.0, 0.0], [0.0, 0.02]]\n")
    out = tmp_path / "out"
    assert sweep_main(["--spec", str(spec), "--attempts", "2", "--out", str(out),
                         "--workers", "1", *FAKE]) == 0
    records = load_records(out).records
    assert sorted(records) == [f"open_loop/thin_cylinder/m0{j}/a{k}"
                               for j in range(2) for k in range(2)]


def test_set_options_follow_the_spec_files_overrides_into_every_record(tmp_path):
    spec = tmp_path / "hit.yaml"
    spec.write_text("objects: [box]\ncontrollers: [memorized]\nattempts: 1\n"
                    "scenario_overrides: ['disturbance.hit_time_s=7.0']\n")
    out = tmp_path / "out"
    assert sweep_main(["--spec", str(spec), "--set",
                         "controller.memorized_corrective.events=[hold_avoid]",
                         "--out", str(out), "--workers", "1", *FAKE]) == 0
    records = load_records(out).records
    assert len(records) == 9
    for record in records.values():
        assert record["trial"]["scenario_overrides"] == [
            "disturbance.hit_time_s=7.0",
            "controller.memorized_corrective.events=[hold_avoid]"]
    # The same folder with other settings is refused, not mixed.
    assert sweep_main(["--spec", str(spec), "--out", str(out), "--workers", "1",
                         *FAKE]) == 2


def test_trial_errors_give_exit_code_1(tmp_path, capsys):
    code = sweep_main(["--objects", "box", "--controllers", "memorized", "--attempts", "2",
                         "--out", str(tmp_path), "--workers", "2", "--no-progress",
                         "--trial-function", "tests.fake_trials:failing_fake_trial"])
    assert code == 1
    assert "9 trial(s) raised" in capsys.readouterr().out


@pytest.mark.parametrize("arguments, message, code", [
    (["--objects", "box", "teapot"], "field 'objects': unknown object 'teapot'", 2),
    (["--controllers", "pid"], "field 'controllers': unknown controller 'pid'", 2),
    (["--attempts", "0"], "--attempts must be a positive integer, got 0", 1),
    (["--workers", "0"], "--workers must be at least 1", 1),
    (["--benchmark", "--scheduler", "tcp://127.0.0.1:8786"], "drop --scheduler", 1),
    (["--set", "controller.memorized_corrective.events=[hold_smash]"],
     "error: --set 'controller.memorized_corrective.events=[hold_smash]': field "
     "'controller.memorized_corrective.events[0]' must name a corrective event", 2),
    (["--set", "object.name=box"],
     "error: --set 'object.name=box': 'object.name' is set per trial by the sweep", 2),
])
def test_bad_options_stop_before_any_trial(tmp_path, capsys, arguments, message, code):
    """Exit 2 for a spec refused (the options that set its fields), 1 for a runner's option
    or a number outside its range (bad input, as for any command)."""
    out = tmp_path / "out"
    assert sweep_main([*arguments, "--out", str(out), *FAKE]) == code
    assert message in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize("given, refused", [
    ("grasp.hold_s=1e7", "--set 'grasp.hold_s=1e7': field 'grasp.hold_s' must lie in"),
    ("grasp.hold_s=2", "field 'scenario_overrides[0]' 'grasp.grip_force=5000': field "
                       "'grasp.grip_force' must lie in"),
])
def test_a_refused_override_is_named_where_it_was_written(tmp_path, capsys, given, refused):
    """A spec file's entry by the file and its index; one given with --set by the option."""
    spec = tmp_path / "s.yaml"
    entries = "[grasp.grip_force=5000]" if given == "grasp.hold_s=2" else "[grasp.hold_s=2]"
    spec.write_text(f"objects: [box]\nscenario_overrides: {entries}\n")
    out = tmp_path / "out"
    assert sweep_main(["--spec", str(spec), "--set", given, "--out", str(out), *FAKE]) == 2
    err = capsys.readouterr().err
    assert refused in err, err
    where = f"{spec}: " if given == "grasp.hold_s=2" else "error: --set"
    assert where in err and "scenarios.yaml" not in err, err
    assert not out.exists()


@pytest.mark.parametrize("address, message", [
    ("tls://127.0.0.1:8786", "names the protocol tls://; tegrasp connects to a Dask "
     "scheduler over tcp:// only"),
    ("ucx://127.0.0.1:8786", "names the protocol ucx://"),
    ("WSS://127.0.0.1:8786", "names the protocol wss://"),
    ("tcp://127.0.0.1:0", "names port 0, which no scheduler listens on; give the port"),
])
def test_a_scheduler_address_tegrasp_cannot_connect_to_is_refused_by_its_form(
        tmp_path, capsys, address, message):
    """Only tcp:// (tls:// would need certificates, which no option gives) and a port a
    scheduler can listen on: refused in one line before any connection, exit 1."""
    out = tmp_path / "out"
    assert sweep_main(["--objects", "box", "--scheduler", address, "--out", str(out),
                         *FAKE]) == 1
    err = capsys.readouterr().err
    assert f"--scheduler {address!r} {message}" in err
    assert not out.exists()


def test_a_logs_folder_that_cannot_be_written_is_a_bad_option_as_out_is(tmp_path, capsys):
    """--logs where no folder can be made is bad input, exit 1 (as for --out), not the 2 of
    a refused spec."""
    (tmp_path / "afile").write_text("mine")
    out = tmp_path / "out"
    assert sweep_main(["--objects", "box", "--controllers", "memorized", "--attempts", "1",
                         "--logs", str(tmp_path / "afile" / "logs"), "--out", str(out),
                         *FAKE]) == 1
    err = capsys.readouterr().err
    assert f"--logs {tmp_path / 'afile' / 'logs'}" in err and "give a folder you can write" in err
    assert not (out / "trials").exists()
    assert (tmp_path / "afile").read_text() == "mine"


@pytest.mark.parametrize("text, message", [
    ("grid: []\n", "field 'grid': is empty"),
    ("grid: {normal_offsets_m: [0.0], stroke_offsets_m: []}\n",
     "field 'grid.stroke_offsets_m': is empty"),
    ("grid: [[0.0, zero]]\n", "field 'grid'"),
    ("objects: [box]\nspeed: 3\n", "field 'speed': unknown field"),
])
def test_bad_spec_file_stops_before_any_trial(tmp_path, capsys, text, message):
    spec, out = tmp_path / "bad.yaml", tmp_path / "out"
    spec.write_text(text)
    assert sweep_main(["--spec", str(spec), "--out", str(out), *FAKE]) == 2
    err = capsys.readouterr().err
    assert str(spec) in err and message in err
    assert not out.exists()


@pytest.mark.parametrize("arguments, spec_text, message", [
    (["--objects", "thick_cylinder", "--set",
      "controller.memorized_corrective.events=[hold_avoid]"], None,
     "no memorized events of object 'thick_cylinder'"),
    ([], "objects: [cup]\ncontrollers: [open_loop, memorized]\nuser_objects:\n"
         "  cup: {shape: cylinder, size: [0.03, 0.1], mass: 0.1, friction: 0.5}\n",
     "trial memorized/cup/m00/a0"),
])
def test_missing_memorized_events_stop_the_real_sweep_before_any_trial(
        tmp_path, capsys, arguments, spec_text, message):
    """The real trial function's events are checked once per object and controller
    before anything runs: one line naming the trial, the folders and what to do, exit 1
    (bad input: a file), no results folder (not one error record per trial)."""
    out = tmp_path / "out"
    if spec_text is not None:
        spec = tmp_path / "cup.yaml"
        spec.write_text(spec_text)
        arguments = ["--spec", str(spec)]
    assert sweep_main([*arguments, "--out", str(out), "--no-progress"]) == 1
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err and "Traceback" not in err
    assert not out.exists()


def test_dry_run_prints_the_plan_and_runs_nothing(tmp_path, capsys):
    spec = tmp_path / "wide.yaml"
    spec.write_text("objects: [box, cup]\ncontrollers: [open_loop, memorized]\nattempts: 2\n"
                    "grid: {normal_offsets_m: [-0.015, 0.0], stroke_offsets_m: [0.0, 0.025]}\n"
                    "user_objects:\n"
                    "  cup: {shape: cylinder, size: [0.03, 0.1], mass: 0.1, friction: 0.5}\n")
    out = tmp_path / "out"
    assert sweep_main(["--spec", str(spec), "--base-seed", "7", "--dry-run",
                         "--out", str(out), *FAKE]) == 0
    text = capsys.readouterr().out
    assert "32 trials (2 objects x 4 markers x 2 attempts x 2 controllers)" in text
    assert "base seed 7" in text and "about 16 core-minutes at 30 s a trial" in text
    assert "cup (cylinder [0.03, 0.1] m, 0.1 kg, friction 0.5)" in text
    assert "m01 (-15, +25)" in text
    assert not out.exists()


def test_dry_run_prints_its_plan_for_a_folder_another_run_is_writing_and_says_so(tmp_path,
                                                                                   capsys):
    """A dry run writes nothing, so a run writing into --out does not stop it; the lock says
    no more than that some run holds it (here a `tegrasp trial`'s), so no kind is named."""
    from tegrasp_drake.commands.run_folder import claimed_run_folder
    spec = tmp_path / "one.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0]]\n")
    out = tmp_path / "out"
    out.mkdir()
    with claimed_run_folder(out):  # a trial, still running
        code = cli.main(["sweep", "--spec", str(spec), "--dry-run", "--out", str(out), *FAKE])
    said = capsys.readouterr()
    assert code == 0, said
    assert "sweep plan (nothing run): 1 trial" in said.out
    assert said.err.strip().splitlines() == [
        f"tegrasp: warning: --out {out} is in use: another run is writing there now; the plan "
        "counts the records finished so far, and a real run is refused until it ends"]
    assert list(out.iterdir()) == []


def _files(folder):
    """Every file under `folder`: {relative path: (bytes, mtime_ns)}."""
    return {str(path.relative_to(folder)): (path.read_bytes(), path.stat().st_mtime_ns)
            for path in sorted(folder.rglob("*")) if path.is_file()}


def test_a_held_out_folder_refuses_a_resume_with_nothing_left_to_run(tmp_path, capsys):
    """The hold covers the whole command, its reports too: a resume of a finished sweep
    (nothing left to run, only reports to write) into a folder another run holds is
    refused at once in one line, and no report is rewritten."""
    from tegrasp_drake.rig.files import held_folder
    spec = tmp_path / "one.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0]]\n")
    out = tmp_path / "out"
    arguments = ["sweep", "--spec", str(spec), "--out", str(out), "--workers", "1", *FAKE]
    assert cli.main(arguments) == 0, capsys.readouterr()
    before = _files(out)
    assert "table1.md" in before
    capsys.readouterr()
    with held_folder(out):  # another run of it, writing its reports
        code = cli.main(arguments)
    said = capsys.readouterr()
    assert code == cli.EXIT_ERROR, said
    assert said.out == ""
    lines = said.err.strip().splitlines()
    assert len(lines) == 1 and "another run is writing there now" in lines[0], lines
    assert str(out) in lines[0]
    assert _files(out) == before


def _still_held(folder) -> bool:
    """Whether another hold has `folder` now (a second hold of it is refused)."""
    from tegrasp_drake.rig.files import FolderHeldError, held_folder
    try:
        with held_folder(folder):
            return False
    except FolderHeldError:
        return True


@pytest.mark.parametrize("command_name", ["sweep", "transfer", "sensitivity"])
def test_a_command_holds_its_out_folder_while_it_writes_its_reports(tmp_path, capsys,
                                                                    monkeypatch,
                                                                    command_name):
    """The runs (stubbed here: nothing is simulated) and then the reports, all under one
    hold of --out: a second run is refused while the reports are written, not only while
    trials run."""
    import tegrasp_drake.sensitivity.report as sensitivity_report
    import tegrasp_drake.sensitivity.study as study
    import tegrasp_drake.transfer.matrix as matrix
    import tegrasp_drake.transfer.report as transfer_report
    from tegrasp_drake.sweep.runner import SweepSummary
    out = tmp_path / "out"
    held_while_reporting = []

    def reports(*_, **__):
        held_while_reporting.append(_still_held(out))
        return []
    summary = SweepSummary(out_dir=out, total=1, skipped=1, ran=0, errors=(), unfinished=(),
                           corrupt=(), backend="processes:1", wall_time_s=0.0,
                           trial_ids=("t",), other_records=0, unwritten_log=None)
    monkeypatch.setattr(command, "run_sweep", lambda *_, **__: summary)
    monkeypatch.setattr(command, "write_reports", reports)
    monkeypatch.setattr(matrix, "run_transfer", lambda *_, **__: {"cell": summary})
    monkeypatch.setattr(transfer_report, "write_transfer_reports", reports)
    monkeypatch.setattr(study, "run_sensitivity", lambda *_, **__: {"point": summary})
    monkeypatch.setattr(sensitivity_report, "write_sensitivity_report", reports)
    sweep = ("sweep: {controllers: [memorized], attempts: 1, objects: [box], "
             "grid: [[0.0, 0.0]]}\n")
    spec = tmp_path / "spec.yaml"
    if command_name == "sweep":
        spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                        "grid: [[0.0, 0.0]]\n")
        arguments = ["sweep", "--spec", str(spec)]
    elif command_name == "transfer":
        spec.write_text("worlds: {a: {scenario: memorizing_world}}\ncells: [[a, a]]\n"
                        + sweep)
        arguments = ["transfer", str(spec)]
    else:
        spec.write_text("parameters: [tactile.pad_modulus_pa]\n" + sweep)
        arguments = ["sensitivity", str(spec)]
    code = cli.main([*arguments, "--out", str(out), "--workers", "1", *FAKE])
    assert code == 0, capsys.readouterr()
    assert held_while_reporting == [True]
    assert not _still_held(out)  # and given back at the end


@pytest.mark.parametrize("attempts, code, stream, words", [
    # One object, marker, attempt and controller read "1 object", not "1 objects".
    (1, 0, "out", "1 trial (1 object x 1 marker x 1 attempt x 1 controller)"),
    # The size refusal (a usage error) names the factors as the plan does.
    (100001, 2, "err", "100001 attempts x 1 object x 1 marker x 1 controller"),
])
def test_a_plan_counts_its_factors_in_the_singular_where_one(tmp_path, capsys, attempts, code,
                                                              stream, words):
    spec = tmp_path / "one.yaml"
    spec.write_text(f"objects: [box]\ncontrollers: [open_loop]\nattempts: {attempts}\n"
                    "grid: [[0.0, 0.0]]\n")
    assert sweep_main(["--spec", str(spec), "--dry-run", "--out", str(tmp_path / "out"),
                         *FAKE]) == code
    assert words in getattr(capsys.readouterr(), stream)


def test_dry_run_checks_the_events_as_the_real_sweep_does(tmp_path, capsys):
    """A dry run of the real trial function refuses missing events as a run would (exit 1,
    one line), so a plan it prints is one whose events are all there."""
    spec = tmp_path / "cup.yaml"
    spec.write_text("objects: [cup]\ncontrollers: [memorized]\nuser_objects:\n"
                    "  cup: {shape: cylinder, size: [0.03, 0.1], mass: 0.1, friction: 0.5}\n")
    out = tmp_path / "out"
    # the package's events folder: one of events, without the user object's
    assert sweep_main(["--spec", str(spec), "--dry-run", "--events", str(package_events_dir()),
                         "--out", str(out), "--no-progress"]) == 1
    captured = capsys.readouterr()
    assert "trial memorized/cup/m00/a0" in captured.err and "sweep plan" not in captured.out
    assert not out.exists()


def test_dry_run_refuses_a_logs_path_that_is_not_a_folder_as_the_run_does(tmp_path, capsys):
    (tmp_path / "trial.npz").write_bytes(b"PK\x03\x04 not a folder")
    arguments = ["--objects", "box", "--controllers", "memorized", "--attempts", "1",
                 "--logs", str(tmp_path / "trial.npz"), "--out", str(tmp_path / "out"), *FAKE]
    for dry_run in ([], ["--dry-run"]):
        assert sweep_main([*arguments, *dry_run]) == 1, dry_run
        captured = capsys.readouterr()
        assert f"--logs {tmp_path / 'trial.npz'}" in captured.err, (dry_run, captured.err)
        assert "sweep plan" not in captured.out


def test_dry_run_refuses_an_out_folder_of_records_made_with_other_settings(tmp_path, capsys):
    out = tmp_path / "out"
    common = ["--objects", "box", "--controllers", "memorized", "--attempts", "1",
              "--out", str(out), *FAKE]
    assert sweep_main(common) == 0
    capsys.readouterr()
    records = {path: path.stat().st_mtime_ns for path in (out / "trials").iterdir()}
    for dry_run in (["--dry-run"], []):  # the plan, then the run, refused alike
        assert sweep_main([*common, "--base-seed", "7", *dry_run]) == 2, dry_run
        captured = capsys.readouterr()
        assert "made with other settings" in captured.err, captured.err
        assert "sweep plan" not in captured.out
    assert {path: path.stat().st_mtime_ns for path in (out / "trials").iterdir()} == records


@pytest.mark.parametrize("damage", ["checksum", "fifo"])
def test_dry_run_names_a_damaged_record_and_prices_the_trials_left(tmp_path, capsys, damage):
    import os
    out = tmp_path / "out"
    common = ["--objects", "box", "--controllers", "memorized", "--attempts", "1",
              "--out", str(out), *FAKE]
    assert sweep_main(common) == 0  # 9 trials, all finished
    capsys.readouterr()
    record = sorted((out / "trials").glob("*.json"))[0]
    if damage == "checksum":
        record.write_text(record.read_text().replace('"box"', '"bux"', 1))
    else:
        record.unlink()
        os.mkfifo(record)
    assert sweep_main([*common, "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert "9 trials (1 object x 9 markers x 1 attempt x 1 controller), 8 already finished" \
        in text and "1 to run" in text, text
    assert f"corrupt record set aside as NAME.corrupt-<pid> and run again: {record}" in text
    assert "about 0 core-minutes" in text and "about 4 core-minutes" not in text  # 1 trial, not 9
    assert record.name in {path.name for path in (out / "trials").iterdir()}  # nothing moved


def test_a_missing_trial_function_is_reported(tmp_path, capsys):
    out = tmp_path / "out"
    assert sweep_main(["--out", str(out), "--no-progress",
                         "--trial-function", "no_such_module_xyz:run"]) == 2
    assert "cannot load the trial function no_such_module_xyz:run" in capsys.readouterr().err
    assert not out.exists()


def test_benchmark_prints_wall_times_and_speed_up(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    code = sweep_main(["--benchmark", "--objects", "box", "--attempts", "1",
                         "--no-progress", "--trial-function", "tests.fake_trials:slow_fake_trial"])
    assert code == 0
    lines = capsys.readouterr().out.splitlines()
    assert "1 worker(s): 9 trials" in lines[1] and "speed-up 1.00x" in lines[1]
    assert "2 worker(s): 9 trials" in lines[2] and "speed-up" in lines[2]
    assert lines[3].endswith("results identical across worker counts: yes")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("arguments, unused", [
    (["--workers", "1", "--out", "swb"], "drop --workers, --out"),
    (["--oversubscribe", "--format", "svg"], "drop --oversubscribe, --format"),
])
def test_benchmark_refuses_the_runner_options_it_does_not_use(tmp_path, monkeypatch, capsys,
                                                               arguments, unused):
    monkeypatch.chdir(tmp_path)
    assert sweep_main(["--benchmark", *arguments, *FAKE]) == 1
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "--benchmark times the local process pool" in error
    assert unused in error
    assert list(tmp_path.iterdir()) == []


def test_benchmark_dry_run_prints_the_plan_of_the_sweep_it_times(tmp_path, monkeypatch,
                                                                 capsys):
    monkeypatch.chdir(tmp_path)
    assert sweep_main(["--benchmark", "--dry-run", "--objects", "box", *FAKE]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("sweep plan (nothing run): 27 trials")
    assert lines[2] == "  controllers: memorized"
    assert lines[-1] == ("  the benchmark runs it on 1 and then 2 worker(s), each into a "
                         "temporary folder")


def test_statistics_json_is_valid(tmp_path):
    sweep_main(["--objects", "box", "--attempts", "1", "--workers", "2",
                  "--out", str(tmp_path), *FAKE])
    statistics = json.loads((tmp_path / "statistics.json").read_text())
    records = [json.loads(path.read_text()) for path in (tmp_path / "trials").glob("*.json")]
    by_controller = {}
    for record in records:
        by_controller.setdefault(record["trial"]["controller"], {})[
            record["trial"]["pair_id"]] = record["result"]
    assert set(statistics["controllers"]) == set(by_controller) == {
        "memorized", "heuristic", "open_loop"}
    for name, results in by_controller.items():  # each figure recomputed from the records
        figures = statistics["controllers"][name]
        assert figures["trials"] == len(results) == 9
        assert figures["false_triggers"]["total"] == sum(
            r["false_triggers"] for r in results.values())
        assert figures["corrective_actions"]["trials_with_any"] == sum(
            bool(r["corrective_actions"]) for r in results.values())
        latencies = [r["detection_latency_s"].get("reach_load") for r in results.values()]
        detected = [value for value in latencies if value is not None]
        if name == "open_loop":  # a script detects nothing: no latency, no figure
            assert not detected and figures["detection_latency_s"] == {}
            continue
        latency = figures["detection_latency_s"]["reach_load"]
        assert latency["n"] == len(detected)
        assert latency["not_detected"] == len(latencies) - len(detected)
        if detected:
            assert latency["median"] == pytest.approx(statistics_median(detected))
    comparisons = statistics["paired_comparisons"]
    assert len(comparisons) == 6  # 3 controller pairs x (hold, unload)
    for comparison in comparisons:
        key = "hold_success" if comparison["phase"] == "hold" else "unload_success"
        a = by_controller[comparison["controller_a"]]
        b = by_controller[comparison["controller_b"]]
        assert comparison["pairs"] == len(a.keys() & b.keys()) == 9
        assert comparison["a_success"] == sum(a[pair][key] for pair in a)
        assert comparison["b_success"] == sum(b[pair][key] for pair in b)
        assert comparison["a_only"] == sum(a[pair][key] and not b[pair][key] for pair in a)
        assert comparison["b_only"] == sum(b[pair][key] and not a[pair][key] for pair in a)
        assert 0.0 <= comparison["p_value"] <= 1.0


def test_a_smaller_spec_in_a_reused_folder_counts_only_its_own_trials(tmp_path, capsys):
    """--attempts 2, then --attempts 1 into the same folder: the second run counts and
    tabulates its own 9 trials, not all 18 in the folder."""
    out = tmp_path / "out"
    common = ["--objects", "box", "--controllers", "memorized", "--workers", "2",
              "--out", str(out), *FAKE]
    assert sweep_main([*common, "--attempts", "2"]) == 0
    capsys.readouterr()
    assert sweep_main([*common, "--attempts", "1"]) == 0
    stdout = capsys.readouterr().out
    assert "sweep: 9 trials, 9 already finished" in stdout
    assert "9 record(s) of trials not in this spec are in" in stdout
    rows = (out / "table1.csv").read_text().splitlines()
    header, box = rows[0].split(","), rows[1].split(",")
    trials = sum(int(box[header.index(f"{placement}_hold_trials")])
                 for placement in ("well_placed", "misplaced"))
    assert trials == 9


class _FakeClient:
    closed = False

    def close(self):
        self.closed = True


@pytest.mark.parametrize("verbose, held", [(0, True), (2, False)])
def test_the_scheduler_connection_holds_dasks_logs_until_its_client_is_closed(
        verbose, held, monkeypatch):
    """Entered: connected, distributed's logger silenced (unless -vv); left, also by an
    error: the client closed, then the logger's level given back."""
    import logging
    from tegrasp_drake.sweep import runner
    client = _FakeClient()
    monkeypatch.setattr(runner, "connect_scheduler", lambda address, announce=None: client)
    dask_logger = logging.getLogger("distributed")
    monkeypatch.setattr(dask_logger, "level", logging.INFO)
    args = argparse.Namespace(scheduler="tcp://127.0.0.1:8786", verbose=verbose)
    with pytest.raises(KeyError):
        with command.scheduler_connection(args, "sweep") as connected:
            assert connected is client and not client.closed
            assert (dask_logger.level > logging.CRITICAL) == held
            raise KeyError("the command's body failed")
    assert client.closed and dask_logger.level == logging.INFO


def test_a_scheduler_that_does_not_answer_is_an_option_error(monkeypatch):
    from tegrasp_drake.sweep import runner

    def refuse(address, announce=None):
        raise runner.SweepError(f"cannot reach the Dask scheduler at {address}")
    monkeypatch.setattr(runner, "connect_scheduler", refuse)
    args = argparse.Namespace(scheduler="tcp://127.0.0.1:9", verbose=0)
    with pytest.raises(command.OptionError, match="cannot reach the Dask scheduler"):
        with command.scheduler_connection(args, "sweep"):
            pass


# Rule: distributed retries an address where nothing listens until its timeout (half a minute
# and more): the command says what it connects to, and for how long at most, before it tries,
# unless --quiet; the refusal follows as its one error line.
@pytest.mark.parametrize("quiet", [False, True])
def test_the_scheduler_connection_says_what_it_connects_to_before_it_tries(
        quiet, monkeypatch, capsys):
    from tegrasp_drake.sweep import runner
    said = []

    def refuse(address, announce=None):
        announce()  # the extra found: said just before connecting
        said.append(capsys.readouterr().err)  # what was on stderr when the connect began
        raise runner.SweepError(f"cannot reach the Dask scheduler at {address}")
    monkeypatch.setattr(runner, "connect_scheduler", refuse)
    args = argparse.Namespace(scheduler="tcp://127.0.0.1:1", verbose=0, quiet=quiet)
    with command.refusals_said() as refused:
        with command.scheduler_connection(args, "transfer"):
            pass
    assert refused.exit_code == 1
    expected = ("" if quiet else "tegrasp transfer: connecting to the Dask scheduler at "
                f"tcp://127.0.0.1:1 (at most {runner.DASK_ANSWER_BOUND_S:.0f} s) ...\n")
    assert said == [expected]
    assert capsys.readouterr().err == ("tegrasp: error: cannot reach the Dask "
                                       "scheduler at tcp://127.0.0.1:1\n")


@pytest.mark.parametrize("error, code", [
    (command.OptionError("--workers 0"), 1),
    (command.SchedulerLostError("lost the Dask scheduler"), 1),
    (command.ConfigError("field 'attempts'"), 2),
    (command.SweepError("another sweep's records"), 2)])
def test_a_sweep_commands_refusal_is_one_line_and_its_exit_code(error, code, capsys):
    with command.refusals_said() as refused:
        raise error
    assert refused.exit_code == code
    assert capsys.readouterr().err == f"tegrasp: error: {error}\n"


def test_unreadable_memorized_events_end_a_sweep_command_as_bad_input():
    from tegrasp_drake.events import MemorizedEventError
    with pytest.raises(SystemExit, match="^tegrasp: error: ") as ended:
        with command.refusals_said():
            raise MemorizedEventError("events/index.json", "not JSON")
    assert "events/index.json" in str(ended.value)
