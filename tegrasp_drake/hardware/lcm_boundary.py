"""LCM messages through the message boundary (message_boundary.py).

`decode_lcm` refuses, by reason, bytes too short for a fingerprint, another type's
fingerprint and bytes that end before the fields; a type's own check follows it.
`CheckedLcmSubscriber` is Drake's LcmSubscriberSystem decoding through a boundary's check
(a rejected message leaves the last good one, whose unchanged utime the watchdog sees as
silence), counted by a second subscription on the same DrakeLcm. A DrakeLcm subscription
holds one message per HandleSubscriptions, so two messages in one diagram step lose the
first, good or bad, before any count. `checked_handler` is a plain callback that passes on
checked messages only.
"""

from collections.abc import Callable

from pydrake.common.value import AbstractValue
from pydrake.systems.lcm import LcmSubscriberSystem, SerializerInterface

from tegrasp_drake.hardware.message_boundary import MessageBoundary, RejectedMessage

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
    """An LcmSubscriberSystem serializer that decodes through `boundary`'s check, counting
    nothing; a rejected message leaves the value (the last good one) unchanged.
    """

    def __init__(self, lcm_type, boundary: MessageBoundary):
        SerializerInterface.__init__(self)
        self._lcm_type = lcm_type
        self._boundary = boundary

    def CreateDefaultValue(self):
        return AbstractValue.Make(self._lcm_type())

    def Deserialize(self, data, abstract_value):
        message = self._boundary.check_quietly(data)
        if message is not None:
            abstract_value.set_value(message)

    def Serialize(self, abstract_value):
        return abstract_value.get_value().encode()


def CheckedLcmSubscriber(*, channel: str, lcm_type, boundary: MessageBoundary,
                         lcm) -> LcmSubscriberSystem:
    """Drake's LcmSubscriberSystem on `channel`, checked by `boundary`, which counts every
    message on the channel."""
    lcm.Subscribe(channel, checked_handler(boundary, lambda message: None))
    return LcmSubscriberSystem(channel, CheckedLcmSerializer(lcm_type, boundary), lcm)


def checked_handler(boundary: MessageBoundary, on_message: Callable) -> Callable:
    """A subscription callback (DrakeLcm's `handler(data)` or lcm's `handler(channel,
    data)`) that passes `on_message` the messages `boundary` accepts."""
    def handler(*arguments):
        message = boundary.accept(arguments[-1])
        if message is not None:
            on_message(message)
    return handler
