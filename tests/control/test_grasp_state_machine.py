"""GraspStateMachine through its ports, with hand-set inputs (no plant)."""

import dataclasses
import math
import pathlib

import numpy as np
import pytest
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.analysis import Simulator

from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.arm_kinematics import (R_WG_SIDE_GRASP, make_arm_control_plant,
                                              solve_grasp_frame_ik)
from tegrasp_drake.control.cartesian_arm_controller import (_follow as follow_pose,
                                                            grasp_frame_jacobian,
                                                            jaco_joint_limits)
from tegrasp_drake.control.corrective_actions import R_G_PAD
from tegrasp_drake.control.motion_profiles import minimum_jerk, minimum_jerk_slope
from tegrasp_drake.control.controller_config import (AvoidConfig, MemorizedControllerConfig,
                                                     TaxelAwareControllerConfig)
from tegrasp_drake.control.grasp_modes import Mode, Stage, Trigger
from tegrasp_drake.control.grasp_state_machine import GraspStateMachine
from tegrasp_drake.control.noise_thresholds import resolve_noise_thresholds
from tegrasp_drake.control.taxel_aware import TAXEL_AWARE_TABLE
from tegrasp_drake.control.taxel_aware.hands import LINKAGE_ONLY, PRISMATIC_ONLY
from tegrasp_drake.scenario.scenario import LoadScenario, grasp_plan
from tegrasp_drake.simulation.pad_vibration_sensor import (VibrationSensorConfig,
                                                           ra_noise_std_mps2)

EVENT_INDICES = {"reach_load": 0, "load_lift": 1, "place_unload": 2}


def make_machine(**config_changes):
    scenario = LoadScenario(name="box")
    config = MemorizedControllerConfig(**config_changes)
    machine = GraspStateMachine(plan=grasp_plan(scenario), config=config,
                                event_indices=EVENT_INDICES, event_trigger=Trigger.MEMORIZED_EVENT)
    return machine, scenario


def status(opening_m=ru.STROKE_M, obj=ru.ObjectStatus.MOVING, fault=0, request_byte=None):
    values = np.zeros(ru.STATUS_SIZE)
    values[ru.STATUS_PR] = (ru.position_byte_from_opening(opening_m) if request_byte is None
                            else request_byte)
    values[ru.STATUS_ACT], values[ru.STATUS_GTO], values[ru.STATUS_STA] = 1, 1, 3
    values[ru.STATUS_OBJ], values[ru.STATUS_FLT] = obj, fault
    values[ru.STATUS_PO] = ru.position_byte_from_opening(opening_m)
    return values


class Inputs:
    """Fixed values on the machine's input ports, changeable between AdvanceTo calls."""

    def __init__(self, machine, context):
        self.machine, self.context = machine, context
        self.set(match=0.0, channels=[0.0, 0.0, 0.0, 0.0], status=status(),
                 slip_vibration=[0.0, 0.0])
        machine.GetInputPort("scores").FixValue(context, np.zeros(4))

    def set(self, *, match=None, channels=None, status=None, pad_acceleration=None,
            slip_vibration=None):
        for name, value in (("match", [match] if match is not None else None),
                            ("channels", channels), (ports.GRIPPER_STATUS, status),
                            ("pad_acceleration", pad_acceleration),
                            ("slip_vibration", slip_vibration)):
            if value is not None:
                self.machine.GetInputPort(name).FixValue(self.context, np.asarray(value, float))


def start(machine):
    simulator = Simulator(machine)
    context = simulator.get_mutable_context()
    inputs = Inputs(machine, context)
    simulator.Initialize()
    return simulator, context, inputs


def mode(machine, context):
    return Mode(int(machine.GetOutputPort("mode").Eval(context)[0]))


def run_until_mode(simulator, machine, wanted: Mode, limit_s: float) -> float:
    """Advances tick by tick until the machine is in `wanted`; returns the time."""
    context = simulator.get_context()
    end = context.get_time() + limit_s
    while mode(machine, context) != wanted:
        assert context.get_time() < end, f"still {mode(machine, context)}, never {wanted}"
        simulator.AdvanceTo(context.get_time() + 0.001)
    return context.get_time()


