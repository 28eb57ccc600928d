"""WindowNormalizer through its ports."""

import numpy as np
import pytest
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, TrajectorySource

from tegrasp_drake.tactile.max_normalization import normalize_by_max
from tegrasp_drake.events.replay import channels_trajectory
from tegrasp_drake.events.synthetic import (SyntheticGraspConfig, SyntheticSensorsConfig,
                                             synthetic_grasp)
from tegrasp_drake.tactile.window_normalizer import WindowNormalizer, WindowNormalizerConfig

NOISY_GRASP = SyntheticGraspConfig(sensors=SyntheticSensorsConfig(sa_noise_n=0.05, ra_noise=0.2,
                                                                 seed=4))


def simulate(source, config, t_end):
    builder = DiagramBuilder()
    source = builder.AddSystem(source)
    normalizer = builder.AddSystem(WindowNormalizer(config))
    builder.Connect(source.get_output_port(), normalizer.GetInputPort("channels"))
    simulator = Simulator(builder.Build())
    simulator.AdvanceTo(t_end)
    return normalizer, normalizer.GetMyContextFromRoot(simulator.get_context())


def expected_window(trajectory, rows, rate_hz, length, t_end):
    """The trajectory at the last `length` ticks of `rate_hz` before t_end, normalised."""
    ticks = (np.floor(t_end * rate_hz) - np.arange(length)[::-1]) / rate_hz
    samples = np.array([trajectory.value(t)[rows, 0] for t in ticks]).T
    return normalize_by_max(samples).ravel()


def test_ports_have_stable_names_and_sizes():
    normalizer = WindowNormalizer()
    assert normalizer.get_input_port(0).get_name() == "channels"
    assert normalizer.get_input_port(0).size() == 4
    assert normalizer.GetOutputPort("sa_window").size() == 2 * 50
    assert normalizer.GetOutputPort("ra_window").size() == 2 * 500


@pytest.mark.parametrize("sa_rate_hz", [100.0, 1000.0])
def test_windows_hold_the_last_half_second_normalised(sa_rate_hz):
    trajectory = channels_trajectory(synthetic_grasp(NOISY_GRASP, sa_rate_hz=sa_rate_hz))
    config = WindowNormalizerConfig(sa_rate_hz=sa_rate_hz)
    t_end = 1.1375  # 0.3375 s after first contact, between ticks
    normalizer, context = simulate(TrajectorySource(trajectory), config, t_end)
    sa_length = round(0.5 * sa_rate_hz)
    np.testing.assert_allclose(
        normalizer.GetOutputPort("sa_window").Eval(context),
        expected_window(trajectory, [0, 1], sa_rate_hz, sa_length, t_end), atol=1e-12)
    np.testing.assert_allclose(
        normalizer.GetOutputPort("ra_window").Eval(context),
        expected_window(trajectory, [2, 3], 1000.0, 500, t_end), atol=1e-12)


def test_a_partly_filled_window_is_zero_before_the_start():
    normalizer, context = simulate(ConstantVectorSource([2.0, 4.0, 1.0, 1.0]),
                                   WindowNormalizerConfig(), 0.2005)
    sa = normalizer.GetOutputPort("sa_window").Eval(context).reshape(2, 50)
    np.testing.assert_array_equal(sa[:, :29], 0.0)  # ticks at 0, 0.01, ..., 0.2: 21 samples
    np.testing.assert_array_equal(sa[:, 29:], 1.0)


def test_an_all_zero_input_gives_zero_windows_without_nan():
    normalizer, context = simulate(ConstantVectorSource(np.zeros(4)), WindowNormalizerConfig(),
                                   0.6)
    for port in ("sa_window", "ra_window"):
        np.testing.assert_array_equal(normalizer.GetOutputPort(port).Eval(context), 0.0)


def test_history_lives_in_the_context():
    normalizer, context = simulate(ConstantVectorSource([2.0, 4.0, 1.0, 1.0]),
                                   WindowNormalizerConfig(), 0.6)
    fresh = normalizer.CreateDefaultContext()
    assert np.any(normalizer.GetOutputPort("ra_window").Eval(context) != 0.0)
    np.testing.assert_array_equal(normalizer.GetOutputPort("ra_window").Eval(fresh), 0.0)


@pytest.mark.parametrize("sa_rate_hz, groups", [(100.0, ("sa", "ra")), (1000.0, ("sa_ra",))])
def test_rate_windows_hold_the_windows_it_normalises(sa_rate_hz, groups):
    trajectory = channels_trajectory(synthetic_grasp(NOISY_GRASP, sa_rate_hz=sa_rate_hz))
    config = WindowNormalizerConfig(sa_rate_hz=sa_rate_hz)
    normalizer, context = simulate(TrajectorySource(trajectory), config, 1.1375)
    channels = []  # raw windows in CHANNEL_NAMES order
    for window, name in zip(normalizer.rate_windows, groups, strict=True):
        assert window.group.name == name
        channels += list(window.layout.current(
            context.get_discrete_state(window.state).value()))
    np.testing.assert_array_equal(normalizer.GetOutputPort("sa_window").Eval(context),
                                  normalize_by_max(np.array(channels[:2])).ravel())
    np.testing.assert_array_equal(normalizer.GetOutputPort("ra_window").Eval(context),
                                  normalize_by_max(np.array(channels[2:])).ravel())


def test_a_subclass_state_must_start_with_an_empty_window():
    config = WindowNormalizerConfig()
    size = WindowNormalizer(config).rate_windows[0].layout.size
    for name, state in (("too short", np.zeros(size - 1)), ("not empty", np.ones(size + 3))):
        with pytest.raises(ValueError, match="must start with an empty window"):
            WindowNormalizer(config, window_states={"sa": state, "ra": np.zeros(10_000)})


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_a_non_finite_sample_enters_as_the_channels_previous_one(bad):
    normalizer = WindowNormalizer(WindowNormalizerConfig(sa_rate_hz=1000.0))
    simulator = Simulator(normalizer)
    context = simulator.get_mutable_context()
    port = normalizer.get_input_port(0)
    for time, channels in ((0.0025, [1.0, 2.0, 3.0, 4.0]), (0.0035, [bad, 5.0, 6.0, bad]),
                           (0.0045, [7.0, 8.0, 9.0, 10.0])):
        port.FixValue(context, channels)
        simulator.AdvanceTo(time)  # one tick (1 kHz) per value, the first three at once
    window, = normalizer.rate_windows
    window = window.layout.current(context.get_discrete_state(window.state).value())
    np.testing.assert_array_equal(window[:, -5:].T, [[1, 2, 3, 4]] * 3 + [[1, 5, 6, 4],
                                                                         [7, 8, 9, 10]])
    assert np.all(np.isfinite(normalizer.GetOutputPort("sa_window").Eval(context)))
