"""What the GraspStateMachine remembers (MachineState, one abstract state value) and the
plan it follows (GraspPlan: the grasp script placed for the expected object)."""

import dataclasses

from tegrasp_drake.rig.api_boundary import public_dataclass
from tegrasp_drake.rig.objects import ObjectConfig
from tegrasp_drake.rig.ranges import bounded, check_ranges, field_range
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import Mode, Stage, Transition
from tegrasp_drake.control.motion_profiles import MotionSegment
from tegrasp_drake.control.scripted_grasp import GraspScriptConfig, grasp_frame_xy
from tegrasp_drake.control.taxel_aware.estimator import ContactMemory
from tegrasp_drake.simulation.station import ArmDriverConfig


@dataclasses.dataclass(frozen=True)
class ModeTimers:
    """What a mode measures while it lasts, fresh at each transition (times [s], -1: not
    running); sa_history: Hold's SA for a memorized hit; ra_history: Hold's RA for the hit's
    level; the sums: Avoid's sensing."""
    closing_since: float = -1.0
    one_sided_since: float = -1.0
    slip_since: float = -1.0
    motion_done_since: float = -1.0
    sa_history: tuple = ()
    ra_history: tuple = ()
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


def _ranged_as(cls: type, name: str):
    """A field without a default, with the Range of `cls`'s field `name` (declared once)."""
    return bounded(**dataclasses.asdict(field_range(cls, name)))


# The arm's reach along each world axis [m] (as its start pose's), and how far the grasp frame's
# target lies beyond the marker along x: the pads' centres' offset from the grasp frame,
# -9.3 mm open to +4.4 mm closed on the linkage hand, 0 on the prismatic one (gripper_hands).
_REACH = field_range(ArmDriverConfig, "initial_gripper_xyz")
_PAD_OFFSET_BOUND_M = 0.01


@public_dataclass
@dataclasses.dataclass(frozen=True)
class GraspPlan:
    """The grasp script's timing and targets placed for the expected object [m, s, N]. Each
    number takes the range of the setting it comes from (the grasp script's, the arm's start,
    the object's sizes), checked when it is built (a hand-made plan included)."""
    start_xyz: tuple[float, float, float] = _ranged_as(ArmDriverConfig, "initial_gripper_xyz")
    # the grasp frame's target for the expected object (grasp_frame_xy): the marker, within
    # the arm's reach, moved by the pads' offset
    object_xy: tuple[float, float] = bounded(
        low=_REACH.low - _PAD_OFFSET_BOUND_M, high=_REACH.high + _PAD_OFFSET_BOUND_M, unit="m",
        length=2, why="the marker within the JACO2's reach, moved by the pads' offset, under "
                      "1 cm")
    object_width: float = _ranged_as(ObjectConfig, "size")  # along the stroke, for Re-Reach
    grasp_height: float = _ranged_as(GraspScriptConfig, "grasp_height")
    # for whether a pushed object stands when let go (taxel_aware)
    object_height: float = _ranged_as(ObjectConfig, "size")
    lift_height: float = _ranged_as(GraspScriptConfig, "lift_height")
    place_press: float = _ranged_as(GraspScriptConfig, "place_press")
    settle_s: float = _ranged_as(GraspScriptConfig, "settle_s")
    reach_s: float = _ranged_as(GraspScriptConfig, "reach_s")
    lift_s: float = _ranged_as(GraspScriptConfig, "lift_s")
    hold_s: float = _ranged_as(GraspScriptConfig, "hold_s")
    place_s: float = _ranged_as(GraspScriptConfig, "place_s")
    unload_s: float = _ranged_as(GraspScriptConfig, "unload_s")
    retract_s: float = _ranged_as(GraspScriptConfig, "retract_s")
    retract_distance: float = _ranged_as(GraspScriptConfig, "retract_distance")
    close_speed: float = _ranged_as(GraspScriptConfig, "close_speed")
    grip_force: float = _ranged_as(GraspScriptConfig, "grip_force")
    # the script's close command to the start of its lift
    load_s: float = _ranged_as(GraspScriptConfig, "load_s")
    # where the script puts the object down, from where it took it
    place_offset: tuple[float, float] = _ranged_as(GraspScriptConfig, "place_offset")
    gripper_model: str = "linkage"  # the hand (gripper_hands.py): where its pads lie
    # the expected object's name (rig/objects.py): memorized events must have been felt on
    # it; "" for a plan of no named object (then no event is checked against it)
    object_name: str = ""

    def __post_init__(self):
        """ConfigError naming the first field outside its range."""
        check_ranges(self, type(self).__name__)

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
            place_offset=tuple(g.place_offset), gripper_model=gripper_model,
            object_name=object.name)
