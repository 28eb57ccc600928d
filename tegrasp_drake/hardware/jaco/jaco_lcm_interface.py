"""Builders that wire the JACO2 LCM systems into a diagram for either end of the bus:
`AddJacoLcmDriver` (hardware) and `AddJacoLcmEmulator` (a simulation answering commands, as
Drake's hardware_sim). Both need an `LcmInterfaceSystem` for the same `lcm`; what each
receives crosses a MessageBoundary."""

import dataclasses

from drake import lcmt_jaco_command, lcmt_jaco_status
from pydrake.systems.framework import DiagramBuilder, InputPort, OutputPort
from pydrake.systems.lcm import LcmPublisherSystem, LcmSubscriberSystem

from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_LCM_PERIOD, JACO_STATUS_CHANNEL, JacoCommandReceiver,
    JacoCommandSender, JacoStatusReceiver, JacoStatusSender, check_jaco_command,
    jaco_status_boundary)
from tegrasp_drake.hardware.lcm_boundary import CheckedLcmSubscriber
from tegrasp_drake.hardware.message_boundary import MessageBoundary
from tegrasp_drake.rig.jaco_velocity_tracker import (
    JacoVelocityTracker, JacoVelocityTrackerConfig)


@dataclasses.dataclass
class JacoLcmDriverSystems:
    """The hardware-side systems: feed `tracker`'s desired_state (and stop), read
    `status_receiver`'s *_measured outputs."""
    tracker: JacoVelocityTracker
    command_sender: JacoCommandSender
    command_publisher: LcmPublisherSystem
    status_subscriber: LcmSubscriberSystem
    status_receiver: JacoStatusReceiver
    status_boundary: MessageBoundary  # the KINOVA_JACO_STATUS messages' counts


@dataclasses.dataclass
class JacoLcmEmulatorSystems:
    """The emulator-side systems."""
    command_subscriber: LcmSubscriberSystem
    command_receiver: JacoCommandReceiver
    status_sender: JacoStatusSender
    status_publisher: LcmPublisherSystem
    command_boundary: MessageBoundary  # the KINOVA_JACO_COMMAND messages' counts


def AddJacoLcmDriver(builder: DiagramBuilder, *, lcm, prefix: str = "jaco",
                     tracker_config: JacoVelocityTrackerConfig | None = None,
                     publish_period: float = JACO_LCM_PERIOD,
                     boundary: MessageBoundary | None = None) -> JacoLcmDriverSystems:
    """Adds tracker -> command sender -> publisher and subscriber -> status receiver, the
    tracker's feedback from the receiver; status messages cross `boundary`
    (jaco_status_boundary() by default)."""
    tracker = builder.AddNamedSystem(f"{prefix}_velocity_tracker",
                                     JacoVelocityTracker(tracker_config))
    sender = builder.AddNamedSystem(f"{prefix}_command_sender", JacoCommandSender())
    publisher = builder.AddNamedSystem(f"{prefix}_command_publisher", LcmPublisherSystem.Make(
        channel=JACO_COMMAND_CHANNEL, lcm_type=lcmt_jaco_command, lcm=lcm,
        publish_period=publish_period))
    boundary = boundary or jaco_status_boundary()
    subscriber = builder.AddNamedSystem(f"{prefix}_status_subscriber", CheckedLcmSubscriber(
        channel=JACO_STATUS_CHANNEL, lcm_type=lcmt_jaco_status, boundary=boundary, lcm=lcm))
    receiver = builder.AddNamedSystem(f"{prefix}_status_receiver", JacoStatusReceiver())
    builder.Connect(subscriber.get_output_port(), receiver.GetInputPort("lcmt_jaco_status"))
    builder.Connect(receiver.GetOutputPort("position_measured"),
                    tracker.GetInputPort("position_measured"))
    builder.Connect(tracker.GetOutputPort("commanded_state"),
                    sender.GetInputPort("desired_state"))
    builder.Connect(sender.GetOutputPort("lcmt_jaco_command"), publisher.get_input_port())
    return JacoLcmDriverSystems(tracker, sender, publisher, subscriber, receiver, boundary)


def AddJacoLcmEmulator(builder: DiagramBuilder, *, lcm, desired_state_input: InputPort,
                       position_output: OutputPort, velocity_output: OutputPort,
                       torque_output: OutputPort, prefix: str = "jaco_emulator",
                       command_timeout: float = 0.05,
                       publish_period: float = JACO_LCM_PERIOD,
                       boundary: MessageBoundary | None = None) -> JacoLcmEmulatorSystems:
    """Adds subscriber -> command receiver -> `desired_state_input` and the measured outputs ->
    status sender -> publisher; commands cross `boundary` (new by default)."""
    boundary = boundary or MessageBoundary(f"jaco: {JACO_COMMAND_CHANNEL}",
                                           check_jaco_command)
    subscriber = builder.AddNamedSystem(f"{prefix}_command_subscriber", CheckedLcmSubscriber(
        channel=JACO_COMMAND_CHANNEL, lcm_type=lcmt_jaco_command, boundary=boundary,
        lcm=lcm))
    receiver = builder.AddNamedSystem(f"{prefix}_command_receiver",
                                      JacoCommandReceiver(command_timeout=command_timeout))
    sender = builder.AddNamedSystem(f"{prefix}_status_sender", JacoStatusSender())
    publisher = builder.AddNamedSystem(f"{prefix}_status_publisher", LcmPublisherSystem.Make(
        channel=JACO_STATUS_CHANNEL, lcm_type=lcmt_jaco_status, lcm=lcm,
        publish_period=publish_period))
    builder.Connect(subscriber.get_output_port(), receiver.GetInputPort("lcmt_jaco_command"))
    builder.Connect(position_output, receiver.GetInputPort("position_measured"))
    builder.Connect(receiver.GetOutputPort("desired_state"), desired_state_input)
    builder.Connect(position_output, sender.GetInputPort("position_measured"))
    builder.Connect(velocity_output, sender.GetInputPort("velocity_measured"))
    builder.Connect(torque_output, sender.GetInputPort("torque_measured"))
    builder.Connect(sender.GetOutputPort("lcmt_jaco_status"), publisher.get_input_port())
    return JacoLcmEmulatorSystems(subscriber, receiver, sender, publisher, boundary)
