"""The grasp controllers' settings, one config class per controller, selected by the YAML
tag of the scenario's `controller` field (`controller.name` is a shorthand). Every number
declares its unit and range on its field; `problem` checks what relates fields. ClassVars
give the name in results, the events folder and the extra time allowed; the rest of a
controller is its entry in controller_registry.py. Imports no Drake (the command line reads it)."""

import dataclasses
import typing
from tegrasp_drake.rig.api_boundary import public_dataclass, register_moved_fields
from tegrasp_drake.rig.event_matching import SCORE_RANGE, EventMatchingConfig
from tegrasp_drake.rig.objects import ENSEMBLE_EVENTS_FOLDER
from tegrasp_drake.rig.ranges import READ_PERIOD, SAMPLE_BLOCK, bounded, distinct_names, within
from tegrasp_drake.rig.unset_fields import unset_when_empty



# RA thresholds in noise sigmas (control/noise_thresholds.py).
_SIGMAS_WHY = "noise alone crosses 5.51 in one trial of a thousand"
_SIGMAS_BELOW = "must be zero (the number alone) or positive [noise sigmas]"


# A timeout of zero would give up before its event could come (the user guide: refused)
TIMEOUT_BELOW = "must be positive [s]: a zero timeout gives up before its event can come"
# An arm move's duration: the hand cannot move in no time (a move too short for the arm to
# follow is refused with the shortest it may take, scenario._check_hand_speeds).
MOVE_BELOW = ("must be positive [s]: the arm cannot move the hand in no time (to leave the "
              "move out, set its 'enabled' false)")

@public_dataclass
@dataclasses.dataclass
class HeuristicTriggerConfig:
    """Hand-set thresholds (Romano et al. 2011, IEEE Trans. Robotics 27(6)), tuned on the box."""
    # Reach-Load: each finger's SA above this [N]
    contact_force_n: float = bounded(1.0, low=0.0, high=50.0, unit="N",
                                     below="must be zero or positive [N]")
    # Load-Lift: each finger's SA above this fraction of the grip
    grip_fraction: float = bounded(0.9, low=0.0, low_open=True, high=1.0)
    # Place-Unload: either RA above this [m/s^2]
    place_ra_mps2: float = bounded(3.0, low=0.0, high=1000.0, unit="m/s^2",
                                   below="must be zero or positive [m/s^2]")
    # ... and above this many RA noise sigmas (0: the number alone)
    place_ra_sigmas: float = bounded(5.51, low=0.0, high=100.0, unit="noise sigmas",
                                     why=_SIGMAS_WHY, below=_SIGMAS_BELOW)


@public_dataclass
@dataclasses.dataclass
class FingerStrikeConfig:
    """The taxel_aware controller's finger-strike sense (control/finger_strike.py): a finger's
    front striking the object in the approach, seen in the joint torques as a force on G.
    Measured figures: docs/controller.md, "Finger strike"."""
    enabled: bool = True
    # force on G over its approach-start value [N]: 2.5x the Reach's 0.81 N, half a strike's 3.9
    force_n: float = bounded(2.0, low=0.0, low_open=True, high=100.0, unit="N",
                             below="must be positive [N]")
    # the wrist force for this long [s]: no single spike, still far inside the 0.13 s before
    # the object moves (a film's onset acts at once: docs/controller.md, "Finger strike")
    sustain_s: float = bounded(0.01, low=0.0, high=1.0, unit="s",
                               below="must be zero or positive [s]")
    # the summed side moment [N m] (left: +) tells the finger above half the smallest strike's
    min_moment_nm: float = bounded(0.05, low=0.0, high=10.0, unit="N m",
                                   below="must be zero or positive [N m]")


_HANDS_THRESHOLDS = "the hand's thresholds for this event"


