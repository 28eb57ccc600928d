"""Cost of one control tick of the event matcher, for the active event.

Four channels with full 0.5 s windows, RA at 1 kHz, SA at 100 Hz or at 1 kHz; the live
signal is a noisy synthetic grasp. Each figure is the median over `repeats` of the mean
wall time per 1 kHz tick [us] (a mean, so that the SA updates every tenth tick count):

- core_*: the streaming core (StreamingCorrelator.push: a sliding window and its
  SlidingCorrelation, numpy and BLAS), outside Drake;
- reference_*: the straightforward numpy.correlate scoring of the four windows;
- fft_rebuild_ra_us: an RA push that recomputes the correlations exactly by FFT (at an
  event change, and at a buffer compaction every 0.1 s);
- system_*: a Simulator running TrajectorySource -> EventMatcher, added as the grasp
  controller adds it (add_event_matcher), wall time / ticks; system_blocks_*: the same
  with the RA samples taken in 10 ms blocks (EventMatcherConfig.block_s);
- framework_tick_us: the same diagram with a Python system whose 1 kHz update only reads
  its input, i.e. the part of system_* that any Python LeafSystem pays;
- window_normalizer_tick_us: TrajectorySource -> WindowNormalizer alone, wall time / ticks
  (the part of system_* that keeps the windows: the EventMatcher is a WindowNormalizer).

Run `python -m benchmarks.matcher` to print them.
"""

import argparse
import dataclasses
import statistics
import time

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import ConstantVectorSource, TrajectorySource

from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.channels import CHANNEL_NAMES, RA_CHANNELS, SA_CHANNELS
from tegrasp_drake.events.correlation import event_scores_reference
from tegrasp_drake.events.event_matcher import EventMatcherConfig, add_event_matcher
from tegrasp_drake.events.extraction import extract_memorized_events
from tegrasp_drake.events.replay import channels_trajectory
from tegrasp_drake.tactile.sample_block import BLOCK_PERIOD_S
from tegrasp_drake.tactile.sampling import rate_groups
from tegrasp_drake.tactile.sliding_window import SLACK_FRACTION
from tegrasp_drake.events.streaming_correlation import StreamingCorrelator
from tegrasp_drake.events.transitions import NO_EVENT
from tegrasp_drake.events.synthetic import (SyntheticGraspConfig, SyntheticSensorsConfig,
                                             synthetic_grasp)
from tegrasp_drake.tactile.window_normalizer import WindowNormalizer, WindowNormalizerConfig

RA_RATE_HZ = 1000.0
WINDOW_S = 0.5
_LIVE = SyntheticGraspConfig(sensors=SyntheticSensorsConfig(sa_noise_n=0.05, ra_noise=0.2, seed=1))


def _memorized_events(sa_rate_hz: float):
    ideal = synthetic_grasp(SyntheticGraspConfig(), sa_rate_hz=sa_rate_hz)
    return extract_memorized_events(ideal, object_name="benchmark", sa_rate_hz=sa_rate_hz,
                                    ra_rate_hz=RA_RATE_HZ, package_versions={})


def _templates(events, channels) -> np.ndarray:
    """The reach_load windows of `channels` (indices into CHANNEL_NAMES)."""
    return np.array([events["reach_load"].channel(CHANNEL_NAMES[c]) for c in channels])


def _group_samples(trial, channels) -> np.ndarray:
    """The trial's samples of `channels`: (samples, channels)."""
    return np.hstack([trial.sa, trial.ra]) if len(channels) == 4 else (
        trial.sa if channels == SA_CHANNELS else trial.ra)


def _median_us(measure, repeats: int) -> float:
    """Median over repeats of measure(), which returns seconds per tick."""
    return 1e6 * statistics.median(measure() for _ in range(repeats))


