"""analysis/compare_hands.py (and compare_geometry.py, which reads its classes): each changed
trial and the linkage run's failures are named by the package's failure classes
(sweep/failure_classes.py), not by a text of the script's own."""

import shutil

import pytest

from tests.fake_trials import timeline_ending, whole_result
from tests.analysis_script import ANALYSIS, load_analysis_script

RECORDS = ANALYSIS / "results_linkage" / "paper_grid" / "trials"


def compare_hands():
    return load_analysis_script("compare_hands")


TRIAL = {"trial_id": "taxel_aware/box/m02/a0", "controller": "taxel_aware",
         "object_name": "box", "well_placed": False, "marker_dx_m": 0.0, "marker_dy_m": 0.025}
HELD = whole_result(hold_success=True, unload_success=True, failure="", final_mode="Done",
                    hold_time_s=4.7, released=True, lift_height_m=0.06, final_tilt_deg=0.5,
                    transitions=timeline_ending("Done"))
REASON = ("the left finger struck the object during the approach (2.7 N at the wrist), "
          "after 4 Re-Reach attempts")
STRUCK = whole_result(hold_success=False, unload_success=False, failure=REASON,
                      final_mode="Failed", lift_height_m=0.0, final_tilt_deg=0.5,
                      transitions=[{"t": 5.0, "from": "Reach", "to": "Failed",
                                    "trigger": "corrective", "reason": REASON,
                                    "code": "finger_strike"}])


def test_a_changed_trial_and_the_failures_are_named_by_the_packages_failure_class():
    text = compare_hands().report({TRIAL["trial_id"]: (TRIAL, HELD)},
                                  {TRIAL["trial_id"]: (TRIAL, STRUCK)})
    assert "| taxel_aware/box/m02/a0 | +0, +25 | held and unloaded | struck on approach |" \
        in text, text
    assert "| taxel_aware | struck on approach | 1 |" in text, text


def test_a_folder_with_a_corrupt_record_is_refused_before_anything_is_printed(tmp_path,
                                                                               capsys):
    """A folder holding a corrupt record is refused (a comparison without that trial would be
    wrong) in one line, before a word of the comparison is said."""
    linkage, prismatic, out = tmp_path / "linkage", tmp_path / "prismatic", tmp_path / "out.md"
    (linkage / "trials").mkdir(parents=True)
    (prismatic / "trials").mkdir(parents=True)
    record = sorted(RECORDS.glob("*.json"))[0]
    shutil.copy(record, prismatic / "trials")
    (linkage / "trials" / record.name).write_text("{not json")
    with pytest.raises(SystemExit) as refused:
        compare_hands().main([str(out), str(linkage), str(prismatic)])
    assert str(refused.value).startswith(f"compare_hands: error: 1 corrupt trial record(s) in "
                                         f"{linkage}")
    assert capsys.readouterr() == ("", "")
    assert not out.exists()


@pytest.mark.parametrize("second", ["{linkage}", "{linkage}/../linkage", "{prismatic}"])
def test_one_folder_given_for_both_hands_or_twice_is_refused(tmp_path, capsys, second):
    """One hand's trials compared with themselves would say the hands agree."""
    linkage, prismatic, out = tmp_path / "linkage", tmp_path / "prismatic", tmp_path / "out.md"
    for folder in (linkage, prismatic):
        (folder / "trials").mkdir(parents=True)
        shutil.copy(sorted(RECORDS.glob("*.json"))[0], folder / "trials")
    again = second.format(linkage=linkage, prismatic=prismatic)
    with pytest.raises(SystemExit) as refused:
        compare_hands().main([str(out), str(linkage), str(prismatic), again])
    given = "linkage" if "linkage" in second else "prismatic"
    said = str(refused.value)  # the path cut to about 80 characters where long
    assert said.startswith("compare_hands: error: prismatic folder '"), said
    assert said.endswith(f"' is the {given} folder given before it; give each hand's own "
                         "`tegrasp sweep --out` folder, each once"), said
    assert capsys.readouterr() == ("", "")
    assert not out.exists()