@public_dataclass
@dataclasses.dataclass
class RegraspConfig:
    """The taxel_aware re-grasp of an object held tilted: put it down and grasp it again."""
    enabled: bool = True
    # held tilted: the contact line turned this far, or the contacts this far apart (half a
    # column)
    tilt_limit_deg: float = bounded(10.0, low=0.0, high=90.0, unit="deg")
    height_mismatch_m: float = bounded(0.0033, low=0.0, high=0.05, unit="m",
                                       below="must be zero or positive [m]")
    # for this long [s] (one tick of noise is not a tilt)
    tilt_sustain_s: float = bounded(0.1, low=0.0, high=1.0, unit="s",
                                    below="must be zero or positive [s]")
    max_regrasps: int = bounded(1, low=0, high=10, below="must be zero or positive")


@public_dataclass
@dataclasses.dataclass
class TaxelAwareConfig:
    """The taxel-aware corrections; a pad row is 6 mm along the approach, a column 6.7 mm."""
    # Re-Reach along the approach when the contact is this far off centre [m]: 2/3 of a row
    centre_tolerance_m: float = bounded(0.004, low=0.0, high=0.05, unit="m",
                                        below="must be zero or positive [m]")
    # at most this far per such Re-Reach [m]: the pad's half length (12 mm) plus a quarter row
    max_approach_shift_m: float = bounded(0.015, low=0.0, high=0.1, unit="m",
                                          below="must be zero or positive [m]")
    # Re-Reaches of either axis: the paper's 2 plus one per axis the taxels add
    max_re_reaches: int = bounded(4, low=0, high=10, below="must be zero or positive")
    # back off this far after a touch in the approach [m], back along the Reach's path: the pad
    # less its palm row, 18 mm, up; on the default path (3 cm in, 9 cm down) it lifts a finger
    # struck on an object's top 19 mm, past the 0.2 mm it sank
    # (docs/controller.md, "Finger strike")
    approach_retreat_m: float = bounded(0.02, low=0.0, high=0.1, unit="m",
                                        below="must be zero or positive [m]")
    # one finger alone within this of the width loads [m]: a Re-Reach would shift < 1/3 row
    one_sided_width_margin_m: float = bounded(0.004, low=0.0, high=0.05, unit="m",
                                              below="must be zero or positive [m]")
    # a first touch on the distal row alone, centroid beyond [m]: the row's 9 mm less 0.5 mm
    beyond_pads_centroid_m: float = bounded(0.0085, low=0.0, high=0.05, unit="m",
                                            below="must be zero or positive [m]")
    regrasp: RegraspConfig = dataclasses.field(default_factory=RegraspConfig)
    # lift at the Load timeout only with each pad's sum above this [N] (load_timeout_both_pads):
    # the number is contact_force_n plus ideal force taxels' margin; sa_noise_floor raises it
    # to contact_force_n in force plus the loaded noise's (noise_thresholds.held_margin)
    lift_pad_sum_n: float = bounded(0.5, low=0.0, high=50.0, unit="N",
                                    below="must be zero or positive [N]")
    # Eq. 3 [SA, RA] per ensemble event; empty: the hand's (analysis/choose_ensemble_thresholds.py)
    reach_load_thresholds: list[float] = unset_when_empty(
        _HANDS_THRESHOLDS, bounded(default_factory=list, **SCORE_RANGE))
    load_lift_thresholds: list[float] = unset_when_empty(
        _HANDS_THRESHOLDS, bounded(default_factory=list, **SCORE_RANGE))
    place_unload_thresholds: list[float] = unset_when_empty(
        _HANDS_THRESHOLDS, bounded(default_factory=list, **SCORE_RANGE))
    finger_strike: FingerStrikeConfig = dataclasses.field(default_factory=FingerStrikeConfig)
    # a close's first RA onset is one film above this [m/s^2] (ra_onset.py): the number is
    # Avoid's hit (avoid.hit_ra_mps2); ra_onset_sigmas raises it to that many of the RA noise
    # at rest (noise_thresholds.resolve_noise_thresholds); 0 disables the rule
    ra_onset_mps2: float = bounded(3.0, low=0.0, high=1000.0, unit="m/s^2",
                                   below="must be zero or positive [m/s^2]")
    # the raw magnitude's rule (docs/model.md, "Thresholds in noise sigmas")
    ra_onset_sigmas: float = bounded(5.51, low=0.0, high=100.0, unit="noise sigmas",
                                     why=_SIGMAS_WHY, below=_SIGMAS_BELOW)

    def problem(self) -> tuple[str, str, object] | None:
        """(field, must, value) of the first threshold pair neither [] nor [SA, RA]; else None."""
        for name in ("reach_load_thresholds", "load_lift_thresholds",
                     "place_unload_thresholds"):
            pair = getattr(self, name)
            if len(pair) not in (0, 2):
                return (name, "must be [] (the hand's chosen thresholds) or [SA, RA], each in "
                        "[-1, 1] (Eq. 3 scores)", pair)
        return None

    def event_thresholds(self, chosen: dict | None = None) -> dict[str, tuple[float, float]]:
        """{transition: (SA, RA)}: the ones set here, else `chosen` (the hand's)."""
        chosen = chosen or {}
        given = {"reach_load": self.reach_load_thresholds,
                 "load_lift": self.load_lift_thresholds,
                 "place_unload": self.place_unload_thresholds}
        return {t: tuple(pair) if pair else tuple(chosen[t]) for t, pair in given.items()}


