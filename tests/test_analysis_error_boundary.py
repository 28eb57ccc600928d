"""Every script of analysis/ given a path that cannot be what it asks for (a junk file where a
folder, trial log or results page belongs; a path under a file where it writes) ends with one
line on stderr and a non-zero exit code, never a Python traceback, never success on nothing."""

import os
import subprocess

import pytest

from tegrasp_drake.commands.error_boundary import EXIT_ERROR, EXIT_USAGE
from tegrasp_drake.sweep import SweepSpec, run_sweep
from tests.analysis_script import ANALYSIS, load_analysis_script
from tests.forked_runs import run_analysis_script
from tests.fake_trials import fake_trial

# The scripts that take no file or folder from the user, and why they are not run here.
NO_USER_PATHS = {"measure_finger_strike": "takes no arguments; its scenes are built in"}


def script_arguments(junk, under_junk) -> dict[str, list[str]]:
    """Each script's arguments: `junk` (a regular file of non-UTF-8 bytes) for what it reads,
    `under_junk` (a path below that file, which no folder can hold) for what it writes."""
    j, u = str(junk), str(under_junk)
    return {
        "check_rule_engine_equivalence": ["--base", "HEAD", "--out", u],
        "choose_corrective_thresholds": [j, j, u],
        "choose_ensemble_thresholds": [j, u],
        "compare_geometry": [u, j, j],
        "compare_hands": [u, j, j],
        "compare_ra_transients": [u + ".png"],
        "corrective_feasibility": [j, j, j],
        "detection_quality": [u, j],
        "explain_open_loop": [u + ".png"],
        "grip_rise": [j],
        "hold_creep": [j, j],
        "judge_corrective_triggers": [u],
        "linkage_figure": [u + ".png"],
        "make_corrective_test_windows": [j, j],
        "make_success_maps": [j],
        "make_table1": [j],
        "measure_load_lift": ["--events", j],
        "record_corrective_events": [u],
        "record_ensemble_events": [u],
        "rejudge_from_logs": [j, j, u],
        "roc_from_sweep_logs": [j, u],
        "transfer_diagnosis": [j, j],
        "transfer_matrix": [j, j],
        "update_results_page": [j],
        "weak_stimuli": [j, j],
    }


SCRIPTS = sorted(path.stem for path in ANALYSIS.glob("*.py"))


def run_script(name: str, arguments: list[str], cwd) -> subprocess.CompletedProcess:
    """analysis/`name`.py run as a user runs it, from `cwd` (not the repository)."""
    return run_analysis_script(name, arguments, cwd)


def test_every_script_is_listed():
    arguments = script_arguments("junk", "junk/x")
    assert sorted(set(arguments) | set(NO_USER_PATHS)) == SCRIPTS
    assert not set(arguments) & set(NO_USER_PATHS)


