"""The analysis scripts' outputs are checked before any work (a figure name of no format, a
device, a path no file can take: one line, EXIT_ERROR), and a script that makes a table or
figure from a sweep folder refuses one holding a corrupt record, as `tegrasp plot` does,
rather than writing a table that silently lost a trial."""

import pathlib
import re

import pytest

from tegrasp_drake.commands import script_output
from tegrasp_drake.commands.error_boundary import EXIT_ERROR
from tegrasp_drake.sweep import SweepSpec, run_sweep
from tests.analysis_script import ANALYSIS, load_analysis_script
from tests.fake_trials import fake_trial
from tests.test_analysis_error_boundary import run_script


def output_arguments(junk: str, out: str) -> dict[str, list[str]]:
    """Each script that writes a report or figure, with `junk` for what it reads and `out`
    for what it writes."""
    return {"check_rule_engine_equivalence": ["--base", junk, "--out", out, "--scenes", junk],
            "choose_corrective_thresholds": [junk, junk, out],
            "choose_ensemble_thresholds": [junk, out],
            "detection_quality": [out, junk],
            "hold_creep": [junk, junk, "--out", out],
            "make_success_maps": [junk, "--file", out],
            "roc_from_sweep_logs": [junk, out],
            "transfer_matrix": [junk, out],  # its reports go into the results folder
            "update_results_page": [out]}  # the page it reads, written again


# A path a script reads and writes again (the results page, transfer_matrix's results folder)
# is an input first: one that is no file (or folder) to read is named as the input it is.
READ_AND_WRITTEN = {"update_results_page": "results page '/dev/full' is a device, not a file",
                    "transfer_matrix": "results folder '/dev/full' is a device, pipe or socket, "
                                       "not a folder"}


