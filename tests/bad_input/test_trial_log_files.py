"""A trial log's file and metadata are checked by both of its readers: duplicate or unknown
members, arrays and time bases that do not cover one run at its logger's period, metadata
of the wrong form or out of range, mode names, a stored scenario or controller the log
contradicts; each is refused in one line naming the log and member, and a log the plots
refuse is not streamed either."""

import io
import json
import pathlib
import struct
import warnings
import zipfile

import numpy as np
import pytest

import tegrasp_drake as T
from tegrasp_drake.emulators.myrio_emulator import TactileRecordingError, load_tactile_recording
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_from_yaml, scenario_to_yaml
from tegrasp_drake.scenario.trial_log_file import (ARRAY_FIELDS, FORMAT_VERSION, TrialLogError,
                                                   load_trial_log)
from tests.bad_input.probes import (META, SCENARIO, TIMELINE, assert_one_line_error,
                                    deny_reading, log_refusal, meta_refused, one_line_of,
                                    refused_log, refused_meta, result_refused, run_cli,
                                    run_probe, trial_log, trial_log_with)
from tests.fake_trials import small_trial_log, whole_result
from tests.trial_log_contents import read_trial_log_contents, write_trial_log_contents


def _truncate(path):
    data = path.read_bytes()
    path.write_bytes(data[:len(data) // 2])


def _flip_bits(path):
    data = bytearray(path.read_bytes())
    for k in range(200, len(data) - 200, 50):
        data[k] ^= 0x10
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("make, expected", [
    (lambda p: _truncate(trial_log(p)), "is incomplete or damaged, not one an earlier "
     "version wrote: it starts as a zip archive but has no zip directory at its end"),
    (lambda p: _flip_bits(trial_log(p)), "is incomplete or damaged, not one an earlier "
     "version wrote"),
    (lambda p: trial_log(p, channels=np.ones((50, 4))),
     "'channels' has shape (50, 4), but 101 samples of 't_ra' need (101, 4)"),
    (lambda p: trial_log(p, channels=np.full((101, 4), np.nan)),
     "the arrays ['channels'] hold NaN or infinite values"),
])
def test_a_damaged_trial_log_is_named_and_not_plotted(make, expected, tmp_path, capfd):
    path = tmp_path / "trial.npz"
    make(path)
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, str(path), expected)
    assert not (tmp_path / "x.png").exists()


def _with_meta(path, meta):
    """A small trial log whose metadata is `meta` alone."""
    trial_log(path)
    return write_trial_log_contents(path, {**read_trial_log_contents(path), "meta": meta})


# Rule: a trial log whose metadata names no format version (`{}`, or a null version) is said to
# be no trial log of tegrasp's, with how to make one, never "format version None"; a log of
# another version says which, and to run the trial again.
@pytest.mark.parametrize("meta, expected", [
    ({}, "its metadata has no format version, so `tegrasp trial` did not write it; run the "
         "trial again (`tegrasp trial --out DIR` writes DIR/trial.npz)"),
    ({"format_version": None}, "its metadata has no format version"),
    ({"format_version": 7}, "has format version 7, this package reads 1; run the trial again"),
])
def test_a_trial_log_without_a_format_version_says_so_and_how_to_remake_it(meta, expected,
                                                                           tmp_path, capfd):
    path = _with_meta(tmp_path / "meta_empty.npz", meta)
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "x.png")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, str(path), expected)
    assert "None" not in text, text


def test_a_logged_scenario_is_checked_as_a_loaded_one():
    text = scenario_to_yaml(LoadScenario(name="box"))
    assert scenario_from_yaml(text).object.mass > 0
    damaged = text.replace("mass: 0.15", "mass: .nan", 1)
    assert damaged != text
    with pytest.raises(ConfigError, match="run log 'x': field 'object.mass' must be a finite"):
        scenario_from_yaml(damaged, "run log 'x'")


# Rule: a logged scenario is walked field by field as a loaded one is (check_fields): a section
# corrupt bytes made a scalar is named, never an AssertionError inside Drake's loader.
def test_a_logged_scenario_whose_section_is_text_names_the_field():
    with pytest.raises(ConfigError, match="run log 'x': field 'object' must be a mapping"):
        scenario_from_yaml("object: name-box\n", "run log 'x'")


