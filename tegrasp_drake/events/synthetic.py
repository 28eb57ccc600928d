"""Synthetic tactile channels of a grasp, shaped like the simulated ones, for tests.
SA per finger [N]: contact, load, a dip at table touch, unload, as smooth steps. RA per
finger [m/s^2]: ring-downs at contact, lift-off and table touch plus the lift's motion.
Noise is Gaussian on SA and on each RA axis before the magnitude (a positive floor, as |a|)."""

import dataclasses

import numpy as np

from tegrasp_drake.events.extraction import TactileTrial


@dataclasses.dataclass(frozen=True)
class SyntheticSignalsConfig:
    """The grasp's signals: forces [N], accelerations and RA bursts [m/s^2]."""
    touch_force_n: float = 0.8  # the light touch at first contact
    grip_force_n: float = 4.0  # the grip, reached while loading
    place_dip: float = 0.08  # fraction of the grip lost at the table touch, back in 0.15 s
    lift_acceleration: float = 1.5  # peak of the lift motion's |a|
    lift_off_burst: float = 4.0  # RA ring-down peaks: at lift-off,
    contact_burst: float = 20.0  # at first contact,
    place_burst: float = 25.0  # at the table touch
    burst_decay_s: float = 0.015  # the ring-downs' time constant [s]
    burst_frequency_hz: float = 180.0  # and their ringing [Hz]


@dataclasses.dataclass(frozen=True)
class SyntheticSensorsConfig:
    """How the signals are read: delays [s], scales, white noise and its seed."""
    right_delay_s: float = 0.0  # the right finger's events come this much later
    ra_delay_s: float = 0.0  # RA events come this much later than SA events
    sa_scale: float = 1.0
    ra_scale: float = 1.0
    sa_noise_n: float = 0.0  # standard deviation [N]
    ra_noise: float = 0.0  # standard deviation per axis [m/s^2]
    seed: int = 0


@dataclasses.dataclass(frozen=True)
class SyntheticGraspConfig:
    """The timing of a synthetic grasp [s], its signals and how they are read."""
    duration_s: float = 4.0
    contact_s: float = 0.8  # first contact (reach_load)
    contact_rise_s: float = 0.12
    load_delay_s: float = 0.3  # contact to the start of loading
    load_s: float = 0.4  # loading time: the grip rises to signals.grip_force_n
    lift_delay_s: float = 0.1  # grip reached to the start of the lift motion (load_lift)
    lift_motion_s: float = 0.5
    lift_off_delay_s: float = 0.15  # start of the lift motion to lift-off (lift_hold)
    place_s: float = 3.0  # table touch (place_unload)
    unload_delay_s: float = 0.3
    unload_s: float = 0.2
    signals: SyntheticSignalsConfig = SyntheticSignalsConfig()
    sensors: SyntheticSensorsConfig = SyntheticSensorsConfig()

    def transition_times(self) -> dict[str, float]:
        """Times of the physical events of the transitions (left finger, SA)."""
        lift_start = self.contact_s + self.load_delay_s + self.load_s + self.lift_delay_s
        return {
            "reach_load": self.contact_s,
            "load_lift": lift_start,
            "lift_hold": lift_start + self.lift_off_delay_s,
            "place_unload": self.place_s,
        }


def _smoothstep(t: np.ndarray, start: float, duration: float) -> np.ndarray:
    u = np.clip((t - start) / duration, 0.0, 1.0)
    return u * u * (3.0 - 2.0 * u)


def _ring_down(t: np.ndarray, start: float, peak: float,
               signals: SyntheticSignalsConfig) -> np.ndarray:
    dt = t - start
    after = dt >= 0.0
    envelope = np.exp(-np.where(after, dt, 0.0) / signals.burst_decay_s)
    ringing = np.abs(np.sin(2.0 * np.pi * signals.burst_frequency_hz * dt + 0.5 * np.pi))
    return np.where(after, peak * envelope * ringing, 0.0)


def synthetic_sa(t: np.ndarray, config: SyntheticGraspConfig, delay_s: float = 0.0):
    """Noise-free SA channel [N] of one finger at times t [s]."""
    c, s = config, config.signals
    events = {name: time + delay_s for name, time in c.transition_times().items()}
    load_start = events["reach_load"] + c.load_delay_s
    force = (s.touch_force_n * _smoothstep(t, events["reach_load"], c.contact_rise_s)
             + (s.grip_force_n - s.touch_force_n) * _smoothstep(t, load_start, c.load_s))
    dip = s.place_dip * s.grip_force_n * (
        _smoothstep(t, events["place_unload"], 0.03)
        - _smoothstep(t, events["place_unload"] + 0.03, 0.15))
    release = 1.0 - _smoothstep(t, events["place_unload"] + c.unload_delay_s, c.unload_s)
    return c.sensors.sa_scale * (force - dip) * release


def synthetic_ra(t: np.ndarray, config: SyntheticGraspConfig, delay_s: float = 0.0):
    """Noise-free RA channel [m/s^2] of one finger at times t [s]."""
    c, s = config, config.signals
    events = {name: time + delay_s for name, time in c.transition_times().items()}
    lift_start = events["load_lift"]
    phase = np.clip((t - lift_start) / c.lift_motion_s, 0.0, 1.0)
    lift = s.lift_acceleration * np.abs(np.sin(2.0 * np.pi * phase))
    magnitude = (lift + _ring_down(t, events["reach_load"], s.contact_burst, s)
                 + _ring_down(t, events["lift_hold"], s.lift_off_burst, s)
                 + _ring_down(t, events["place_unload"], s.place_burst, s))
    return c.sensors.ra_scale * magnitude


def synthetic_grasp(config: SyntheticGraspConfig = SyntheticGraspConfig(), *,
                    sa_rate_hz: float = 100.0, ra_rate_hz: float = 1000.0) -> TactileTrial:
    """A grasp's channels sampled at the given rates from t = 0, with sensor noise."""
    sensors = config.sensors
    rng = np.random.default_rng(sensors.seed)
    t_sa = np.arange(int(round(config.duration_s * sa_rate_hz)) + 1) / sa_rate_hz
    t_ra = np.arange(int(round(config.duration_s * ra_rate_hz)) + 1) / ra_rate_hz
    sa = np.stack([synthetic_sa(t_sa, config, delay) for delay in
                   (0.0, sensors.right_delay_s)], axis=1)
    sa = sa + sensors.sa_noise_n * rng.standard_normal(sa.shape)
    ra_clean = np.stack([synthetic_ra(t_ra, config, sensors.ra_delay_s + delay) for delay in
                         (0.0, sensors.right_delay_s)], axis=1)
    noise = sensors.ra_noise * rng.standard_normal((3,) + ra_clean.shape)
    ra = np.sqrt((ra_clean + noise[0]) ** 2 + noise[1] ** 2 + noise[2] ** 2)
    return TactileTrial(t_sa=t_sa, sa=sa, t_ra=t_ra, ra=ra,
                        transition_times=config.transition_times())
