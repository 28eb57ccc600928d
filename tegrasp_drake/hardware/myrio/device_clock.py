"""The myRIO's own clock against the host's. Each frame carries the device's timestamp, one
frame period (1 ms) per frame. Measured from a reference frame, the device time elapsed can
run ahead of the host's (time.monotonic() of arrival) by no more than the reference's own
delay in reaching the host: frames cannot leave the device faster than it takes them. A
stream whose device time runs more than `allowance` [s] ahead of the host's has a clock the
host cannot trust (a device streaming much faster than its documented 1000 frames a second,
or another device's stream): a fault.

The reference must therefore be a frame the host read promptly. A loaded host reads frames
late and in bursts, and after a stall it drains the backlog in quick reads: a frame of that
backlog, taken as reference, would make every promptly read frame after it look ahead by
the stall. So the reference is the most promptly read frame (the least arrival time minus
device time, drift allowed) among those that arrived between `SETTLE_S` and `HISTORY_S` ago:
an honest stream is then never ahead of it, however late or bursty the host, unless the
host read every frame of those seconds more than the allowance late. A flood from an honest
start is caught within allowance/(rate - 1) of host time; one from the first frame once
its first frames settle (`SETTLE_S` later). A device running less than 1 + allowance/
`HISTORY_S` times its rate (1.1x) is not told apart from a drifting one. A restarted device
(its time stepping by what its sequence numbers do not explain) starts the history again.
Pure numbers: `device_clock_after_frames` is a function of its arguments."""

import dataclasses
import math

from tegrasp_drake.hardware.myrio.tactile_frame import (
    FRAME_PERIOD_US, SEQUENCE_MODULUS, TIME_TOLERANCE_FRACTION, TIME_TOLERANCE_US)

ALLOWANCE_S = 1.0  # [s] device time ahead of the host's before the stream is implausible
# Crystal drift allowed on top, as a fraction of the host time since the reference: a
# myRIO's and a PC's oscillators differ by tens of ppm; 0.1 % is ten times that.
DRIFT = 1e-3
BUCKET_S = 0.1     # [s] of host time per slot of the reference's history (its best frame)
SETTLE_BUCKETS = 2  # a slot serves as reference once the host is 2 slots past it (0.1-0.2 s)
HISTORY_S = 10.0   # [s] slots older than this are forgotten (a slow device's credit with them)
_HISTORY_BUCKETS = round(HISTORY_S / BUCKET_S)


@dataclasses.dataclass(frozen=True)
class DeviceClock:
    """The history of promptly read frames, per `BUCKET_S` slot of host time: (slot,
    device time [s], arrival time [s]) of each slot's most promptly read frame; the latest
    frame's sequence and device time; `lead` [s] how far the device's elapsed time ran ahead
    of the host's since the reference, at the latest frame; `implausible` once it ran more
    than the allowance ahead (latched)."""
    history: tuple = ()
    reference: tuple | None = None  # (device time, arrival) [s] of the reference frame
    started: bool = False
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
        """How many times the host's time the device's ran since the reference."""
        return self.device_elapsed / self.host_elapsed


def follows(previous_sequence: int, previous_time: float, sequence: int,
            device_time: float) -> bool:
    """Whether a frame's device time [s] advanced by what its sequence gap explains (the
    decoder's rule, hardware/myrio/TACTILE_FRAME.md); not: the device restarted."""
    gap = (sequence - previous_sequence) % SEQUENCE_MODULUS
    expected_us = gap * FRAME_PERIOD_US
    step_us = (device_time - previous_time) * 1e6
    return abs(step_us - expected_us) <= TIME_TOLERANCE_US + TIME_TOLERANCE_FRACTION * expected_us


def _lateness(device_time: float, arrival: float, drift: float) -> float:
    """Arrival [s, host] less device time [s], the host's clock slowed by the drift allowed:
    the smaller, the more promptly read (relative to other frames of the same stream)."""
    return (1.0 + drift) * arrival - device_time


def _reference(history: list, slot: int, drift: float):
    """The most promptly read settled frame (device time, arrival) of the history, or None."""
    settled = [(t, a) for s, t, a in history if s <= slot - SETTLE_BUCKETS]
    return min(settled, key=lambda frame: _lateness(*frame, drift), default=None)


def device_clock_after_frames(clock: DeviceClock, frames, *, allowance: float = ALLOWANCE_S,
                              drift: float = DRIFT) -> DeviceClock:
    """The check after these frames (oldest first; each with `sequence`, `time` [s, device]
    and `arrival_time` [s, host]); pure. Once implausible it stays so, unchanged."""
    if clock.implausible or not frames:
        return clock
    # Plain numbers in the loop (1000 frames a second pass here): the reference changes only
    # when the host's clock enters another slot; one DeviceClock at the end.
    history = list(clock.history)
    started, last_time, last_sequence = clock.started, clock.last_device_time, clock.last_sequence
    lead, device_elapsed, host_elapsed = clock.lead, clock.device_elapsed, clock.host_elapsed
    slot = history[-1][0] if history else None
    reference = clock.reference
    slot_best = _lateness(*history[-1][1:], drift) if history else math.inf
    implausible = False
    for frame in frames:
        device_time, arrival = frame.time, frame.arrival_time
        if started and not follows(last_sequence, last_time, frame.sequence, device_time):
            history, slot, reference = [], None, None  # a restart: its clock starts anew
        started, last_time, last_sequence = True, device_time, frame.sequence
        frame_slot = math.floor(arrival / BUCKET_S)
        lateness = _lateness(device_time, arrival, drift)
        if slot is None or frame_slot > slot:
            history.append((frame_slot, device_time, arrival))
            history = [entry for entry in history if entry[0] > frame_slot - _HISTORY_BUCKETS]
            slot, slot_best = frame_slot, lateness
            reference = _reference(history, slot, drift)
        elif lateness < slot_best:
            history[-1] = (history[-1][0], device_time, arrival)
            slot_best = lateness
        if reference is None:
            lead = device_elapsed = host_elapsed = 0.0
            continue
        device_elapsed = device_time - reference[0]
        host_elapsed = arrival - reference[1]
        lead = device_elapsed - host_elapsed
        if lead > allowance + drift * host_elapsed:
            implausible = True
            break
    return DeviceClock(tuple(history), reference, started, last_time, last_sequence, lead,
                       device_elapsed, host_elapsed, implausible)


def implausible_clock_description(clock: DeviceClock, port: str, overflowed: int) -> str:
    """The fault's one line: how fast the device's clock ran, where, what was lost, what
    to check."""
    return (f"frames arrive faster than the myRIO's 1000 a second: its clock ran "
            f"{clock.ratio:.1f} times the host's on {port} "
            f"({clock.device_elapsed:.2f} s of device time in {clock.host_elapsed:.2f} s); "
            f"{overflowed} frames dropped when the queue overflowed; check that tactile.port "
            "is the myRIO's and that it streams one frame per millisecond "
            "(hardware/myrio/TACTILE_FRAME.md)")
