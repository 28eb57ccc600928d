"""Sweep records are read by what they hold: a record that is not a file, whose result is out
of range, contradicts itself or is not its trial's, of another trial or of a trial no sweep
makes, is corrupt, kept aside with a warning and run again; a trial function's result the
records would refuse is an error, not a record; records and reports of a folder without
records are refused in one line."""

import json
import os

import pytest

import tegrasp_drake
from tegrasp_drake.rig import files
from tegrasp_drake.sweep.records import _checksum, load_records, record_path
from tegrasp_drake.sweep.runner import run_sweep, run_trial_safely
from tegrasp_drake.sweep.spec import RandomisationConfig, SweepSpec, expand_trials
from tests.bad_input.probes import (assert_one_line_error, deny_reading, events_copy_with_index,
                                    finished_fake_sweep, forge_record, run_cli,
                                    sweep_with_events)
from tests.fake_trials import fake_trial, whole_result


def test_records_of_a_file_or_of_no_folder_are_refused(tmp_path):
    log = tmp_path / "trial.npz"
    log.write_bytes(b"PK")
    with pytest.raises(files.UserPathError, match="'out_dir'.*is a file, not a folder"):
        tegrasp_drake.load_records(log)
    with pytest.raises(files.UserPathError, match="'out_dir'.*does not exist"):
        tegrasp_drake.load_records(tmp_path / "not yet")
    assert tegrasp_drake.load_records(tmp_path).records == {}


def test_records_of_a_folder_that_does_not_exist_are_an_error(tmp_path):
    with pytest.raises(files.UserPathError, match="'out_dir'.*does not exist"):
        tegrasp_drake.load_records(tmp_path / "nonexistent")


# --- 2. a folder in place of a sweep record ------------------------------------------------------

def test_a_folder_in_place_of_a_sweep_record_is_refused_before_the_trial_runs(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0]]\n")
    argv = ["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"), "--workers", "1",
            "--no-progress", "--trial-function", "tests.fake_trials:fake_trial"]
    assert run_cli(argv, capfd)[0] == 0
    record = next((tmp_path / "out" / "trials").glob("*.json"))
    record.unlink()
    record.mkdir()
    (record / "mine.txt").write_text("kept")
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, str(record), "is a folder", "nothing was run")
    assert (record / "mine.txt").read_text() == "kept"


# Rule: `tegrasp sweep --dry-run` refuses an --out the real run refuses, by the same check
# and in the same words, as a folder that cannot be used (exit 1): a folder in a record's
# place, a `trials` that is no folder (a file, a dangling link); a corrupt record file the
# run sets aside is no refusal.
@pytest.mark.parametrize("make, words", [
    (lambda trials, record: (record.mkdir(parents=True), (record / "mine.txt").write_text("x")),
     "is a folder where a file belongs"),
    (lambda trials, record: trials.write_text("x"), "trials is not a folder"),
    (lambda trials, record: trials.symlink_to(trials.parent / "gone"), "trials is not a folder"),
])
def test_a_dry_run_refuses_the_record_places_the_run_refuses(make, words, tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0]]\n")
    out = tmp_path / "out"
    out.mkdir()
    trial_id = expand_trials(SweepSpec(objects=("box",), controllers=("open_loop",),
                                       attempts=1, grid=((0.0, 0.0),)))[0].trial_id
    make(out / "trials", record_path(out, trial_id))
    argv = ["sweep", "--spec", str(spec), "--out", str(out), "--workers", "1", "--no-progress",
            "--trial-function", "tests.fake_trials:fake_trial"]
    dry = run_cli([*argv, "--dry-run"], capfd)
    real = run_cli(argv, capfd)
    assert dry[0] == real[0] == 1, (dry, real)  # a folder that cannot be used
    assert_one_line_error(dry[0], dry[1], words, "nothing was run")
    assert dry[1] == real[1]


# Rule: a `trials` folder this user cannot write in (another user's) is refused before any
# trial runs, by the real run and its dry run alike, as a folder that cannot be used (exit 1):
# a trial's result is never simulated only to be lost.
def test_a_trials_folder_that_cannot_be_written_is_refused_before_any_trial(
        tmp_path, capfd, monkeypatch):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0], [0.01, 0.0]]\n")
    out = tmp_path / "out"
    argv = ["sweep", "--spec", str(spec), "--out", str(out), "--workers", "1", "--no-progress",
            "--trial-function", "tests.fake_trials:fake_trial"]
    assert run_cli(argv, capfd)[0] == 0
    records = sorted((out / "trials").glob("*.json"))
    records[0].unlink()
    kept = records[1].read_bytes()
    access = files.os.access  # the folder is another user's (root ignores modes: said here)
    monkeypatch.setattr(files.os, "access", lambda path, mode, **kw: (
        False if str(path) == str(out / "trials") else access(path, mode, **kw)))
    dry = run_cli([*argv, "--dry-run"], capfd)
    real = run_cli(argv, capfd)
    assert dry[0] == real[0] == 1, (dry, real)
    assert_one_line_error(real[0], real[1], f"{out / 'trials'} is not writable",
                          "give a folder you can write", "nothing was run")
    assert "free some space" not in real[1]
    assert dry[1] == real[1]
    assert not records[0].exists() and records[1].read_bytes() == kept


