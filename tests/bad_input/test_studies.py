"""Transfer matrices and sensitivity studies are checked before anything runs: null sections,
worlds on the hardware station or that cannot be made, damaged files in their --out,
overrides of what a world sets, and studies over their bound (with their cost and the
option that runs them) or over the ceiling even confirmed are refused in one line; checking
many worlds parses the scenario file once and says what it checks."""

import pathlib
import shutil

import pytest

from tegrasp_drake import cli
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
from tegrasp_drake.sweep.runner import SweepError
from tegrasp_drake.sweep.spec import MAX_TRIALS
from tegrasp_drake.transfer.matrix import LoadTransferSpec
from tests.bad_input.probes import (BOX_SWEEP, FAKE_TRIALS, SEEDED_SWEEP, assert_one_line_error,
                                    no_recording, refusal, run_cli, transfer_out)


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


def _one_line_refusal(code, message, *words):
    assert code == 1, message
    assert message.startswith("tegrasp: error: ") and "internal error" not in message, message
    assert message.count("\n") == 0, message
    for word in words:
        assert word in message, message


# Rule: a run's own state files in its --out (a transfer's world.json and events index, a
# sensitivity study's points.json) are read with a bound and checked for their shape; a
# damaged one is refused in one line naming it (exit 1, bad input), a folder in its place
# too, before anything is recorded or run.
@pytest.mark.parametrize("damage", ["truncated", "not_a_list", "folder", "too_large"])
def test_a_damaged_world_json_in_a_transfer_out_is_refused_naming_it(tmp_path, capfd, damage):
    spec, events = transfer_out(tmp_path)
    marker = events / "world.json"
    if damage == "truncated":
        marker.write_text('{"x": [1,')
    elif damage == "not_a_list":
        marker.write_text('{"x": 1}')
    elif damage == "folder":
        marker.unlink()
        marker.mkdir()
    else:
        with open(marker, "wb") as sparse:
            sparse.truncate(400 * 2**20)
    code, message = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                             "--workers", "1", "--no-progress", *FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(marker))
    assert not (tmp_path / "out" / "cells").exists()


def test_a_file_where_a_worlds_events_folder_belongs_is_refused_naming_it(tmp_path, capfd):
    spec, events = transfer_out(tmp_path)
    shutil.rmtree(events)
    events.write_text("not a folder")
    code, message = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                             "--workers", "1", "--no-progress", *FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(events), "not a folder")


@pytest.mark.parametrize("text", ['[{"object": ', "{}"])
def test_a_damaged_events_index_in_a_transfer_out_is_bad_input(tmp_path, capfd, text):
    spec, events = transfer_out(tmp_path)
    (events / "index.json").write_text(text)
    code, message = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                             "--workers", "1", "--no-progress", *FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(events / "index.json"))


@pytest.mark.parametrize("text", ["[1,2", "[1,2]", '{"default": [1]}'])
def test_a_damaged_points_json_in_a_sensitivity_out_is_refused_naming_it(tmp_path, capfd,
                                                                          text):
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.position_loop_hz]\n" + BOX_SWEEP)
    out = tmp_path / "out"
    out.mkdir()
    (out / "points.json").write_text(text)
    code, message = run_cli(["sensitivity", str(spec), "--out", str(out), "--workers", "1",
                             "--no-progress", *FAKE_TRIALS], capfd)
    _one_line_refusal(code, message.strip(), str(out / "points.json"))
    assert not (out / "cells").exists()


# Rule: a transfer spec's worlds are all checked when it is loaded, one no cell uses too.
def test_a_transfer_world_no_cell_uses_is_checked_like_the_others(tmp_path, monkeypatch):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    monkeypatch.chdir(tmp_path)
    spec = pathlib.Path("t.yaml")
    spec.write_text("worlds:\n  a: {scenario: memorizing_world}\n"
                    "  b: {scenario: faithful_world, overrides: [grasp.grip_force=-5.0]}\n"
                    "cells: [[a, a]]\n" + BOX_SWEEP)
    with pytest.raises(ConfigError) as refused:
        LoadTransferSpec(spec)
    # One line naming the spec and the world's entry at fault, as the user wrote it; not the
    # package's scenario file nor the preset's own assignments.
    message = str(refused.value)
    assert "\n" not in message and len(message) < 400, message
    for word in (str(spec), "worlds.b.overrides[0]' 'grasp.grip_force=-5.0'", "got -5.0"):
        assert word in message, message
    assert str(paths.scenarios_file()) not in message and "--set" not in message, message
    assert "gripper.model" not in message, message


