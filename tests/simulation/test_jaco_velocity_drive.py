"""The simulated JACO2's joint-velocity drive (simulation/jaco_velocity_drive.py): its
command latency measured end to end through the station's ports, its servo, its settings."""

import math

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.primitives import DiscreteTimeDelay, ZeroOrderHold

from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario import MakeSimulatedStation
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.simulation.jaco_velocity_drive import (latency_register,
                                                          velocity_servo_set_point)
from tegrasp_drake.simulation.station import ArmDriverConfig, initial_arm_positions

STEP_AT_S = 0.203  # between two 100 Hz samples: the command waits 7 ms for the next one
JOINT = 0  # the base joint (continuous)
STEP_SPEED = 0.1  # [rad/s], well inside its 36 deg/s
# "Responds": the measured speed passes 1 % of the step. At rest it reads 1e-8 rad/s or
# less (the solver's round-off); one plant step of the 400 N m/rad, 40 N m s/rad servo
# after the command acts gives about 10 % of the step.
RESPONSE_FRACTION = 0.01


def _velocity_step_response_time(overrides) -> tuple[float, float, float]:
    """(time the measured joint speed responds, sample time the command waits for, plant
    step) [s] after arm.desired_state steps from rest to STEP_SPEED on JOINT at STEP_AT_S."""
    scenario = LoadScenario(overrides=overrides)
    station = MakeSimulatedStation(scenario)
    context = station.CreateDefaultContext()
    q0 = initial_arm_positions(scenario.arm)
    desired = station.GetInputPort(ports.ARM_DESIRED_STATE)
    desired.FixValue(context, np.concatenate([q0, np.zeros(6)]))
    station.GetInputPort(ports.GRIPPER_COMMAND).FixValue(context, np.zeros(3))
    simulator = Simulator(station, context)
    simulator.AdvanceTo(STEP_AT_S)
    v_desired = np.zeros(6)
    v_desired[JOINT] = STEP_SPEED
    desired.FixValue(context, np.concatenate([q0, v_desired]))
    speed = station.GetOutputPort(ports.ARM_VELOCITY_MEASURED)
    h = scenario.plant_config.time_step
    period = 1.0 / scenario.arm.command_rate_hz
    sample_s = math.ceil(round(STEP_AT_S / period, 9)) * period
    for k in range(1, 200):
        simulator.AdvanceTo(STEP_AT_S + k * h)
        if abs(speed.Eval(context)[JOINT]) > RESPONSE_FRACTION * STEP_SPEED:
            return context.get_time(), sample_s, h
    raise AssertionError("the arm never responded")


@pytest.mark.parametrize("latency_s", [0.01, 0.025])
def test_the_arm_responds_one_sample_and_the_latency_after_a_step_command(latency_s):
    responded_s, sample_s, h = _velocity_step_response_time(
        [f"arm.command_latency_s={latency_s}"])
    # The command waits for the next 100 Hz sample, then the latency; the measured speed
    # shows the step at the end of the first plant step that runs under it.
    assert sample_s + latency_s <= responded_s + 1e-9
    assert responded_s <= sample_s + latency_s + h + 1e-9


def test_the_carriage_responds_as_late_as_the_arm():
    latency_s = 0.02
    responded_s, sample_s, h = _velocity_step_response_time(
        [f"arm.command_latency_s={latency_s}", "station.arm=carriage"])
    assert sample_s + latency_s <= responded_s + 1e-9
    assert responded_s <= sample_s + latency_s + h + 1e-9


def test_the_servo_set_point_integrates_the_commanded_velocity():
    h = 0.001
    q0 = np.arange(6) * 0.1
    servo = velocity_servo_set_point(q0, h)
    context = servo.CreateDefaultContext()
    v = np.array([0.1, -0.2, 0.0, 0.3, 0.0, -0.5])
    servo.get_input_port().FixValue(context, np.concatenate([np.full(6, 9.0), v]))
    simulator = Simulator(servo, context)
    simulator.AdvanceTo(0.1)  # 100 steps
    y = servo.get_output_port().Eval(context)
    np.testing.assert_allclose(y[:6], q0 + 0.1 * v, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(y[6:], v)  # the desired positions play no part


@pytest.mark.parametrize("latency_s, kind", [(0.001, type(None)), (0.002, ZeroOrderHold),
                                             (0.01, DiscreteTimeDelay)])
def test_the_latency_register_is_a_compiled_system_or_none(latency_s, kind):
    # One plant step of latency is the plant's own; the end-to-end tests above measure
    # the rest.
    register = latency_register(ArmDriverConfig(command_latency_s=latency_s), 0.001, 12)
    assert isinstance(register, kind)


@pytest.mark.parametrize("override, field", [
    ("arm.command_latency_s=0.0105", "arm.command_latency_s"),
    ("arm.command_latency_s=0", "arm.command_latency_s"),
    ("arm.command_rate_hz=300", "arm.command_rate_hz"),
    ("arm.command_rate_hz=0", "arm.command_rate_hz"),
    ("arm.tracker.kp=-1", "arm.tracker.kp"),
    ("arm.tracker.max_joint_speed=[0.6, 0.6]", "arm.tracker.max_joint_speed"),
])
def test_a_bad_drive_setting_is_refused_naming_its_field(override, field):
    with pytest.raises(ConfigError, match=f"field '{field}'"):
        LoadScenario(overrides=[override])
