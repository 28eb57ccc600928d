"""The sensitivity report's numbers from known records: misplaced held and placed per point,
the tornado's bars, the failure classes at each end, the figure written."""

from tegrasp_drake.scenario.grasp_outcome import LIFTED_HEIGHT_M
from tegrasp_drake.scenario.trial_result import UPRIGHT_TILT_DEG
from tegrasp_drake.sensitivity.parameters import parameter
from tegrasp_drake.sensitivity.report import (point_rows, tornado_bars,
                                              write_sensitivity_report)
from tegrasp_drake.sensitivity.study import (SensitivitySpec, one_at_a_time,
                                             point_folder_cell, transfer_spec)
from tegrasp_drake.sweep.records import make_record, write_record
from tegrasp_drake.sweep.spec import SweepSpec, expand_trials
from tegrasp_drake.transfer.matrix import cell_folder, running_sweep
from tests.fake_trials import result_of_trial, timeline_ending, whole_result

SPEC = SensitivitySpec(parameters=(parameter("gripper.screw_efficiency"),), sweep=SweepSpec(
    objects=("box",), controllers=("memorized",), grid=((0.0, 0.0), (0.01, 0.0)),
    attempts=2, base_seed=600))
HELD_AND_PLACED = whole_result(hold_success=True, unload_success=True, final_mode="Done",
                               transitions=timeline_ending("Done"), released=True,
                               lift_height_m=LIFTED_HEIGHT_M + 0.05, final_tilt_deg=0.0)
DROPPED = {**HELD_AND_PLACED, "hold_success": False, "unload_success": False}
TOPPLED = {**HELD_AND_PLACED, "unload_success": False, "final_tilt_deg": UPRIGHT_TILT_DEG + 30}
# Per point, its two misplaced trials' outcomes (the well-placed two are held and placed).
MISPLACED = {"default": (HELD_AND_PLACED, HELD_AND_PLACED),
             "gripper_screw_efficiency_low": (HELD_AND_PLACED, DROPPED),
             "gripper_screw_efficiency_high": (TOPPLED, HELD_AND_PLACED)}


def write_known_records(out_dir):
    points = one_at_a_time(SPEC)
    matrix = transfer_spec(SPEC, points)
    for point in points:
        trials = [t.to_dict() for t in expand_trials(running_sweep(matrix, point.name))]
        misplaced = iter(MISPLACED[point.name])
        folder = cell_folder(out_dir, *point_folder_cell(SPEC, point))
        for trial in trials:
            result = HELD_AND_PLACED if trial["well_placed"] else next(misplaced)
            write_record(folder, make_record(trial, result=result_of_trial(result, trial)))
    return points


def test_the_rates_and_failure_classes_of_each_point_come_from_its_records(tmp_path):
    points = write_known_records(tmp_path)
    rows = {row.point: row for row in point_rows(SPEC, points, tmp_path)}
    assert {name: (r.misplaced, r.held, r.placed) for name, r in rows.items()} == {
        "default": (2, 2, 2), "gripper_screw_efficiency_low": (2, 1, 1),
        "gripper_screw_efficiency_high": (2, 2, 1)}
    assert rows["default"].failures == ()
    assert rows["gripper_screw_efficiency_low"].failures == (("dropped in Hold", 1),)
    assert rows["gripper_screw_efficiency_high"].failures == (("toppled at release", 1),)


def test_the_tornado_bars_run_from_the_default_to_each_end(tmp_path):
    points = write_known_records(tmp_path)
    rows = point_rows(SPEC, points, tmp_path)
    (held,) = tornado_bars(points, rows, "memorized", "held")
    assert (held.default, held.low, held.high, held.swing) == (1.0, 0.5, 1.0, 0.5)
    (placed,) = tornado_bars(points, rows, "memorized", "placed")
    assert (placed.default, placed.low, placed.high) == (1.0, 0.5, 0.5)


def test_the_report_names_the_classes_at_each_end_and_draws_the_tornado(tmp_path):
    points = write_known_records(tmp_path)
    written = write_sensitivity_report(SPEC, points, tmp_path)
    assert [p.name for p in written] == ["sensitivity.md", "tornado.png"]
    assert written[1].stat().st_size > 0
    text = written[0].read_text()
    assert ("| `gripper.screw_efficiency` | memorized | dropped in Hold 1 | none | "
            "toppled at release 1 |") in text
    assert ("| gripper_screw_efficiency_low | `gripper.screw_efficiency` 0.26 | memorized | 4 "
            "| 50 % (1/2) | 50 % (1/2) | dropped in Hold 1 |") in text
    assert "| memorized | 2 | 50 / 75 / 100 % | 50 / 50 / 50 % |" in text


def test_a_point_without_records_is_named_as_not_run(tmp_path):
    points = write_known_records(tmp_path)
    folder = cell_folder(tmp_path, *point_folder_cell(SPEC, points[2]))
    for record in (folder / "trials").glob("*.json"):
        record.unlink()
    text = write_sensitivity_report(SPEC, points, tmp_path)[0].read_text()
    assert "Not run yet (no finished trial): gripper_screw_efficiency_high." in text
