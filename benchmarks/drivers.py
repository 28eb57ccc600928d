"""Driver benchmark: tactile latency from the wire to the output port, and loop jitter.

1. Latency: the myRIO emulator, in its own process like the real device, streams a
   synthetic trial on a pty; a TactileSerialReader and TactileSerialReceiver (1 kHz
   update) run in a Simulator at real-time rate 1. After every step a monitor reads the
   receiver's `time_measured`; each new value is matched to the emulator's write time of
   that frame. latency = first time the port shows the frame - time the frame's bytes
   were written (`time.monotonic()`, CLOCK_MONOTONIC, shared by the processes). It
   includes the reader's wake-up, decoding, the wait for the next 1 kHz tick, and the
   update itself.
2. Jitter: wall-clock periods of a 1 kHz periodic publish event, for a diagram with only
   that tick and for the same tick next to the tactile receiver (the latency run).

Run: `python -m benchmarks.drivers [--duration 5]`.
"""

import argparse
import dataclasses
import multiprocessing
import time

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, EventStatus, LeafSystem

from tegrasp_drake.rig.number_text import number_option
from tegrasp_drake.emulators.myrio_emulator import (
    MyRioEmulator, MyRioEmulatorConfig, TactileRecording)
from tegrasp_drake.hardware.myrio.tactile_calibration import TactileCalibration
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver

TICK_PERIOD = 1e-3  # [s]


class LoopTick(LeafSystem):
    """A benchmark probe: a periodic publish that appends `time.perf_counter()` to a list
    it was given (the measurement leaves the diagram on purpose; it holds no state).

    .. pydrake_system::

        name: LoopTick

    No ports: the wall-clock times [s] go to the list, one per `period` [s].
    """

    def __init__(self, wall_times: list, period: float = TICK_PERIOD):
        super().__init__()
        self.DeclarePeriodicPublishEvent(period, 0.0, lambda context: wall_times.append(
            time.perf_counter()))


@dataclasses.dataclass
class Percentiles:
    """median, p99 and max [us] of a sample, and its size."""
    median: float
    p99: float
    max: float
    count: int

    @staticmethod
    def of(seconds) -> "Percentiles":
        us = np.asarray(seconds) * 1e6
        if us.size == 0:
            return Percentiles(np.nan, np.nan, np.nan, 0)
        return Percentiles(float(np.median(us)), float(np.percentile(us, 99)),
                           float(us.max()), int(us.size))

    def __str__(self):
        return (f"median {self.median:8.1f} us   p99 {self.p99:8.1f} us   "
                f"max {self.max:8.1f} us   (n = {self.count})")


@dataclasses.dataclass
class DriverBenchmarkResult:
    tactile_latency: Percentiles
    loop_period_bare: Percentiles
    loop_period_with_tactile: Percentiles
    realtime_rate_with_tactile: float
    frames_sent: int
    frames_seen_at_port: int


def synthetic_trial(duration: float, seed: int = 0) -> TactileRecording:
    """Forces pressing in and out and a noisy vibration, for the latency run."""
    rng = np.random.default_rng(seed)
    times = np.arange(0.0, duration, 1e-3)
    press = 2.0 * np.clip(np.sin(np.pi * times / max(duration, 1e-3)), 0, None)
    forces = np.outer(press, np.linspace(0.2, 1.0, 12))
    vibration = rng.normal(0.0, 1.0, (len(times), 3))
    return TactileRecording(times, forces, forces[:, ::-1], times, vibration, vibration[:, 0])


def _periods(wall_times) -> np.ndarray:
    # The first ticks include start-up; skip them.
    return np.diff(np.asarray(wall_times[10:]))


def measure_bare_loop(duration: float) -> Percentiles:
    wall_times = []
    simulator = Simulator(LoopTick(wall_times))
    simulator.set_target_realtime_rate(1.0)
    simulator.AdvanceTo(duration)
    return Percentiles.of(_periods(wall_times))