# Rule: a dry run leaves no trace: its checks that --out, its trials/ and --logs can be
# written ask os.access (files.unprobed_folder_checks), making no probe entry there, so no
# folder's modification time changes, and no missing folder is made.
def test_a_dry_run_makes_no_probe_in_the_folders_it_checks(tmp_path, capfd, monkeypatch):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0]]\n")
    out, logs = tmp_path / "out", tmp_path / "logs"
    (out / "trials").mkdir(parents=True)
    logs.mkdir()
    monkeypatch.setattr(files.tempfile, "mkdtemp",
                        lambda *a, **k: pytest.fail(f"a probe was made in {k.get('dir')}"))
    folders = (tmp_path, out, out / "trials", logs)
    before = {folder: os.stat(folder).st_mtime_ns for folder in folders}
    new = tmp_path / "new"
    for given_out, given_logs in ((out, logs), (new / "out", new / "logs")):
        code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(given_out), "--logs",
                              str(given_logs), "--trial-function",
                              "tests.fake_trials:fake_trial", "--dry-run"], capfd)
        assert code == 0, text
    assert {folder: os.stat(folder).st_mtime_ns for folder in folders} == before
    assert not (tmp_path / "new").exists()
    assert list((out / "trials").iterdir()) == [] and list(logs.iterdir()) == []


def test_a_write_refused_for_permission_is_not_told_to_free_space(tmp_path, monkeypatch):
    def refused(*args, **kwargs):
        raise PermissionError(13, "Permission denied")
    monkeypatch.setattr(files, "staged_file", refused)
    with pytest.raises(files.UserPathError) as raised:
        files.write_atomically(tmp_path / "a.json", "{}", start=files.JSON_OBJECT_START)
    assert "Permission denied; give a folder you can write" in str(raised.value)
    assert "space" not in str(raised.value)

    def full(*args, **kwargs):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(files, "staged_file", full)
    with pytest.raises(files.UserPathError, match="No space left on device; free some space"):
        files.write_atomically(tmp_path / "a.json", "{}", start=files.JSON_OBJECT_START)


def test_a_dry_run_plans_over_a_corrupt_record_the_run_sets_aside(tmp_path, capfd):
    out = tmp_path / "out"
    trial_id = expand_trials(SweepSpec(objects=("box",), controllers=("open_loop",),
                                       attempts=1, grid=((0.0, 0.0),)))[0].trial_id
    record_path(out, trial_id).parent.mkdir(parents=True)
    record_path(out, trial_id).write_text("{")
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "open_loop",
                          "--attempts", "1", "--out", str(out), "--dry-run"], capfd)
    assert code == 0, text
    assert record_path(out, trial_id).read_text() == "{"


def test_record_result_refuses_what_is_not_a_trial_record():
    from tegrasp_drake.sweep.records import record_result
    with pytest.raises(ValueError, match="argument 'record' is not a sweep record .*got the "
                                         "keys a\\)"):
        record_result({"a": 1})
    with pytest.raises(ValueError, match="no 'result'; got an empty dict\\); give a record"):
        record_result({})
    with pytest.raises(ValueError, match="'result' is not a trial's result"):
        record_result({"status": "ok", "result": {"a": 1}})
    assert record_result({"status": "error", "result": None}) is None


# Rule: a corrupt record in a sweep's folder is said, one line naming the file, before its
# trial runs again, and kept aside rather than overwritten.
def test_a_corrupt_sweep_record_is_said_and_kept_aside_before_its_trial_reruns(tmp_path, caplog):
    from tegrasp_drake.sweep.records import record_path
    from tegrasp_drake.sweep.runner import run_sweep
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    from tests.fake_trials import fake_trial
    spec = SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                     grid=((0.0, 0.0),))
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    damaged = record_path(tmp_path, expand_trials(spec)[0].trial_id)
    damaged.write_text('{"trunc')
    with caplog.at_level("WARNING", logger="tegrasp_drake.sweep.runner"):
        summary = run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    assert summary.ran == 1
    said = [r.getMessage() for r in caplog.records if str(damaged) in r.getMessage()]
    assert len(said) == 1 and "re-run" in said[0] and "\n" not in said[0]
    (kept,) = tmp_path.glob(f"**/{damaged.name}.corrupt-*")
    assert kept.read_text() == '{"trunc'


# Rule: a file under trials/ whose name is no trial's record (CONTROLLER.OBJECT.MARKER.aK.json)
# is the user's, not the sweep's: a resumed sweep leaves it exactly where and as it is, says so
# in one line (no trial is re-run for it), and the reports do not count it as a corrupt record;
# the sweep's own corrupt record beside it is still set aside and its trial run again.
def test_a_users_file_among_the_records_is_left_alone_and_said_not_the_sweeps(tmp_path,
                                                                             caplog):
    from tegrasp_drake.sweep.records import record_path
    spec = SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                     grid=((0.0, 0.0), (0.0, 0.005)))
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    stray = tmp_path / "trials" / "zzz.json"
    stray.write_text('{"my": "notes"}')
    damaged = record_path(tmp_path, expand_trials(spec)[0].trial_id)
    damaged.write_text('{"trunc')
    with caplog.at_level("WARNING", logger="tegrasp_drake.sweep.runner"):
        summary = run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    assert stray.read_text() == '{"my": "notes"}'  # not renamed, not changed
    assert not list(stray.parent.glob("zzz.json.corrupt-*"))
    said = [r.getMessage() for r in caplog.records if str(stray) in r.getMessage()]
    assert said == [f"sweep: {stray}: its name is no trial's record (records are named "
                    "CONTROLLER.OBJECT.MARKER.aK.json), so it is not the sweep's; left alone "
                    "as it is"], said
    assert (summary.ran, summary.corrupt) == (1, (str(damaged),))
    (kept,) = damaged.parent.glob(f"{damaged.name}.corrupt-*")  # the sweep's own: set aside
    assert kept.read_text() == '{"trunc'
    loaded = load_records(tmp_path)
    assert loaded.corrupt == {} and loaded.others == (stray,)
    assert loaded.corrupt_problem(tmp_path) is None  # the reports are made