def _core_tick(sa_rate_hz: float, ticks: int, repeats: int) -> float:
    """Streaming core, mean seconds per 1 kHz tick (every group pushed at its rate)."""
    events = _memorized_events(sa_rate_hz)
    live = synthetic_grasp(_LIVE, sa_rate_hz=sa_rate_hz)
    groups = rate_groups(sa_rate_hz=sa_rate_hz, ra_rate_hz=RA_RATE_HZ, window_s=WINDOW_S)
    cores = []
    for group in groups:
        correlator = StreamingCorrelator(
            [_templates(events, group.channels)], min_contrast=0.25,
            slack=max(1, int(group.window_length * SLACK_FRACTION)))
        every = int(round(RA_RATE_HZ / group.rate_hz))
        channels = _group_samples(live, group.channels)
        state = correlator.initial_state()
        for samples in channels[:group.window_length]:  # fill the window
            correlator.push(state, samples, 0)
        cores.append((correlator, state, every, channels[group.window_length:]))

    def measure():
        start = time.perf_counter()
        for tick in range(ticks):
            for correlator, state, every, channels in cores:
                if tick % every == 0:
                    correlator.push(state, channels[(tick // every) % len(channels)], 0)
        return (time.perf_counter() - start) / ticks
    return _median_us(measure, repeats)


def _reference_tick(sa_rate_hz: float, repeats: int) -> float:
    """numpy.correlate scoring of the four full windows, seconds per evaluation."""
    events = _memorized_events(sa_rate_hz)
    event = events["reach_load"]
    templates = list(event.sa) + list(event.ra)
    rng = np.random.default_rng(0)
    live = [rng.random(len(y)) for y in templates]

    def measure():
        start = time.perf_counter()
        for _ in range(50):
            event_scores_reference(live, templates, 0.25)
        return (time.perf_counter() - start) / 50
    return _median_us(measure, repeats)


def _fft_rebuild(repeats: int) -> float:
    """An RA push that recomputes the correlations exactly (by FFT), seconds."""
    events = _memorized_events(100.0)
    length = int(WINDOW_S * RA_RATE_HZ)
    correlator = StreamingCorrelator(
        [_templates(events, RA_CHANNELS)] * 2, min_contrast=0.25,
        slack=max(1, int(length * SLACK_FRACTION)))
    state = correlator.initial_state()
    rng = np.random.default_rng(0)
    for _ in range(length):  # fill the window: scores (and rebuilds) start when it is full
        correlator.push(state, rng.random(2), NO_EVENT)

    def measure():
        start = time.perf_counter()
        for i in range(50):
            correlator.push(state, rng.random(2), i % 2)  # alternating events: rebuilds
        return (time.perf_counter() - start) / 50
    return _median_us(measure, repeats)


class _InputReader(LeafSystem):
    """A 1 kHz update that only reads its input: the cost any Python LeafSystem pays.

    .. pydrake_system::

        name: _InputReader
        input_ports:
        - channels

    Ports:
        channels: [sa_left, sa_right, ra_left, ra_right] (N, N, m/s^2, m/s^2), copied into
            discrete state each tick; there is no output.
    """

    def __init__(self):
        super().__init__()
        self._input = self.DeclareVectorInputPort("channels", 4)
        self._state = self.DeclareDiscreteState(4)
        self.DeclarePeriodicDiscreteUpdateEvent(1.0 / RA_RATE_HZ, 0.0, self._read)

    def _read(self, context, discrete_state):
        discrete_state.get_mutable_vector(self._state).SetFromVector(self._input.Eval(context))


def _fed_by_channels(make_system):
    """add_system for _simulated_tick: make_system() with its `channels` input connected."""
    def add_system(builder, channels):
        system = builder.AddSystem(make_system())
        builder.Connect(channels, system.GetInputPort("channels"))
        return system
    return add_system


def _simulated_tick(add_system, sa_rate_hz: float, seconds: float, repeats: int) -> float:
    """Wall seconds per 1 kHz tick of TrajectorySource -> the systems that
    add_system(builder, channels port) adds, after a full window; the system it returns gets
    event 0 on its `expected_event` input, if it has one."""
    live = synthetic_grasp(_LIVE, sa_rate_hz=sa_rate_hz)
    builder = DiagramBuilder()
    source = builder.AddSystem(TrajectorySource(channels_trajectory(live)))
    system = add_system(builder, source.get_output_port())
    if system.HasInputPort("expected_event"):
        expected = builder.AddSystem(ConstantVectorSource([0.0]))
        builder.Connect(expected.get_output_port(), system.GetInputPort("expected_event"))
    simulator = Simulator(builder.Build())

    def measure():
        simulator.get_mutable_context().SetTime(0.0)
        simulator.Initialize()
        simulator.AdvanceTo(WINDOW_S)
        start = time.perf_counter()
        simulator.AdvanceTo(WINDOW_S + seconds)
        return (time.perf_counter() - start) / (seconds * RA_RATE_HZ)
    return _median_us(measure, repeats)


def run_matcher_benchmark(*, repeats: int = 5, ticks: int = 2000) -> dict[str, float]:
    """Median microseconds per control tick; see the module docstring for each figure."""
    seconds = ticks / RA_RATE_HZ
    results = {}
    for sa_rate_hz, label in ((100.0, "sa100"), (1000.0, "sa1k")):
        events = _memorized_events(sa_rate_hz)
        config = EventMatcherConfig(sa_rate_hz=sa_rate_hz, ra_rate_hz=RA_RATE_HZ)
        results[f"core_tick_{label}_us"] = _core_tick(sa_rate_hz, ticks, repeats)
        results[f"reference_tick_{label}_us"] = _reference_tick(sa_rate_hz, repeats)
        for name, block_s in (("system", 0.0), ("system_blocks", BLOCK_PERIOD_S)):
            results[f"{name}_tick_{label}_us"] = _simulated_tick(
                lambda builder, channels, block_s=block_s: add_event_matcher(
                    builder, events, dataclasses.replace(config, block_s=block_s),
                    channels=channels),
                sa_rate_hz, seconds, repeats)
    results["fft_rebuild_ra_us"] = _fft_rebuild(repeats)
    results["framework_tick_us"] = _simulated_tick(
        _fed_by_channels(_InputReader), 100.0, seconds, repeats)
    results["window_normalizer_tick_us"] = _simulated_tick(
        _fed_by_channels(lambda: WindowNormalizer(WindowNormalizerConfig())), 100.0, seconds,
        repeats)
    return results


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=integer_option, default=7)
    parser.add_argument("--ticks", type=integer_option, default=2000)
    args = parser.parse_args(argv)
    for name, value in run_matcher_benchmark(repeats=args.repeats, ticks=args.ticks).items():
        print(f"{name:28s} {value:8.1f} us")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