# Rule: a transfer matrix or a sensitivity study is one run: its trials (cells x each cell's
# sweep) and event recordings together are bounded as a sweep's trials are, refused with
# the cost before any world is checked or anything recorded.
def _no_world_checked(monkeypatch):
    from tegrasp_drake.transfer import matrix

    def checked(spec, running):
        raise AssertionError(f"world {running} checked before the size was")
    monkeypatch.setattr(matrix, "running_sweep", checked)


def test_a_sensitivity_study_of_too_many_trials_is_refused_with_its_cost(tmp_path,
                                                                         monkeypatch):
    from tegrasp_drake.sensitivity.study import (LoadSensitivitySpec, latin_hypercube,
                                                 run_sensitivity)
    from tests.fake_trials import fake_trial_with_events
    spec_file = tmp_path / "s.yaml"
    spec_file.write_text("parameters: [gripper.position_loop_hz]\n")
    spec = LoadSensitivitySpec(spec_file)
    points = latin_hypercube(spec, 1000)
    _no_world_checked(monkeypatch)
    refusal(lambda: run_sensitivity(spec, points, fake_trial_with_events, tmp_path / "out",
                                     workers=1, progress=False),
             "1001 cells x 243 trials", "core-hours", "100000")
    assert not (tmp_path / "out").exists()


def test_a_transfer_matrix_of_too_many_trials_is_refused_with_its_cost(tmp_path, monkeypatch):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    names = [f"w{k}" for k in range(21)]
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n" + "".join(f"  {n}: {{scenario: memorizing_world}}\n"
                                          for n in names)
                    + f"cells: {{memorize_in: [{', '.join(names)}], run_in: "
                      f"[{', '.join(names)}]}}\n")
    _no_world_checked(monkeypatch)
    refusal(lambda: LoadTransferSpec(spec), str(spec), "441 cells x 243 trials", "core-hours")

_REACHED = "the run was reached"


def _stop_at_the_run(monkeypatch):
    """The runs of sweep, transfer and sensitivity replaced by a refusal saying _REACHED
    (the command got past every check); the calls (their keyword arguments) are listed in
    the list returned."""
    from tegrasp_drake.commands import sweep
    from tegrasp_drake.transfer import matrix
    calls = []

    def reached(*args, **kwargs):
        calls.append(kwargs)
        raise SweepError(_REACHED)

    monkeypatch.setattr(sweep, "run_sweep", reached)
    monkeypatch.setattr(matrix, "run_transfer", reached)
    return calls


def _transfer_spec(tmp_path, worlds=21):
    """A transfer spec of worlds x worlds cells of the paper's sweep: 441 x 243 trials and
    63 recordings (each memorizing world's, of 3 objects)."""
    names = [f"w{k}" for k in range(worlds)]
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n" + "".join(f"  {n}: {{scenario: memorizing_world}}\n"
                                          for n in names)
                    + f"cells: {{memorize_in: [{', '.join(names)}], run_in: "
                      f"[{', '.join(names)}]}}\n")
    return spec


def _sensitivity_spec(tmp_path):
    """A sensitivity spec whose 11 Latin-hypercube points (with the default) of a
    16200-trial sweep are 178200 trials and 33 recordings (each point's, of 3 objects)."""
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.position_loop_hz]\nsweep: {attempts: 200}\n")
    return spec


# (command line after the command's name, the study's simulations: trials and recordings)
_STUDIES = {
    "sweep": (["--attempts", "1235"], 3 * 9 * 1235 * 3),
    "transfer": (["T"], 441 * 243 + 21 * 3),
    "sensitivity": (["S", "--latin-hypercube", "10"], 11 * 200 * 81 + 11 * 3),
}


def _argv(command, tmp_path, *more):
    words, simulations = _STUDIES[command]
    spec = {"T": str(_transfer_spec(tmp_path)), "S": str(_sensitivity_spec(tmp_path))}
    return ([command, *[spec.get(w, w) for w in words], *FAKE_TRIALS, "--workers", "1",
             "--no-progress", "--out", str(tmp_path / "out"), *more], simulations)


