import numpy as np

from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.robotiq import linkage
from pydrake.systems.analysis import Simulator

from tegrasp_drake.robotiq import drive
from tegrasp_drake.simulation import robotiq_drive_step as step
from tegrasp_drake.simulation.sim_robotiq_driver import (HELD, MOVING, STUCK,
                                                         GripperDriverConfig,
                                                         MakeSimRobotiqDriver,
                                                         drive_set_point, has_arrived,
                                                         object_status, reference_step)

PRISMATIC = GripperDriverConfig(model="prismatic")
TIME_STEP = 1e-3
# The linkage's drive at the defaults, and a driver blocked on a 45 mm object.
INERTIA = drive.drive_inertia()
GAIN, DAMPING = drive.loop_gains(drive.POSITION_LOOP_HZ, INERTIA)
THETA = linkage.driver_angle(0.0225)
LIMIT = 2 * ru.FORCE_MIN_N * -linkage.half_opening_rate(THETA)  # the cap at 20 N [N m]


def _drive(**overrides):
    """drive_set_point of the blocked driver closing (+1) at rest, the loop far behind its
    reference, with `overrides`."""
    arguments = dict(a=THETA, v=0.0, v_prev=0.0, set_point=(THETA, 0.0), phase=MOVING,
                     anchor=THETA, reference=(THETA + 0.5, 0.0), limit=LIMIT, direction=1.0,
                     gain=GAIN, damping=DAMPING, inertia=INERTIA, time_step=TIME_STEP)
    return drive_set_point(**{**arguments, **overrides})


def _after_one_drive_step(driver, context):
    """Advances the driver alone past its first drive step (half a plant step in)."""
    simulator = Simulator(driver, context)
    simulator.AdvanceTo(0.75 * TIME_STEP)
    return simulator.get_context()


def _states(driver, context):
    """The planner's state and the drive's memory (mutable vectors) in a driver's context
    (MakeSimRobotiqDriver: robotiq_drive_step.PLANNER, MEMORY)."""
    planner = driver.GetSubsystemByName("planner")
    memory = driver.GetSubsystemByName("drive_memory")
    return (planner.GetMyMutableContextFromRoot(context).get_mutable_discrete_state(0)
            .get_mutable_value(),
            memory.GetMyMutableContextFromRoot(context).get_mutable_discrete_state(0)
            .get_mutable_value())


def test_reference_accelerates_toward_the_goal_then_cruises():
    assert reference_step(0.04, 0.0, 0.0, 0.025, 0.5, 0.005) == -0.5
    assert reference_step(0.03, -0.025, 0.0, 0.025, 0.5, 0.005) == 0.0


def test_reference_brakes_to_stop_at_the_goal():
    assert reference_step(0.0005, -0.025, 0.0, 0.025, 0.5, 0.005) > 0.0


def test_reference_comes_to_rest_on_the_goal_instead_of_circling_it():
    q, v, a, dt = 0.02, -0.025, 0.5, 0.005
    velocities = []
    for _ in range(300):
        if has_arrived(q, v, 0.0, a, dt):
            q, v = 0.0, 0.0
        acceleration = reference_step(q, v, 0.0, 0.025, a, dt)
        q, v = q + v * dt + 0.5 * acceleration * dt * dt, v + acceleration * dt
        velocities.append(v)
    assert q == 0.0 and not any(velocities[-100:])


def test_object_status_reports_a_stall_before_the_goal_while_closing():
    assert object_status(0.0225, 0.0, 0.010, 0.0, 0.002) == ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    assert object_status(0.0100, 0.0, 0.030, 0.0425, 0.002) == ru.ObjectStatus.STOPPED_ON_CONTACT_OPENING
    assert object_status(0.0200, -0.02, 0.019, 0.0, 0.002) == ru.ObjectStatus.MOVING
    assert object_status(0.0, 0.0, 0.0, 0.0, 0.002) == ru.ObjectStatus.AT_REQUESTED_POSITION


def test_force_limit_bounds_the_setpoint_offset():
    config = PRISMATIC
    driver = MakeSimRobotiqDriver(config=config, time_step=TIME_STEP)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, 0])  # close at 20 N
    driver.GetInputPort("finger_state").FixValue(context, [0.02, 0.0])
    # Put the reference far inside the object: the set-point stays within 2 F / kp.
    planner, _ = _states(driver, context)
    planner[step.REF_Q] = 0.0
    context = _after_one_drive_step(driver, context)
    desired = driver.GetOutputPort("desired_state").Eval(context)
    assert np.isclose(0.02 - desired[0], 2 * ru.FORCE_MIN_N / config.position_gain)