@public_dataclass
@dataclasses.dataclass
class ReReachConfig:
    """Re-Reach (Sec. III-C): open, shift toward the touching finger, close again."""
    enabled: bool = True
    one_sided_contact_s: float = bounded(0.1, low=0.0, high=10.0, unit="s",
                                         below="must be zero or positive [s]")
    reach_event_timeout_s: float = bounded(2.0, low=0.0, low_open=True, high=60.0,
                                           unit="s", below=TIMEOUT_BELOW)
    max_re_reaches: int = bounded(2, low=0, high=10, below="must be zero or positive")
    # time to shift the open gripper sideways [s]
    move_s: float = bounded(0.8, low=0.0, low_open=True, high=10.0, unit="s",
                            below=MOVE_BELOW)
    # the gripper counts as open beyond this opening [m]
    opened_m: float = bounded(0.080, low=0.0, high=0.085, unit="m",
                              why="the 2F-85's 85 mm stroke",
                              below="must be zero or positive [m]")


@public_dataclass
@dataclasses.dataclass
class LiftLoadConfig:
    """Lift-Load (Sec. III-C): the slip band above slip_vibration_mps2 for slip_s in Lift:
    Load at force_factor times the grip, lift again at grip_fraction of it."""
    enabled: bool = True
    # a lift reads <= 0.68 m/s^2, sliding pads 1.9-5.1 (docs/model.md, "Slip: the texture")
    slip_vibration_mps2: float = bounded(1.0, low=0.0, high=1000.0, unit="m/s^2",
                                         below="must be zero or positive [m/s^2]")
    # ... and above this many sigmas of the band's noise (0: the number alone)
    slip_vibration_sigmas: float = bounded(2.34, low=0.0, high=100.0, unit="noise sigmas",
                                           why=_SIGMAS_WHY, below=_SIGMAS_BELOW)
    # texture slip at a lift's 40 mm/s rings at 80 Hz, the squeeze below 10 Hz
    slip_band_hz: float = bounded(80.0, low=0.0, low_open=True, high=10_000.0, unit="Hz")
    slip_window_s: float = bounded(0.01, low=0.0, low_open=True, high=1.0, unit="s",
                                   below="must be positive [s]: the slip band's window")
    slip_s: float = bounded(0.02, low=0.0, high=1.0, unit="s",
                            below="must be zero or positive [s]")
    force_factor: float = bounded(2.0, low=1.0, high=10.0, below="must be at least 1")
    max_lift_loads: int = bounded(2, low=0, high=10, below="must be zero or positive")
    # the raised grip's cap; at least grasp.grip_force (LoadScenario checks), else a slip
    # would loosen the grip
    max_grip_force_n: float = bounded(235.0, low=20.0, high=235.0, unit="N",
                                      why="the 2F-85 grips with 20 to 235 N, Robotiq 2F-85 "
                                          "manual")
    # a 50 N request reads 44.9 N of SA on the box (the patch spreads past the taxels)
    grip_fraction: float = bounded(0.8, low=0.0, low_open=True, high=1.0)
    # and RA quiet (the slip has stopped) before lifting again [s]
    relift_settle_s: float = bounded(0.2, low=0.0, high=10.0, unit="s",
                                     below="must be zero or positive [s]")

    def problem(self, *, ra_rate_hz: float) -> tuple[str, str, object] | None:
        """(field, must, value) when the slip band does not fit RA at ra_rate_hz [Hz]; else None."""
        if self.slip_band_hz >= ra_rate_hz / 2:
            return ("slip_band_hz", "must lie below half the RA rate "
                    f"({ra_rate_hz / 2:g} Hz, vibration.sample_rate_hz / 2): the slip band's "
                    "high-pass runs on the RA samples", self.slip_band_hz)
        return None


