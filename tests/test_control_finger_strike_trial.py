"""The finger-strike sense in a closed-loop trial (issue #14): a yawed box 25 mm along the
stroke lies in the left finger's path; open loop knocks it over (analysis/results_beyond,
second grid), taxel_aware feels the strike in the joint torques, backs off, shifts toward
the left finger and holds the box."""

import dataclasses

import pytest

from tegrasp_drake.experiments.scenario import LoadScenario
from tegrasp_drake.experiments.trial import run_trial

pytestmark = pytest.mark.slow


def test_a_struck_box_is_backed_off_from_shifted_and_held():
    base = LoadScenario(name="box")
    scenario = dataclasses.replace(
        base, object_offset=[0.0, 0.025], object_yaw_deg=-11.8, random_seed=700,
        controller=dataclasses.replace(base.controller, name="taxel_aware"))
    result = run_trial(scenario).result
    first = result["transitions"][0]
    assert (first["from"], first["to"]) == ("Reach", "Re-Reach")
    assert "left finger struck" in first["reason"]
    assert first["offset_m"] > 0.01  # toward the left finger (+y)
    assert first["approach_offset_m"] < 0  # backed off
    assert result["hold_success"] and result["unload_success"]
