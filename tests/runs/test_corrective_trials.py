"""A closed-loop trial of the memorized hit trigger: a hit that no template or
threshold choice saw sends Hold to Avoid by the memorized hit event, and the grasp
succeeds. (The heuristic trigger's trial: runs/test_closed_loop_trial.py.)"""

import pytest

from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.runs.trial import run_trial

pytestmark = pytest.mark.slow


def test_a_hit_in_hold_is_avoided_by_the_memorized_hit_event():
    hit_time = 6.9
    result = run_trial(LoadScenario(overrides=[
        "controller.memorized_corrective.events=[hold_avoid]",
        f"disturbance.hit_time_s={hit_time}", "disturbance.hit_force_n=[0.0, -22.0, 0.0]"])
    ).result
    avoids = [e for e in result["transitions"] if e["to"] == "Avoid"]
    assert len(avoids) == 1
    assert avoids[0]["from"] == "Hold" and avoids[0]["trigger"] == "corrective_event"
    assert 0.0 <= avoids[0]["t"] - hit_time <= 0.06  # the hit matched within 60 ms
    assert result["corrective_actions"] == ["avoid"]
    assert result["hold_success"] and result["unload_success"]
    # The judge keeps the hit as the Avoid's physical event (the sweep's detection report).
    assert result["physical_events"]["hit"] == pytest.approx(hit_time)
