"""The analysis scripts' reports are written whole (rig/files.write_atomically): a report that
cannot be written is one line naming it, and an earlier report stays as it was."""

import shutil

import pytest

from tests.analysis_script import ANALYSIS, load_analysis_script

RECORDS = ANALYSIS / "results_linkage" / "paper_grid" / "trials"


@pytest.fixture
def results(tmp_path):
    """A results folder of three committed sweep records."""
    folder = tmp_path / "results"
    (folder / "trials").mkdir(parents=True)
    for record in sorted(RECORDS.glob("*.json"))[:3]:
        shutil.copy(record, folder / "trials")
    return folder


def arguments(script, out, results):
    other = results.with_name("other_hand")  # compare_hands refuses one folder for both hands
    if script == "compare_hands" and not other.exists():
        shutil.copytree(results, other)
    return {"compare_geometry": [str(out), str(results), str(results)],
            "compare_hands": [str(out), str(results), str(other)],
            "detection_quality": [str(out), str(results)],
            "hold_creep": [str(results), str(results), "--out", str(out)]}[script]


@pytest.mark.parametrize("script", ["compare_geometry", "compare_hands", "detection_quality",
                                    "hold_creep"])
def test_a_report_that_cannot_be_written_is_one_line_naming_it(script, results, tmp_path):
    out = tmp_path / "no such folder" / "report.md"
    with pytest.raises(SystemExit) as stopped:
        load_analysis_script(script).main(arguments(script, out, results))
    message = str(stopped.value)
    assert message.startswith(f"{script}: ") and str(out) in message
    assert "\n" not in message


@pytest.mark.parametrize("script", ["compare_geometry", "detection_quality"])
def test_a_written_report_is_a_markdown_page_and_no_staging_file_is_left(script, results,
                                                                          tmp_path):
    out = tmp_path / "report.md"
    assert load_analysis_script(script).main(arguments(script, out, results)) == 0
    assert out.read_text().startswith("# ")
    assert [p.name for p in tmp_path.iterdir() if p.is_file()] == ["report.md"]
