"""The ideal open-loop grasp (Sec. III-A): a timed script of minimum-jerk arm moves and
gripper commands (PHASES), planned for the object's expected position, which it never
checks. The side grasp approaches along world +x, the stroke along world y."""

import dataclasses
import functools

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import bounded, check_ranges, field_range
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.rig.arm_kinematics import GRASP_HEIGHT_RANGE, R_WG_SIDE_GRASP
from tegrasp_drake.control.motion_profiles import interpolate_pose, minimum_jerk
from tegrasp_drake.simulation.gripper_hands import gripper_hand
from tegrasp_drake.rig.api_boundary import public_dataclass

PHASES = ("settle", "reach", "load", "lift", "hold", "place", "unload", "retract", "done")


@public_dataclass
@dataclasses.dataclass
class GraspScriptConfig:
    """Timing and targets of the ideal open-loop grasp (side grasp, approach along +x)."""
    # m, pad centre above the table
    grasp_height: float = bounded(0.055, **dataclasses.asdict(GRASP_HEIGHT_RANGE))
    settle_s: float = bounded(0.3, low=0.0, high=10.0, unit="s")
    reach_s: float = bounded(2.5, low=0.0, low_open=True, high=30.0, unit="s")
    close_speed: float = bounded(0.05, low=0.02, high=0.15, unit="m/s",
                                 why="the 2F-85 closes at 20-150 mm/s, Robotiq 2F-85 manual")
    grip_force: float = bounded(25.0, low=20.0, high=235.0, unit="N",
                                why="the 2F-85 grips with 20 to 235 N, Robotiq 2F-85 manual")
    # close command to lift [s]: the close (1.24 s for the 25 mm cylinder) plus 0.56 s on the
    # object, the grip's settling and half a memorized window (recording/paper_events.py checks)
    load_s: float = bounded(1.8, low=0.0, low_open=True, high=30.0, unit="s")
    # a trial judges the object held only once it is 2 cm above where it rested
    # (scenario/grasp_outcome.py, LIFTED_HEIGHT_M): a lower lift could never be held (and a lift
    # of 0 stalls Lift, whose remaining share divides by it)
    lift_height: float = bounded(0.06, low=0.02, high=0.3, unit="m",
                                 why="a trial counts the object held 2 cm above its rest")
    lift_s: float = bounded(1.5, low=0.0, low_open=True, high=30.0, unit="s")
    hold_s: float = bounded(3.0, low=0.0, high=60.0, unit="s",
                            why="the paper holds 3 s; a minute is the longest hold test")
    place_s: float = bounded(1.5, low=0.0, low_open=True, high=30.0, unit="s")
    # m below the lift-off height at the end of Place
    place_press: float = bounded(0.003, low=0.0, high=0.02, unit="m")
    unload_s: float = bounded(1.0, low=0.0, low_open=True, high=30.0, unit="s")
    retract_s: float = bounded(1.2, low=0.0, low_open=True, high=30.0, unit="s")
    # m back along the approach (state machine; no nearer than the start pose, where the
    # wrist nears its singularity)
    retract_distance: float = bounded(0.10, low=0.0, high=0.3, unit="m")
    place_offset: list[float] = bounded(default_factory=lambda: [0.0, 0.0], low=-0.2, high=0.2,
                                        unit="m", length=2)


@dataclasses.dataclass(frozen=True)
class ScriptSegment:
    """One phase: G moves from X_start to X_end over [t_start, t_end] [s], one gripper command.
    A phase may last no time (grasp.settle_s and grasp.hold_s may be 0: sample_plan passes
    over it), never less."""
    phase: str
    t_start: float = bounded(low=0.0, unit="s", why="time since the script's start")
    t_end: float = bounded(low=0.0, unit="s", why="time since the script's start")
    X_start: RigidTransform
    X_end: RigidTransform
    gripper_command: tuple

    def __post_init__(self):
        """ConfigError naming the first time out of its range, or t_end before t_start."""
        check_ranges(self, type(self).__name__)
        if self.t_end < self.t_start:
            raise ConfigError(
                f"{type(self).__name__}: field 't_end' must not be before t_start = "
                f"{number_text(self.t_start)} s (a phase lasts zero or more seconds), got "
                f"{number_text(self.t_end)}")


@functools.lru_cache(maxsize=256)
def gripper_command(opening_m: float, speed_mps: float, force_n: float) -> tuple:
    """The (rPR, rSP, rFR) bytes for a target opening, speed and force (cached: asked per tick)."""
    return (float(ru.position_byte_from_opening(opening_m)),
            float(ru.speed_byte_from_speed(speed_mps)),
            float(ru.force_byte_from_force(force_n)))