def test_expected_event_does_not_feed_through_from_match():
    machine, _ = make_machine()
    for port in ("match", "channels", ports.GRIPPER_STATUS):
        assert not machine.HasDirectFeedthrough(machine.GetInputPort(port).get_index(),
                                                machine.GetOutputPort("expected_event").get_index())


def test_reach_moves_then_closes_and_asks_for_contact():
    machine, scenario = make_machine()
    simulator, context, _ = start(machine)
    pose = machine.GetOutputPort("X_WG_desired").Eval(context)
    np.testing.assert_allclose(pose.translation(), scenario.arm.initial_gripper_xyz)
    np.testing.assert_array_equal(pose.rotation().matrix(), R_WG_SIDE_GRASP.matrix())
    assert machine.GetOutputPort("expected_event").Eval(context)[0] == EVENT_INDICES["reach_load"]
    command = machine.GetOutputPort("gripper_command").Eval(context)
    assert command[ru.COMMAND_POSITION] <= ru.POSITION_OPEN_BYTE + 1  # open while reaching
    g = scenario.grasp
    simulator.AdvanceTo(g.settle_s + g.reach_s + 0.01)
    pose = machine.GetOutputPort("X_WG_desired").Eval(context)
    # The frame stops short of the expected object (0.72, 0) by the linkage pads' offset
    # along the approach at the box's width, 1.79 mm: the closing pads meet its centre line.
    np.testing.assert_allclose(pose.translation(), [0.72 - 0.00179, 0.0, g.grasp_height],
                               atol=1e-5)
    command = machine.GetOutputPort("gripper_command").Eval(context)
    assert command[ru.COMMAND_POSITION] >= ru.POSITION_CLOSED_BYTE - 1  # closing
    assert command[ru.COMMAND_FORCE] == ru.force_byte_from_force(g.grip_force)
    assert mode(machine, context) == Mode.REACH


def test_a_full_grasp_driven_through_the_ports():
    machine, scenario = make_machine()
    simulator, context, inputs = start(machine)
    g = scenario.grasp
    simulator.AdvanceTo(g.settle_s + g.reach_s + 0.2)
    inputs.set(channels=[10.0, 10.0, 0.1, 0.1], match=1.0)
    run_until_mode(simulator, machine, Mode.LOAD, 0.01)
    assert machine.GetOutputPort("expected_event").Eval(context)[0] == EVENT_INDICES["load_lift"]
    run_until_mode(simulator, machine, Mode.LIFT, 0.01)
    inputs.set(match=0.0)
    z0 = machine.GetOutputPort("X_WG_desired").Eval(context).translation()[2]
    simulator.AdvanceTo(context.get_time() + g.lift_s + 0.01)
    assert mode(machine, context) == Mode.HOLD
    z1 = machine.GetOutputPort("X_WG_desired").Eval(context).translation()[2]
    assert z1 - z0 == pytest.approx(g.lift_height, abs=1e-3)
    assert machine.GetOutputPort("expected_event").Eval(context)[0] == -1
    simulator.AdvanceTo(context.get_time() + g.hold_s + 0.01)
    assert mode(machine, context) == Mode.PLACE
    simulator.AdvanceTo(context.get_time() + 0.5)
    inputs.set(match=1.0)
    simulator.AdvanceTo(context.get_time() + 0.01)
    assert mode(machine, context) == Mode.UNLOAD
    stopped = machine.GetOutputPort("X_WG_desired").Eval(context).translation()
    simulator.AdvanceTo(context.get_time() + 0.3)
    np.testing.assert_allclose(machine.GetOutputPort("X_WG_desired").Eval(context).translation(),
                               stopped, atol=1e-12)  # the descent stops at the event
    inputs.set(match=0.0, channels=[0.0, 0.0, 0.1, 0.1],
               status=status(ru.STROKE_M, ru.ObjectStatus.AT_REQUESTED_POSITION))
    simulator.AdvanceTo(context.get_time() + g.retract_s + 0.2)
    assert mode(machine, context) == Mode.DONE
    timeline = machine.timeline(context)
    assert [(e["from"], e["to"], e["trigger"]) for e in timeline] == [
        ("Reach", "Load", "memorized_event"), ("Load", "Lift", "memorized_event"),
        ("Lift", "Hold", "timer"), ("Hold", "Place", "timer"),
        ("Place", "Unload", "memorized_event"), ("Unload", "Done", "timer")]


