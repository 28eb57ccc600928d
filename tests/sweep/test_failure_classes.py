import pytest

from tegrasp_drake.runs.trial_result import TrialResult
from tegrasp_drake.sweep.failure_classes import (FAILURE_CLASSES, failure_class,
                                                 failure_class_counts, failure_classes_markdown)


def result(**changes):
    """A held and unloaded trial's result, changed by `changes`."""
    base = {"hold_success": True, "unload_success": True, "failure": "", "final_mode": "Done",
            "lift_height_m": 0.06, "final_tilt_deg": 0.5, "transitions": []}
    return {**base, **changes}


FAILED = dict(hold_success=False, unload_success=False, final_mode="Failed",
              lift_height_m=0.0)


@pytest.mark.parametrize("changes, expected", [
    ({}, None),
    ({**FAILED, "failure": "the gripper closed on nothing, after 2 Re-Reach attempts"},
     "closed on nothing"),
    ({**FAILED, "failure": "only the left finger touched, after 2 Re-Reach attempts"},
     "one finger only"),
    ({**FAILED, "failure": "no Reach-Load event 2 s after closing, after 2 Re-Reach attempts"},
     "event never matched"),
    ({**FAILED, "failure": "no Load-Lift event within 2 s; Re-Reach is switched off"},
     "event never matched"),
    ({**FAILED, "failure": "the object still slips after 2 Lift-Load corrections"},
     "slipped in Lift"),
    ({**FAILED, "failure": "no Load-Lift event within 2 s after Lift-Load"}, "slipped in Lift"),
    ({**FAILED, "failure": "object lost: no finger in contact", "lift_height_m": 0.03},
     "object lost"),
    ({**FAILED, "failure": "gripper fault overcurrent"}, "device fault"),
    ({**FAILED, "failure": "tactile: no new data for more than 500 ms",
      "transitions": [{"t": 5.0, "from": "Hold", "to": "Failed", "trigger": "fault",
                       "reason": "tactile: ..."}]}, "device fault"),
    ({**FAILED, "failure": "something new"}, "other"),
    ({"hold_success": False, "unload_success": False, "lift_height_m": 0.001}, "not lifted"),
    ({"hold_success": False, "unload_success": False, "lift_height_m": 0.05},
     "dropped in Hold"),
    ({"unload_success": False, "final_tilt_deg": 35.0}, "toppled at release"),
    ({"unload_success": False, "final_tilt_deg": 2.0}, "not placed"),
])
def test_each_failure_has_its_class(changes, expected):
    assert failure_class(TrialResult.from_dict(result(**changes))) == expected


def test_counts_per_controller_and_object_and_the_table():
    records = [
        {"status": "ok", "trial": {"controller": "memorized", "object_name": "box"},
         "result": result()},
        {"status": "ok", "trial": {"controller": "memorized", "object_name": "box"},
         "result": result(unload_success=False, final_tilt_deg=40.0)},
        {"status": "error", "trial": {"controller": "memorized", "object_name": "box"},
         "result": None},
        {"status": "ok", "trial": {"controller": "open_loop", "object_name": "thin_cylinder"},
         "result": result()},
    ]
    counts = failure_class_counts(records)
    assert counts["memorized"]["box"]["toppled at release"] == 1
    assert sum(counts["memorized"]["box"].values()) == 1
    assert set(counts["open_loop"]["thin_cylinder"]) == set(FAILURE_CLASSES)
    table = failure_classes_markdown(counts)
    assert "| box | 1 |" in table and "toppled at release" in table
    assert "not lifted" not in table  # only the classes that occur
