"""LCM messages through the message boundary (message_boundary.py). `decode_lcm`
refuses, by reason, short bytes, another type's fingerprint and truncated fields;
`CheckedLcmSubscriber` is Drake's LcmSubscriberSystem decoding through a boundary (a rejected
message leaves the last good one). No Python callback is subscribed on a DrakeLcm a diagram
pumps: docs/hardware.md, "The real-time loop on a busy host"."""

import dataclasses
import time
from collections.abc import Callable

from pydrake.common.value import AbstractValue
from pydrake.systems.lcm import LcmSubscriberSystem, SerializerInterface

from tegrasp_drake.hardware.message_boundary import (
    MessageBoundary, MessageCounters, RejectedMessage)

FINGERPRINT_SIZE = 8  # bytes: every LCM message starts with its type's fingerprint

TOO_SHORT = "too short"
WRONG_TYPE = "wrong type"
TRUNCATED = "truncated"


def decode_lcm(lcm_type, data: bytes):
    """`data` decoded as `lcm_type`, or RejectedMessage naming what is wrong."""
    data = bytes(data)
    if len(data) < FINGERPRINT_SIZE:
        raise RejectedMessage(TOO_SHORT, f"{len(data)} bytes, not a {lcm_type.__name__}")
    if data[:FINGERPRINT_SIZE] != lcm_type._get_packed_fingerprint():
        raise RejectedMessage(WRONG_TYPE, f"not a {lcm_type.__name__} (its fingerprint is "
                              f"{data[:FINGERPRINT_SIZE].hex()})")
    try:
        return lcm_type.decode(data)
    except Exception as e:  # noqa: BLE001: struct.error, MemoryError on a huge count, ...
        raise RejectedMessage(TRUNCATED, f"a {lcm_type.__name__} of {len(data)} bytes that "
                              f"does not decode ({type(e).__name__}: {e})") from None


class CheckedLcmSerializer(SerializerInterface):
    """A subscriber's serializer decoding via `boundary`; a rejected message keeps the last."""

    def __init__(self, lcm_type, boundary: MessageBoundary):
        SerializerInterface.__init__(self)
        self._lcm_type = lcm_type
        self._boundary = boundary
        self.counting = True
        self.quiet_tally = None  # while not counting: where a wait counts what it looked at
        self.last_accepted = False  # whether the last message decoded passed the check

    def CreateDefaultValue(self):
        return AbstractValue.Make(self._lcm_type())

    def Deserialize(self, data, abstract_value):
        message = (self._boundary.accept(data) if self.counting
                   else self._boundary.check_quietly(data, tally=self.quiet_tally))
        self.last_accepted = message is not None
        if message is not None:
            abstract_value.set_value(message)

    def Serialize(self, abstract_value):
        return abstract_value.get_value().encode()


def CheckedLcmSubscriber(*, channel: str, lcm_type, boundary: MessageBoundary,
                         lcm) -> LcmSubscriberSystem:
    """Drake's LcmSubscriberSystem on `channel` through `boundary`, on the DrakeLcm `lcm`."""
    serializer = CheckedLcmSerializer(lcm_type, boundary)
    subscriber = LcmSubscriberSystem(channel, serializer, lcm)
    subscriber.checked_serializer = serializer
    return subscriber


@dataclasses.dataclass
class WaitTally(MessageCounters):
    """What a wait for a checked message saw (wait_for_checked_message): `arrived`, the
    messages the subscriber received while it waited; of them the ones it read (the newest
    at each look) counted as accepted or rejected by reason, `first_rejection` in words."""
    arrived: int = 0
    first_rejection: str = ""

    def count_rejection(self, rejection: RejectedMessage) -> None:
        if not self.first_rejection:
            self.first_rejection = str(rejection)
        super().count_rejection(rejection)


def wait_for_checked_message(lcm, subscriber: LcmSubscriberSystem, deadline: float,
                             tally: WaitTally | None = None) -> bool:
    """Pumps `lcm` until `subscriber` received a message its boundary accepts (True) or
    time.monotonic() passes `deadline`. Counts nothing on the boundary (call it before the
    Simulator runs); `tally`, when given, counts what the wait saw, so that a wait that
    ends without a good message can say whether messages came and why they were refused."""
    serializer = subscriber.checked_serializer
    probe = serializer.CreateDefaultValue()
    received = start = subscriber.WaitForMessage(0, None, 1e-6)
    while time.monotonic() < deadline:
        lcm.HandleSubscriptions(10)
        serializer.counting, serializer.quiet_tally = False, tally
        try:
            count = subscriber.WaitForMessage(received, probe, 1e-6)
        finally:
            serializer.counting, serializer.quiet_tally = True, None
        if count > received:
            received = count
            if tally is not None:
                tally.arrived = count - start
            if serializer.last_accepted:
                return True
    return False


def checked_handler(boundary: MessageBoundary, on_message: Callable) -> Callable:
    """An `lcm` subscription callback passing `on_message` the messages `boundary` accepts."""
    def handler(*arguments):
        message = boundary.accept(arguments[-1])
        if message is not None:
            on_message(message)
    return handler
