"""Jaco LCM senders/receivers, the velocity tracker and the builders, over memq:// LCM."""

import numpy as np
import pytest
from drake import lcmt_jaco_command, lcmt_jaco_status
from pydrake.common.value import AbstractValue
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.lcm import LcmInterfaceSystem, LcmPublisherSystem, LcmSubscriberSystem
from pydrake.systems.primitives import ConstantVectorSource

from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL, JacoCommandReceiver, JacoCommandSender,
    WRONG_JOINT_COUNT, JacoStatusReceiver, JacoStatusSender, check_jaco_status,
    make_jaco_command, make_jaco_status)
from tegrasp_drake.hardware.message_boundary import RejectedMessage
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver, AddJacoLcmEmulator
from tegrasp_drake.rig.jaco_velocity_tracker import (
    JacoVelocityTracker, JacoVelocityTrackerConfig, velocity_command)

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

Q = np.array([0.1, 2.8, 0.9, -0.4, 0.5, -0.6])  # [rad] inside the JACO2's joint ranges
V = np.array([0.01, 0.02, -0.03, 0.04, -0.05, 0.06])
TAU = np.array([1.0, 2.0, 3.0, -4.0, -5.0, -6.0])


def test_ports_have_the_station_sizes():
    sender, receiver = JacoCommandSender(), JacoStatusReceiver()
    assert sender.GetInputPort("desired_state").size() == 12
    for name in ("position_measured", "velocity_measured", "torque_measured"):
        assert receiver.GetOutputPort(name).size() == 6
    assert receiver.GetOutputPort("time_measured").size() == 1


def test_command_round_trip_through_memq_lcm():
    lcm = DrakeLcm("memq://")
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    source = builder.AddSystem(ConstantVectorSource(np.concatenate([Q, V])))
    sender = builder.AddSystem(JacoCommandSender())
    publisher = builder.AddSystem(LcmPublisherSystem.Make(
        channel=JACO_COMMAND_CHANNEL, lcm_type=lcmt_jaco_command, lcm=lcm,
        publish_period=0.01))
    subscriber = builder.AddSystem(LcmSubscriberSystem.Make(
        channel=JACO_COMMAND_CHANNEL, lcm_type=lcmt_jaco_command, lcm=lcm))
    receiver = builder.AddSystem(JacoCommandReceiver())
    measured = builder.AddSystem(ConstantVectorSource(np.zeros(6)))
    builder.Connect(source.get_output_port(), sender.GetInputPort("desired_state"))
    builder.Connect(sender.GetOutputPort("lcmt_jaco_command"), publisher.get_input_port())
    builder.Connect(subscriber.get_output_port(), receiver.GetInputPort("lcmt_jaco_command"))
    builder.Connect(measured.get_output_port(), receiver.GetInputPort("position_measured"))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.05)
    context = receiver.GetMyContextFromRoot(simulator.get_context())
    np.testing.assert_allclose(receiver.GetOutputPort("desired_state").Eval(context),
                               np.concatenate([Q, V]))
    message = subscriber.get_output_port().Eval(
        subscriber.GetMyContextFromRoot(simulator.get_context()))
    assert message.num_fingers == 0 and message.num_joints == 6
    assert 0 < message.utime <= 50_000


def test_status_round_trip_through_memq_lcm():
    lcm = DrakeLcm("memq://")
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    sender = builder.AddSystem(JacoStatusSender())
    for name, value in (("position_measured", Q), ("velocity_measured", V),
                        ("torque_measured", TAU)):
        source = builder.AddSystem(ConstantVectorSource(value))
        builder.Connect(source.get_output_port(), sender.GetInputPort(name))
    publisher = builder.AddSystem(LcmPublisherSystem.Make(
        channel=JACO_STATUS_CHANNEL, lcm_type=lcmt_jaco_status, lcm=lcm, publish_period=0.01))
    subscriber = builder.AddSystem(LcmSubscriberSystem.Make(
        channel=JACO_STATUS_CHANNEL, lcm_type=lcmt_jaco_status, lcm=lcm))
    receiver = builder.AddSystem(JacoStatusReceiver())
    builder.Connect(sender.GetOutputPort("lcmt_jaco_status"), publisher.get_input_port())
    builder.Connect(subscriber.get_output_port(), receiver.GetInputPort("lcmt_jaco_status"))
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(0.035)
    context = receiver.GetMyContextFromRoot(simulator.get_context())
    np.testing.assert_allclose(receiver.GetOutputPort("position_measured").Eval(context), Q)
    np.testing.assert_allclose(receiver.GetOutputPort("velocity_measured").Eval(context), V)
    np.testing.assert_allclose(receiver.GetOutputPort("torque_measured").Eval(context), TAU)
    assert receiver.GetOutputPort("time_measured").Eval(context)[0] == pytest.approx(0.03)


def test_status_receiver_outputs_zeros_before_the_first_message():
    receiver = JacoStatusReceiver()
    context = receiver.CreateDefaultContext()
    receiver.GetInputPort("lcmt_jaco_status").FixValue(context, lcmt_jaco_status())
    assert not receiver.GetOutputPort("position_measured").Eval(context).any()
    assert receiver.GetOutputPort("time_measured").Eval(context)[0] == 0.0


def test_the_status_check_rejects_a_message_with_the_wrong_joint_count():
    message = make_jaco_status(5, Q, V, TAU)
    message.num_joints = 7
    message.joint_position = list(Q) + [0.0]
    for name in ("joint_velocity", "joint_torque", "joint_torque_external", "joint_current"):
        setattr(message, name, list(getattr(message, name)) + [0.0])
    with pytest.raises(RejectedMessage, match="num_joints = 7") as refused:
        check_jaco_status(message.encode())
    assert refused.value.reason == WRONG_JOINT_COUNT


