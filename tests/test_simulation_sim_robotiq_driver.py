import numpy as np

from tegrasp_drake.robotiq import units as ru
from tegrasp_drake.robotiq import linkage
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig, SimRobotiqDriver,
                                                         has_arrived, nut_set_point,
                                                         object_status, reference_step)

PRISMATIC = GripperDriverConfig(model="prismatic")


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
    driver = SimRobotiqDriver(config=config)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, 0])  # close at 20 N
    driver.GetInputPort("finger_state").FixValue(context, [0.02, 0.0])
    # Put the reference far inside the object: the set-point stays within 2 F / kp.
    state = context.get_mutable_discrete_state(0).get_mutable_value()
    state[0] = 0.0
    desired = driver.GetOutputPort("desired_state").Eval(context)
    assert np.isclose(0.02 - desired[0], 2 * ru.FORCE_MIN_N / config.position_gain)


def test_status_reports_activation_and_position_bytes():
    driver = SimRobotiqDriver(config=PRISMATIC)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [0, 0, 0])
    driver.GetInputPort("finger_state").FixValue(context, [0.0425, 0.0])
    status = driver.GetOutputPort("status").Eval(context)
    assert status[ru.STATUS_STA] == ru.ActivationStatus.ACTIVE
    assert status[ru.STATUS_PO] == ru.POSITION_OPEN_BYTE


def test_linkage_status_position_comes_from_the_driver_angle_through_the_linkage():
    driver = SimRobotiqDriver(config=GripperDriverConfig(model="linkage"))
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [0, 0, 0])
    for opening in (0.085, 0.045, 0.010):
        theta = linkage.driver_angle(opening / 2)
        driver.GetInputPort("finger_state").FixValue(context, [theta, 0.0])
        status = driver.GetOutputPort("status").Eval(context)
        assert status[ru.STATUS_PO] == ru.position_byte_from_opening(opening)


def test_linkage_force_limit_is_the_pad_force_through_the_lever():
    config = GripperDriverConfig(model="linkage")
    driver = SimRobotiqDriver(config=config)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, 0])  # close at 20 N
    theta = linkage.driver_angle(0.0225)  # blocked on a 45 mm object
    driver.GetInputPort("finger_state").FixValue(context, [theta, 0.0])
    state = context.get_mutable_discrete_state(0).get_mutable_value()
    state[0] = 0.0  # the reference far inside the object
    state[10] = 1.0  # closing
    desired = driver.GetOutputPort("desired_state").Eval(context)
    lever = -linkage.half_opening_rate(theta)
    # One actuator drives both fingers: 2 F lever of torque, and no more.
    assert np.isclose(config.driver_position_gain * (desired[0] - theta),
                      2 * ru.FORCE_MIN_N * lever)
    assert desired[1] == 0.0  # the nut stands


def test_the_nut_moves_only_in_the_commanded_direction():
    # Closing (+1): a load pushing the finger open leaves the nut where it is...
    assert nut_set_point(0.30, limited=0.28, reference=0.50, direction=1.0) == 0.30
    # ...and so does one pushing it further closed than the reference.
    assert nut_set_point(0.30, limited=0.45, reference=0.30, direction=1.0) == 0.30
    # It advances up to the force limit, never past the reference.
    assert nut_set_point(0.30, limited=0.32, reference=0.50, direction=1.0) == 0.32
    assert nut_set_point(0.30, limited=0.60, reference=0.50, direction=1.0) == 0.50
    # Opening (-1) mirrors it.
    assert nut_set_point(0.30, limited=0.33, reference=0.10, direction=-1.0) == 0.30
    assert nut_set_point(0.30, limited=0.20, reference=0.10, direction=-1.0) == 0.20


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


def test_simulated_and_emulated_grippers_report_the_same_current_when_gripping():
    from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulatorConfig, RobotiqGripperModel
    force_byte = 128
    driver = SimRobotiqDriver(config=GripperDriverConfig(model="linkage"))
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, force_byte])
    theta = linkage.driver_angle(0.0225)  # stopped on a 45 mm object
    driver.GetInputPort("finger_state").FixValue(context, [theta, 0.0])
    state = context.get_mutable_discrete_state(0).get_mutable_value()
    state[0], state[5], state[7] = 0.0, ru.force_from_byte(force_byte), 2  # ref closed; gOBJ 2
    simulated = driver.GetOutputPort("status").Eval(context)[ru.STATUS_CU]
    model = RobotiqGripperModel(RobotiqEmulatorConfig(activation_duration=0.0,
                                                      object_opening=0.045), now=0.0)
    model.write(1000, [0x0900, 255, (255 << 8) | force_byte], now=0.0)
    emulated = model.status(now=5.0)
    assert emulated[ru.STATUS_OBJ] == ru.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    assert simulated == emulated[ru.STATUS_CU] > 0