@public_dataclass
@dataclasses.dataclass
class AvoidConfig:
    """Avoid (Sec. III-C): in Hold, RA above hit_ra_mps2 over its own level (its mean over
    hit_level_s before) after hit_refractory_s (the lift's stop rings) is a hit; stop sense_s
    to see its push, move distance_m that way over move_s, at most max_avoids times a grasp."""
    enabled: bool = True
    hit_ra_mps2: float = bounded(3.0, low=0.0, high=1000.0, unit="m/s^2",
                                 below="must be zero or positive [m/s^2]")
    # ... and above this many RA noise sigmas (as the slip's)
    hit_ra_sigmas: float = bounded(5.51, low=0.0, high=100.0, unit="noise sigmas",
                                   why=_SIGMAS_WHY, below=_SIGMAS_BELOW)
    hit_refractory_s: float = bounded(0.3, low=0.0, high=10.0, unit="s",
                                      below="must be zero or positive [s]")
    # A hit is a burst above the film's level in Hold, not the level: each film's RA counts
    # from its mean over this long before the tick [s] (0: from zero, the number alone). A
    # grip that creeps makes the film read its force's slope through the amplifier's
    # high-pass, a steady tau dF/dt / m_mode = 3.3 m/s^2 per N/s that noise alone lifts over
    # the number (docs/controller.md, "Corrective actions", Avoid). 0.1 s: 20 ticks, so the
    # mean's own noise is sigma / sqrt(20) (0.16 m/s^2), a creep's level moves by hundredths
    # in it, and it lies in Hold once the 0.3 s refractory time has passed.
    hit_level_s: float = bounded(0.1, low=0.0, high=1.0, unit="s",
                                 below="must be zero (the number alone) or positive [s]")
    sense_s: float = bounded(0.03, low=0.0, high=1.0, unit="s",
                             below="must be zero or positive [s]")
    sa_asymmetry_n: float = bounded(1.0, low=0.0, high=100.0, unit="N",
                                    below="must be zero or positive [N]")
    distance_m: float = bounded(0.05, low=0.0, high=0.3, unit="m",
                                below="must be zero or positive [m]")
    move_s: float = bounded(0.6, low=0.0, low_open=True, high=10.0, unit="s",
                            below=MOVE_BELOW)
    # Avoids in one grasp; a hit past them is not avoided (Hold goes on to Place). Each
    # moves the held object distance_m, so 3 keep it within 0.15 m of where it was lifted,
    # over the table the grasp was planned on, while hits keep coming; the paper's test
    # strikes once a trial.
    max_avoids: int = bounded(3, low=0, high=10, below="must be zero or positive")


@public_dataclass
@dataclasses.dataclass
class PlaceConfig:
    """Place: the object set down on the table, Unload on the Place-Unload event."""
    # without the Place-Unload event, unload anyway this long after the arm stops [s]
    event_timeout_s: float = bounded(1.0, low=0.0, low_open=True, high=60.0,
                                     unit="s", below=TIMEOUT_BELOW)


