"""Memorized corrective events: a slip during Lift (`lift_load`) and a hit during Hold
(`hold_avoid`), matched by Eq. 3 like the grasp transitions, recorded from open-loop grasps
of perturbed scenes ("template" runs make the events, "held_out" runs choose the thresholds).
docs/controller.md, "Memorized corrective triggers"."""

import dataclasses

import numpy as np

from tegrasp_drake.control.scripted_grasp import GraspScriptConfig
from tegrasp_drake.scenario.trial_log_file import LogNotWritten
from tegrasp_drake.recording.campaign import (CORRECTIVE_BASE_SEED, CampaignRun,
                                              record_campaign)
from tegrasp_drake.rig.objects import CORRECTIVE_EVENTS_FOLDER
from tegrasp_drake.scenario.scenario import LoadScenario, grasp_plan

CORRECTIVE_FOLDER = CORRECTIVE_EVENTS_FOLDER  # the events folder's subfolder (rig/objects.py)
PRE_TRANSITION_S = 0.45  # the live window looks most like it ~50 ms after the event
SLIP_DISPLACEMENT_M = 0.001  # the pads' rise over the object's that counts as slip [m]
# The modes in which each corrective event is looked for, and its action.
CORRECTIVE_SITUATIONS = {"lift_load": "slip during Lift", "hold_avoid": "a hit during Hold"}
# The default script's phase times [s]: Lift from 4.6 s to 6.1 s, Hold from 6.1 s to 9.1 s.
_SCRIPT = GraspScriptConfig()
LIFT_START_S = _SCRIPT.settle_s + _SCRIPT.reach_s + _SCRIPT.load_s
LIFT_END_S = LIFT_START_S + _SCRIPT.lift_s
HOLD_END_S = LIFT_END_S + _SCRIPT.hold_s
# Simulated time of a run [s]: a hit just past the script's Hold, a slip 0.4 s past its Lift.
RUN_DURATION_S = {"hold_avoid": round(HOLD_END_S + 0.1, 3),
                  "lift_load": round(LIFT_END_S + 0.4, 3)}


@dataclasses.dataclass(frozen=True)
class CorrectiveRun:
    """One recorded open-loop run of a corrective situation."""
    transition: str  # "lift_load" or "hold_avoid"
    label: str
    seed_offset: int  # its seed: CORRECTIVE_BASE_SEED + seed_offset
    overrides: tuple[str, ...]  # scenario --set assignments
    role: str  # "template" or "held_out"

    @property
    def seed(self) -> int:
        return CORRECTIVE_BASE_SEED + self.seed_offset


def _hit(force_y: float, into_hold_s: float) -> tuple[str, ...]:
    """The overrides of a hit of force_y [N] into_hold_s [s] after the script's Hold began."""
    time_s = round(LIFT_END_S + into_hold_s, 3)
    return (f"disturbance.hit_time_s={time_s}", f"disturbance.hit_force_n=[0.0, {force_y}, 0.0]")


# Hits after the lift's ring-down has faded; frictions whose grip cannot hold the box.
CORRECTIVE_RUNS = (
    CorrectiveRun("hold_avoid", "hit +y 20 N 0.9 s into Hold", 0, _hit(20.0, 0.9), "template"),
    CorrectiveRun("hold_avoid", "hit -y 20 N 0.5 s into Hold", 1, _hit(-20.0, 0.5), "template"),
    CorrectiveRun("hold_avoid", "hit +y 15 N 1.3 s into Hold", 2, _hit(15.0, 1.3), "held_out"),
    CorrectiveRun("hold_avoid", "hit -y 25 N 0.7 s into Hold", 3, _hit(-25.0, 0.7), "held_out"),
    CorrectiveRun("lift_load", "friction 0.008", 4, ("object.friction=0.008",), "template"),
    CorrectiveRun("lift_load", "friction 0.010", 5, ("object.friction=0.010",), "template"),
    CorrectiveRun("lift_load", "friction 0.012", 6, ("object.friction=0.012",), "held_out"),
    CorrectiveRun("lift_load", "friction 0.020, mass 0.25 kg", 7,
                  ("object.friction=0.020", "object.mass=0.25"), "held_out"),
)


