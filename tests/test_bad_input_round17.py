"""Bad inputs the seventeenth review found, one test per rule."""

import json
import pathlib
import shutil

import pytest

from tegrasp_drake.rig.paths import package_events_dir
from tests.test_bad_input import assert_one_line_error, run_cli


def _events_copy(tmp_path, entries=None) -> pathlib.Path:
    """A copy of the package's events folder; `entries` (a function of the index's entries)
    rewrites the index."""
    folder = tmp_path / "events"
    shutil.copytree(package_events_dir(), folder)
    if entries is not None:
        index = json.loads((folder / "index.json").read_text())
        index["events"] = entries(index["events"])
        (folder / "index.json").write_text(json.dumps(index))
    return folder


# Rule: an events index that lists no events is a damaged events folder, refused where the
# index is read (so every reader of it, the plot, a trial, a sweep, names it alike) in one
# line naming the index and how to remake it; not an internal error of the figure.
def test_an_index_listing_no_events_is_refused_naming_it(tmp_path, capfd):
    from tegrasp_drake.events import MemorizedEventError, read_index
    folder = _events_copy(tmp_path, entries=lambda entries: [])
    with pytest.raises(MemorizedEventError, match="lists no events"):
        read_index(folder)
    code, error = run_cli(["plot", "events", "--events", str(folder),
                           "--out", str(tmp_path / "events.png")], capfd)
    assert code == 1, error
    assert_one_line_error(code, error, "index.json", "lists no events")
    assert not (tmp_path / "events.png").exists()


# Rule: a sweep spec's `user_objects` entry that `objects` does not name is refused, naming it
# and saying to add it to `objects`, wherever a spec is checked (the file's reader, a
# SweepSpec built in Python, the command line); not dropped while the default objects run.
# A command line's `--objects` chooses the objects to run: the spec's other definitions are
# then the user's choice not to run them.
MUG = "{mug: {shape: cylinder, size: [0.04, 0.1], mass: 0.3, friction: 0.5}}"


@pytest.mark.parametrize("text", [f"user_objects: {MUG}\n",
                                  f"objects: [box]\nuser_objects: {MUG}\n"])
def test_a_user_object_the_spec_does_not_run_is_refused(tmp_path, capfd, text):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sweep import LoadSweepSpec
    spec = tmp_path / "spec.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=r"user_objects\.mug.*add it to 'objects'"):
        LoadSweepSpec(spec)
    code, error = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                           "--workers", "1", "--base-seed", "640", "--no-progress"], capfd)
    assert_one_line_error(code, error, "user_objects.mug", "objects")
    assert not (tmp_path / "out").exists()


def test_a_user_object_a_python_spec_does_not_run_is_refused():
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.sweep import SweepSpec, expand_trials
    mug = ObjectConfig(name="mug", shape="cylinder", size=[0.04, 0.1], mass=0.3, friction=0.5)
    with pytest.raises(ConfigError, match=r"user_objects\.mug"):
        expand_trials(SweepSpec(objects=("box",), user_objects={"mug": mug}))


def test_objects_chosen_on_the_command_line_leave_the_other_definitions_unrun(tmp_path):
    import argparse
    from tegrasp_drake.commands.sweep import spec_from_arguments
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"objects: [box, mug]\nuser_objects: {MUG}\n")
    args = argparse.Namespace(spec=str(spec), objects=["box"], controllers=None, attempts=None,
                              base_seed=None, overrides=None, confirm_trials=None)
    assert spec_from_arguments(args).objects == ("box",)


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


# Every public function's folder declarations hold at its call: a folder argument declared
# to exist (Folder(exists=True)) is refused, naming the argument, when it does not.
def _existing_folder_arguments():
    import inspect
    import typing
    import tegrasp_drake as T
    from tegrasp_drake.rig.api_boundary import Folder
    for name in T.__all__:
        function = getattr(T, name)
        if not callable(function) or inspect.isclass(function):
            continue
        hints = typing.get_type_hints(inspect.unwrap(function), include_extras=True)
        for argument, hint in hints.items():
            if any(isinstance(m, Folder) and m.exists for m in getattr(hint, "__metadata__", ())):
                yield name, argument


@pytest.mark.parametrize("name, argument", list(_existing_folder_arguments()))
def test_every_folder_declared_to_exist_is_checked_at_the_call(tmp_path, name, argument):
    import tegrasp_drake as T
    from tegrasp_drake.rig.files import UserPathError
    with pytest.raises(UserPathError, match=f"argument '{argument}'.*does not exist"):
        getattr(T, name).bind_now(**{argument: tmp_path / "missing"})