# Rule: a record that names no format_version (absent or null) is said to be none a sweep
# wrote, never "format_version None".
@pytest.mark.parametrize("remove", [lambda data: data.pop("format_version"),
                                    lambda data: data.update(format_version=None)])
def test_a_sweep_record_without_a_format_version_says_no_sweep_wrote_it(remove, tmp_path):
    spec = SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                     grid=((0.0, 0.0),))
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    damaged = record_path(tmp_path, expand_trials(spec)[0].trial_id)
    record = json.loads(damaged.read_text())
    remove(record)
    damaged.write_text(json.dumps(record))
    why = load_records(tmp_path).corrupt[damaged]
    assert why == "it has no format_version, so no sweep wrote it", why


# Rule: a record saved with a UTF-8 byte-order mark is said to start with one (the reader of
# every JSON file says so), not "is not ASCII text".
def test_a_sweep_record_with_a_byte_order_mark_says_so(tmp_path):
    spec = SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                     grid=((0.0, 0.0),))
    run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    damaged = record_path(tmp_path, expand_trials(spec)[0].trial_id)
    damaged.write_bytes(b"\xef\xbb\xbf" + damaged.read_bytes())
    why = load_records(tmp_path).corrupt[damaged]
    assert why.startswith("starts with a UTF-8 byte-order mark"), why


# Rule: a public function checks its arguments as the command line does. Reports of a folder
# that holds no trial records (none at all, or only corrupt ones) are refused naming the
# argument and the folder, and nothing is written; `tegrasp plot table1` refuses it alike.
@pytest.mark.parametrize("corrupt", [False, True])
def test_reports_of_a_folder_without_trial_records_are_refused(tmp_path, corrupt):
    import tegrasp_drake as T
    (tmp_path / "trials").mkdir()
    if corrupt:
        (tmp_path / "trials" / "memorized.box.m00.a0.json").write_text("{not json")
    before = sorted(p.name for p in tmp_path.rglob("*"))
    with pytest.raises(ValueError, match=r"write_reports: argument 'out_dir'.*no trial record"):
        T.write_reports(tmp_path)
    assert sorted(p.name for p in tmp_path.rglob("*")) == before


def test_records_that_do_not_name_their_events_are_kept_with_a_warning(tmp_path, capfd,
                                                                       caplog):
    from tegrasp_drake.sweep import load_records
    from tegrasp_drake.sweep.records import _checksum
    events, out = events_copy_with_index(tmp_path), tmp_path / "out"
    code, text = sweep_with_events(tmp_path, out, events, capfd)
    assert code == 0, text
    paths = sorted((out / "trials").glob("*.json"))
    old = json.loads(paths[0].read_text())  # as a record of format 1 was written
    del old["events"], old["checksum"]
    old["format_version"] = 1
    old["checksum"] = _checksum(old)
    paths[0].write_text(json.dumps(old))
    paths[1].unlink()
    code, text = sweep_with_events(tmp_path, out, events, capfd)
    assert code == 0, text
    assert "1 finished record(s) do not name the memorized events" in caplog.text
    assert len(load_records(out).records) == 2


# Rule: a sweep record names the events folder it matched against resolved (absolute), so a
# record read from another working folder names the right one; a record naming it relative
# (as records did before) still loads.
def test_a_sweep_record_names_its_events_folder_resolved(tmp_path, monkeypatch):
    import shutil

    from tegrasp_drake.rig import paths
    from tegrasp_drake.sweep.records import check_record, make_record
    from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
    from tegrasp_drake.sweep.trial_function import events_identities
    shutil.copytree(paths.package_events_dir() / "box", tmp_path / "ev" / "box")
    shutil.copy(paths.package_events_dir() / "index.json", tmp_path / "ev")
    monkeypatch.chdir(tmp_path)
    trials = [t.to_dict() for t in expand_trials(SweepSpec(
        objects=("box",), controllers=("memorized",), attempts=1, grid=((0.0, 0.0),)))]
    identity = events_identities(trials, "ev")[trials[0]["trial_id"]]
    assert identity["folder"] == str(tmp_path.resolve() / "ev")
    old = make_record(trials[0], result=fake_trial(trials[0]),
                      events={**identity, "folder": "ev"})
    assert check_record(old) is None

ONE_TRIAL = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1,
                      grid=((0.0, 0.0),))


def _forge(folder, edit):
    """Runs ONE_TRIAL into `folder`, then rewrites its record's result with `edit` and a
    checksum that matches, as a hand edit would; returns the record's path."""
    summary = run_sweep(ONE_TRIAL, fake_trial, folder, workers=1, progress=False)
    path = record_path(folder, summary.trial_ids[0])
    record = json.loads(path.read_text())
    edit(record["result"])
    del record["checksum"]
    record["checksum"] = _checksum(record)
    path.write_text(json.dumps(record))
    return path


def _set(**fields):
    return lambda result: result.update(fields)


@pytest.mark.parametrize("edit, field", [
    (_set(hold_success="yes"), "hold_success"),
    (_set(final_mode="Exploded"), "Exploded"),
    (_set(final_tilt_deg=720.0), "final_tilt_deg"),
    (lambda result: result["transitions"][0].update(t=-3.0), "field 't'"),
])
def test_a_record_whose_result_is_out_of_range_is_corrupt_and_runs_again(
        tmp_path, edit, field):
    path = _forge(tmp_path, edit)
    loaded = load_records(tmp_path)
    assert loaded.records == {}
    assert field in loaded.corrupt[path] and "'result'" in loaded.corrupt[path]
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.skipped, summary.corrupt) == (1, 0, (str(path),))
    assert list(tmp_path.glob("trials/*.corrupt-*"))  # kept aside, not lost
    assert load_records(tmp_path).corrupt == {}