# Rule: a study over the trial bound (sweep, transfer, sensitivity) is refused with its cost
# and the option that runs it; the option, given at least the study's size, runs it; given
# less, it is refused again: a confirmation never covers a bigger study than the user saw.
@pytest.mark.parametrize("command", sorted(_STUDIES))
def test_a_study_over_the_bound_is_refused_with_the_option_that_runs_it(
        tmp_path, monkeypatch, capsys, command):
    calls = _stop_at_the_run(monkeypatch)
    argv, simulations = _argv(command, tmp_path)
    assert simulations > MAX_TRIALS
    assert cli.main(argv) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "core-hours" in error, error
    assert f"add --confirm-trials {simulations} to run it" in error, error
    assert not calls

    assert cli.main(_argv(command, tmp_path, "--confirm-trials",
                          str(simulations - 1))[0]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1, error
    assert f"--confirm-trials {simulations - 1}" in error, error
    assert f"add --confirm-trials {simulations} to run it" in error, error
    assert not calls

    assert cli.main(_argv(command, tmp_path, "--confirm-trials", str(simulations))[0]) == 2
    assert _REACHED in capsys.readouterr().err and len(calls) == 1


# Rule: --confirm-trials is a count of trials, and one under the study's is refused even
# for a study under the bound: it confirms a study other than the one given.
@pytest.mark.parametrize("value, words", [
    ("0", "at least 1"), ("-5", "at least 1"), ("many", "is not an integer"),
    ("242", "add --confirm-trials 243 to run it")])
def test_a_confirmation_that_is_no_count_or_too_few_is_refused(tmp_path, monkeypatch, capsys,
                                                               value, words):
    calls = _stop_at_the_run(monkeypatch)
    try:
        code = cli.main(["sweep", "--confirm-trials", value, *FAKE_TRIALS, "--workers", "1",
                         "--no-progress", "--out", str(tmp_path / "out")])
    except SystemExit as stopped:  # argparse's refusal of text that is no integer
        code = stopped.code
    # a count that is none: the option's value (1); too few: argparse (2), the study's size (2)
    assert code == (1 if value in ("0", "-5") else 2)
    error = capsys.readouterr().err
    assert "--confirm-trials" in error and value in error and words in error, error
    assert "Traceback" not in error and not calls, error


def _count_scenario_file_parses(monkeypatch):
    """A list that grows by one each time the built-in scenario file's text is parsed."""
    from tegrasp_drake.rig import paths, typed_yaml
    parses, parse = [], typed_yaml.parse_yaml

    def counted(text, source, **kwargs):
        if source == str(paths.scenarios_file()):
            parses.append(source)
        return parse(text, source, **kwargs)
    monkeypatch.setattr(typed_yaml, "parse_yaml", counted)
    return parses


def _worlds(count):
    """A transfer matrix of `count` worlds of the default scenario, each its own point."""
    from tegrasp_drake.sweep.spec import SweepSpec
    from tegrasp_drake.transfer.matrix import TransferSpec, TransferWorld
    names = [f"w{k}" for k in range(count)]
    return TransferSpec(worlds={n: TransferWorld(
        "default", (f"gripper.position_loop_hz={40.0 + k}",))
                                for k, n in enumerate(names)},
                        cells=tuple((n, n) for n in names), sweep=SweepSpec())


# Rule: checking a study's worlds (each world's preset and overrides with every controller)
# parses the scenario file once, not once a world and controller: a 1000-point study's check
# took a minute, most of it parsing the same file.
def test_checking_many_worlds_parses_the_scenario_file_at_most_once(monkeypatch):
    from tegrasp_drake.transfer.matrix import check_worlds
    parses = _count_scenario_file_parses(monkeypatch)
    check_worlds(_worlds(5), "study")
    assert len(parses) <= 1, parses  # none when an earlier check read it in this process


# Rule: a check of many worlds, which takes a while, says so on stderr when it starts and
# how long it took when it ends, rather than running silently.
def test_a_long_check_of_worlds_says_what_it_checks_and_how_long_it_took(capsys):
    from tegrasp_drake.transfer.matrix import check_worlds
    check_worlds(_worlds(3), "study")
    assert capsys.readouterr().err == ""
    check_worlds(_worlds(50), "study")
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 2, lines
    assert lines[0].startswith("checking 50 worlds"), lines
    assert lines[1].startswith("checked 50 worlds in "), lines


def test_the_python_api_bounds_a_study_as_the_commands_do(tmp_path, monkeypatch):
    """run_sweep and run_transfer, called from a script, refuse a study over the trial bound
    with its cost before listing a trial, and run it when confirmed."""
    from tegrasp_drake.sweep import runner
    from tegrasp_drake.sweep.spec import SweepSpec, trial_count
    from tegrasp_drake.transfer import matrix

    spec = SweepSpec(attempts=1235)
    assert trial_count(spec) > MAX_TRIALS

    def listed(*args, **kwargs):
        raise AssertionError("the trials were listed before the study's size was checked")

    monkeypatch.setattr(runner, "expand_trials", listed)
    with pytest.raises(Exception, match="add --confirm-trials 100035 to run it"):
        runner.run_sweep(spec, print, tmp_path / "out", workers=1)
    with pytest.raises(AssertionError, match="listed before"):  # confirmed: past the check
        runner.run_sweep(spec, print, tmp_path / "out", workers=1, confirmed_trials=100035)

    transfer = matrix.LoadTransferSpec(_transfer_spec(tmp_path), confirmed_trials=10**6)
    with pytest.raises(Exception, match="add --confirm-trials 107226 to run it"):
        matrix.run_transfer(transfer, print, tmp_path / "t")

_TRANSFER = "worlds:\n  a: {scenario: faithful_world}\ncells:\n  memorize_in: [a]\n  run_in: [a]\n"


# Rule: a section of a transfer or sensitivity spec written as null is refused, as a null
# field of any configuration is; only a section left out takes its default (the paper's
# sweep, every uncertain parameter).
@pytest.mark.parametrize("text, field", [
    (_TRANSFER + "sweep: null\n", "sweep"),
], ids=["transfer-sweep"])
def test_a_null_section_of_a_transfer_spec_is_refused(tmp_path, text, field):
    spec = tmp_path / "t.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=f"field '{field}' is empty \\(null\\): give its "
                       "fields, or remove"):
        LoadTransferSpec(spec)