def lift(simulator, machine, context, inputs, scenario):
    """Drives the machine from Reach into Lift; returns the time Lift began [s]."""
    g = scenario.grasp
    simulator.AdvanceTo(g.settle_s + g.reach_s + 0.2)
    inputs.set(channels=[10.0, 10.0, 0.1, 0.1], match=1.0)
    run_until_mode(simulator, machine, Mode.LOAD, 0.01)
    started = run_until_mode(simulator, machine, Mode.LIFT, 0.01)
    inputs.set(match=0.0)
    return started


def test_a_squeeze_in_the_ra_channel_is_not_a_slip():
    # The film reads a rising grip as RA of about 165 m/s^2 (README, "Vibration (RA)
    # model"); only the slip band's vibration may trigger Lift-Load.
    machine, scenario = make_machine()
    simulator, context, inputs = start(machine)
    lift(simulator, machine, context, inputs, scenario)
    inputs.set(channels=[10.0, 10.0, 165.0, 165.0], slip_vibration=[0.5, 0.5])
    simulator.AdvanceTo(context.get_time() + 0.2)
    assert mode(machine, context) == Mode.LIFT


def test_slip_band_vibration_for_slip_s_is_a_lift_load():
    machine, scenario = make_machine()
    simulator, context, inputs = start(machine)
    lift(simulator, machine, context, inputs, scenario)
    config = MemorizedControllerConfig()
    inputs.set(slip_vibration=[0.0, 2.0 * config.lift_load.slip_vibration_mps2])
    began = context.get_time()
    t = run_until_mode(simulator, machine, Mode.LOAD, 0.1)
    assert config.lift_load.slip_s <= t - began <= config.lift_load.slip_s + 2 * config.update_period_s
    command = machine.GetOutputPort("gripper_command").Eval(context)
    assert command[ru.COMMAND_FORCE] == ru.force_byte_from_force(
        scenario.grasp.grip_force * config.lift_load.force_factor)


def test_one_sided_contact_re_reaches_toward_the_touching_finger():
    machine, scenario = make_machine()
    simulator, context, inputs = start(machine)
    g = scenario.grasp
    simulator.AdvanceTo(g.settle_s + g.reach_s + 0.1)
    opening = 0.070  # the left finger meets a 45 mm box 12.5 mm off centre
    inputs.set(channels=[2.0, 0.0, 0.5, 0.5], status=status(opening))
    simulator.AdvanceTo(context.get_time() + 0.15)
    assert mode(machine, context) == Mode.RE_REACH
    entry = machine.timeline(context)[-1]
    assert entry["offset_m"] == pytest.approx((opening - 0.045) / 2, abs=1e-4)
    y0 = machine.GetOutputPort("X_WG_desired").Eval(context).translation()[1]
    inputs.set(channels=[0.0, 0.0, 0.0, 0.0],
               status=status(ru.STROKE_M, ru.ObjectStatus.AT_REQUESTED_POSITION))
    t_reach = run_until_mode(simulator, machine, Mode.REACH, 1.2)
    assert t_reach > entry["t"] + 0.8  # opening, then the shift of re_reach.move_s
    y1 = machine.GetOutputPort("X_WG_desired").Eval(context).translation()[1]
    assert y1 - y0 == pytest.approx(entry["offset_m"], abs=1e-5)  # toward +y, the left finger


