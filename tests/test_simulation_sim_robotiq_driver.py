import numpy as np

from tegrasp_drake.rig import robotiq_units as ru
from tegrasp_drake.simulation.sim_robotiq_driver import (GripperDriverConfig, SimRobotiqDriver,
                                                         has_arrived, object_status,
                                                         reference_step)


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
    config = GripperDriverConfig()
    driver = SimRobotiqDriver(config=config)
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [255, 255, 0])  # close at 20 N
    driver.GetInputPort("finger_state").FixValue(context, [0.02, 0.02, 0.0, 0.0])
    # Put the reference far inside the object: the set-point stays within 2 F / kp.
    state = context.get_mutable_discrete_state(0).get_mutable_value()
    state[0] = 0.0
    desired = driver.GetOutputPort("desired_state").Eval(context)
    assert np.isclose(0.02 - desired[0], 2 * ru.FORCE_MIN_N / config.position_gain)


def test_status_reports_activation_and_position_bytes():
    driver = SimRobotiqDriver(config=GripperDriverConfig())
    context = driver.CreateDefaultContext()
    driver.GetInputPort("command").FixValue(context, [0, 0, 0])
    driver.GetInputPort("finger_state").FixValue(context, [0.0425, 0.0425, 0.0, 0.0])
    status = driver.GetOutputPort("status").Eval(context)
    assert status[ru.STATUS_STA] == ru.ActivationStatus.ACTIVE
    assert status[ru.STATUS_PO] == ru.POSITION_OPEN_BYTE