def _small_trial_log(path, channels: int) -> pathlib.Path:
    n = 4
    times = np.arange(n) * 0.01
    shapes = {"taxels": 24, "true_taxels": 24, "channels": channels, "pad_acceleration": 6,
              "arm_q": 6, "arm_q_desired": 6, "gripper_command": 3, "gripper_status": 8,
              "object_state": 13}
    arrays = {name: np.zeros((n, shapes[name])) if name in shapes else times
              for name in ARRAY_FIELDS}
    arrays["phase"] = np.zeros(n)
    arrays["object_state"][:, 0] = 1.0  # the identity orientation, a unit quaternion
    for name in ("arm_q", "arm_q_desired"):  # joints 2 and 3 within the JACO2's limits
        arrays[name][:, 1:3] = [3.0, 1.0]
    # written as it stands (TrialLog.save refuses such a log): what the readers are given
    return write_trial_log_contents(
        path, {"meta": {"format_version": FORMAT_VERSION, "controller": "memorized"}, **arrays})


def test_a_trial_log_the_plots_refuse_is_not_streamed_either(tmp_path):
    path = _small_trial_log(tmp_path / "trial.npz", channels=3)
    with pytest.raises(ValueError, match="'channels' has shape"):
        load_trial_log(path)
    with pytest.raises(TactileRecordingError) as refused:
        load_tactile_recording(path)
    assert "'channels' has shape" in one_line_of(refused.value)
    assert load_tactile_recording(_small_trial_log(tmp_path / "ok.npz", channels=4))


# Rule: a trial log's arrays are finite, every one a reader may draw or judge (not only the
# tactile signals), and a plot's preconditions are said in one line: the Avoid figure of a
# controller without an Avoid reaction is "no Avoid transition", not an internal error.
def test_trial_log_arrays_and_the_avoid_plots_precondition(tmp_path):
    import numpy as np

    from tegrasp_drake.cli import main
    from tegrasp_drake.scenario.trial_log_file import FORMAT_VERSION, TrialLogError
    for name, shape in (("object_state", (11, 13)), ("arm_q", (11, 6)),
                        ("gripper_status", (11, 8))):
        path = trial_log(tmp_path / f"{name}.npz", **{name: np.full(shape, np.nan)})
        with pytest.raises(TrialLogError, match=rf"\['{name}'\] hold NaN or infinite"):
            T.load_trial_log(path)
    path = trial_log(tmp_path / "open_loop.npz")
    with np.load(path) as stored:
        arrays = {key: stored[key] for key in stored.files if key != "meta"}
    scenario = T.with_controller(T.LoadScenario(name="box"), "open_loop")
    meta = {"format_version": FORMAT_VERSION, "scenario": T.scenario_to_yaml(scenario),
            "controller": "open_loop", "transitions": []}
    write_trial_log_contents(path, {"meta": meta, **arrays})
    with pytest.raises(SystemExit) as refused:
        main(["plot", "avoid", str(path), "--out", str(tmp_path / "a.png")])
    assert "no Avoid transition" in str(refused.value.code), refused.value.code

_BOX = scenario_to_yaml(LoadScenario(name="box"))


# Rule: every metadata field of a trial log that a reader uses has one declared form
# (trial_log_file.META_FIELDS), checked when the log is read: a number where names belong,
# a map of times that holds text, a result that is not one, is refused naming the file and
# the field; a log without the scenario the figures need is refused as such.
@pytest.mark.parametrize("meta, words", [
    ({"phases": [1, 2, 3]}, "meta 'phases' must be a non-empty list of names"),
    ({"controller": 5}, "meta 'controller' must be a controller name, one of memorized"),
    ({"scenario": 5}, "meta 'scenario' must be the scenario's YAML text"),
    ({"campaign_run": ["a"]}, "meta 'campaign_run' must be"),
    ({"events": 5}, "meta 'events' must map event names to times [s]"),
    ({"events": {"reach_load": "soon"}}, "meta 'events' must map event names to times [s]"),
    ({"result": [1]}, "meta 'result' must be a trial result's JSON form"),
    ({"result": {"final_mode": 3}, "scenario": _BOX}, "'result' is not a trial result's JSON form"),
    ({}, "its metadata has no 'scenario'"),
])
def test_a_trial_log_metadata_field_of_the_wrong_form_is_refused_naming_it(
        meta, words, tmp_path, monkeypatch, capfd):
    make = lambda folder: trial_log_with(folder / "t.npz", meta)  # noqa: E731
    before, _, code, text = run_probe(make, ["plot", "trial", "t.npz", "--out", "x.png"],
                                      tmp_path, monkeypatch, capfd)
    assert_one_line_error(code, text, "trial log 't.npz'", words)
    assert not (tmp_path / "x.png").exists()