def test_gripper_fault_fails_with_its_name():
    machine, _ = make_machine()
    simulator, context, inputs = start(machine)
    inputs.set(status=status(fault=0x08))
    simulator.AdvanceTo(0.02)
    assert mode(machine, context) == Mode.FAILED
    assert ru.fault_name(0x08) in machine.timeline(context)[-1]["reason"]
    assert machine.timeline(context)[-1]["code"] == "gripper_fault"


def test_device_fault_input_fails_with_the_message():
    machine, _ = make_machine()
    simulator, context, _ = start(machine)
    machine.GetInputPort(ports.DEVICE_FAULT).FixValue(context, AbstractValue.Make(
        "tactile: no frame since 1.234 s"))
    simulator.AdvanceTo(0.02)
    assert mode(machine, context) == Mode.FAILED
    assert machine.timeline(context)[-1]["reason"] == "tactile: no frame since 1.234 s"
    assert machine.timeline(context)[-1]["code"] == "device_fault"


def test_closed_on_nothing_needs_a_status_that_echoes_the_close_request():
    machine, scenario = make_machine()
    simulator, context, inputs = start(machine)
    g = scenario.grasp
    simulator.AdvanceTo(g.settle_s + g.reach_s + 0.05)
    # A late status of the open request: "at requested position", echo = the open byte.
    inputs.set(status=status(ru.STROKE_M, ru.ObjectStatus.AT_REQUESTED_POSITION))
    simulator.AdvanceTo(context.get_time() + 0.3)
    assert mode(machine, context) == Mode.REACH
    closed = machine.GetOutputPort("gripper_command").Eval(context)[ru.COMMAND_POSITION]
    inputs.set(status=status(0.0, ru.ObjectStatus.AT_REQUESTED_POSITION, request_byte=closed))
    run_until_mode(simulator, machine, Mode.RE_REACH, 0.2)
    assert machine.timeline(context)[-1]["code"] == "closed_on_nothing"


def test_hits_in_hold_are_avoided_at_most_max_avoids_times():
    machine, scenario = make_machine(avoid=AvoidConfig(max_avoids=1))
    simulator, context, inputs = start(machine)
    lift(simulator, machine, context, inputs, scenario)
    run_until_mode(simulator, machine, Mode.HOLD, scenario.grasp.lift_s + 0.1)
    config = MemorizedControllerConfig()
    quiet, hit = [10.0, 10.0, 0.1, 0.1], [10.0, 10.0, 10.0 * config.avoid.hit_ra_mps2, 0.1]
    simulator.AdvanceTo(context.get_time() + config.avoid.hit_refractory_s + 0.01)
    inputs.set(channels=hit)
    run_until_mode(simulator, machine, Mode.AVOID, 0.01)
    inputs.set(channels=quiet)
    run_until_mode(simulator, machine, Mode.HOLD, config.avoid.sense_s + config.avoid.move_s + 0.1)
    simulator.AdvanceTo(context.get_time() + config.avoid.hit_refractory_s + 0.01)
    inputs.set(channels=hit)  # a second hit: past max_avoids, Hold goes on
    simulator.AdvanceTo(context.get_time() + 0.1)
    assert mode(machine, context) == Mode.HOLD
    assert [e["to"] for e in machine.timeline(context)].count("Avoid") == 1


# The films' RA at each controller tick of two Holds of the wide grid's taxel-aware trials
# at the (+15, -12.5) mm marker (seed 980), both creeping grips (a slick 0.25 kg box whose grip
# fell at 0.57 N/s, a 60 mm box held on its edges, at 1.6 N/s) that the film reads as a
# steady 1.9 and 5.4 m/s^2. The slick box's Hold went to Avoid at its last tick (2.34 s, the
# right film at 4.93 m/s^2, over the 3.93 in force); the wide box's at its first armed tick
# (0.3 s), whose recording goes on through the Avoid's 30 ms stop, the arm still.
CREEPING_HOLDS = np.load(pathlib.Path(__file__).parents[1] / "data" / "creeping_hold_ra.npz")


