"""What the GraspStateMachine remembers (MachineState, one abstract state value) and the
plan it follows (GraspPlan: the grasp script placed for the expected object)."""

import dataclasses

from tegrasp_drake.rig.api_boundary import public_dataclass
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import Mode, Stage, Transition
from tegrasp_drake.control.motion_profiles import MotionSegment
from tegrasp_drake.control.scripted_grasp import grasp_frame_xy
from tegrasp_drake.control.taxel_aware.estimator import ContactMemory


@dataclasses.dataclass(frozen=True)
class ModeTimers:
    """What a mode measures while it lasts, fresh at each transition (times [s], -1: not
    running); sa_history: Hold's SA for a memorized hit; the sums: Avoid's sensing."""
    closing_since: float = -1.0
    one_sided_since: float = -1.0
    slip_since: float = -1.0
    motion_done_since: float = -1.0
    sa_history: tuple = ()
    acceleration_sum: tuple = (0.0, 0.0, 0.0)
    sa_gain_sum: tuple = (0.0, 0.0)


@dataclasses.dataclass(frozen=True)
class MachineState:
    """Everything the machine remembers (times in s of simulated time)."""
    mode: Mode
    mode_start: float
    segment: MotionSegment
    gripper: tuple  # (opening [m], speed [m/s], force [N]) requested
    gripper_request_time: float
    grip_force: float
    stage: Stage = Stage.NONE  # the step within a mode
    counters: Counters = Counters()
    timers: ModeTimers = ModeTimers()
    contact: ContactMemory = ContactMemory()
    reentry_shift: tuple = (0.0, 0.0)  # Re-Reach shift along world x and y [m]
    regrasp_pending: bool = False  # the Place puts a tilted object down to re-grasp it
    resume_approach: bool = False  # the Re-Reach stopped the approach: finish it, then close
    sa_before: tuple = (0.0, 0.0)  # SA [N] at the last Hold tick (the hit's baseline)
    timeline: tuple[Transition, ...] = ()
    failure: str = ""

    def __deepcopy__(self, memo):
        # immutable: Drake copies abstract state often, and the timeline is costly to copy
        return self


@public_dataclass
@dataclasses.dataclass(frozen=True)
class GraspPlan:
    """The grasp script's timing and targets placed for the expected object [m, s, N]."""
    start_xyz: tuple
    object_xy: tuple  # the grasp frame's target for the expected object (grasp_frame_xy)
    object_width: float  # along the stroke, for the Re-Reach shift
    grasp_height: float
    object_height: float  # for whether a pushed object stands when let go (taxel_aware)
    lift_height: float
    place_press: float
    settle_s: float
    reach_s: float
    lift_s: float
    hold_s: float
    place_s: float
    unload_s: float
    retract_s: float
    retract_distance: float
    close_speed: float
    grip_force: float
    load_s: float  # the script's close command to the start of its lift
    place_offset: tuple  # where the script puts the object down, from where it took it
    gripper_model: str = "linkage"  # the hand (gripper_hands.py): where its pads lie

    @staticmethod
    def make(grasp, *, start_xyz, expected_object_xy, object, gripper_model: str
             ) -> "GraspPlan":
        """The plan of GraspScriptConfig `grasp` for `object` expected at
        `expected_object_xy` [m, world], from `start_xyz` [m, world]."""
        g = grasp
        return GraspPlan(
            start_xyz=tuple(start_xyz),
            object_xy=tuple(grasp_frame_xy(expected_object_xy, object.width_along_stroke(),
                                           gripper_model)),
            object_width=object.width_along_stroke(), grasp_height=g.grasp_height,
            object_height=object.height(),
            lift_height=g.lift_height, place_press=g.place_press, settle_s=g.settle_s,
            reach_s=g.reach_s, lift_s=g.lift_s, hold_s=g.hold_s, place_s=g.place_s,
            unload_s=g.unload_s, retract_s=g.retract_s, retract_distance=g.retract_distance,
            close_speed=g.close_speed, grip_force=g.grip_force, load_s=g.load_s,
            place_offset=tuple(g.place_offset), gripper_model=gripper_model)