# Rule: every metadata field the writer stores has a declared range (a grip force the
# gripper can exert, durations >= 0).
@pytest.mark.parametrize("meta, expected", [
    ({"grip_force": -5}, "meta 'grip_force' must be"),
    ({"grip_force": "strong"}, "meta 'grip_force' must be"),
    ({"sim_time_s": -1.0}, "meta 'sim_time_s' must be"),
    ({"wall_time_s": "3 s"}, "meta 'wall_time_s' must be"),
    ({"versions": {"drake": 1}}, "meta 'versions' must map"),
], ids=["grip-negative", "grip-text", "sim-time", "wall-time", "versions"])
def test_trial_log_meta_fields_have_ranges(tmp_path, meta, expected):
    assert expected in refused_log(tmp_path, meta)


# Rule: meta 'sim_time_s' is when the run ended; every logger samples until then, so each
# time base's last sample lies at or before it and within one of its periods; the stored
# result's sim_time_s is the same time. Another is refused naming the member and its sample.
@pytest.mark.parametrize("meta, expected", [
    ({"sim_time_s": 1e9}, "meta 'sim_time_s' is 1000000000 s, but 't_sa' ends at sample 10, "
                          "0.0925926 s"),
    ({"sim_time_s": 0.05}, "meta 'sim_time_s' is 0.05 s, but 't_sa' ends at sample 10"),
    ({"sim_time_s": 0.0999}, "meta 'sim_time_s' is 0.0999 s, but 't_ra' ends at sample 100, "
                             "0.1 s"),
    ({**META, "sim_time_s": 1e9}, "meta 'sim_time_s' is 1000000000 s, but 't_sa' ends at "
                                  "sample 10"),
    ({**META, "sim_time_s": 0.1, "result": {**META["result"], "sim_time_s": 0.09}},
     "meta 'sim_time_s' is 0.1 s, but its 'result' sim_time_s is 0.09 s"),
], ids=["far-after", "before", "before-one-base", "with-result", "result"])
def test_a_simulated_time_the_samples_disagree_with_is_refused(tmp_path, meta, expected):
    assert expected in refused_log(tmp_path, meta)


def test_plot_trial_refuses_a_simulated_time_past_the_log(tmp_path, capfd):
    path = trial_log_with(tmp_path / "t.npz", {"sim_time_s": 1e9})
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "x.png")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, f"trial log '{path}'", "meta 'sim_time_s' is 1000000000",
                          "'t_sa' ends at sample 10")
    assert not (tmp_path / "x.png").exists()


def test_a_simulated_time_within_a_period_after_the_last_samples_is_read(tmp_path):
    path = trial_log_with(tmp_path / "t.npz", {"sim_time_s": 0.1005})  # half an RA period
    assert load_trial_log(path).meta["sim_time_s"] > 0.1


# Rule: the metadata is JSON read as every JSON file is (rig/files.load_json): a text holding a
# lone surrogate escape ("\\ud800") is no text, refused naming the field.
def test_trial_log_meta_text_with_a_lone_surrogate_is_refused_naming_the_field(tmp_path):
    assert "its metadata field 'campaign_run' holds \\ud800" in refused_log(
        tmp_path, {"campaign_run": "run \ud800"})


def _npy(array) -> bytes:
    buffer = io.BytesIO()
    np.save(buffer, array)
    return buffer.getvalue()


def _rezipped(path, extra_members):
    """`path` (an .npz) rewritten with `extra_members` ((member name, array) pairs) appended."""
    with np.load(path) as data:
        contents = {name: data[name] for name in data.files}
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, array in contents.items():
            archive.writestr(f"{name}.npy", _npy(array))
        with warnings.catch_warnings():  # zipfile warns of the duplicate this makes
            warnings.simplefilter("ignore", UserWarning)
            for name, array in extra_members:
                archive.writestr(name, _npy(array))
    return path