def hold_with_film_readings(ra_mps2: np.ndarray) -> tuple[list, float]:
    """The paper's machine (its Avoid threshold in force at the default film) driven into Hold,
    then fed ra_mps2 (ticks, 2) one controller tick each with the pads at 25 N: its
    transitions out of Hold, and the time Hold began [s]."""
    in_force = resolve_noise_thresholds(
        MemorizedControllerConfig(), ra_noise_std_mps2=ra_noise_std_mps2(VibrationSensorConfig()),
        ra_rate_hz=1000.0)
    machine, scenario = make_machine(avoid=in_force.avoid)
    simulator, context, inputs = start(machine)
    lift(simulator, machine, context, inputs, scenario)
    inputs.set(channels=[25.0, 25.0, 0.0, 0.0])
    run_until_mode(simulator, machine, Mode.HOLD, scenario.grasp.lift_s + 0.1)
    hold_start = machine.timeline(context)[-1]["t"]
    period = in_force.update_period_s
    for k, (left, right) in enumerate(ra_mps2):
        inputs.set(channels=[25.0, 25.0, left, right])
        simulator.AdvanceTo(hold_start + (k + 0.5) * period)  # the tick k * period reads them
    return [e for e in machine.timeline(context) if e["from"] == "Hold"], hold_start


@pytest.mark.parametrize("hold", ["slick_heavy_box", "wide_light_box"])
def test_a_creeping_grips_steady_film_reading_in_hold_is_not_a_hit(hold):
    left_hold, _ = hold_with_film_readings(CREEPING_HOLDS[f"{hold}_ra_mps2"])
    assert left_hold == []


def test_a_hit_on_a_creeping_grip_is_seen_at_its_first_tick():
    # The default scene's hit (20 N for 20 ms) read 7.4 and then 55 m/s^2 on the films.
    ra = CREEPING_HOLDS["slick_heavy_box_ra_mps2"].copy()
    hit_tick = 300
    ra[hit_tick:hit_tick + 3] += [[7.4, 7.4], [55.5, 50.6], [106.1, 97.5]]
    left_hold, hold_start = hold_with_film_readings(ra)
    assert [e["to"] for e in left_hold] == ["Avoid"]
    period = MemorizedControllerConfig().update_period_s
    assert left_hold[0]["t"] == pytest.approx(hold_start + hit_tick * period, abs=1e-9)


def taxel_aware_machine(gripper_model: str) -> GraspStateMachine:
    scenario = LoadScenario(name="box", overrides=[f"gripper.model={gripper_model}"])
    return GraspStateMachine(plan=grasp_plan(scenario), config=TaxelAwareControllerConfig(),
                             event_indices=EVENT_INDICES, event_trigger=Trigger.MEMORIZED_EVENT,
                             rules=TAXEL_AWARE_TABLE)


def names(table) -> set:
    return {item.name for item in (*table.all_rules(), *table.all_guards())}


def test_the_machine_runs_only_the_rules_kept_to_its_hand():
    prismatic_only = {item.name for item in (*TAXEL_AWARE_TABLE.all_rules(),
                                             *TAXEL_AWARE_TABLE.all_guards())
                      if item.hands == PRISMATIC_ONLY}
    linkage_only = {item.name for item in TAXEL_AWARE_TABLE.all_rules()
                    if item.hands == LINKAGE_ONLY}
    assert {"caged", "tipping_guard", "approach_contact"} <= prismatic_only
    assert {"curled_fingertips"} <= linkage_only
    linkage = taxel_aware_machine("linkage").rule_table()
    assert not names(linkage) & prismatic_only
    assert names(linkage) | prismatic_only == names(TAXEL_AWARE_TABLE)
    prismatic = taxel_aware_machine("prismatic").rule_table()
    assert not names(prismatic) & linkage_only
    assert names(prismatic) | linkage_only == names(TAXEL_AWARE_TABLE)