@pytest.mark.parametrize("name", sorted(script_arguments("junk", "junk/x")))
def test_script_refuses_a_junk_path_in_one_line(name, tmp_path):
    junk = tmp_path / "junk"
    junk.write_bytes(b"\xff\xfe\x00junk\x80" * 64)
    done = run_script(name, script_arguments(junk, junk / "x")[name], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert "Traceback" not in done.stderr and "internal error" not in done.stderr, done.stderr
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith(f"{name}: error: "), lines  # which script it was, an error


@pytest.mark.parametrize("name", SCRIPTS)
def test_script_refuses_a_command_line_that_does_not_parse_in_one_line(name, tmp_path):
    """Every script's parser (script_output.script_parser) ends an unknown option with the
    code of a command line that does not parse and one line naming the script, no usage."""
    done = run_script(name, ["--no-such-option"], tmp_path)
    assert done.returncode == EXIT_USAGE, (done.stdout, done.stderr)
    assert done.stdout == ""
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith(f"{name}: error: ") and f"{name}.py --help" in lines[0], lines


@pytest.mark.parametrize("name", ["compare_ra_transients", "explain_open_loop",
                                  "linkage_figure"])
def test_a_figure_name_of_no_format_is_bad_input_not_a_command_line_error(name, tmp_path):
    done = run_script(name, [str(tmp_path / "figure.jpg")], tmp_path)
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{name}: error: "), done.stderr
    assert "must end in one of .png, .pdf, .svg" in lines[0]
    assert list(tmp_path.iterdir()) == []


# Each script's numeric options, one family a row: a number that parses but lies outside its
# range is refused before any work as the package's commands refuse one (`tegrasp sweep
# --workers 0`): bad input, one line naming the option and its range.
@pytest.mark.parametrize("name, arguments, words", [
    ("explain_open_loop", ["out.png", "--workers", "0"], "--workers must be at least 1, got 0"),
    ("judge_corrective_triggers", ["out.md", "--workers", "-2"], "--workers must be at least 1"),
    ("measure_load_lift", ["--workers", "0"], "--workers must be at least 1"),
    ("measure_load_lift", ["--seed", "-1"], "--seed must lie in [0, 4294967295]"),
    ("record_corrective_events", ["logs", "--workers", "0"], "--workers must be at least 1"),
    ("record_ensemble_events", ["logs", "--workers", "0"], "--workers must be at least 1"),
    ("record_ensemble_events", ["logs", "--runs", "-3"], "--runs must be at least 1, got -3"),
    ("record_ensemble_events", ["logs", "--template-runs", "0"],
     "--template-runs must be at least 1"),
    ("record_ensemble_events", ["logs", "--runs", "2", "--template-runs", "3"],
     "--template-runs must be at most --runs (2), got 3"),
    ("choose_ensemble_thresholds", ["logs", "out.md", "--runs", "5", "-3"],
     "--runs must be at least 0 (the index of a run"),
    ("roc_from_sweep_logs", ["logs", "out.md", "--limit", "0"], "--limit must be at least 1"),
    ("compare_ra_transients", ["out.png", "--speed", "-0.1"], "--speed must be above 0 m/s"),
    ("transfer_diagnosis", ["events", "run", "--ra-envelope-hz", "-1"],
     "--ra-envelope-hz must be 0 (no RA envelope)"),
])
def test_a_numeric_option_out_of_its_range_is_refused_as_bad_input(name, arguments, words,
                                                                   tmp_path):
    done = run_script(name, arguments, tmp_path)
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert lines == [f"{name}: error: {lines[0].split(': error: ', 1)[-1]}"], done.stderr
    assert words in lines[0], lines
    assert list(tmp_path.iterdir()) == []  # refused before any work


# A script's number option reads its text as every command's does (rig.number_text): what only
# Python's float() reads as a number (nan, `1_0`) is a command line that does not parse.
@pytest.mark.parametrize("text", ["nan", "1_0"])
def test_a_number_option_that_is_no_number_text_does_not_parse(text, tmp_path):
    done = run_script("compare_ra_transients", ["out.png", "--speed", text], tmp_path)
    assert done.returncode == EXIT_USAGE, (done.stdout, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and f"argument --speed: {text!r} is not a number" in lines[0], lines
    assert list(tmp_path.iterdir()) == []


def test_results_page_refuses_a_fifo_without_opening_it(tmp_path):
    fifo = tmp_path / "results.md"
    os.mkfifo(fifo)  # no writer: open() for reading would block for ever
    done = run_script("update_results_page", [str(fifo)], tmp_path)
    assert done.returncode == 1 and "named pipe" in done.stderr, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def fake_trial_with_avoid(trial):
    """fake_trial's result with a Hold that an Avoid ended (hold_creep's trials)."""
    result = fake_trial(trial)
    chain = ("Reach", "Load", "Lift", "Hold", "Avoid")
    result.update(hold_success=False, unload_success=False, released=False,
                  final_mode="Avoid", corrective_actions=["avoid"], transitions=[
                      {"t": 1.0 + 0.5 * k, "from": a, "to": b, "reason": "",
                       "trigger": "memorized_event" if k == 0 else "timer"}
                      for k, (a, b) in enumerate(zip(chain, chain[1:]))])
    return result


@pytest.fixture
def sweep_without_logs(tmp_path):
    """(a sweep's results folder of two trials with an Avoid, an empty logs folder)."""
    results, logs = tmp_path / "results", tmp_path / "logs"
    logs.mkdir()
    run_sweep(SweepSpec(objects=("box",), attempts=2), fake_trial_with_avoid, results,
              workers=1, progress=False)
    return results, logs


@pytest.mark.parametrize("empty", ["results", "logs"])
def test_rejudge_refuses_when_it_has_nothing_to_judge(empty, sweep_without_logs, tmp_path):
    results, logs = sweep_without_logs
    if empty == "results":
        results = tmp_path / "empty"
        results.mkdir()
    out = tmp_path / "rejudged"
    with pytest.raises(SystemExit, match="holds no" if empty == "results" else "holds none of"):
        load_analysis_script("rejudge_from_logs").main([str(results), str(logs), str(out)])
    assert not out.exists()


def test_hold_creep_refuses_logs_that_match_no_record(sweep_without_logs):
    results, logs = sweep_without_logs
    with pytest.raises(SystemExit, match="holds none of the logs of the .* trials with an Avoid"):
        load_analysis_script("hold_creep").main([str(results), str(logs)])


def test_hold_creep_refuses_a_folder_without_records(tmp_path):
    with pytest.raises(SystemExit, match="holds no trial record"):
        load_analysis_script("hold_creep").main([str(tmp_path), str(tmp_path)])


def run_script_into_full_disk(name: str, arguments: list[str], cwd):
    """run_script with its standard output on /dev/full (a disk with no room)."""
    return run_analysis_script(name, arguments, cwd, stdout="/dev/full")


@pytest.mark.parametrize("name", SCRIPTS)
def test_help_that_cannot_be_written_is_an_error_naming_standard_output(name, tmp_path):
    """argparse drops an OSError printing --help; the scripts' boundary tells it, as `tegrasp
    --help >/dev/full` does, rather than exit 0 with the help lost."""
    done = run_script_into_full_disk(name, ["--help"], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, done.stderr
    assert lines == [f"{name}: error: cannot write to standard output: No space left on "
                     "device"], done.stderr


def test_a_report_printed_to_a_full_disk_names_standard_output(tmp_path):
    from tegrasp_drake.sweep import SweepSpec, run_sweep
    from tests.fake_trials import fake_trial
    results = tmp_path / "results"
    run_sweep(SweepSpec(objects=("box",), attempts=1, controllers=("open_loop",)), fake_trial,
              results, workers=1, progress=False)
    done = run_script_into_full_disk("detection_quality",
                                     [str(tmp_path / "dq.md"), str(results)], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, done.stderr
    assert lines == ["detection_quality: error: cannot write to standard output: No space "
                     "left on device"], done.stderr
    assert (tmp_path / "dq.md").is_file()  # the report file was written before the print


# Rule: a script's input (a folder, or a file, it reads) that is missing or of the other kind
# is named by the script's own argument ("results folder", "--events folder"), never by a
# function's parameter (`load_records: argument 'out_dir'`), with what to give; it is checked
# before any output, so an input that cannot be read is never blamed on writing.
SWEEP = "give the --out folder of `tegrasp sweep`"
EVENTS = "give a folder of memorized events (`tegrasp record-events --out`)"
CORRECTIVE = "give the folder analysis/record_corrective_events.py wrote"
ENSEMBLE = "give the folder analysis/record_ensemble_events.py wrote"
INPUTS = [  # (script, its arguments with IN the input and OUT an output, what, advice)
    ("make_table1", ["IN"], "results folder", SWEEP),
    ("make_success_maps", ["IN"], "results folder", SWEEP),
    ("detection_quality", ["OUT/dq.md", "IN"], "results folder", SWEEP),
    ("compare_geometry", ["OUT/cg.md", "IN", "IN"], "reference folder", SWEEP),
    ("compare_hands", ["OUT/ch.md", "IN", "IN"], "linkage folder", SWEEP),
    ("hold_creep", ["IN", "IN", "--out", "OUT/hc.md"], "results folder", SWEEP),
    ("rejudge_from_logs", ["IN", "IN", "OUT/r"], "results folder", SWEEP),
    ("weak_stimuli", ["IN", "IN"], "results folder", SWEEP),
    ("roc_from_sweep_logs", ["IN", "OUT/roc.md"], "logs folder",
     "give the --logs folder of a `tegrasp sweep`"),
    ("choose_ensemble_thresholds", ["IN", "OUT/t.md"], "logs folder", ENSEMBLE),
    ("choose_corrective_thresholds", ["IN", "IN", "OUT/t.md"], "corrective logs folder",
     CORRECTIVE),
    ("make_corrective_test_windows", ["IN", "IN"], "corrective logs folder", CORRECTIVE),
    ("corrective_feasibility", ["IN", "IN", "IN"], "corrective logs folder", CORRECTIVE),
    ("measure_load_lift", ["--events", "IN"], "--events folder", EVENTS),
    ("transfer_diagnosis", ["IN", "IN"], "events folder", EVENTS),
    ("transfer_matrix", ["spec.yaml", "IN"], "results folder",
     "give the --out folder of `tegrasp transfer`"),
]


@pytest.mark.parametrize("kind", ["missing", "a file"])
@pytest.mark.parametrize("name, arguments, what, advice", INPUTS,
                         ids=[row[0] for row in INPUTS])
def test_an_input_folder_is_named_by_the_scripts_own_argument(name, arguments, what, advice,
                                                              kind, tmp_path):
    given = tmp_path / "in"
    if kind == "a file":
        given.write_text("not a folder\n")
    (tmp_path / "spec.yaml").write_text("base: {}\n")
    (tmp_path / "out").write_text("a file where the outputs' folder belongs\n")
    # Paths relative to the script's folder, tmp_path: a message echoes a long path cut short.
    argv = [a.replace("IN", "in").replace("OUT", "out") for a in arguments]
    done = run_script(name, argv, tmp_path)
    why = "does not exist" if kind == "missing" else "is a file, not a folder"
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert done.stderr == f"{name}: error: {what} 'in' {why}; {advice}\n", done.stderr
    assert "argument '" not in done.stderr and "cannot write" not in done.stderr


def test_make_table1_names_its_results_argument_not_load_records(tmp_path):
    done = run_script("make_table1", ["nonexist"], tmp_path)
    assert done.returncode == EXIT_ERROR
    assert done.stderr == ("make_table1: error: results folder 'nonexist' does "
                           "not exist; give the --out folder of `tegrasp sweep`\n"), done.stderr


def test_an_empty_results_folder_says_it_holds_no_records(tmp_path):
    (tmp_path / "empty").mkdir()
    done = run_script("make_table1", [str(tmp_path / "empty")], tmp_path)
    assert done.returncode == EXIT_ERROR
    assert done.stderr.startswith("make_table1: error: no trial records under "), done.stderr


@pytest.mark.parametrize("name, arguments, what", [
    ("update_results_page", ["IN"], "results page 'IN' is a folder, not a file; give the "
                                    "Markdown results page"),
    ("grip_rise", ["IN"], "trial log 'IN' is a folder, not a file"),
    ("transfer_matrix", ["IN", "IN"], "IN: cannot read the transfer spec: it is a folder"),
])
def test_a_folder_where_an_input_file_belongs_is_named(name, arguments, what, tmp_path):
    given = tmp_path / "in"
    given.mkdir()
    done = run_script(name, [a.replace("IN", "in") for a in arguments], tmp_path)
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert done.stderr.startswith(f"{name}: error: {what.replace('IN', 'in')}"), done.stderr
    assert "cannot write" not in done.stderr and len(done.stderr.splitlines()) == 1