def _npy_with_header(array, header_dict: bytes, padding: int = 0) -> bytes:
    """A version-2.0 .npy of `array` whose header is `header_dict` and `padding` spaces."""
    header = header_dict + b" " * padding + b"\n"
    return (b"\x93NUMPY\x02\x00" + struct.pack("<I", len(header)) + header
            + np.ascontiguousarray(array).tobytes())


def _with_channels_member(path, member: bytes):
    """`path` (an .npz) rewritten with its 'channels' member replaced by `member`."""
    with np.load(path) as data:
        contents = {name: data[name] for name in data.files}
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, array in contents.items():
            archive.writestr(f"{name}.npy", member if name == "channels" else _npy(array))
    return path


def _channels_header(path) -> bytes:
    with np.load(path) as data:
        channels = data["channels"]
    return repr({"descr": channels.dtype.str, "fortran_order": False,
                 "shape": channels.shape}).encode()


# Rule: a member's .npy header that is too long or unreadable is refused in the package's one
# line (the file, the array, what is wrong, run the trial again), never numpy's own message,
# which spans lines and advises allow_pickle=True.
@pytest.mark.parametrize("make_header, expected", [
    (lambda header: header + b" " * 3_000_000, "'channels' has a .npy header of 3000"),
    (lambda header: b"{'descr': <f8, 'shape': (}" + b" " * 40, "'channels' has a .npy header "
                                                              "that cannot be read"),
], ids=["huge", "unreadable"])
def test_a_trial_log_member_with_a_bad_npy_header_is_one_line_without_numpys_advice(
        tmp_path, capfd, make_header, expected):
    path = trial_log(tmp_path / "trial.npz")
    with np.load(path) as data:
        channels = data["channels"]
    _with_channels_member(path, _npy_with_header(channels, make_header(_channels_header(path))))
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, str(path), expected, "run the trial again")
    assert "allow_pickle" not in text and "max_header_size" not in text and "\\n" not in text
    assert not (tmp_path / "x.png").exists()


# Rule: a trial log's zip holds each array once and only the arrays the format has: with two
# members of one name, which one is read is the zip library's choice.
@pytest.mark.parametrize("member, expected", [
    ("meta.npy", "'meta.npy' is stored twice"),
    ("zzz.npy", "'zzz.npy' is not an array a trial log has"),
], ids=["duplicate", "unknown"])
def test_a_trial_log_with_duplicate_or_unknown_members_is_refused_naming_the_member(
        tmp_path, member, expected):
    path = _rezipped(trial_log(tmp_path / "trial.npz"),
                     [(member, np.array(json.dumps({"format_version": 1})))])
    log_refusal(path, expected)


def _with_last(times, value):
    times = times.copy()
    times[-1] = value
    return times


# Rule: each time base is sampled at one period (the logger's): a last sample 1e12 s after the
# others would make a 0.1 s log span 31,700 years.
@pytest.mark.parametrize("name, times", [
    ("t_ra", _with_last(np.linspace(0, 0.1, 101), 1e12)),
    ("t_sa", _with_last(np.linspace(0, 0.1, 11), 0.1005)),
    ("t_slow", np.concatenate([np.linspace(0, 0.05, 6), np.linspace(0.07, 0.12, 5)])),
], ids=["huge-last", "late-last", "gap"])
def test_a_trial_log_time_base_not_sampled_at_one_period_is_refused(tmp_path, name, times):
    log_refusal(trial_log(tmp_path / "trial.npz", **{name: times}),
             f"'{name}' is not sampled at one period")


def test_a_trial_log_with_the_controllers_mode_names_is_read(tmp_path):
    from tegrasp_drake.control.grasp_modes import Mode
    names = [mode.label for mode in Mode]
    path = trial_log_with(tmp_path / "trial.npz", {"mode_names": names})
    assert load_trial_log(path).meta["mode_names"] == names


# Rule: mode_names (what `phase` indexes) are the controllers' modes' labels, in their order,
# as the trial writes them: other names would label the phase plot with what never ran.
@pytest.mark.parametrize("names", [["A"] * 10, ["Reach", "Load"]], ids=["renamed", "short"])
def test_a_trial_log_whose_mode_names_are_not_the_modes_is_refused(tmp_path, names):
    refused_meta(tmp_path, {"mode_names": names}, "meta 'mode_names' must be the modes' labels")