def test_status_reports_activation_and_position_bytes():
    driver = MakeSimRobotiqDriver(config=PRISMATIC, time_step=TIME_STEP)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [0, 0, 0])
    driver.GetInputPort("finger_state").FixValue(context, [0.0425, 0.0])
    status = driver.GetOutputPort("status").Eval(context)
    assert status[ru.STATUS_STA] == ru.ActivationStatus.ACTIVE
    assert status[ru.STATUS_PO] == ru.POSITION_OPEN_BYTE


def test_linkage_status_position_comes_from_the_driver_angle_through_the_linkage():
    driver = MakeSimRobotiqDriver(config=GripperDriverConfig(model="linkage"), time_step=TIME_STEP)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [0, 0, 0])
    for opening in (0.085, 0.045, 0.010):
        theta = linkage.driver_angle(opening / 2)
        driver.GetInputPort("finger_state").FixValue(context, [theta, 0.0])
        status = driver.GetOutputPort("status").Eval(context)
        assert status[ru.STATUS_PO] == ru.position_byte_from_opening(opening)


def test_linkage_force_limit_is_the_pad_force_through_the_lever():
    set_a, set_v, phase, motor, _ = _drive()
    # One motor drives both fingers: 2 F lever of torque from the PD, and no more.
    assert motor == LIMIT and phase == MOVING
    assert np.isclose(GAIN * (set_a - THETA - TIME_STEP * set_v), LIMIT)


def test_within_the_limit_the_plants_pd_is_the_position_loop_on_its_reference():
    reference = (THETA + 1e-3, 0.1)
    set_a, set_v, phase, motor, _ = _drive(reference=reference)
    assert (set_a, set_v, phase) == (*reference, MOVING)
    assert np.isclose(motor, GAIN * 1e-3 + DAMPING * 0.1)


def test_a_load_that_would_drive_the_rotor_back_stops_it_where_it_stands():
    # The rotor has just turned back (v < 0) under a load above the capped motor torque:
    # the PD's torque over the last step was 1.3 times the cap at no acceleration.
    held_set_point = THETA + 1.3 * LIMIT / GAIN
    set_a, set_v, phase, motor, anchor = _drive(v=-1e-4, v_prev=-1e-4,
                                                set_point=(held_set_point, -1e-4))
    load = 1.3 * LIMIT
    assert phase == HELD and anchor == THETA and set_v == 0.0
    assert np.isclose(GAIN * (set_a - THETA), load)  # the screw carries all of it


def test_stuck_below_the_limit_the_screw_holds_until_the_motor_outpushes_the_load():
    held_set_point = THETA + 0.5 * LIMIT / GAIN  # a load of half the cap, standing
    weak = (THETA + 0.2 * LIMIT / GAIN, 0.0)  # the loop asks for a fifth of the cap
    assert _drive(set_point=(held_set_point, 0.0), phase=STUCK, reference=weak)[:3] == (
        held_set_point, 0.0, STUCK)
    strong = (THETA + 0.8 * LIMIT / GAIN, 0.0)
    set_a, _, phase, motor, _ = _drive(set_point=(held_set_point, 0.0), phase=STUCK,
                                       reference=strong)
    assert phase == MOVING and set_a == strong[0] and np.isclose(motor, 0.8 * LIMIT)


def test_held_the_motor_draws_nothing_and_the_set_point_stays_until_the_object_is_lost():
    held_set_point = THETA + 1.2 * LIMIT / GAIN
    assert _drive(set_point=(held_set_point, 0.0), phase=HELD) == (
        held_set_point, 0.0, HELD, 0.0, THETA)
    # The object slips out: the finger closes on by more than half the held squeeze.
    lost = THETA + 0.6 * (held_set_point - THETA)
    set_a, _, phase, motor, _ = _drive(a=lost, set_point=(held_set_point, 0.0), phase=HELD)
    assert phase == MOVING and motor == LIMIT


def test_float_helpers_equal_the_numpy_forms_bit_for_bit():
    # The driver's per-update helpers run on Python floats; the same numbers as numpy's.
    import numpy as np
    from tegrasp_drake.robotiq import units as ru
    from tegrasp_drake.simulation.sim_robotiq_driver import (command_targets, reference_step,
                                                             status_position_byte)

    def numpy_reference_step(q, v, goal, max_speed, acceleration, dt):
        distance = goal - q
        stopping_speed = np.sqrt(2.0 * acceleration * abs(distance))
        target_v = np.sign(distance) * min(max_speed, stopping_speed)
        if abs(distance) < 1e-6:
            target_v = 0.0
        return float(np.clip((target_v - v) / dt, -acceleration, acceleration))

    rng = np.random.default_rng(8)
    for _ in range(20000):
        q, goal = rng.uniform(0.0, 0.0425, size=2)
        if rng.random() < 0.1:
            goal = q + rng.choice([0.0, 1e-7, -1e-7, 2e-6])
        v = rng.normal(scale=0.05)
        args = (q, v, goal, rng.uniform(0.01, 0.075), 0.5, 0.005)
        assert reference_step(*args) == numpy_reference_step(*args)
        opening = rng.uniform(-0.01, 0.1)
        assert status_position_byte(opening / 2) == float(ru.position_byte_from_opening(opening))
    for position in [-3.0, 0.0, 0.5, 1.5, 2.5, 3.0, 127.5, 230.0, 254.5, 255.0, 300.0]:
        for speed, force in [(0.0, 0.0), (128.0, 77.0), (255.0, 255.0), (-1.0, 400.0)]:
            position_byte = np.clip(np.round(position), 0, 255)
            assert command_targets(position, speed, force) == (
                position_byte, ru.opening_from_position_byte(position_byte) / 2,
                ru.speed_from_byte(speed) / 2, ru.force_from_byte(force))