def grasp_frame_xy(expected_object_xy, object_width: float, gripper_model: str
                   ) -> tuple[float, float]:
    """Where the grasp frame goes [m, world (x, y)] so that the pads' centres close on the
    object's centre line (the linkage's pads travel along +x as they close)."""
    x0, y0 = expected_object_xy
    offset = gripper_hand(gripper_model).pad_center_offset(object_width)
    return x0 - offset, y0


def plan_scripted_grasp(plan) -> list[ScriptSegment]:
    """The phase segments of the ideal grasp of `plan` (machine_state.GraspPlan)."""
    x0, y0 = plan.object_xy
    start = RigidTransform(R_WG_SIDE_GRASP, plan.start_xyz)
    grasp = RigidTransform(R_WG_SIDE_GRASP, [x0, y0, plan.grasp_height])
    lifted = RigidTransform(R_WG_SIDE_GRASP, [x0, y0, plan.grasp_height + plan.lift_height])
    dx, dy = plan.place_offset
    placed = RigidTransform(R_WG_SIDE_GRASP,
                            [x0 + dx, y0 + dy, plan.grasp_height - plan.place_press])
    retracted = RigidTransform(R_WG_SIDE_GRASP, np.add(plan.start_xyz, [dx, dy, 0.0]))
    opened = gripper_command(ru.STROKE_M, plan.close_speed, plan.grip_force)
    closed = gripper_command(0.0, plan.close_speed, plan.grip_force)
    steps = [("settle", plan.settle_s, start, start, opened),
             ("reach", plan.reach_s, start, grasp, opened),
             ("load", plan.load_s, grasp, grasp, closed),
             ("lift", plan.lift_s, grasp, lifted, closed),
             ("hold", plan.hold_s, lifted, lifted, closed),
             ("place", plan.place_s, lifted, placed, closed),
             ("unload", plan.unload_s, placed, placed, opened),
             ("retract", plan.retract_s, placed, retracted, opened)]
    segments, t = [], 0.0
    for phase, duration, X_start, X_end, command in steps:
        segments.append(ScriptSegment(phase, t, t + duration, X_start, X_end, command))
        t += duration
    return segments


def sample_plan(segments: list[ScriptSegment], t: float):
    """(X_WG, gripper command, phase index into PHASES) of the script at time t [s]."""
    for segment in segments:
        if t < segment.t_end:
            tau = (t - segment.t_start) / (segment.t_end - segment.t_start)
            X = interpolate_pose(segment.X_start, segment.X_end, minimum_jerk(tau))
            return X, segment.gripper_command, PHASES.index(segment.phase)
    last = segments[-1]
    return last.X_end, last.gripper_command, PHASES.index("done")


def plan_duration(segments: list[ScriptSegment]) -> float:
    return segments[-1].t_end


def longest_script_s() -> float:
    """The longest grasp script [s] its fields' ranges allow: each phase's duration field
    (`settle_s`, ... `retract_s`, one per PHASES entry before "done") at its range's high
    end. LoadScenario refuses a script over MAX_SCRIPT_S unless allow_long; a builder given
    a scenario accepts one up to this."""
    return sum(field_range(GraspScriptConfig, f"{phase}_s").high for phase in PHASES[:-1])


class ScriptedGraspSource(LeafSystem):
    """Plays the open-loop grasp script; outputs depend on time only.

    .. pydrake_system::

        name: ScriptedGraspSource
        output_ports:
        - X_WG_desired
        - gripper_command
        - phase

    Ports:
        X_WG_desired: (abstract RigidTransform) the grasp frame G's desired pose in world.
        gripper_command: (3) [rPR, rSP, rFR] bytes.
        phase: (1) index into PHASES.
    """

    def __init__(self, segments: list[ScriptSegment]):
        super().__init__()
        self._segments = segments
        time_only = {self.time_ticket()}
        self.DeclareAbstractOutputPort(
            "X_WG_desired", lambda: AbstractValue.Make(RigidTransform()),
            lambda context, output: output.set_value(
                sample_plan(self._segments, context.get_time())[0]),
            prerequisites_of_calc=time_only)
        self.DeclareVectorOutputPort(
            "gripper_command", 3,
            lambda context, output: output.SetFromVector(
                sample_plan(self._segments, context.get_time())[1]),
            prerequisites_of_calc=time_only)
        self.DeclareVectorOutputPort(
            "phase", 1,
            lambda context, output: output.SetFromVector(
                [sample_plan(self._segments, context.get_time())[2]]),
            prerequisites_of_calc=time_only)