# Rule: the log's controller is the one its trial result names: a figure labels the run with
# one and annotates it with the other's outcome.
def test_a_trial_log_whose_controller_differs_from_its_results_is_refused(tmp_path):
    result = whole_result(controller="memorized")
    path = trial_log_with(tmp_path / "ok.npz", {"controller": "memorized", "phase_starts": {},
                                                  "result": result})
    # a hand-made result, not the judge's of the small log's data: not judged again here
    assert load_trial_log(path, rejudge=False).meta["controller"] == "memorized"
    refused_meta(tmp_path, {"controller": "heuristic", "result": result},
                  "meta 'controller' is 'heuristic', but its 'result' is of 'memorized'")


# Rule: the log's trial result is of the seed its scenario ran with.
def test_a_trial_log_whose_result_seed_differs_from_its_scenarios_is_refused(tmp_path):
    scenario = "random_seed: 680\nobject:\n  name: box\n"
    trial = {"object_name": "box", "controller": "memorized"}  # the log's (META's)
    path = trial_log_with(tmp_path / "ok.npz", {"scenario": scenario, "phase_starts": {},
                                                 "result": whole_result(trial, seed=680)})
    assert load_trial_log(path, rejudge=False).meta["result"]["seed"] == 680  # hand-made
    refused_meta(tmp_path, {"scenario": scenario, "result": whole_result(trial, seed=681)},
                  "meta 'result' is of seed 681, but its 'scenario' ran with random_seed 680")


# Rule: the scenario a log stores is one the package can run (its sensors set the ranges above);
# a stored number outside its declared range is named, as a scenario file's would be.
def test_a_trial_log_storing_a_scenario_out_of_its_ranges_is_refused(tmp_path):
    path = trial_log_with(tmp_path / "trial.npz",
                           {"scenario": SCENARIO + "tactile:\n  noise_std_n: 7.0\n"})
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert (str(path) in message and "meta 'scenario'" in message
            and "tactile.noise_std_n" in message and "\n" not in message), message


def _with_times(tmp_path, scenario, name, change):
    """The small trial log storing `scenario` (None: none) with time base `name` changed."""
    with np.load(trial_log(tmp_path / "base.npz")) as base:
        times = change(base[name].copy())
    meta = {"scenario": scenario} if scenario is not None else {}
    return trial_log_with(tmp_path / "trial.npz", meta, **{name: times})


# Rule: each time base is sampled at the period its logger writes at in the log's scenario
# (a 1e-9-scaled RA base drew a raster-overflowing plot, exit 70).
@pytest.mark.parametrize("name, change, expected", [
    ("t_ra", lambda t: t * 1e-9, "'t_ra' is sampled every 1e-12 s, but its scenario's logger "
                                 "writes it every 0.001 s"),
    ("t_slow", lambda t: t * 2.0, "'t_slow' is sampled every 0.02 s, but its scenario's logger "
                                  "writes it every 0.01 s"),
    ("t_sa", lambda t: np.arange(len(t)) / 100.0, "'t_sa' is sampled every 0.01 s, but its "
                                                  "scenario's logger writes it every 0.00925926 s"),
], ids=["ra-scaled", "slow-doubled", "sa-at-100-hz"])
def test_a_time_base_not_at_its_loggers_period_is_refused(tmp_path, name, change, expected):
    log_refusal(_with_times(tmp_path, SCENARIO, name, change), expected)


# Rule: the three time bases cover one run: they start and end together, within the slower
# period (a log storing no scenario, or a bare recording, included).
@pytest.mark.parametrize("scenario", [SCENARIO, None], ids=["scenario", "none"])
@pytest.mark.parametrize("name, change, expected", [
    ("t_ra", lambda t: t - 100.0, "'t_sa' starts at 0 s but 't_ra' at -100 s; a trial's time "
                                  "bases cover one run"),
    ("t_slow", lambda t: t + 0.05, "'t_sa' starts at 0 s but 't_slow' at 0.05 s"),
    ("t_sa", lambda t: t + 0.0925926 * 2, "'t_sa' starts at 0.185185 s but 't_ra' at 0 s"),
], ids=["ra-100-s-early", "slow-late", "sa-late"])
def test_time_bases_that_do_not_cover_one_run_are_refused(tmp_path, scenario, name, change,
                                                         expected):
    log_refusal(_with_times(tmp_path, scenario, name, change), expected)


