"""The myRIO tactile stream as a Drake system with the simulated pads' ports. Every `period` (1 ms)
an update drains the reader thread's frames without blocking and calibrates them. A burst is played
one frame per tick, two while more than two wait, all but `max_backlog` beyond that, keeping the
newest counts and the largest piezo sample (docs/hardware.md, "Serial bursts and the slip band").
The frames' device times are checked against their arrival (device_clock.py): a stream that
runs ahead of the host's clock is a fault on the `fault` port."""

import dataclasses
import time

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from tegrasp_drake.rig.channels import FINGER_NAMES, TAXELS_PER_PAD
from tegrasp_drake.hardware.state_outputs import declare_scalar_state_outputs
from tegrasp_drake.hardware.device_fault import IMPLAUSIBLE, DeviceFault
from tegrasp_drake.hardware.myrio.device_clock import (
    DeviceClock, device_clock_after_frames, implausible_clock_description)
from tegrasp_drake.hardware.myrio.tactile_calibration import (
    PadCalibration, PadZeroing, TactileCalibration, acceleration_from_piezo,
    forces_from_counts)


_NO_SAMPLES = np.zeros((0, len(FINGER_NAMES)))


@dataclasses.dataclass(frozen=True)
class TactileReceiverState:
    """What the receiver knows, kept in the Context."""
    forces: tuple = (np.zeros(TAXELS_PER_PAD), np.zeros(TAXELS_PER_PAD))  # [N]
    accelerations: tuple = (0.0, 0.0)   # [m/s^2], along the film's axis
    device_time: float = 0.0            # [s], timestamp of the played frame; 0 before any
    arrival_time: float = -np.inf       # time.monotonic() [s] of the newest frame received
    stale: bool = True
    pads: tuple = (PadCalibration(), PadCalibration())
    zeroing: tuple = (PadZeroing(), PadZeroing())
    zeroed: bool = False
    pending: tuple = ()                 # frames received, not yet played (oldest first)
    played_arrival_time: float = -np.inf  # time.monotonic() [s] the played frame arrived
    played_samples: np.ndarray = dataclasses.field(  # (n, 2) [m/s^2] played in the last tick
        default_factory=lambda: _NO_SAMPLES)  # noqa: the one empty array, never changed
    clock: DeviceClock = DeviceClock()  # the device's clock against the frames' arrival
    faults: tuple = ()                  # DeviceFault: the implausible clock, once seen

    def __deepcopy__(self, memo):
        # Immutable (replaced, never changed), so Drake's 1 kHz Context copies can share it.
        return self


def initial_receiver_state(calibration: TactileCalibration) -> TactileReceiverState:
    return TactileReceiverState(pads=calibration.pads(),
                                zeroed=calibration.zero_samples <= 0)


def receiver_state_after_frames(state: TactileReceiverState, frames,
                                calibration: TactileCalibration) -> TactileReceiverState:
    """The state after these frames (oldest first); pure."""
    forces, accelerations = list(state.forces), list(state.accelerations)
    pads, zeroing, zeroed = state.pads, state.zeroing, state.zeroed
    peak = [None, None]  # the largest-magnitude piezo sample of these frames, per pad
    samples = []  # every piezo sample of these frames once zeroed, oldest first, per pad
    volts_per_count = calibration.piezo_volts_per_count
    for frame in frames:
        counts = (frame.left_counts, frame.right_counts)
        if not zeroed:
            zeroing = tuple(z.add(c, p * volts_per_count)
                            for z, c, p in zip(zeroing, counts, frame.piezo))
            if all(z.done(calibration.zero_samples) for z in zeroing):
                pads = tuple(z.zeroed(pad) for z, pad in zip(zeroing, pads))
                zeroed = True
            continue
        for i, pad in enumerate(pads):
            if counts[i] is not None:
                forces[i] = forces_from_counts(counts[i], pad.gain, pad.offset)
        frame_samples = [float(acceleration_from_piezo(
            piezo, volts_per_count, pad.piezo_gain, pad.piezo_offset))
            for piezo, pad in zip(frame.piezo, pads)]
        for i, acceleration in enumerate(frame_samples):
            if peak[i] is None or abs(acceleration) > abs(peak[i]):
                peak[i] = acceleration
        samples.append(frame_samples)
    accelerations = [a if p is None else p for a, p in zip(accelerations, peak)]
    if not frames:
        return state
    return dataclasses.replace(
        state, forces=tuple(forces), accelerations=tuple(accelerations),
        device_time=frames[-1].time, arrival_time=frames[-1].arrival_time, pads=pads,
        zeroing=zeroing, zeroed=zeroed,
        played_samples=np.array(samples).reshape(len(samples), len(FINGER_NAMES)))


def receiver_state_after_tick(state: TactileReceiverState, received, calibration:
                              TactileCalibration, max_backlog: int) -> TactileReceiverState:
    """The state after a tick that received these frames (oldest first): one frame played, two
    while more than two wait, more when over `max_backlog` wait; all while zeroing. Pure."""
    if received:
        clock = device_clock_after_frames(state.clock, received)
        if clock is not state.clock:
            state = dataclasses.replace(state, clock=clock)
    pending = state.pending + tuple(received)
    if not pending:
        return (state if not len(state.played_samples) else
                dataclasses.replace(state, played_samples=_NO_SAMPLES))
    catching_up = 2 if len(pending) > 2 else 1
    count = max(catching_up, len(pending) - max_backlog) if state.zeroed else len(pending)
    played = receiver_state_after_frames(state, pending[:count], calibration)
    return dataclasses.replace(played, pending=pending[count:],
                               arrival_time=pending[-1].arrival_time,
                               played_arrival_time=pending[count - 1].arrival_time)


