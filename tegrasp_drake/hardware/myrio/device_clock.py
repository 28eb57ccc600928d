"""The myRIO's own clock against the host's. Each frame carries the device's timestamp, one
frame period (1 ms) per frame; frames cannot arrive faster than the device takes them, so
the device time elapsed since a reference frame can only run ahead of the host's
(time.monotonic() of arrival) by the reader's batching. A stream whose device time runs
more than `allowance` [s] ahead has a clock the host cannot trust (a device streaming much
faster than its documented 1000 frames a second, or another device's stream): a fault.

A loaded host reads frames late and in bursts: lateness makes the device's elapsed time
fall behind the host's, and the reference then moves to that frame (the check measures
from the most promptly read frame), so a late host never faults. A restarted device
(its time stepping by what its sequence numbers do not explain) also moves the reference.
Pure numbers: `device_clock_after_frames` is a function of its arguments."""

import dataclasses

from tegrasp_drake.hardware.myrio.tactile_frame import (
    FRAME_PERIOD_US, SEQUENCE_MODULUS, TIME_TOLERANCE_FRACTION, TIME_TOLERANCE_US)

ALLOWANCE_S = 1.0  # [s] device time ahead of the host's before the stream is implausible
# Crystal drift allowed on top, as a fraction of the host time since the reference: a
# myRIO's and a PC's oscillators differ by tens of ppm; 0.1 % is ten times that.
DRIFT = 1e-3


@dataclasses.dataclass(frozen=True)
class DeviceClock:
    """The reference frame (device time [s], host arrival time [s], sequence) and the
    latest one; `lead` [s] how far the device's elapsed time runs ahead of the host's since
    the reference; `implausible` once it ran more than the allowance ahead (latched)."""
    reference_device_time: float | None = None
    reference_arrival_time: float = 0.0
    last_device_time: float = 0.0
    last_sequence: int = 0
    lead: float = 0.0
    device_elapsed: float = 0.0  # [s] since the reference, at the latest frame
    host_elapsed: float = 0.0    # [s] since the reference, at the latest frame
    implausible: bool = False

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's copies of the Context's state can share it

    @property
    def ratio(self) -> float:
        """How many times the host's time the device's ran since the reference (inf when
        the host saw no time pass)."""
        return (self.device_elapsed / self.host_elapsed if self.host_elapsed > 0
                else float("inf"))


def follows(previous_sequence: int, previous_time: float, sequence: int,
            device_time: float) -> bool:
    """Whether a frame's device time [s] advanced by what its sequence gap explains (the
    decoder's rule, hardware/myrio/TACTILE_FRAME.md); not: the device restarted."""
    gap = (sequence - previous_sequence) % SEQUENCE_MODULUS
    expected_us = gap * FRAME_PERIOD_US
    step_us = (device_time - previous_time) * 1e6
    return abs(step_us - expected_us) <= TIME_TOLERANCE_US + TIME_TOLERANCE_FRACTION * expected_us


def device_clock_after_frames(clock: DeviceClock, frames, *, allowance: float = ALLOWANCE_S,
                              drift: float = DRIFT) -> DeviceClock:
    """The check after these frames (oldest first; each with `sequence`, `time` [s, device]
    and `arrival_time` [s, host]); pure. Once implausible it stays so, unchanged."""
    if clock.implausible or not frames:
        return clock
    # Plain numbers in the loop (1000 frames a second pass here); one DeviceClock at the end.
    reference_time, reference_arrival = clock.reference_device_time, clock.reference_arrival_time
    last_time, last_sequence = clock.last_device_time, clock.last_sequence
    lead, device_elapsed, host_elapsed = clock.lead, clock.device_elapsed, clock.host_elapsed
    implausible = False
    for frame in frames:
        device_time, arrival = frame.time, frame.arrival_time
        anchored = reference_time is not None and follows(last_sequence, last_time,
                                                          frame.sequence, device_time)
        if anchored:
            device_elapsed = device_time - reference_time
            host_elapsed = arrival - reference_arrival
            lead = device_elapsed - host_elapsed
        if not anchored or lead < 0:  # first frame, a restart, or the host read it late
            reference_time, reference_arrival = device_time, arrival
            lead = device_elapsed = host_elapsed = 0.0
        last_time, last_sequence = device_time, frame.sequence
        if lead > allowance + drift * host_elapsed:
            implausible = True
            break
    return DeviceClock(reference_time, reference_arrival, last_time, last_sequence, lead,
                       device_elapsed, host_elapsed, implausible)


def implausible_clock_description(clock: DeviceClock, port: str, overflowed: int) -> str:
    """The fault's one line: how fast the device's clock ran, where, what was lost, what
    to check."""
    if clock.host_elapsed > 0:
        ran = f"its clock ran {clock.ratio:.1f} times the host's"
    else:
        ran = "its clock ran while the host's stood still"
    return (f"frames arrive faster than the myRIO's 1000 a second: {ran} on {port} "
            f"({clock.device_elapsed:.2f} s of device time in {clock.host_elapsed:.2f} s); "
            f"{overflowed} frames dropped when the queue overflowed; check that tactile.port "
            "is the myRIO's and that it streams one frame per millisecond "
            "(hardware/myrio/TACTILE_FRAME.md)")