def avoid_along(direction_W) -> tuple:
    """The paper's machine in Hold on the box at its marker, hit with the pads' common
    acceleration along direction_W (world, horizontal) and their SA alike: (the Avoid's move,
    MotionSegment; its transition, JSON form)."""
    machine, scenario = make_machine()
    simulator, context, inputs = start(machine)
    lift(simulator, machine, context, inputs, scenario)
    run_until_mode(simulator, machine, Mode.HOLD, scenario.grasp.lift_s + 0.1)
    config = MemorizedControllerConfig()
    simulator.AdvanceTo(context.get_time() + config.avoid.hit_refractory_s + 0.01)
    # the left pad's acceleration that reads direction_W in world (pad_accelerations_in_world)
    R_W_left = (R_WG_SIDE_GRASP @ R_G_PAD[0]).matrix()
    inputs.set(channels=[10.0, 10.0, 10.0 * config.avoid.hit_ra_mps2, 0.1],
               pad_acceleration=np.r_[R_W_left.T @ (5.0 * np.asarray(direction_W)), 0, 0, 0])
    run_until_mode(simulator, machine, Mode.AVOID, 0.01)
    inputs.set(channels=[10.0, 10.0, 0.1, 0.1])
    simulator.AdvanceTo(context.get_time() + config.avoid.sense_s + 0.01)
    state = machine.state(context)
    assert state.stage == Stage.MOVING
    return state.segment, machine.timeline(context)[-1]


def joint_speed_use(segment, samples=201) -> float:
    """The most any joint turns along the minimum-jerk `segment`, as a fraction of its speed
    limit (jaco_joint_limits: 90 % of the published), the joints solved pose by pose (each
    seeded by the one before, the branch the differential IK follows) and their rates from the
    grasp frame's Jacobian: the hand's velocity, orientation held."""
    plant = make_arm_control_plant()
    plant_context = plant.CreateDefaultContext()
    start, end = np.asarray(segment.p_start), np.asarray(segment.p_end)
    limits = jaco_joint_limits()[2]
    q, use = solve_grasp_frame_ik(plant, RigidTransform(R_WG_SIDE_GRASP, start)), 0.0
    for tau in np.linspace(0.0, 1.0, samples):
        s = float(minimum_jerk(float(tau)))
        q = follow_pose(plant, plant_context, q, start + s * (end - start))
        velocity = (end - start) * minimum_jerk_slope(float(tau)) / segment.duration
        rates = np.linalg.solve(grasp_frame_jacobian(plant, plant_context, q),
                                np.r_[0.0, 0.0, 0.0, velocity])
        use = max(use, float(np.max(np.abs(rates) / limits)))
    return use


def test_an_avoid_the_arm_cannot_follow_in_move_s_is_stretched_to_what_it_follows():
    # 165 deg from +x (toward the start pose, the wrist near its singularity): the slowest of
    # the 24 horizontal directions (docs/model.md, "What each setting may be": 1.04 s).
    away = np.array([math.cos(math.radians(165)), math.sin(math.radians(165)), 0.0])
    segment, avoid = avoid_along(away)
    assert avoid["direction"] == pytest.approx(list(away), abs=1e-3)
    assert segment.duration == pytest.approx(1.037, abs=0.005)
    assert avoid["move_s"] == segment.duration
    assert "stretched from 0.6 s to" in avoid["reason"]
    # The bound is the joints' limits: the stretched move turns the busiest joint at its limit,
    # to within 4 % (the bound samples 11 poses; sampled at 201 the busiest joint reaches 1.036
    # of the IK's 90 % limit, 93 % of its published top speed), the 0.6 s move far past it.
    assert 0.97 <= joint_speed_use(segment) <= 1.04
    assert joint_speed_use(dataclasses.replace(segment, duration=0.6)) > 1.5


def test_an_avoid_the_arm_follows_in_move_s_keeps_it():
    # 60 deg from +x: the hand's fastest horizontal direction here (0.42 s would do)
    away = np.array([math.cos(math.radians(60)), math.sin(math.radians(60)), 0.0])
    segment, avoid = avoid_along(away)
    assert segment.duration == MemorizedControllerConfig().avoid.move_s == 0.6
    assert avoid["move_s"] == 0.6 and avoid["reason"] == "hit: RA above the hit threshold"
    assert joint_speed_use(segment) < 0.8