class TactileSerialReceiver(LeafSystem):
    """Both tactile pads from a `TactileSerialReader` (module docstring).

    .. pydrake_system::

        name: TactileSerialReceiver
        output_ports:
        - left_taxel_forces
        - left_pad_acceleration
        - right_taxel_forces
        - right_pad_acceleration
        - pad_acceleration_samples
        - time_measured
        - stale
        - arrival_time
        - zeroing
        - fault

    Ports: taxel forces (12) [N]; pad accelerations (3) [m/s^2], the film's value in the pad
    frame's x; samples: (n, 6) rows [left xyz, right xyz] played in the tick; time_measured:
    the played frame's device time [s]; stale: 1 after `stale_timeout` [s] without a frame;
    arrival_time: its host time.monotonic() [s]; zeroing: 1 until zeroed; fault: a tuple of
    DeviceFault, empty while the frames' device time keeps to the host's (device_clock.py),
    else the IMPLAUSIBLE fault (latched).
    """

    def __init__(self, reader, *, calibration: TactileCalibration | None = None,
                 period: float = 1e-3, stale_timeout: float = 0.05, max_backlog: int = 8):
        super().__init__()
        self._reader = reader
        self._max_backlog = max_backlog
        self._calibration = dataclasses.replace(calibration or TactileCalibration())
        self._stale_timeout = stale_timeout
        self._state_index = self.DeclareAbstractState(
            AbstractValue.Make(initial_receiver_state(self._calibration)))
        self._start_state = None  # set by zero_before_start
        self.DeclareInitializationUnrestrictedUpdateEvent(self._initialize)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        state_ticket = {self.abstract_state_ticket(self._state_index)}
        for i, finger in enumerate(FINGER_NAMES):
            self.DeclareVectorOutputPort(
                f"{finger}_taxel_forces", TAXELS_PER_PAD, self._make_calc_forces(i),
                prerequisites_of_calc=state_ticket)
            self.DeclareVectorOutputPort(
                f"{finger}_pad_acceleration", 3, self._make_calc_acceleration(i),
                prerequisites_of_calc=state_ticket)
        self.DeclareAbstractOutputPort(
            "pad_acceleration_samples", lambda: AbstractValue.Make(np.zeros((0, 6))),
            self._calc_samples, prerequisites_of_calc=state_ticket)
        declare_scalar_state_outputs(self, self._state_index, {
            "time_measured": lambda state: state.device_time,
            "stale": lambda state: state.stale,
            "arrival_time": lambda state: state.played_arrival_time,
            "zeroing": lambda state: not state.zeroed})
        self.DeclareAbstractOutputPort(
            "fault", lambda: AbstractValue.Make(()),
            lambda context, out: out.set_value(self._state(context).faults),
            prerequisites_of_calc=state_ticket)

    @property
    def reader(self):
        """The reader (for its counters)."""
        return self._reader

    def zero_before_start(self, deadline: float) -> bool:
        """Zeroes the untouched pads before the Simulator starts, blocking until `zero_samples`
        sequences per finger arrived or `deadline` [s, monotonic] passes; True when zeroed."""
        state = initial_receiver_state(self._calibration)
        while not state.zeroed and time.monotonic() < deadline:
            frames = self._reader.drain()
            if frames:
                state = receiver_state_after_frames(state, frames, self._calibration)
            else:
                time.sleep(0.002)
        if state.zeroed:
            self._start_state = dataclasses.replace(state, played_samples=_NO_SAMPLES)
        return state.zeroed

    @property
    def zero_samples(self) -> int:
        """How many count sequences per finger zeroing averages."""
        return self._calibration.zero_samples

    def _initialize(self, context, state):
        if self._start_state is not None:
            state.get_mutable_abstract_state(self._state_index).set_value(self._start_state)

    def _state(self, context) -> TactileReceiverState:
        return context.get_abstract_state(self._state_index).get_value()

    def _update(self, context, state):
        new = receiver_state_after_tick(self._state(context), self._reader.drain(),
                                        self._calibration, self._max_backlog)
        stale = time.monotonic() - new.arrival_time > self._stale_timeout
        if stale != new.stale:
            new = dataclasses.replace(new, stale=stale)
        if new.clock.implausible and not new.faults:
            description = implausible_clock_description(
                new.clock, self._reader.port, self._reader.counters().queue_overflows)
            new = dataclasses.replace(new, faults=(DeviceFault(
                "tactile", IMPLAUSIBLE, description, since_sim_time=context.get_time(),
                since_wall_time=time.time()),))
        state.get_mutable_abstract_state(self._state_index).set_value(new)

    def _calc_samples(self, context, output):
        played = self._state(context).played_samples
        rows = np.zeros((len(played), 6))
        rows[:, 0], rows[:, 3] = played[:, 0], played[:, 1]
        output.set_value(rows)

    def _make_calc_forces(self, finger: int):
        def calc(context, output):
            state = self._state(context)
            output.SetFromVector(state.forces[finger] if state.zeroed
                                 else np.zeros(TAXELS_PER_PAD))
        return calc

    def _make_calc_acceleration(self, finger: int):
        def calc(context, output):
            state = self._state(context)
            value = state.accelerations[finger] if state.zeroed else 0.0
            output.SetFromVector([value, 0.0, 0.0])
        return calc
