"""Fixed-input tests of the hardware log's sender systems: every input lands in its message
field, in its units (utime in whole microseconds, bytes rounded), and survives LCM's
encoding and the replay's decoder."""

import time

import numpy as np

from tegrasp_drake.hardware.device_log_messages import (GripperStatusSender,
                                                        TactileStatusSender, tactile_arrays)
from tegrasp_drake.lcmtypes import lcmt_tegrasp_gripper, lcmt_tegrasp_tactile

LEFT_TAXELS = np.linspace(0.0, 1.1, 12)  # N
RIGHT_TAXELS = np.linspace(2.0, -0.2, 12)
LEFT_FILM, RIGHT_FILM = [0.5, 0.0, 0.0], [-1.25, 0.0, 0.0]  # m/s^2


def _tactile_message(t: float) -> tuple[lcmt_tegrasp_tactile, float, float]:
    """The message at Context time t, and the monotonic clock just before and after."""
    sender = TactileStatusSender()
    context = sender.CreateDefaultContext()
    context.SetTime(t)
    for name, value in (("left_taxel_forces", LEFT_TAXELS), ("right_taxel_forces", RIGHT_TAXELS),
                        ("left_pad_acceleration", LEFT_FILM),
                        ("right_pad_acceleration", RIGHT_FILM),
                        ("time_measured", [12.3456786]), ("stale", [1.0]), ("zeroing", [0.0]),
                        ("arrival_time", [5021.25])):
        sender.GetInputPort(name).FixValue(context, value)
    before = time.monotonic()
    message = sender.GetOutputPort("lcmt_tegrasp_tactile").Eval(context)
    return message, before, time.monotonic()


def test_tactile_message_carries_every_input_in_its_units():
    message, before, after = _tactile_message(1.2345676)
    assert message.utime == 1234568  # us, to the nearest
    assert message.device_utime == 12345679  # 12.3456786 s, to the nearest us
    assert (message.stale, message.zeroing) == (True, False)
    assert message.arrival_s == 5021.25
    assert before <= message.tick_s <= after  # the host clock when the message was built
    assert message.num_taxels == 12
    np.testing.assert_array_equal(message.left_taxel_forces, LEFT_TAXELS)
    np.testing.assert_array_equal(message.right_taxel_forces, RIGHT_TAXELS)
    np.testing.assert_array_equal(message.left_pad_acceleration, LEFT_FILM)
    np.testing.assert_array_equal(message.right_pad_acceleration, RIGHT_FILM)


def test_tactile_messages_decode_back_to_the_arrays_through_lcm_bytes():
    messages = [lcmt_tegrasp_tactile.decode(_tactile_message(t)[0].encode())
                for t in (0.001, 0.002)]
    arrays = tactile_arrays(messages)
    np.testing.assert_allclose(arrays["t"], [0.001, 0.002], rtol=0, atol=1e-12)
    np.testing.assert_allclose(arrays["device_t"], [12.345679] * 2, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(arrays["taxels"],
                                  np.tile(np.concatenate([LEFT_TAXELS, RIGHT_TAXELS]), (2, 1)))
    np.testing.assert_array_equal(arrays["pad_acceleration"],
                                  np.tile(LEFT_FILM + RIGHT_FILM, (2, 1)))
    np.testing.assert_array_equal(arrays["stale"], [True, True])
    np.testing.assert_array_equal(arrays["zeroing"], [False, False])


def _gripper_message(command) -> lcmt_tegrasp_gripper:
    sender = GripperStatusSender()
    context = sender.CreateDefaultContext()
    context.SetTime(0.25)
    if command is not None:
        sender.GetInputPort("command").FixValue(context, command)
    sender.GetInputPort("status").FixValue(context, [1, 1, 3, 2, 0, 229.6, 140.4, 31.5])
    sender.GetInputPort("time_measured").FixValue(context, [77.5])
    return lcmt_tegrasp_gripper.decode(
        sender.GetOutputPort("lcmt_tegrasp_gripper").Eval(context).encode())


def test_gripper_message_rounds_command_and_status_to_bytes():
    message = _gripper_message([230.0, 127.6, 54.5])
    assert message.utime == 250000
    assert message.status_arrival_s == 77.5
    assert list(message.command) == [230, 128, 54]  # round half to even: 54.5 -> 54
    assert list(message.status) == [1, 1, 3, 2, 0, 230, 140, 32]


def test_gripper_message_logs_an_unconnected_command_as_zeros():
    assert list(_gripper_message(None).command) == [0, 0, 0]