@public_dataclass
@dataclasses.dataclass
class MemorizedCorrectiveConfig:
    """Corrective events matched by Eq. 3 (docs/controller.md, "Memorized corrective triggers")."""
    # of "hold_avoid", "lift_load" (matches every normal lift: comparison only); []: heuristic
    events: list[str] = distinct_names(items="corrective events")
    # Eq. 3 [SA, RA], chosen on held-out runs: analysis/corrective_thresholds.md
    lift_load_thresholds: list[float] = bounded(default_factory=lambda: [0.45, 0.60],
                                                length=2, **SCORE_RANGE)
    hold_avoid_thresholds: list[float] = bounded(default_factory=lambda: [0.45, 0.40],
                                                 length=2, **SCORE_RANGE)
    # Avoid's SA baseline this long before the match [s]: the 60 ms latency target
    hit_baseline_s: float = bounded(0.06, low=0.0, high=1.0, unit="s",
                                    below="must be zero or positive [s]")
    # armed this long into Hold [s]: hit_refractory_s plus the 0.5 s window (no stop's ring)
    hit_armed_s: float = bounded(0.8, low=0.0, high=10.0, unit="s",
                                 below="must be zero or positive [s]")

    def thresholds(self) -> dict[str, tuple[float, float]]:
        """{corrective transition: (SA, RA)} for the corrective EventMatcher."""
        return {"lift_load": tuple(self.lift_load_thresholds),
                "hold_avoid": tuple(self.hold_avoid_thresholds)}

    def problem(self) -> tuple[str, str, object] | None:
        """(field, must, value) of the first event that is not a corrective event; None if none."""
        from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS  # Drake: on use
        for k, name in enumerate(self.events):
            if name not in CORRECTIVE_TRANSITIONS:
                return (f"events[{k}]", "must name a corrective event "
                        f"({', '.join(CORRECTIVE_TRANSITIONS)})", name)
        return None


@public_dataclass
@dataclasses.dataclass
class GraspControllerConfig:
    """The closed-loop controllers' settings: tick, contact force, a section per correction."""
    # state machine tick [s]
    update_period_s: float = bounded(0.005, low=0.0, low_open=True, high=READ_PERIOD.high, unit="s",
                                     below="must be positive [s]")
    # film samples in blocks of this long [s] (tactile/sample_block.py); 0: per sample
    sensor_block_s: float = within(0.0, SAMPLE_BLOCK)
    # contact of a finger, of a taxel [N] (10x a force taxel's 5 mN noise)
    contact_force_n: float = bounded(0.3, low=0.0, high=50.0, unit="N",
                                     below="must be zero or positive [N]")
    taxel_contact_n: float = bounded(0.05, low=0.0, high=50.0, unit="N",
                                     below="must be zero or positive [N]")
    # Raise each SA threshold to the taxels' noise (control/noise_thresholds.py)
    sa_noise_floor: bool = True
    # Load without the Load-Lift event: give up [s]
    load_event_timeout_s: float = bounded(2.0, low=0.0, low_open=True, high=60.0,
                                          unit="s", below=TIMEOUT_BELOW)
    # Lost object: in Lift, Hold, Avoid or Place, both SA below contact_force_n.
    drop_check_enabled: bool = True
    # object fields the events' object may differ in, e.g. [friction] (a slippery box)
    event_object_may_differ: list[str] = distinct_names(items="object fields")
    re_reach: ReReachConfig = dataclasses.field(default_factory=ReReachConfig)
    lift_load: LiftLoadConfig = dataclasses.field(default_factory=LiftLoadConfig)
    avoid: AvoidConfig = dataclasses.field(default_factory=AvoidConfig)
    place: PlaceConfig = dataclasses.field(default_factory=PlaceConfig)
    memorized_corrective: MemorizedCorrectiveConfig = dataclasses.field(
        default_factory=MemorizedCorrectiveConfig)

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        """(field path, what it must be, its value) of the first setting that does not fit another
        or the RA stream (ra_rate_hz [Hz]; approach ends at approach_s [s]); None when all fit."""
        from tegrasp_drake.rig.objects import DESCRIPTION_FIELDS
        for k, name in enumerate(self.event_object_may_differ):
            if name not in DESCRIPTION_FIELDS:
                return (f"event_object_may_differ[{k}]", "must name a field of the object "
                        f"({', '.join(DESCRIPTION_FIELDS)})", name)
        problem = _block_problem(self.sensor_block_s, ra_rate_hz)
        if problem is not None:
            return problem
        for section, found in (("lift_load", self.lift_load.problem(ra_rate_hz=ra_rate_hz)),
                               ("memorized_corrective", self.memorized_corrective.problem())):
            if found is not None:
                return (f"{section}.{found[0]}",) + found[1:]
        return None