def _failed(result):
    """The result of a trial that failed in Load, with a reason of 50000 characters."""
    result["transitions"][1:] = [{"t": 2.0, "from": "Load", "to": "Failed", "trigger": "timer",
                                  "reason": "no Load-Lift event"}]
    result.update(final_mode="Failed", hold_success=False, unload_success=False,
                  released=False, failure="x" * 50000)


@pytest.mark.parametrize("edit, field", [
    (_set(hold_success=False, unload_success=True), "'unload_success' is true"),
    (lambda result: result["detection_latency_s"].update({"reach->load": 1e300}),
     "detection_latency_s.reach->load"),
    (lambda result: result["transitions"][0].update(t=9.0), "transitions[0].t"),
    (_set(physical_events={"reach_load": 50.0}), "physical_events.reach_load"),
    (_set(hold_time_s=9.0), "hold_time_s"),
    (_failed, "'failure' must be at most"),
])
def test_a_record_whose_result_contradicts_itself_is_corrupt(tmp_path, edit, field):
    path = _forge(tmp_path, edit)
    loaded = load_records(tmp_path)
    assert loaded.records == {}
    assert field in loaded.corrupt[path]


def unload_without_hold_trial(trial):
    """fake_trial's result, unloaded without a hold: no trial run produces it."""
    return {**fake_trial(trial), "hold_success": False, "unload_success": True}


def test_a_trial_function_result_the_records_would_refuse_is_an_error_not_a_record(tmp_path):
    summary = run_sweep(ONE_TRIAL, unload_without_hold_trial, tmp_path, workers=1,
                        progress=False)
    record = load_records(tmp_path).records[summary.errors[0]]
    assert record["error"]["type"] == "InvalidResult"
    assert "'unload_success' is true" in record["error"]["message"]


def _forge_record(folder, edit):
    return forge_record(folder, ONE_TRIAL, None, edit)


# Rule: a record is its trial's: a result naming another seed, controller or object, or a
# record holding both a result and an error, is corrupt (kept aside, its trial run again).
@pytest.mark.parametrize("edit, words", [
    (lambda r: r["result"].update(seed=r["trial"]["seed"] + 1), "result's seed"),
    # another controller that fires the trial's triggers (else those are named first)
    (lambda r: r["result"].update(controller="taxel_aware"), "result's controller"),
    (lambda r: r["result"].update(object="thin_cylinder"), "result's object"),
    (lambda r: r.update(status="error", error={"type": "RuntimeError", "message": "x"}),
     "an error and no result"),
    (lambda r: r["trial"].update(trial_id="heuristic/box/m00/a0"), "trial_id"),
])
def test_a_record_of_another_trial_is_corrupt_and_runs_again(tmp_path, edit, words):
    path = _forge_record(tmp_path, edit)
    loaded = load_records(tmp_path)
    assert loaded.records == {} and words in loaded.corrupt[path], loaded.corrupt
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.skipped) == (1, 0)


# Rule: a FIFO or a device link in a record's place is a record that cannot be read: named in
# one warning, kept aside as NAME.corrupt-PID (the entry itself), and its trial runs again.
@pytest.mark.parametrize("make", [
    lambda path: __import__("os").mkfifo(path),
    lambda path: path.symlink_to("/dev/zero"),
], ids=["fifo", "device-link"])
def test_a_record_that_is_no_file_is_kept_aside_with_a_warning(tmp_path, caplog, make):
    import logging
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    path = record_path(tmp_path, summary.trial_ids[0])
    path.unlink()
    make(path)
    with caplog.at_level(logging.WARNING):
        summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.skipped) == (1, 0)
    assert any(path.name in message and "kept as" in message for message in caplog.messages)
    (kept,) = list(path.parent.glob(f"{path.name}.corrupt-*"))
    assert kept.is_symlink() or not kept.is_file()
    assert path.is_file() and load_records(tmp_path).corrupt == {}


# Two markers, so that one trial is well placed and one is not.
SPEC = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1,
                 grid=((0.0, 0.0), (0.01, 0.0)), base_seed=620)

WELL_PLACED, MISPLACED = "memorized/box/m00/a0", "memorized/box/m10/a0"


def _forge_spec_record(folder, trial_id, edit):
    """SPEC's record of `trial_id`, hand-edited with `edit` (forge_record)."""
    return forge_record(folder, SPEC, trial_id, edit)


def _trial(**fields):
    return lambda record: record["trial"].update(fields)


def _perturbation(**fields):
    return lambda record: record["trial"]["perturbation"].update(fields)


def _seeds(seed):
    def edit(record):
        record["trial"]["seed"] = seed
        record["result"]["seed"] = seed
    return edit


def _assert_corrupt_and_run_again(folder, path, words):
    loaded = load_records(folder)
    assert path not in {record_path(folder, t) for t in loaded.records}
    assert words in loaded.corrupt[path] and "'trial'" in loaded.corrupt[path], loaded.corrupt
    summary = run_sweep(SPEC, fake_trial, folder, workers=1, progress=False)
    assert (summary.ran, summary.corrupt) == (1, (str(path),))
    assert list(path.parent.glob(f"{path.name}.corrupt-*"))  # kept aside, not lost
    assert load_records(folder).corrupt == {}


