"""analysis/compare_hands.py (and compare_geometry.py, which reads its classes): each changed
trial and the linkage run's failures are named by the package's failure classes
(sweep/failure_classes.py), not by a text of the script's own."""


from tests.fake_trials import timeline_ending
from tests.analysis_script import load_analysis_script


def compare_hands():
    return load_analysis_script("compare_hands")


TRIAL = {"trial_id": "taxel_aware/box/m02/a0", "controller": "taxel_aware",
         "object_name": "box", "well_placed": False, "marker_dx_m": 0.0, "marker_dy_m": 0.025}
HELD = {"hold_success": True, "unload_success": True, "failure": "", "final_mode": "Done",
        "hold_time_s": 4.7, "released": True, "lift_height_m": 0.06, "final_tilt_deg": 0.5,
        "transitions": timeline_ending("Done")}
REASON = ("the left finger struck the object during the approach (2.7 N at the wrist), "
          "after 4 Re-Reach attempts")
STRUCK = {"hold_success": False, "unload_success": False, "failure": REASON,
          "final_mode": "Failed", "lift_height_m": 0.0, "final_tilt_deg": 0.5,
          "transitions": [{"t": 5.0, "from": "Reach", "to": "Failed", "trigger": "corrective",
                           "reason": REASON, "code": "finger_strike"}]}


def test_a_changed_trial_and_the_failures_are_named_by_the_packages_failure_class():
    text = compare_hands().report({TRIAL["trial_id"]: (TRIAL, HELD)},
                                  {TRIAL["trial_id"]: (TRIAL, STRUCK)})
    assert "| taxel_aware/box/m02/a0 | +0, +25 | held and unloaded | struck on approach |" \
        in text, text
    assert "| taxel_aware | struck on approach | 1 |" in text, text