def _command_receiver_simulator(message):
    receiver = JacoCommandReceiver(command_timeout=0.05)
    simulator = Simulator(receiver)
    context = simulator.get_mutable_context()
    receiver.GetInputPort("lcmt_jaco_command").FixValue(context, AbstractValue.Make(message))
    receiver.GetInputPort("position_measured").FixValue(context, Q + 1.0)
    return receiver, simulator


def test_command_receiver_passes_a_fresh_command():
    receiver, simulator = _command_receiver_simulator(make_jaco_command(1000, Q, V))
    simulator.AdvanceTo(0.02)
    np.testing.assert_allclose(receiver.GetOutputPort("desired_state").Eval(
        simulator.get_context()), np.concatenate([Q, V]))


def test_command_receiver_stops_the_arm_when_commands_stop():
    receiver, simulator = _command_receiver_simulator(make_jaco_command(1000, Q, V))
    simulator.AdvanceTo(0.2)  # the same utime for 0.2 s > command_timeout
    np.testing.assert_allclose(receiver.GetOutputPort("desired_state").Eval(
        simulator.get_context()), np.concatenate([Q + 1.0, np.zeros(6)]))


def test_command_receiver_holds_still_before_any_command():
    receiver, simulator = _command_receiver_simulator(lcmt_jaco_command())
    simulator.AdvanceTo(0.01)
    np.testing.assert_allclose(receiver.GetOutputPort("desired_state").Eval(
        simulator.get_context()), np.concatenate([Q + 1.0, np.zeros(6)]))


def test_velocity_command_adds_the_position_error_and_clips():
    config = JacoVelocityTrackerConfig(kp=2.0)
    v = velocity_command(Q, V, Q - 0.01, config)
    np.testing.assert_allclose(v, V + 0.02)
    far = velocity_command(Q + 10.0 * np.array([0, 1, 0, 0, 0, 0]), V, Q, config)
    assert far[1] == pytest.approx(config.max_joint_speed[1])


def test_velocity_command_wraps_continuous_joints_only():
    config = JacoVelocityTrackerConfig(kp=1.0, max_joint_speed=[100.0] * 6)
    q_desired = np.array([np.pi - 0.1, 0, 0, 0, 0, 0])
    q_measured = np.array([-np.pi + 0.1, 0, 0, 0, 0, 0])
    assert velocity_command(q_desired, np.zeros(6), q_measured, config)[0] == (
        pytest.approx(-0.2))
    config.continuous_joints = [False] * 6
    assert velocity_command(q_desired, np.zeros(6), q_measured, config)[0] == (
        pytest.approx(2 * np.pi - 0.2))


def test_tracker_stop_holds_the_measured_position():
    tracker = JacoVelocityTracker()
    context = tracker.CreateDefaultContext()
    tracker.GetInputPort("desired_state").FixValue(context, np.concatenate([Q, V]))
    tracker.GetInputPort("position_measured").FixValue(context, Q - 0.1)
    tracker.GetInputPort("stop").FixValue(context, [0.0])
    assert tracker.GetOutputPort("commanded_state").Eval(context)[6:].any()
    tracker.GetInputPort("stop").FixValue(context, [1.0])
    np.testing.assert_allclose(tracker.GetOutputPort("commanded_state").Eval(context),
                               np.concatenate([Q - 0.1, np.zeros(6)]))


class VelocityModeArm(LeafSystem):
    """A test arm that, like the Jaco in velocity mode, integrates only the commanded
    velocities (the positions in desired_state are ignored)."""

    def __init__(self, q0, period=1e-3):
        super().__init__()
        self._desired = self.DeclareVectorInputPort("desired_state", 12)
        self._q = self.DeclareDiscreteState(np.asarray(q0, dtype=float))
        self.DeclarePeriodicDiscreteUpdateEvent(period, 0.0, self._step)
        self._period = period
        self.DeclareStateOutputPort("position", self._q)
        self.DeclareVectorOutputPort("zeros", 6, lambda context, out: out.SetZero())

    def _step(self, context, state):
        q = context.get_discrete_state(self._q).get_value()
        v = self._desired.Eval(context)[6:]
        state.get_mutable_vector(self._q).SetFromVector(q + self._period * v)


def test_velocity_mode_arm_reaches_the_goal_through_both_builders():
    lcm = DrakeLcm("memq://")
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    arm = builder.AddSystem(VelocityModeArm(Q - 0.5))
    AddJacoLcmEmulator(builder, lcm=lcm, desired_state_input=arm.GetInputPort("desired_state"),
                       position_output=arm.GetOutputPort("position"),
                       velocity_output=arm.GetOutputPort("zeros"),
                       torque_output=arm.GetOutputPort("zeros"), command_timeout=0.1)
    driver = AddJacoLcmDriver(builder, lcm=lcm)
    goal = builder.AddSystem(ConstantVectorSource(np.concatenate([Q, np.zeros(6)])))
    builder.Connect(goal.get_output_port(), driver.tracker.GetInputPort("desired_state"))
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(2.0)
    context = driver.status_receiver.GetMyContextFromRoot(simulator.get_context())
    measured = driver.status_receiver.GetOutputPort("position_measured").Eval(context)
    np.testing.assert_allclose(measured, Q, atol=0.01)