@pytest.mark.parametrize("text, field, words", [
    ("parameters: [gripper.pad_friction]\nsweep: null\n", "sweep",
     "is empty \\(null\\): give its fields, or remove"),
    ("parameters: null\nsweep: {objects: [box]}\n", "parameters",
     "is null: give a value, or leave"),
], ids=["sweep", "parameters"])
def test_a_null_section_of_a_sensitivity_spec_is_refused(tmp_path, text, field, words):
    spec = tmp_path / "s.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=f"field '{field}' {words}"):
        LoadSensitivitySpec(spec)


def _count_listings(monkeypatch):
    """A list that grows by one each time a sweep's trials are listed (expand_trials)."""
    from tegrasp_drake.sweep import runner, spec
    listed = []

    def counted(*args, **kwargs):
        listed.append(1)
        raise AssertionError("the trials were listed")
    monkeypatch.setattr(spec, "expand_trials", counted)
    monkeypatch.setattr(runner, "expand_trials", counted)
    return listed


# Rule: a study has a ceiling a confirmation cannot lift (its trials are listed in memory
# before the first runs): from the command line and from Python, refused before listing.
def test_a_study_over_the_ceiling_is_refused_even_confirmed(tmp_path, monkeypatch, capsys):
    from tegrasp_drake import cli
    from tegrasp_drake.sweep.runner import SweepError, run_sweep
    from tegrasp_drake.sweep.spec import SweepSpec
    from tests.fake_trials import fake_trial_with_events
    ceiling = 1_000_000  # MAX_CONFIRMED_TRIALS
    listed = _count_listings(monkeypatch)
    attempts = ceiling // 81 + 1  # 81 trials an attempt: 3 objects, 9 markers, 3 controllers
    code = cli.main(["sweep", "--objects", "box", "thick_cylinder", "thin_cylinder",
                     "--attempts", str(attempts), "--trial-function",
                     "tests.fake_trials:fake_trial_with_events",
                     "--workers", "1", "--no-progress", "--out", str(tmp_path / "o")])
    error = capsys.readouterr().err
    assert code != 0 and f"at most {ceiling} " in error and "split it" in error, error
    assert "Traceback" not in error and not listed, error
    with pytest.raises((ConfigError, SweepError, ValueError), match=f"{ceiling}"):
        run_sweep(SweepSpec(attempts=attempts), fake_trial_with_events, tmp_path / "p",
                  confirmed_trials=attempts * 81)
    assert not listed