# Rule: `--overwrite` replaces the earlier run in the folder wherever that folder has been
# moved or copied to: its files are known by their names (result.json, trial.npz, the
# figures' STEM.FORMAT), not by the absolute paths its result.json recorded; the user's own
# files stay.
@pytest.mark.parametrize("how", ["moved", "copied"])
def test_an_overwrite_into_a_moved_or_copied_run_folder_replaces_the_earlier_run(tmp_path, how):
    from tegrasp_drake.commands import run_folder
    written = tmp_path / "written"
    written.mkdir()
    for name in ("trial.npz", "states.png", "signals.png", "contact_ra.png"):
        (written / name).write_bytes(b"earlier")
    (written / "mynotes.txt").write_text("the user's own file")
    (written / "result.json").write_text(json.dumps(
        {"log": str(written / "trial.npz"), "figure": str(written / "states.png"),
         "signals_figure": str(written / "signals.png"),
         "contact_ra_figure": str(written / "contact_ra.png"),
         "result": str(written / "result.json")}))
    folder = tmp_path / "elsewhere"
    (shutil.move if how == "moved" else shutil.copytree)(written, folder)
    with run_folder.staged_run(folder) as stage:
        for name in ("trial.npz", "states.svg", "signals.svg"):
            (stage / name).write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz"),
                                              "figure": str(stage / "states.svg"),
                                              "signals_figure": str(stage / "signals.svg")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "mynotes.txt", "result.json", "signals.svg", "states.svg", "trial.npz"]
    if how == "copied":  # the folder it was copied from is not touched
        assert sorted(p.name for p in written.iterdir()) == [
            "contact_ra.png", "mynotes.txt", "result.json", "signals.png", "states.png",
            "trial.npz"]


# Rule: a result.json is no list of files to delete: a file of the folder it names stays,
# whatever the key, the replay an earlier --html wrote too (a file the user named, which may
# be theirs by now).
def test_an_overwrite_deletes_no_file_the_earlier_result_names(tmp_path):
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    for name in ("trial.npz", "thesis.tex", "notes.html", "replay.html"):
        (folder / name).write_bytes(b"earlier")
    (folder / "result.json").write_text(json.dumps(
        {"log": str(folder / "trial.npz"), "figure": str(folder / "thesis.tex"),
         "signals_figure": str(folder / "notes.html"),
         run_folder.REPLAY_KEY: str(folder / "replay.html")}))
    with run_folder.staged_run(folder) as stage:
        (stage / "trial.npz").write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "notes.html", "replay.html", "result.json", "thesis.tex", "trial.npz"]


# Rule: the memorized events a sweep's trials match against are a setting of the sweep, as
# its seeds and overrides are: each record names them (a content hash, and the folder), and a
# resume whose events differ is refused, naming both, before any trial runs. The same events
# in another folder (a copy) are the same setting.
def _sweep(tmp_path, out, events, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [memorized]\nattempts: 1\nbase_seed: 641\n"
                    "grid: [[0, 0], [0, 0.005]]\n")
    return run_cli(["sweep", "--spec", str(spec), "--out", str(out), "--events", str(events),
                    "--workers", "1", "--no-progress",
                    "--trial-function", "tests.fake_trials:fake_memorized_trial"], capfd)


def test_a_sweep_resumed_with_other_memorized_events_is_refused(tmp_path, capfd):
    from tegrasp_drake.sweep import load_records
    events = _events_copy(tmp_path)
    other = tmp_path / "other_events"
    shutil.copytree(events, other)
    reach_load = other / "box" / "reach_load.json"
    event = json.loads(reach_load.read_text())  # the SA channels swapped: still a valid event
    samples = event["samples"]
    samples["sa_left"], samples["sa_right"] = samples["sa_right"], samples["sa_left"]
    reach_load.write_text(json.dumps(event))
    out = tmp_path / "out"
    code, text = _sweep(tmp_path, out, events, capfd)
    assert code == 0, text
    records = load_records(out).records
    assert len(records) == 2 and all(r["events"]["sha256"] for r in records.values())
    first = sorted(records)[0]
    (out / "trials" / (sorted(records)[1].replace("/", ".") + ".json")).unlink()
    code, text = _sweep(tmp_path, out, other, capfd)
    assert code == 2, text
    assert "other memorized events" in text and str(other) in text and str(events) in text
    assert sorted(load_records(out).records) == [first]  # nothing ran
    same = tmp_path / "same_events"  # a copy of the first events: the sweep resumes
    shutil.copytree(events, same)
    code, text = _sweep(tmp_path, out, same, capfd)
    assert code == 0, text
    assert len(load_records(out).records) == 2


def test_records_that_do_not_name_their_events_are_kept_with_a_warning(tmp_path, capfd,
                                                                       caplog):
    from tegrasp_drake.sweep import load_records
    from tegrasp_drake.sweep.records import _checksum
    events, out = _events_copy(tmp_path), tmp_path / "out"
    code, text = _sweep(tmp_path, out, events, capfd)
    assert code == 0, text
    paths = sorted((out / "trials").glob("*.json"))
    old = json.loads(paths[0].read_text())  # as a record of format 1 was written
    del old["events"], old["checksum"]
    old["format_version"] = 1
    old["checksum"] = _checksum(old)
    paths[0].write_text(json.dumps(old))
    paths[1].unlink()
    code, text = _sweep(tmp_path, out, events, capfd)
    assert code == 0, text
    assert "1 finished record(s) do not name the memorized events" in caplog.text
    assert len(load_records(out).records) == 2