# Settings that moved when the controller's were nested by concern (old field -> its path
# now): assigning an old one is refused naming the new path; scenario/moved_keys.py refuses
# and migrates the old keys of YAML from this table.
MOVED_FIELDS = {
    "re_reach_enabled": "re_reach.enabled",
    "one_sided_contact_s": "re_reach.one_sided_contact_s",
    "reach_event_timeout_s": "re_reach.reach_event_timeout_s",
    "max_re_reaches": "re_reach.max_re_reaches",
    "re_reach_move_s": "re_reach.move_s",
    "opened_m": "re_reach.opened_m",
    "lift_load_enabled": "lift_load.enabled",
    "slip_vibration_mps2": "lift_load.slip_vibration_mps2",
    "slip_vibration_sigmas": "lift_load.slip_vibration_sigmas",
    "slip_band_hz": "lift_load.slip_band_hz",
    "slip_window_s": "lift_load.slip_window_s",
    "slip_s": "lift_load.slip_s",
    "lift_load_force_factor": "lift_load.force_factor",
    "max_lift_loads": "lift_load.max_lift_loads",
    "max_grip_force_n": "lift_load.max_grip_force_n",
    "grip_fraction": "lift_load.grip_fraction",
    "relift_settle_s": "lift_load.relift_settle_s",
    "avoid_enabled": "avoid.enabled",
    "hit_ra_mps2": "avoid.hit_ra_mps2",
    "hit_ra_sigmas": "avoid.hit_ra_sigmas",
    "hit_refractory_s": "avoid.hit_refractory_s",
    "avoid_sense_s": "avoid.sense_s",
    "avoid_sa_asymmetry_n": "avoid.sa_asymmetry_n",
    "avoid_distance_m": "avoid.distance_m",
    "avoid_s": "avoid.move_s",
    "place_event_timeout_s": "place.event_timeout_s",
    "memorized_corrective_events": "memorized_corrective.events",
    "lift_load_event_thresholds": "memorized_corrective.lift_load_thresholds",
    "hold_avoid_event_thresholds": "memorized_corrective.hold_avoid_thresholds",
    "memorized_hit_baseline_s": "memorized_corrective.hit_baseline_s",
    "memorized_hit_armed_s": "memorized_corrective.hit_armed_s",
    "sa_threshold": "matching.sa_threshold",
    "ra_threshold": "matching.ra_threshold",
    "ra_envelope_hz": "matching.ra_envelope_hz",
    "ra_noise_floor_sigmas": "matching.ra_noise_floor_sigmas",
    "ra_noise_quiet_s": "matching.ra_noise_quiet_s",
    "flat_template_needs_flat_window": "matching.flat_template_needs_flat_window",
}
register_moved_fields(GraspControllerConfig, MOVED_FIELDS)
# The taxel_aware re-grasp's settings, nested when the section was full (old field -> path).
TAXEL_AWARE_MOVED_FIELDS = {
    "regrasp_enabled": "regrasp.enabled",
    "tilt_limit_deg": "regrasp.tilt_limit_deg",
    "height_mismatch_m": "regrasp.height_mismatch_m",
    "tilt_sustain_s": "regrasp.tilt_sustain_s",
    "max_regrasps": "regrasp.max_regrasps",
}
register_moved_fields(TaxelAwareConfig, TAXEL_AWARE_MOVED_FIELDS)