def test_a_confirmation_over_the_ceiling_is_refused(tmp_path, capsys):
    from tegrasp_drake import cli
    code = cli.main(["sweep", "--confirm-trials", "1000001", "--objects", "box",
                     "--attempts", "1", "--trial-function",
                     "tests.fake_trials:fake_trial_with_events", "--workers", "1", "--no-progress",
                     "--out", str(tmp_path / "o")])
    error = capsys.readouterr().err
    assert code != 0 and "--confirm-trials" in error and "split" in error, error


# Rule: a transfer's events folder kept from an earlier run (its objects are not recorded
# again) is checked complete, every transition file the cells' controllers read for every
# object it lists, before anything is recorded or run; one line naming the file and the
# remedy, exit 1 (a damaged file, not a refused spec).
def test_a_kept_transfer_events_folder_missing_a_transition_is_refused_at_once(tmp_path,
                                                                            capfd,
                                                                            monkeypatch):
    spec, events = transfer_out(tmp_path)
    (events / "box" / "load_lift.json").unlink()
    no_recording(monkeypatch)
    code, text = run_cli(["transfer", str(spec), "--out", str(tmp_path / "out"),
                          "--workers", "1", "--no-progress"], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error:", str(events / "box" / "load_lift.json"),
                          f"remove {events}")
    assert not (tmp_path / "out" / "cells").exists()


# Rule: a sweep simulates its trials, and a transfer world runs a sweep: an override that
# makes the station the real devices' is refused when the spec is loaded, naming the world.
def test_a_transfer_world_on_the_hardware_station_is_refused(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds:\n  w: {scenario: faithful_world, overrides: "
                    "['station=!HardwareStationConfig {}']}\n"
                    "cells:\n  memorize_in: [w]\n  run_in: [w]\n"
                    "sweep:\n  objects: [box]\n  controllers: [memorized]\n  attempts: 1\n")
    with pytest.raises(ConfigError, match=r"worlds\.w.*HardwareStationConfig.*simulates"):
        LoadTransferSpec(spec)


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


def test_a_world_events_folder_that_cannot_be_made_is_one_line(tmp_path, capfd):
    """OUT/events a link to a folder no world's folder can be made in (/proc): refused in one
    line before anything is recorded, not exit 70 from mkdir."""
    spec = tmp_path / "t.yaml"
    spec.write_text("worlds: {w: {scenario: faithful_world}}\ncells: [[w, w]]\n" + SEEDED_SWEEP)
    out = tmp_path / "out"
    out.mkdir()
    (out / "events").symlink_to("/proc")
    code, text = run_cli(["transfer", str(spec), "--out", str(out), "--workers", "1",
                          "--no-progress", *FAKE_TRIALS], capfd)
    assert code == 1, text
    assert "events/w" in text and "internal error" not in text
    assert len(text.strip().splitlines()) == 1


# Rule: a transfer study runs memorized events in another world, so its sweep needs a
# controller that reads them; one of open_loop alone is refused when the spec is loaded,
# naming the field, before any recording.
def test_a_transfer_whose_controllers_read_no_events_is_refused(tmp_path, monkeypatch):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    monkeypatch.chdir(tmp_path)
    spec = pathlib.Path("t.yaml")
    spec.write_text("worlds:\n  a: {scenario: memorizing_world}\n"
                    "  b: {scenario: faithful_world}\ncells: [[a, b]]\n"
                    "sweep: {objects: [box], controllers: [open_loop], attempts: 1}\n")
    with pytest.raises(ConfigError) as refused:
        LoadTransferSpec(spec)
    message = str(refused.value)
    for word in ("t.yaml", "field 'sweep.controllers': open_loop read no memorized events",
                 "memorized, taxel_aware"):
        assert word in message, message