# Rule: a record's trial is one the sweep makes: each field within the range declared beside
# it (the perturbation within what the randomisation bounds can draw, attempts from 0), its
# ids made of its object, marker and attempt, well placed exactly at the (0, 0) marker, and
# its seed the one its base seed and scene give; any other is corrupt and its trial runs again.
@pytest.mark.parametrize("trial_id, edit, words", [
    (MISPLACED, _perturbation(mass_scale=-1.0), "perturbation.mass_scale"),
    (MISPLACED, _perturbation(mass_scale=5.0), "perturbation.mass_scale"),
    (MISPLACED, _perturbation(friction_scale=0.0), "perturbation.friction_scale"),
    (MISPLACED, _perturbation(dx_m=0.3), "perturbation.dx_m"),
    (MISPLACED, _trial(attempt=-3), "attempt"),
    (MISPLACED, _trial(pair_id="../../x"), "pair_id"),
    (MISPLACED, _trial(marker="../m10"), "marker"),
    (MISPLACED, _trial(well_placed=True), "well_placed"),
    (WELL_PLACED, _trial(marker_dx_m=0.01), "well_placed"),
    (MISPLACED, _seeds(7), "seed"),
    (MISPLACED, _trial(base_seed=9999), "seed"),
    (MISPLACED, _trial(perturbation={"dx_m": 0.0}), "perturbation"),
], ids=["negative-mass", "mass-x5", "no-friction", "jitter-30cm", "attempt", "pair-id",
        "marker", "well-placed", "marker-moved", "seed", "base-seed", "perturbation-fields"])
def test_a_record_whose_trial_no_sweep_makes_is_corrupt_and_runs_again(
        tmp_path, trial_id, edit, words):
    path = _forge_spec_record(tmp_path, trial_id, edit)
    _assert_corrupt_and_run_again(tmp_path, path, words)


def _rebased(base_seed):
    """A forger's edit: another base seed, the seed it gives the scene recomputed, the
    perturbation (what the trial ran with) kept."""
    def edit(record):
        from tegrasp_drake.sweep.spec import scene_seeds
        trial = record["trial"]
        _, seed = scene_seeds(base_seed, trial["object_name"],
                              (trial["marker_dx_m"], trial["marker_dy_m"]), trial["attempt"])
        trial.update(base_seed=base_seed, seed=seed)
        record["result"]["seed"] = seed
    return edit


def _nudged(field, by):
    return lambda record: record["trial"]["perturbation"].update(
        {field: record["trial"]["perturbation"][field] + by})


def _flipped(field):
    return lambda record: record["trial"]["perturbation"].update(
        {field: -record["trial"]["perturbation"][field]})


# Rule: a record's perturbation is its seed's draw (the seed's uniforms under one set of
# randomisation bounds): a base seed changed and its seed recomputed, or a draw edited, is
# corrupt and its trial runs again.
@pytest.mark.parametrize("edit, words", [
    (_rebased(621), "perturbation."),
    (_nudged("dy_m", 1e-6), "perturbation.d"),  # dx and dy share a bound: one is named
    (_flipped("yaw_rad"), "perturbation.yaw_rad"),
], ids=["base-seed-recomputed", "jitter-nudged", "yaw-flipped"])
def test_a_record_whose_perturbation_is_not_its_seeds_draw_is_corrupt_and_runs_again(
        tmp_path, edit, words):
    path = _forge_spec_record(tmp_path, MISPLACED, edit)
    _assert_corrupt_and_run_again(tmp_path, path, words)


def test_a_plot_of_a_record_whose_perturbation_is_not_its_seeds_draw_is_refused_in_one_line(
        tmp_path, monkeypatch, capfd):
    _forge_spec_record(tmp_path / "sweep", MISPLACED, _rebased(621))
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["plot", "latency", "sweep", "--out", "latency.png"], capfd)
    assert_one_line_error(code, text, "memorized.box.m10.a0.json", "perturbation.")
    assert not (tmp_path / "latency.png").exists()


@pytest.mark.parametrize("randomisation", [
    RandomisationConfig(), RandomisationConfig(0.0, 0.0, 0.0, 0.0),
    RandomisationConfig(0.02, 180.0, 0.999999, 1e-12)], ids=["default", "none", "extremes"])
def test_the_draws_of_any_randomisation_bounds_are_read(randomisation):
    from tegrasp_drake.sweep.spec import expand_trials, trial_problem
    spec = SweepSpec(base_seed=620, attempts=2, randomisation=randomisation)
    assert [t.trial_id for t in expand_trials(spec) if trial_problem(t.to_dict())] == []


def test_the_trials_a_sweep_makes_are_read():
    from tegrasp_drake.sweep.spec import expand_trials, trial_problem
    spec = SweepSpec(base_seed=620, attempts=2)  # the paper's objects, grid and controllers
    assert [t.trial_id for t in expand_trials(spec) if trial_problem(t.to_dict())] == []


def _result(**fields):
    return lambda record: record["result"].update(fields)


def _events(**identity):
    return lambda record: record.update(events=identity)


# Rule: a record's result is where its trial put the object (the marker moved by the jitter),
# and its events identity is a SHA-256 and a folder (or null), as a sweep writes it.
@pytest.mark.parametrize("edit, words", [
    (_result(offset_m=[0.19, -0.19]), "offset_m"),
    (_result(offset_m=[0.01, 0.0]), "offset_m"),  # the marker, without its jitter
    (_events(folder="/etc", sha256="zz"), "events.sha256"),
    (_events(folder="", sha256="0" * 64), "events.folder"),
], ids=["offset-far", "offset-without-jitter", "events-digest", "events-folder-empty"])
def test_a_record_whose_result_is_not_its_trials_is_corrupt_and_runs_again(
        tmp_path, edit, words):
    path = _forge_spec_record(tmp_path, MISPLACED, edit)
    loaded = load_records(tmp_path)
    assert words in loaded.corrupt[path], loaded.corrupt
    summary = run_sweep(SPEC, fake_trial, tmp_path, workers=1, progress=False)
    assert (summary.ran, summary.corrupt) == (1, (str(path),))