def _stream_in_child(trial: TactileRecording, config: MyRioEmulatorConfig, connection):
    """Child process: emulate the myRIO, say where, stream on "go", report what was sent."""
    emulator = MyRioEmulator(trial, config)
    try:
        connection.send(emulator.port)
        if connection.poll(30.0) and connection.recv() == "go":
            emulator.start()
            emulator.wait_until_finished(trial.duration + config.lead_in + 30.0)
        connection.send([(f.timestamp_us, f.write_time) for f in emulator.sent()])
    finally:
        emulator.stop()


class _EmulatorProcess:
    """The myRIO emulator in its own process, as the real device is outside the host's
    Python: its threads then do not compete with the receiver for the GIL.
    time.monotonic() is CLOCK_MONOTONIC, shared by both processes."""

    def __init__(self, trial, config):
        context = multiprocessing.get_context("spawn")
        self._connection, child = context.Pipe()
        self._process = context.Process(target=_stream_in_child,
                                        args=(trial, config, child), daemon=True)
        self._process.start()
        if not self._connection.poll(30.0):
            self._process.kill()
            raise RuntimeError("the emulator process did not start")
        self.port = self._connection.recv()

    def go(self):
        self._connection.send("go")

    def sent(self, timeout: float) -> list:
        sent = self._connection.recv() if self._connection.poll(timeout) else []
        self._process.join(5.0)
        if self._process.is_alive():
            self._process.kill()
        return sent


def measure_tactile_loop(duration: float):
    """Latency and loop periods with the tactile receiver in the loop."""
    lead_in = 0.1
    trial = synthetic_trial(duration)
    wall_times = []
    emulator = _EmulatorProcess(trial, MyRioEmulatorConfig(lead_in=lead_in))
    with TactileSerialReader(emulator.port) as reader:
        builder = DiagramBuilder()
        receiver = builder.AddSystem(TactileSerialReceiver(
            reader, calibration=TactileCalibration(zero_samples=4)))
        builder.AddSystem(LoopTick(wall_times))
        simulator = Simulator(builder.Build())
        simulator.set_target_realtime_rate(1.0)
        time_port = receiver.GetOutputPort("time_measured")
        shown = {}  # device timestamp [us] -> monotonic time it first showed at the port

        def monitor(root_context):
            timestamp = int(round(time_port.Eval(
                receiver.GetMyContextFromRoot(root_context))[0] * 1e6))
            if timestamp not in shown:
                shown[timestamp] = time.monotonic()
            return EventStatus.Succeeded()

        simulator.set_monitor(monitor)
        simulator.Initialize()
        emulator.go()
        start = time.monotonic()
        simulator.AdvanceTo(lead_in + trial.duration)
        rate = simulator.get_context().get_time() / (time.monotonic() - start)
        sent = emulator.sent(timeout=10.0)
    written = dict(sent)
    latencies = [shown_at - written[timestamp] for timestamp, shown_at in shown.items()
                 if timestamp in written]
    return Percentiles.of(latencies), Percentiles.of(_periods(wall_times)), rate, len(
        sent), len(latencies)


def run_driver_benchmark(duration: float = 3.0, *, verbose: bool = True) -> DriverBenchmarkResult:
    """Runs both measurements (about 2 x duration of wall time) and prints them."""
    bare = measure_bare_loop(duration)
    latency, with_tactile, rate, sent, seen = measure_tactile_loop(duration)
    result = DriverBenchmarkResult(latency, bare, with_tactile, rate, sent, seen)
    if verbose:
        print(f"Driver benchmark, {duration:.1f} s per run, real-time rate target 1.0")
        print(f"  tactile frame write -> receiver output port: {latency}")
        print(f"    frames sent {sent}, distinct frames seen at the port {seen} "
              "(played one per tick; frames merged while the receiver catches up are "
              "not shown)")
        print(f"  1 kHz loop period, tick only:                {bare}")
        print(f"  1 kHz loop period, with tactile receiver:    {with_tactile}")
        print(f"    achieved real-time rate {rate:.3f}")
    return result


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=number_option, default=5.0, help="seconds per run")
    run_driver_benchmark(parser.parse_args(argv).duration)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