def test_a_scaled_time_base_ends_apart_from_the_others_without_a_scenario(tmp_path):
    log_refusal(_with_times(tmp_path, None, "t_ra", lambda t: t * 1e-9),
             "'t_sa' ends at 0.0925926 s but 't_ra' at 1e-10 s")


# Rule: a result names a registered controller and the corrective actions controllers take.
@pytest.mark.parametrize("data, expected", [
    ({"controller": "evil"}, "field 'controller' must be one of memorized, heuristic"),
    ({"corrective_actions": ["re_reach", "x" * 100_000]},
     "field 'corrective_actions[1]' must be one of avoid, lift_load, load_without_event, "
     "re_reach, regrasp, got 'xxxx"),
], ids=["controller", "action"])
def test_unknown_controllers_and_actions_are_refused(data, expected):
    result_refused({"hold_success": False, **data}, expected)


def test_a_controller_trials_metadata_is_read(tmp_path):
    from tegrasp_drake.scenario.trial_log_file import load_trial_log
    # META's result is hand-made, not the judge's of the small log's data: not judged again
    log = load_trial_log(trial_log_with(tmp_path / "trial.npz", META), rejudge=False)
    assert log.meta["result"]["transitions"] == TIMELINE


# Rule: a log with a timeline says when each of its phases began.
def test_a_log_without_phase_starts_is_refused(tmp_path):
    meta = {key: value for key, value in META.items() if key != "phase_starts"}
    meta_refused(tmp_path, meta, "meta lacks 'phase_starts'")


def test_a_trial_log_whose_metadata_is_a_list_is_not_a_trial_log(tmp_path):
    saved = small_trial_log().save(tmp_path / "saved.npz")
    with np.load(saved) as data:
        arrays = {name: data[name] for name in data.files}
    arrays["meta"] = np.array("[1, 2]")  # the metadata's JSON text: a list
    path = tmp_path / "trial.npz"
    np.savez(path, **arrays)
    with pytest.raises(TrialLogError, match="its metadata is a JSON list, not the object a "
                                            "trial log holds; it is not a trial log"):
        load_trial_log(path)


# Rule: TrialLog.save never writes a log that load_trial_log refuses (one checker for both):
# channels that are not Eq. 1-2 of the taxels, or taxels of another shape, are refused
# naming the path, and nothing is written there.
@pytest.mark.parametrize("spoil, expected", [
    (lambda log: {"channels": log.channels * 2}, "channel"),
    (lambda log: {"taxels": np.zeros((5, 3))}, "taxels"),
])
def test_a_trial_log_the_reader_refuses_is_never_saved(spoil, expected, tmp_path,
                                                       ideal_grasp_log):
    import dataclasses
    log = ideal_grasp_log("box")
    log.save(tmp_path / "whole" / "trial.npz")  # the log as run: saved
    (tmp_path / "whole" / "trial.npz").unlink()
    (tmp_path / "whole").rmdir()
    spoiled = dataclasses.replace(log, **spoil(log))
    path = tmp_path / "spoiled.npz"
    with pytest.raises(TrialLogError, match=f"TrialLog.save: '{path}' not written: .*{expected}"):
        spoiled.save(path)
    assert not path.exists() and list(tmp_path.iterdir()) == []


# Rule: a trial log this user cannot open (another user's: simulated, as root ignores modes)
# is said to be one that cannot be read, never a truncated or corrupt one to run again.
def test_a_trial_log_that_cannot_be_read_is_not_called_corrupt(tmp_path, capfd, monkeypatch):
    from tegrasp_drake.scenario import trial_log_file
    path = tmp_path / "trial.npz"
    trial_log(path)
    deny_reading(monkeypatch, trial_log_file.os, "open", path)
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, f"trial log '{path}' cannot be read (Permission denied)")
    assert "corrupt" not in text and "run the trial again" not in text
    assert not (tmp_path / "x.png").exists()