# Rule: a record names memorized events only for a controller that reads them; the open-loop
# script reads none, so a sweep records null for it.
@pytest.mark.parametrize("controller, corrupt", [("open_loop", True), ("memorized", False)])
def test_a_record_naming_events_its_controller_never_reads_is_corrupt(
        tmp_path, controller, corrupt):
    spec = SweepSpec(objects=("box",), controllers=(controller,), attempts=1,
                     grid=((0.0, 0.0),))
    summary = run_sweep(spec, fake_trial, tmp_path, workers=1, progress=False)
    path = record_path(tmp_path, summary.trial_ids[0])
    record = json.loads(path.read_text())
    record["events"] = {"folder": None, "sha256": "0" * 64}
    del record["checksum"]
    record["checksum"] = _checksum(record)
    path.write_text(json.dumps(record))
    reason = load_records(tmp_path).corrupt.get(path)
    if corrupt:
        assert reason and ("events names memorized events, but its trial's open_loop "
                           "controller reads none") in reason, reason
    else:
        assert reason is None


# Rule: a result's real-time factor is its simulated time over its wall time, as run_trial
# writes it; a factor of 1e300 on a 8 s trial that took 2 s is refused.
@pytest.mark.parametrize("data, words", [
    ({"sim_time_s": 8.0, "wall_time_s": 2.0, "real_time_factor": 1e300}, "sim_time_s / wall"),
    ({"sim_time_s": 8.0, "wall_time_s": 2.0, "real_time_factor": 0.0}, "sim_time_s / wall"),
    ({"sim_time_s": 8.0, "wall_time_s": 0.0, "real_time_factor": 3.0}, "wall_time_s' is 0"),
])
def test_a_real_time_factor_not_simulated_over_wall_time_is_refused(data, words):
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ValueError, match=words):
        TrialResult.from_dict(whole_result(**data))


# Rule: a sweep trial runs at most the longest scenario time limit (a grasp script within
# its limit plus the time for corrections); a record of a longer run is corrupt.
def test_a_record_of_a_run_longer_than_any_sweep_trial_is_corrupt(tmp_path):
    path = _forge_spec_record(tmp_path, MISPLACED, _result(sim_time_s=1e12))
    loaded = load_records(tmp_path)
    assert "sim_time_s" in loaded.corrupt[path], loaded.corrupt

ONE_TRIAL_SPEC = SweepSpec(objects=("box",), controllers=("memorized",), attempts=1, base_seed=650)


def _first_trial() -> dict:
    return expand_trials(ONE_TRIAL_SPEC)[0].to_dict()


@pytest.mark.parametrize("field, value", [("seed", 1), ("controller", "taxel_aware"),
                                          ("object", "thin_cylinder"),
                                          ("offset_m", [0.0123, -0.0045])])
def test_a_result_that_names_another_trial_is_an_invalid_result(field, value):
    trial = _first_trial()
    status, error, _ = run_trial_safely(lambda t: dict(fake_trial(t), **{field: value}), trial)
    assert status == "error" and error["type"] == "InvalidResult", error
    assert f"its result's {field}" in error["message"]


def test_such_a_result_is_recorded_as_an_error_not_as_a_corrupt_record(tmp_path):
    summary = run_sweep(ONE_TRIAL_SPEC, seed_of_another_trial, tmp_path, workers=1, progress=False)
    records = load_records(tmp_path)
    assert not records.corrupt, records.corrupt
    assert len(records.records) == len(summary.trial_ids) == len(summary.errors)
    assert {record["status"] for record in records.records.values()} == {"error"}
    assert {record["error"]["type"] for record in records.records.values()} == {"InvalidResult"}


def seed_of_another_trial(trial):
    """A trial function that reports the next trial's seed (module level: it is pickled)."""
    return dict(fake_trial(trial), seed=trial["seed"] + 1)


def test_a_results_folder_whose_trials_is_a_file_says_so(tmp_path, capfd):
    (tmp_path / "trials").write_text("")
    code, text = run_cli(["plot", "latency", str(tmp_path)], capfd)
    assert_one_line_error(code, text, f"{tmp_path / 'trials'} is not a folder of trial records")


# Rule: a record missing one of its fields (its checksum, say) is said to lack that field by
# name, through `tegrasp plot table1` too, never called "not a JSON object".
def test_a_sweep_record_without_its_checksum_names_the_missing_field(tmp_path, monkeypatch,
                                                                      capfd):
    summary = run_sweep(ONE_TRIAL, fake_trial, tmp_path / "sweep", workers=1, progress=False)
    path = record_path(tmp_path / "sweep", summary.trial_ids[0])
    record = json.loads(path.read_text())
    del record["checksum"]
    path.write_text(json.dumps(record))
    assert "checksum" in load_records(tmp_path / "sweep").corrupt[path]
    monkeypatch.chdir(tmp_path)
    code, text = run_cli(["plot", "table1", "sweep", "--out", "t.png"], capfd)
    assert_one_line_error(code, text, path.name, "missing", "checksum")
    assert "not a JSON object" not in text