def _block_problem(block_s: float, ra_rate_hz: float) -> tuple[str, str, object] | None:
    """sensor_block_s's problem when its blocks miss the RA sample times in floating point."""
    if not (block_s > 0 and ra_rate_hz > 0):
        return None
    from tegrasp_drake.tactile.sample_block import block_samples, block_update_period
    samples = block_samples(ra_rate_hz, block_s)
    try:
        if samples > 1:
            block_update_period(1.0 / ra_rate_hz, samples)
    except ValueError:
        return ("sensor_block_s", f"gives blocks of {samples} samples at "
                f"vibration.sample_rate_hz {ra_rate_hz:g}, which do not fall on the sample "
                "times in floating point; choose a block such as 0.01 or 0.016 s", block_s)
    return None


@dataclasses.dataclass
class EventTriggeredConfig(GraspControllerConfig):
    """A state machine triggered by memorized events matched by Eq. 3."""
    matching: EventMatchingConfig = dataclasses.field(default_factory=EventMatchingConfig)

    def event_thresholds(self, chosen: dict | None = None) -> dict[str, tuple[float, float]]:
        """{transition: (SA, RA)} thresholds that replace matching's (none)."""
        return {}

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        found = super().problem(ra_rate_hz=ra_rate_hz, approach_s=approach_s)
        if found is None:
            found = self.matching.problem(ra_rate_hz=ra_rate_hz, approach_s=approach_s)
            if found is not None:
                found = (f"matching.{found[0]}",) + found[1:]
        return found


@public_dataclass
@dataclasses.dataclass
class MemorizedControllerConfig(EventTriggeredConfig):
    """The paper's algorithm: transitions triggered by the memorized tactile events."""
    name: typing.ClassVar[str] = "memorized"
    # The events folder it reads: the events search path's folders themselves.
    events_folder: typing.ClassVar[str | None] = ""
    extra_time_s: typing.ClassVar[float] = 0.0


@public_dataclass
@dataclasses.dataclass
class HeuristicControllerConfig(GraspControllerConfig):
    """Hand-set transition thresholds in the style of Romano et al. 2011."""
    name: typing.ClassVar[str] = "heuristic"
    events_folder: typing.ClassVar[str | None] = None  # reads no memorized events
    extra_time_s: typing.ClassVar[float] = 0.0
    heuristic: HeuristicTriggerConfig = dataclasses.field(default_factory=HeuristicTriggerConfig)


@public_dataclass
@dataclasses.dataclass
class OpenLoopControllerConfig:
    """The ideal scripted grasp (the scenario's `grasp` section); no settings of its own."""
    name: typing.ClassVar[str] = "open_loop"
    events_folder: typing.ClassVar[str | None] = None
    extra_time_s: typing.ClassVar[float] = 0.0
    # it matches no memorized corrective event
    memorized_corrective: typing.ClassVar[MemorizedCorrectiveConfig] = MemorizedCorrectiveConfig()


@public_dataclass
@dataclasses.dataclass
class TaxelAwareControllerConfig(EventTriggeredConfig):
    """The paper's algorithm with taxel-array corrections and ensemble events."""
    name: typing.ClassVar[str] = "taxel_aware"
    events_folder: typing.ClassVar[str | None] = ENSEMBLE_EVENTS_FOLDER
    # two more Re-Reaches (about 2.5 s each) and a re-grasp (about 9 s), rounded up [s]
    extra_time_s: typing.ClassVar[float] = 15.0
    taxel_aware: TaxelAwareConfig = dataclasses.field(default_factory=TaxelAwareConfig)

    def event_thresholds(self, chosen: dict | None = None) -> dict[str, tuple[float, float]]:
        """{transition: (SA, RA)}: TaxelAwareConfig's, else `chosen`."""
        return self.taxel_aware.event_thresholds(chosen)

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        found = super().problem(ra_rate_hz=ra_rate_hz, approach_s=approach_s)
        if found is None:
            found = self.taxel_aware.problem()
            if found is not None:
                found = (f"taxel_aware.{found[0]}",) + found[1:]
        return found