def test_cached_gripper_command_equals_the_computed_one():
    from tegrasp_drake.control.scripted_grasp import gripper_command
    for request in [(0.0, 0.05, 20.0), (0.085, 0.15, 235.0), (0.04, 0.02, 61.3)]:
        assert gripper_command(*request) == gripper_command.__wrapped__(*request)
        assert gripper_command(*request) == gripper_command(*request)


def test_simulated_and_emulated_grippers_read_no_current_once_stopped_on_an_object():
    # The manual's Modbus example of a finished grasp reads gCU = 0x00: the screw holds.
    from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulatorConfig, RobotiqGripperModel
    force_byte = 128
    driver = MakeSimRobotiqDriver(config=GripperDriverConfig(model="linkage"), time_step=TIME_STEP)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, force_byte])
    driver.GetInputPort("finger_state").FixValue(context, [THETA, 0.0])  # on a 45 mm object
    planner, memory = _states(driver, context)
    planner[step.OBJECT] = ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    memory[step.PHASE], memory[step.MOTOR] = HELD, LIMIT
    simulated = driver.GetOutputPort("status").Eval(context)[ru.STATUS_CU]
    model = RobotiqGripperModel(RobotiqEmulatorConfig(activation_duration=0.0,
                                                      object_opening=0.045), now=0.0)
    model.write(1000, [0x0900, 255, (255 << 8) | force_byte], now=0.0)
    moving = model.status(now=0.01)
    emulated = model.status(now=5.0)
    assert emulated[ru.STATUS_OBJ] == ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    assert simulated == emulated[ru.STATUS_CU] == 0
    assert moving[ru.STATUS_CU] == ru.MOVING_CURRENT


def test_the_simulated_current_follows_the_motors_torque_while_the_fingers_move():
    driver = MakeSimRobotiqDriver(config=GripperDriverConfig(model="linkage"), time_step=TIME_STEP)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, 255])
    driver.GetInputPort("finger_state").FixValue(context, [THETA, 0.0])
    for force, current in ((0.0, ru.MOVING_CURRENT), (ru.FORCE_MAX_N, ru.MAX_GRIPPING_CURRENT)):
        planner, memory = _states(driver, context)  # (getting them marks the outputs stale)
        planner[step.OBJECT] = ru.ObjectStatus.MOVING
        memory[step.MOTOR] = 2 * force * -linkage.half_opening_rate(THETA)
        assert driver.GetOutputPort("status").Eval(context)[ru.STATUS_CU] == current


def test_held_fingers_stay_held_when_the_reference_passes_its_goal_by_a_hair():
    from tegrasp_drake.simulation import sim_robotiq_driver as sim
    driver = MakeSimRobotiqDriver(config=GripperDriverConfig(model="linkage"), time_step=TIME_STEP)
    context = driver.CreateDefaultContext()
    command = [255, 255, 0]  # close at 20 N: the goal is q = 0
    driver.GetInputPort("command").FixValue(context, command)
    driver.GetInputPort("finger_state").FixValue(context, [THETA, 0.0])
    planner, memory = _states(driver, context)
    _, goal, half_speed, force = sim.command_targets(*command)
    for index, value in ((step.GOAL, goal), (step.FORCE, force), (step.HALF_SPEED, half_speed),
                         (step.REF_Q, goal - 5e-5), (step.DIRECTION, 1.0)):
        planner[index] = value
    for index, value in ((step.STARTED, 1.0), (step.PHASE, HELD), (step.ANCHOR, THETA),
                         (step.SET_A, THETA + 1.2 * LIMIT / GAIN), (step.SET_V, 0.0)):
        memory[index] = value
    context = _after_one_drive_step(driver, context)
    planner, memory = _states(driver, context)
    assert memory[step.PHASE] == HELD and planner[step.DIRECTION] == 1.0