# Rule: a row of Table I (one controller on one object) counts records of one memorized
# events set; records that matched against different events (their "events" sha256 differ,
# e.g. one sweep's records copied into another's folder) are refused by every reader of the
# folder in one line naming two of them, their events and what to do. Records of different
# objects or controllers differ by design and are not compared.
def _mixed_events_folder(tmp_path):
    from tests.fake_trials import fake_memorized_trial
    spec = SweepSpec(objects=("box",), controllers=("memorized",), attempts=2, base_seed=650)
    summary = run_sweep(spec, fake_memorized_trial, tmp_path, workers=1, progress=False)
    path = record_path(tmp_path, summary.trial_ids[-1])
    record = json.loads(path.read_text())
    record["events"] = {"folder": "/elsewhere/events", "sha256": "0" * 64}
    del record["checksum"]
    record["checksum"] = _checksum(record)
    path.write_text(json.dumps(record))
    return summary.trial_ids[0], path


def test_records_of_one_table_row_made_with_different_events_are_refused(tmp_path, capfd):
    from tegrasp_drake.sweep import table1_rows, write_table1
    from tests.analysis_script import load_analysis_script
    first, mixed = _mixed_events_folder(tmp_path / "results")
    words = (f"trials/{first.replace('/', '.')}.json", f"trials/{mixed.name}",
             "(memorized on 'box') matched against different memorized events",
             "sha256 000000000000... from /elsewhere/events",
             "keep the records of one events set in a folder")
    out = tmp_path / "t1.png"
    code, text = run_cli(["plot", "table1", str(tmp_path / "results"), "--out", str(out)],
                         capfd)
    assert_one_line_error(code, text, *words)
    assert not out.exists()
    with pytest.raises(SystemExit) as refused:
        load_analysis_script("make_table1").main([str(tmp_path / "results")])
    assert all(w in str(refused.value) for w in words), refused.value
    records = list(load_records(tmp_path / "results").records.values())
    with pytest.raises(ValueError, match="table1_rows: records .* matched against different"):
        table1_rows(records)
    with pytest.raises(ValueError, match="matched against different memorized events"):
        write_table1(records, tmp_path / "results")
    assert not (tmp_path / "results" / "table1.md").exists()


def test_records_of_different_objects_may_name_different_events(tmp_path):
    from tegrasp_drake.sweep.records import mixed_events_problem
    _, mixed = _mixed_events_folder(tmp_path)
    records = list(load_records(tmp_path).records.values())
    for record in records:
        if record["trial_id"] == json.loads(mixed.read_text())["trial_id"]:
            record["trial"] = dict(record["trial"], object_name="thin_cylinder")
    assert mixed_events_problem(records) is None


def test_no_committed_results_folder_mixes_events():
    import pathlib
    root = pathlib.Path(tegrasp_drake.__file__).parent.parent
    folders = [trials.parent for trials in sorted(root.glob("analysis/**/trials"))]
    assert len(folders) >= 50
    for folder in folders:
        assert load_records(folder).table_problem(folder) is None, folder


# Rule: a results folder holds one sweep's records. Records that disagree on what the sweep
# gives its trials alike -- where a marker lies or which marker an offset is (two grids, whose
# marker names mean other offsets), the base seed, sensor noise, scenario overrides, an
# object's definition, a scene's draw -- copied into one folder's trials/ are refused by every
# reader of the folder in one line naming two of them and the field (a table silently counted
# them as one study).
def _two_sweeps_folder(tmp_path, first: SweepSpec, second: SweepSpec, copied="*.json"):
    """A folder holding `first`'s records and, copied in beside them, `second`'s (those named
    as `copied` matches) that `first` has no record of (another sweep's folder copied in)."""
    results, other = tmp_path / "mix", tmp_path / "other"
    run_sweep(first, fake_trial, results, workers=1, progress=False)
    run_sweep(second, fake_trial, other, workers=1, progress=False)
    for path in sorted((other / "trials").glob(copied)):
        if not (results / "trials" / path.name).exists():
            (results / "trials" / path.name).write_bytes(path.read_bytes())
    return results


_ONE_SWEEP = dict(objects=("box",), controllers=("open_loop",), attempts=1, base_seed=650)


@pytest.mark.parametrize("second, words", [
    # one marker: m00 at (0, 0), where the first grid's m00 is (-0.01, 0)
    (dict(grid=((0.0, 0.0),), objects=("thin_cylinder",)),
     ["marker m00 (fields 'trial.marker_dx_m', 'trial.marker_dy_m') lies at [-0.01, 0.0] m "
      "in one, [0.0, 0.0] m in the other"]),
    # the same grid's markers moved by a third offset added below them
    (dict(grid=((-0.02, 0.0), (-0.01, 0.0), (0.0, 0.0)), attempts=2),
     ["marker m00 (fields 'trial.marker_dx_m', 'trial.marker_dy_m') lies at [-0.01, 0.0] m "
      "in one, [-0.02, 0.0] m in the other"]),
    # the same offset under another marker: (0, 0) is m10 in one grid, m20 in the other
    (dict(grid=((-0.02, 0.0), (-0.01, 0.0), (0.0, 0.0)), objects=("thin_cylinder",),
          copied="*.m20.*"),
     ["the marker offset [0.0, 0.0] m (field 'trial.marker') is marker m10 in one, marker "
      "m20 in the other"]),
    (dict(base_seed=651, objects=("thin_cylinder",)),
     ["field 'trial.base_seed' is 650 in one, 651 in the other"]),
    (dict(randomisation=RandomisationConfig(sensor_noise=False), attempts=2),
     ["field 'trial.sensor_noise' is True in one, False in the other"]),
    (dict(scenario_overrides=("gripper.screw_efficiency=0.3",), controllers=("heuristic",)),
     ["field 'trial.scenario_overrides' is ['gripper.screw_efficiency=0.3'] in one, [] in "
      "the other"]),
    (dict(randomisation=RandomisationConfig(placement_xy_bound_m=0.001),
          controllers=("heuristic",)),
     ["scene box/m00/a0 (fields 'trial.seed', 'trial.perturbation'"]),
])
def test_records_of_two_sweeps_in_one_folder_are_refused(tmp_path, capfd, second, words):
    from tegrasp_drake.sweep import table1_rows
    from tests.analysis_script import load_analysis_script
    first = SweepSpec(**_ONE_SWEEP, grid=((-0.01, 0.0), (0.0, 0.0)))
    second = dict(second)
    copied = second.pop("copied", "*.json")
    results = _two_sweeps_folder(tmp_path, first, SweepSpec(**{
        **_ONE_SWEEP, "grid": ((-0.01, 0.0), (0.0, 0.0)), **second}), copied)
    words = ["are not of one sweep", *words, "keep each sweep's records in a folder of their own"]
    for kind in ("success-maps", "table1"):
        out = tmp_path / f"{kind}.png"
        code, text = run_cli(["plot", kind, str(results), "--out", str(out)], capfd)
        assert_one_line_error(code, text, str(results), "records trials/", *words)
        assert not out.exists()
    for script in ("make_table1", "make_success_maps"):
        with pytest.raises(SystemExit) as refused:
            load_analysis_script(script).main([str(results)])
        assert all(w in str(refused.value) for w in words), refused.value
    with pytest.raises(ValueError, match="table1_rows: records .* are not of one sweep"):
        table1_rows(load_records(results).records.values())