@pytest.mark.parametrize("name", sorted(output_arguments("j", "o")))
def test_an_output_that_cannot_be_written_is_refused_before_the_inputs_are_read(name, tmp_path):
    junk = tmp_path / "junk"  # a folder, as the inputs are, whose content is junk
    junk.mkdir()
    (junk / "junk").write_bytes(b"\xff\xfe\x00junk\x80" * 64)
    done = run_script(name, output_arguments(str(junk), "/dev/full")[name], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert len(lines) == 1 and lines[0].startswith(f"{name}: error: "), done.stderr
    assert "/dev/full" in lines[0], lines
    if name in READ_AND_WRITTEN:
        assert READ_AND_WRITTEN[name] in lines[0], lines
    elif name != "make_success_maps":  # a figure's name is checked first (no format)
        assert "cannot write" in lines[0], lines


@pytest.fixture
def sweep(tmp_path):
    """A sweep's results folder of two fake trials."""
    results = tmp_path / "results"
    run_sweep(SweepSpec(objects=("box",), attempts=2), fake_trial, results, workers=1,
              progress=False)
    return results


def test_success_maps_refuse_a_figure_name_of_no_format_before_reading(sweep, tmp_path):
    done = run_script("make_success_maps", [str(sweep), "--file", "o/maps.bmp"], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert len(lines) == 1 and lines[0].startswith("make_success_maps: error: "), lines
    assert "must end in one of .png, .pdf, .svg" in lines[0]


def test_success_maps_file_is_a_path_from_the_current_folder(sweep, tmp_path):
    done = run_script("make_success_maps", [str(sweep), "--file", "o/maps.svg"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "o" / "maps.svg").is_file()
    assert not (sweep / "o").exists()


def corrupt_one_record(results):
    record = sorted((results / "trials").glob("*.json"))[0]
    record.write_text(record.read_text().replace('"box"', '"bux"', 1))
    return record


def sweep_script_arguments(results, tmp_path) -> dict[str, list[str]]:
    r, out = str(results), str(tmp_path / "out")
    return {"make_table1": [r],
            "make_success_maps": [r],
            "hold_creep": [r, r],
            "weak_stimuli": [r, r],
            "rejudge_from_logs": [r, r, out],
            "compare_hands": [str(tmp_path / "report.md"), r, r],
            "compare_geometry": [str(tmp_path / "report.md"), r, r],
            "detection_quality": [str(tmp_path / "report.md"), r]}


# How a script reads a sweep folder's records: sweep.load_records, script_output's
# load_sweep_records (which refuses a corrupt record), or compare_hands' load_folders (through it).
_READS_RECORDS = re.compile(r"\b(load_records|load_sweep_records|load_folders)\(")


def scripts_reading_sweep_folders() -> set[str]:
    return {path.stem for path in ANALYSIS.glob("*.py")
            if _READS_RECORDS.search(path.read_text(encoding="utf-8"))}


def test_every_script_that_reads_a_sweep_folder_is_tried_with_a_corrupt_record():
    """The parametrisation below is every analysis script that reads records, not a list that a
    new script (or one that read records its own way) escapes."""
    assert scripts_reading_sweep_folders() == set(sweep_script_arguments("r", pathlib.Path("t")))


def test_scripts_read_a_sweep_folder_only_through_load_sweep_records():
    """sweep.load_records returns corrupt records beside the good ones; a script calling it
    directly would make its table without them (script_output.load_sweep_records refuses)."""
    direct = {path.stem for path in ANALYSIS.glob("*.py")
              if re.search(r"\bload_records\(", path.read_text(encoding="utf-8"))}
    assert not direct, f"call script_output.load_sweep_records instead in {sorted(direct)}"


@pytest.mark.parametrize("name", sorted(sweep_script_arguments("r", pathlib.Path("t"))))
def test_a_sweep_folder_with_a_corrupt_record_is_refused(name, sweep, tmp_path):
    record = corrupt_one_record(sweep)
    before = {path.name: path.stat().st_mtime_ns for path in sweep.iterdir()}
    with pytest.raises(SystemExit) as stopped:
        load_analysis_script(name).main(sweep_script_arguments(sweep, tmp_path)[name])
    message = str(stopped.value)
    assert message.startswith(f"{name}: error: 1 corrupt trial record(s)"), message
    assert record.name in message and "\n" not in message
    assert {path.name: path.stat().st_mtime_ns for path in sweep.iterdir()} == before


def test_results_page_without_the_table_block_is_refused_naming_the_script(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("# Results\n\nno table here\n")
    done = run_script("update_results_page", [str(page)], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert len(lines) == 1 and lines[0].startswith("update_results_page: error: "), lines
    assert str(page) in lines[0]


def test_a_line_a_script_ends_with_is_led_by_its_name():
    def main(argv):
        raise SystemExit("results: holds nothing")
    with pytest.raises(SystemExit) as stopped:
        script_output.run_script(main, "some_script", [])
    assert str(stopped.value) == "some_script: error: results: holds nothing"


# --- an existing file at a script's output is replaced only when the script wrote it ---

def named_report_arguments(junk: str, out: str) -> dict[str, list[str]]:
    """Each script that writes a report (a bare table, a JSON list of rows) to a file the
    user names, with `junk` for what it reads and `out` for the report."""
    return {"choose_corrective_thresholds": [junk, junk, out],
            "choose_ensemble_thresholds": [junk, out],
            "compare_geometry": [out, junk, junk],
            "compare_hands": [out, junk, junk],
            "detection_quality": [out, junk],
            "hold_creep": [junk, junk, "--out", out],
            "judge_corrective_triggers": [out],
            "measure_load_lift": ["--events", junk, "--json", out],
            "roc_from_sweep_logs": [junk, out],
            "weak_stimuli": [junk, junk, "--out", out]}


USERS_FILES = {"sweep_table": "| controller | well-placed ~Hold |\n|---|---|\n",
               "json": '{"trial_id": "mine"}\n', "notes": "my notes\n"}


@pytest.mark.parametrize("content", sorted(USERS_FILES))
@pytest.mark.parametrize("name", sorted(named_report_arguments("j", "o")))
def test_a_file_the_script_did_not_write_is_kept_and_refused_before_any_work(name, content,
                                                                             tmp_path):
    junk = tmp_path / "junk"  # inputs that exist but hold junk: read, they would be refused
    junk.mkdir()
    out = tmp_path / "mine.md"
    out.write_text(USERS_FILES[content])
    done = run_script(name, named_report_arguments(str(junk), str(out))[name], tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    first = USERS_FILES[content].splitlines()[0]
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"{name}: error: {out} exists and is not a "), lines
    assert lines[0].endswith(f"this script writes (its first line is {first!r}); give another "
                             "file name, or remove it yourself"), lines
    assert out.read_text() == USERS_FILES[content]
    assert sorted(tmp_path.iterdir()) == [junk, out]


def test_every_script_writing_a_named_report_declares_its_title():
    """A report is written through write_report or declared with add_output: none escapes
    the rule by writing its own way."""
    writers = {path.stem for path in ANALYSIS.glob("*.py")
               if re.search(r"\bwrite_report\(|rows=ROW_KEYS", path.read_text(encoding="utf-8"))}
    assert writers == set(named_report_arguments("j", "o"))


def test_a_report_of_the_script_is_replaced_and_one_of_another_title_is_not(sweep, tmp_path):
    out = tmp_path / "quality.md"
    for _ in range(2):
        done = run_script("detection_quality", [str(out), str(sweep)], tmp_path)
        assert done.returncode == 0, done.stderr
    assert out.read_text().startswith("# Detection quality and paired comparison\n")
    before = out.read_bytes()
    done = run_script("detection_quality", [str(out), str(sweep), "--title", "Mine"], tmp_path)
    assert done.returncode == EXIT_ERROR, done.stderr
    assert ("is not a report this script writes (its first line is '# Detection quality and "
            "paired comparison')") in done.stderr
    assert out.read_bytes() == before


def test_a_file_put_at_the_report_during_the_work_is_kept(tmp_path):
    """write_report asks again when it writes: a file that came during the work is kept."""
    out = tmp_path / "report.md"
    out.write_text("my notes\n")
    with pytest.raises(SystemExit, match=r"^detection_quality: error: .*report.md exists and is "
                                         r"not a report this script writes"):
        script_output.write_report(out, "# Detection quality\n", script="detection_quality")
    assert out.read_text() == "my notes\n"
    table = tmp_path / "table.md"
    table.write_text("# My table\n")
    with pytest.raises(SystemExit, match="is not a table this script writes"):
        script_output.write_report(table, "| a |\n", script="judge_corrective_triggers",
                                   start=script_output.MARKDOWN_TABLE_START)


def named_figure_arguments(junk: str, out: str) -> dict[str, list[str]]:
    """Each script that writes a figure to a file the user names."""
    return {"compare_ra_transients": [out], "explain_open_loop": [out],
            "linkage_figure": [out], "make_success_maps": [junk, "--file", out]}


@pytest.mark.parametrize("name", sorted(named_figure_arguments("j", "o")))
def test_a_figure_the_user_names_is_replaced_only_with_overwrite(name, tmp_path):
    from tegrasp_drake.figures.figure_files import new_figure, save_figure
    junk = tmp_path / "junk"
    junk.mkdir()
    out = save_figure(new_figure(1, 1), tmp_path / "photo.png")
    before = out.read_bytes()
    done = run_script(name, named_figure_arguments(str(junk), str(out))[name], tmp_path)
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert done.stderr.strip() == (f"{name}: error: {out} exists (an earlier figure); pass "
                                   "--overwrite to replace it, or give a new file name")
    assert out.read_bytes() == before


def test_a_named_figure_is_replaced_with_overwrite_and_the_folders_own_without(sweep,
                                                                              tmp_path):
    from tegrasp_drake.figures.figure_files import new_figure, save_figure
    out = save_figure(new_figure(1, 1), tmp_path / "photo.png")
    before = out.read_bytes()
    done = run_script("make_success_maps", [str(sweep), "--file", str(out), "--overwrite"],
                      tmp_path)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes() != before
    for _ in range(2):  # RESULTS/success_maps.png, the sweep folder's own figure
        done = run_script("make_success_maps", [str(sweep)], tmp_path)
        assert done.returncode == 0, done.stderr


def test_a_reference_controller_the_results_do_not_hold_is_refused(sweep, tmp_path):
    """A paired table against a controller no trial ran would be empty: refused, naming the
    controllers the folders hold."""
    out = tmp_path / "quality.md"
    done = run_script("detection_quality", [str(out), str(sweep), "--reference", "taxel_aware"],
                      tmp_path)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == EXIT_ERROR, (done.stdout, done.stderr)
    assert len(lines) == 1, lines
    assert lines[0].startswith("detection_quality: error: --reference taxel_aware: the results "
                               "hold no trial of that controller (they hold "), lines
    assert not out.exists()
    done = run_script("detection_quality", [str(out), str(sweep), "--reference", "nonesuch"],
                      tmp_path)
    assert done.returncode != 0 and "nonesuch" in done.stderr and "Traceback" not in done.stderr
    assert not out.exists()
