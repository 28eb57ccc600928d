"""End-to-end closed-loop trials in simulation (station + events + state machine)."""

import json

import pytest

from tegrasp_drake.cli import main
from tegrasp_drake.events import MemorizedEventError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.runs.trial import run_trial

EVENT_TRANSITIONS = [("Reach", "Load"), ("Load", "Lift"), ("Place", "Unload")]


def steps(result):
    return [(e["from"], e["to"]) for e in result["transitions"]]


def trigger_of(result, step):
    return next(e["trigger"] for e in result["transitions"] if (e["from"], e["to"]) == step)


def test_tegrasp_trial_json_at_the_expected_position(tmp_path, capsys):
    assert main(["trial", "--json", "--out", str(tmp_path)]) == 0
    captured = capsys.readouterr()
    result = json.loads(captured.out)
    assert json.loads((tmp_path / "result.json").read_text()) == result
    assert "simulated" not in captured.err  # no progress bar off a terminal
    assert result["hold_success"] and result["unload_success"]
    for entry in result["transitions"]:
        assert {"t", "from", "to", "trigger"} <= set(entry)
    for step in EVENT_TRANSITIONS:
        assert trigger_of(result, step) == "memorized_event"
    assert result["corrective_actions"] == []
    # The 2F-85's screw drive brings the grip force up within a taxel frame of the first
    # contact, so each event transition comes after its physical event, within the 0.5 s a
    # window takes to fill: no false trigger.
    assert result["false_triggers"] == 0
    assert set(result["detection_latency_s"]) == {"reach_load", "load_lift", "place_unload"}
    for name, latency in result["detection_latency_s"].items():
        assert 0.0 <= latency <= 0.5, name
    for name in ("trial.npz", "states.png", "signals.png"):
        assert (tmp_path / name).is_file()


# The Re-Reach rule asks whether one pad alone reads more than controller.contact_force_n
# (0.3 N); the capacitive pad at rest reads about 2 N (sd 1.6 N) of rectified noise, so
# both pads always "touch" and the rule never fires: the Re-Reach of the ideal force
# taxels is lost until the SA thresholds follow the pad's noise.
@pytest.mark.xfail(strict=True, reason="the box slides under one finger's push (about 0.66 N "
                                       "of table friction), below the capacitive pad's noise "
                                       "floor (5.5 N): one pad alone never reads contact")
@pytest.mark.parametrize("offset_y", [0.015, -0.015])
def test_misplaced_along_the_stroke_re_reaches_and_succeeds(offset_y):
    result = run_trial(LoadScenario(overrides=[f"placement.offset=[0.0, {offset_y}]"])).result
    assert result["corrective_actions"] == ["re_reach"]
    re_reach = next(e for e in result["transitions"] if e["to"] == "Re-Reach")
    toward = "left" if offset_y > 0 else "right"  # the left finger is on the +y side
    assert toward in re_reach["reason"]
    assert re_reach["offset_m"] == pytest.approx(offset_y, abs=0.005)
    assert result["hold_success"] and result["unload_success"]
    for step in EVENT_TRANSITIONS:
        assert trigger_of(result, step) == "memorized_event"


def test_a_hit_in_hold_is_avoided_without_dropping_the_object(tmp_path):
    hit_time = 7.0
    trial = run_trial(LoadScenario(overrides=[f"disturbance.hit_time_s={hit_time}"]))
    result = trial.result
    avoid = next(e for e in result["transitions"] if e["to"] == "Avoid")
    assert avoid["from"] == "Hold" and avoid["trigger"] == "threshold"
    assert 0.0 <= avoid["t"] - hit_time <= 0.1
    assert avoid["direction"] == [0.0, 1.0, 0.0]  # the hit pushed along +y
    assert ("Avoid", "Hold") in steps(result)
    assert result["hold_success"] and result["unload_success"]
    # Fig. 9 and Fig. 10 from the saved log, through the command.
    log = trial.log.save(tmp_path / "trial.npz")
    for what in ("trial", "avoid"):
        figure = tmp_path / f"{what}.png"
        assert main(["plot", what, str(log), "--out", str(figure)]) == 0
        assert figure.stat().st_size > 10_000


def test_a_slippery_object_needs_lift_load():
    # The box's events on a slippery box: the friction differs from the recorded one, and
    # the scenario says that this is meant.
    slippery = ["object.friction=0.01", "controller.event_object_may_differ=[friction]"]
    corrected = run_trial(LoadScenario(overrides=slippery)).result
    assert "lift_load" in corrected["corrective_actions"]
    assert corrected["hold_success"]
    without = run_trial(LoadScenario(
        overrides=slippery + ["controller.lift_load.enabled=false"])).result
    # Without Lift-Load the pads slide up the box, which stays on the table. Whatever else
    # the controller then does (the pads still sliding along it in Hold can read as a hit:
    # Hold goes to Avoid), no Lift-Load is taken and nothing is held.
    assert "lift_load" not in without["corrective_actions"]
    assert not without["hold_success"]


def test_memorized_controller_without_events_names_the_command():
    with pytest.raises(MemorizedEventError, match="tegrasp record-events --scenario"):
        run_trial(LoadScenario(name="custom_can"))


def test_demo_keeps_the_ideal_open_loop_grasp_as_an_option(tmp_path, capsys):
    assert main(["demo", "--controller", "open_loop", "--json", "--out", str(tmp_path)]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["controller"] == "open_loop"
    assert result["hold_success"] and result["unload_success"]
    assert {e["trigger"] for e in result["transitions"]} == {"timer"}
    assert (tmp_path / "signals.png").is_file()