def test_records_of_one_sweep_run_in_parts_are_one_study(tmp_path):
    """Objects, controllers and attempts run into one folder by several sweeps of one spec's
    settings are one study."""
    from tegrasp_drake.sweep.records import mixed_records_problem
    first = SweepSpec(**_ONE_SWEEP, grid=((-0.01, 0.0), (0.0, 0.0)))
    results = _two_sweeps_folder(tmp_path, first, SweepSpec(**{
        **_ONE_SWEEP, "grid": ((-0.01, 0.0), (0.0, 0.0)), "objects": ("box", "thin_cylinder"),
        "controllers": ("open_loop", "heuristic"), "attempts": 2}))
    loaded = load_records(results)
    assert len(loaded.records) == 16
    assert mixed_records_problem(loaded.records.values(), results) is None
    assert loaded.table_problem(results) is None


# Rule: a sweep into a folder holding another study's records (another base seed, under
# other trial ids) is refused before it runs, as the folder's readers would refuse the mix
# once it had; the same spec with another controller is one study and runs.
def test_a_sweep_into_a_folder_of_another_study_is_refused_before_it_runs(tmp_path, capfd):
    out = tmp_path / "out"

    def sweep(controller, seed):
        spec = tmp_path / f"{controller}-{seed}.yaml"
        spec.write_text(f"objects: [box]\ncontrollers: [{controller}]\nattempts: 1\n"
                        f"grid: [[0.0, 0.0]]\nbase_seed: {seed}\n")
        return run_cli(["sweep", "--spec", str(spec), "--out", str(out), "--workers", "1",
                        "--no-progress", "--trial-function", "tests.fake_trials:fake_trial"],
                       capfd)
    assert sweep("open_loop", 0)[0] == 0
    before = sorted(path.name for path in (out / "trials").iterdir())
    code, text = sweep("heuristic", 5)
    assert code == 2, text
    assert_one_line_error(code, text, "are not of one sweep", "base_seed", "is 0 in one, 5 in",
                          "this sweep's, not yet run", "nothing was run")
    assert sorted(path.name for path in (out / "trials").iterdir()) == before
    assert sweep("heuristic", 0)[0] == 0


# Rule: a trials folder this user cannot read is said to be one, in one line naming it; not
# a folder without records.
def test_a_trials_folder_that_cannot_be_read_is_not_called_empty(tmp_path, capfd, monkeypatch):
    out = tmp_path / "out"
    finished_fake_sweep(out, capfd)
    deny_reading(monkeypatch, files.os, "scandir", out / "trials")
    with pytest.raises(files.UserPathError, match="trials cannot be read .Permission denied"):
        load_records(out)
    code, text = run_cli(["plot", "table1", str(out), "--out", str(tmp_path / "t.png")], capfd)
    assert_one_line_error(code, text, f"{out / 'trials'} cannot be read (Permission denied)")
    assert "no trial records" not in text and not (tmp_path / "t.png").exists()


# Rule: a record this user cannot read (another user's: simulated, as root ignores modes) is
# no corrupt record: a sweep, its dry run and the reports stop in one line naming it, and it
# is neither set aside nor run again.
def test_a_record_that_cannot_be_read_is_not_set_aside_or_rerun(tmp_path, capfd, monkeypatch):
    out = tmp_path / "out"
    argv = finished_fake_sweep(out, capfd)
    record = sorted((out / "trials").glob("*.json"))[0]
    kept, names = record.read_bytes(), sorted(p.name for p in (out / "trials").iterdir())
    deny_reading(monkeypatch, files, "read_bounded", record)
    for command in ([*argv, "--dry-run"], argv,
                    ["plot", "table1", str(out), "--out", str(tmp_path / "t.png")]):
        code, text = run_cli(command, capfd)
        assert code == 1, text
        assert_one_line_error(code, text, f"{record}: cannot be read (Permission denied)",
                              "neither set aside nor run again")
        assert "corrupt" not in text
    assert sorted(p.name for p in (out / "trials").iterdir()) == names  # nothing set aside
    assert record.read_bytes() == kept