def corrective_scenario(object_name: str, run: CorrectiveRun):
    """The scenario of `run` on `object_name`: the object's scenario with its overrides."""
    return LoadScenario(name=object_name,
                        overrides=[f"random_seed={run.seed}", *run.overrides])


def campaign_run(object_name: str, run: CorrectiveRun) -> CampaignRun:
    """`run` as a campaign run, simulated only as long as its situation needs."""
    return CampaignRun(run.label, corrective_scenario(object_name, run), role=run.role,
                       duration_s=RUN_DURATION_S[run.transition])


def grasp_frame_heights(arm_q: np.ndarray) -> np.ndarray:
    """The grasp frame's height [m, world z up to the arm base's offset] at each logged
    arm configuration (N, 6) [rad], by the controller plant's kinematics."""
    from tegrasp_drake.rig.arm_kinematics import make_arm_control_plant
    plant = make_arm_control_plant()
    context = plant.CreateDefaultContext()
    frame = plant.GetFrameByName("grasp_frame")
    heights = np.empty(len(arm_q))
    for k, q in enumerate(np.asarray(arm_q)):
        plant.SetPositions(context, q)
        heights[k] = frame.CalcPoseInWorld(context).translation()[2]
    return heights


def slip_onset_time(log, scenario) -> float | None:
    """The first time [s] in the script's Lift that the pads (the grasp frame) have risen
    SLIP_DISPLACEMENT_M more than the object since Lift began; None if they never do."""
    from tegrasp_drake.control.scripted_grasp import plan_scripted_grasp
    lift = next(s for s in plan_scripted_grasp(grasp_plan(scenario)) if s.phase == "lift")
    t = np.asarray(log.t_slow)
    in_lift = np.flatnonzero((t >= lift.t_start) & (t <= lift.t_end))
    if in_lift.size == 0:
        return None
    gripper = grasp_frame_heights(np.asarray(log.arm_q)[in_lift])
    obj = np.asarray(log.object_state)[in_lift, 6]
    lag = (gripper - gripper[0]) - (obj - obj[0])
    index = np.flatnonzero(lag > SLIP_DISPLACEMENT_M)
    return float(t[in_lift[index[0]]]) if index.size else None


def corrective_event_time(log, scenario, transition: str) -> float | None:
    """The physical event's time [s] of `transition` in a run: the hit's start
    (disturbance.hit_time_s) or the slip's onset (slip_onset_time)."""
    if transition == "hold_avoid":
        hit = scenario.disturbance.hit_time_s
        return float(hit) if hit >= 0.0 else None
    if transition == "lift_load":
        return slip_onset_time(log, scenario)
    raise ValueError(f"unknown corrective transition '{transition}'; known: "
                     f"{', '.join(CORRECTIVE_SITUATIONS)}")


def record_corrective_events(object_name: str, transition: str, *, log_dir=None):
    """The memorized corrective event of `transition` on `object_name`: the template runs of
    its CORRECTIVE_RUNS combined by their mean (held-out logs kept in `log_dir`);
    LogNotWritten carrying the event when a log cannot be written there (record_campaign)."""
    runs = [campaign_run(object_name, run) for run in CORRECTIVE_RUNS
            if run.transition == transition]
    try:
        events = record_campaign(
            runs, lambda log, scenario: {transition: corrective_event_time(log, scenario,
                                                                           transition)},
            object_name=object_name, nominal_object=LoadScenario(name=object_name).object,
            pre_transition_s=PRE_TRANSITION_S, log_dir=log_dir,
            note=f"corrective template runs of {object_name} ({transition})")
    except LogNotWritten as unwritten:  # the event stands; only a log file is lost
        raise LogNotWritten(unwritten.result[transition], unwritten.path,
                            unwritten.reason) from None
    return events[transition]
