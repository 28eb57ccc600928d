"""The grasp controllers' settings, one config class per controller, selected by the YAML
tag of the scenario's `controller` field as `station:` selects its station:

    controller: !MemorizedControllerConfig {}      # the default: the paper's algorithm
    controller: !HeuristicControllerConfig {heuristic: {contact_force_n: 1.0}}
    controller: !OpenLoopControllerConfig {}       # the ideal scripted grasp
    controller: !TaxelAwareControllerConfig {taxel_aware: {max_re_reaches: 4}}

`controller: {name: heuristic, ...}` and `--set controller.name=heuristic` are shorthands
for the tag. The closed-loop controllers share the state machine's settings
(GraspControllerConfig: the tick and the contact force, and a section per corrective action
of Sec. III-C, e.g. `controller.avoid.hit_ra_mps2`) and add their own (`matching`, the
Eq. 3 settings of those that read memorized events); every number declares its unit and
range on its field, and each class checks what relates its fields (`problem`). A class's
ClassVars say its name in results and sweeps, the events folder it reads and the extra time
its corrections may take. Everything else about a controller is its entry in
controller_registry.py.

This module imports no Drake: the registry, which the command line reads, imports it.
"""

import dataclasses
import typing
from tegrasp_drake.rig.api_boundary import public_dataclass
from tegrasp_drake.rig.event_matching import SCORE_RANGE, EventMatchingConfig
from tegrasp_drake.rig.ranges import bounded


# The folder of an events folder that holds the memorized corrective events
# (MemorizedCorrectiveConfig).
CORRECTIVE_EVENTS_FOLDER = "corrective"

# The thresholds in sigmas of the RA noise (control/noise_thresholds.py): noise alone crosses
# 5.51 sigmas (a raw magnitude) or 2.34 (the slip band's RMS) in one trial of a thousand;
# a hundred is far past any noise.
_SIGMAS_WHY = "noise alone crosses 5.51 in one trial of a thousand"
_SIGMAS_BELOW = "must be zero (the number alone) or positive [noise sigmas]"


@dataclasses.dataclass
class HeuristicTriggerConfig:
    """The hand-set transition thresholds of the heuristic controller, in the style of
    Romano et al. 2011 (IEEE Trans. Robotics 27(6), "Human-inspired robotic grasp control with tactile sensing"): tuned once on the box at its expected position and
    left alone."""
    # Reach-Load: each finger's SA above this [N]
    contact_force_n: float = bounded(1.0, low=0.0, high=50.0, unit="N",
                                     below="must be zero or positive [N]")
    # Load-Lift: each finger's SA above this fraction of the grip
    grip_fraction: float = bounded(0.9, low=0.0, low_open=True, high=1.0)
    # Place-Unload: either RA above this [m/s^2]
    place_ra_mps2: float = bounded(3.0, low=0.0, high=1000.0, unit="m/s^2",
                                   below="must be zero or positive [m/s^2]")
    # ... and above this many sigmas of the RA noise (control/noise_thresholds.py: noise
    # alone crosses it in at most one trial of a thousand); 0: the number alone.
    place_ra_sigmas: float = bounded(5.51, low=0.0, high=100.0, unit="noise sigmas",
                                     why=_SIGMAS_WHY, below=_SIGMAS_BELOW)


@dataclasses.dataclass
class FingerStrikeConfig:
    """The taxel_aware controller's finger-strike sense (control/finger_strike.py): a
    finger's front striking the object during the approach, seen in the arm's joint
    torques (the station's arm.torque_measured) as a force on the grasp frame G.

    Measured (analysis/measure_finger_strike.py: open-loop Reaches of the 45 mm box at
    +-2.5 cm along the stroke, yaw 12 deg, and the thick cylinder at -1.5/-2.5 cm, yaw
    8 deg; the simulated torque is the plant's net actuation, noise-free): the Reach's own
    force on G (accelerating the arm, tracked by the joints' PD) peaks at 0.81 N mid-reach;
    a strike reads 1.4-12 N 1 ms after the finger meets the object and at least 3.9-5.8 N
    from 2 to 40 ms (growing while the arm presses), and the object first moves 1 mm
    0.13-0.15 s after contact."""
    enabled: bool = True
    # A strike: the force on G, less its value at the approach's start, above this [N]:
    # 2.5x the Reach's own 0.81 N, half the 3.9 N a strike holds from 2 ms on. On the
    # JACO2 the port must carry gravity-free joint torques (the baseline removes only a
    # constant); no published figure of its torque sensors' noise was found: re-measure
    # it there.
    force_n: float = bounded(2.0, low=0.0, low_open=True, high=100.0, unit="N",
                             below="must be positive [N]")
    # For this long [s] (three 5 ms ticks): a single sample's spike is not a strike, and
    # the stop comes 10-15 ms after contact, far inside the 0.13 s before the object moves.
    sustain_s: float = bounded(0.01, low=0.0, high=1.0, unit="s",
                               below="must be zero or positive [s]")
    # Which finger struck: the sign of the moments about the approach axis (world x) and
    # the vertical (world z) at G, added, summed over the strike's ticks [N m] (left
    # finger, on +y: positive). A push against the approach at +-42 mm along the stroke
    # turns G about z, and the struck object pressing the finger up or down turns it about
    # x. Measured every 2 ms over the strikes' first 40 ms: +0.11 to +2.3 N m (left),
    # -0.11 to -3.1 (right), never the wrong sign; each moment alone reversed for 1-3 ms
    # after impact. Below min_moment_nm in size (half the smallest strike sample), or when
    # one pad touches, the touching pad says the side.
    min_moment_nm: float = bounded(0.05, low=0.0, high=10.0, unit="N m",
                                   below="must be zero or positive [N m]")


@dataclasses.dataclass
class TaxelAwareConfig:
    """The taxel-aware corrections (control/taxel_aware). Lengths in the pad's terms: a row
    is 6 mm along the approach axis, a column 6.7 mm high."""
    # Re-Reach normal to the palm when the contact's centroid sits more than this far from
    # the pads' centres along the approach axis [m]: two thirds of a row (a line contact
    # between two rows interpolates; within this it presses the two middle rows).
    centre_tolerance_m: float = bounded(0.004, low=0.0, high=0.05, unit="m",
                                        below="must be zero or positive [m]")
    # At most this far per Re-Reach along the approach axis [m]: the pad's half length
    # (12 mm) plus a quarter row; a contact on the edge row only says "at least this far".
    max_approach_shift_m: float = bounded(0.015, low=0.0, high=0.1, unit="m",
                                          below="must be zero or positive [m]")
    # Re-Reaches of either direction, repeated until centred, at most this many (the
    # paper's 2 plus one for each axis the taxels add).
    max_re_reaches: int = bounded(4, low=0, high=10, below="must be zero or positive")
    # A pad touching during the approach: back off this far along the approach axis while
    # shifting along the stroke [m], then approach again; a sideways shift while still
    # pressing would drag the object over. The pad's length less its palm row (18 mm),
    # rounded up: wherever along the pad the object touched, the pad backs off it.
    approach_retreat_m: float = bounded(0.02, low=0.0, high=0.1, unit="m",
                                        below="must be zero or positive [m]")
    # One finger alone touches while the gripper has closed to within this of the
    # object's width [m]: the object is between the fingers, the other finger's contact is
    # off its pad or light; Load (the squeeze brings the second pad on) instead of another
    # Re-Reach that would shift by less than a third of a taxel row (a stall).
    one_sided_width_margin_m: float = bounded(0.004, low=0.0, high=0.05, unit="m",
                                              below="must be zero or positive [m]")
    # The first touch of a close lies on a pad's distal row alone when its contact centroid
    # along the approach axis is at least this far toward the fingertips [m]: the distal
    # row's centre (9 mm) less 0.5 mm. A row-2 taxel above taxel_contact_n (0.05 N) beside
    # a first touch of 0.15 N (the measured edge touch) pulls the centroid to 7.5 mm; the
    # object then lies on the pad's face, not beyond its edge. With the close's push past
    # the tipping limit, the close stops and Re-Reaches forward
    # (taxel_aware/beyond_pads.py).
    beyond_pads_centroid_m: float = bounded(0.0085, low=0.0, high=0.05, unit="m",
                                            below="must be zero or positive [m]")
    # Held tilted: re-grasp (put it down, open, close again, lift) when in Hold the
    # contact line on a pad turns more than tilt_limit_deg, or the two pads' contact
    # heights differ by more than height_mismatch_m [m] (half a column: the contacts
    # lie in different columns).
    regrasp_enabled: bool = True
    tilt_limit_deg: float = bounded(10.0, low=0.0, high=90.0, unit="deg")
    height_mismatch_m: float = bounded(0.0033, low=0.0, high=0.05, unit="m",
                                       below="must be zero or positive [m]")
    # for this long [s] (one tick of noise is not a tilt)
    tilt_sustain_s: float = bounded(0.1, low=0.0, high=1.0, unit="s",
                                    below="must be zero or positive [s]")
    max_regrasps: int = bounded(1, low=0, high=10, below="must be zero or positive")
    # Eq. 3 thresholds [SA, RA] of each ensemble event (events/ensemble); empty: the ones
    # chosen for the simulated hand's own ensemble events (gripper_hands.py), per
    # transition on held-out ensemble runs by analysis/choose_ensemble_thresholds.py, never
    # on a sweep's trials.
    reach_load_thresholds: list[float] = bounded(default_factory=list, **SCORE_RANGE)
    load_lift_thresholds: list[float] = bounded(default_factory=list, **SCORE_RANGE)
    place_unload_thresholds: list[float] = bounded(default_factory=list, **SCORE_RANGE)
    # A finger striking the object during the approach (joint torques): stop, back off
    # approach_retreat_m, shift along the stroke toward the struck finger, approach again
    # (counted in max_re_reaches).
    finger_strike: FingerStrikeConfig = dataclasses.field(default_factory=FingerStrikeConfig)

    def problem(self) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first event's thresholds that are
        neither empty nor a pair; None when all are."""
        for name in ("reach_load_thresholds", "load_lift_thresholds",
                     "place_unload_thresholds"):
            pair = getattr(self, name)
            if len(pair) not in (0, 2):
                return (name, "must be [] (the hand's chosen thresholds) or [SA, RA], each in "
                        "[-1, 1] (Eq. 3 scores)", pair)
        return None

    def event_thresholds(self, chosen: dict | None = None) -> dict[str, tuple[float, float]]:
        """{transition: (SA, RA)} for the EventMatcher: the ones set here, else `chosen`'s
        (the hand's, gripper_hands.py)."""
        chosen = chosen or {}
        given = {"reach_load": self.reach_load_thresholds,
                 "load_lift": self.load_lift_thresholds,
                 "place_unload": self.place_unload_thresholds}
        return {t: tuple(pair) if pair else tuple(chosen[t]) for t, pair in given.items()}


@dataclasses.dataclass
class ReReachConfig:
    """Re-Reach (Sec. III-C): one finger alone in contact for one_sided_contact_s, the gripper
    closed on nothing, or no Reach-Load event within reach_event_timeout_s of closing: open,
    shift along the stroke toward the touching finger, close again."""
    enabled: bool = True
    one_sided_contact_s: float = bounded(0.1, low=0.0, high=10.0, unit="s",
                                         below="must be zero or positive [s]")
    reach_event_timeout_s: float = bounded(2.0, low=0.0, high=60.0, unit="s",
                                           below="must be zero or positive [s]")
    max_re_reaches: int = bounded(2, low=0, high=10, below="must be zero or positive")
    # time to shift the open gripper sideways [s]
    move_s: float = bounded(0.8, low=0.0, high=10.0, unit="s",
                            below="must be zero or positive [s]")
    # the gripper counts as open beyond this opening [m]
    opened_m: float = bounded(0.080, low=0.0, high=0.085, unit="m",
                              why="the 2F-85's 85 mm stroke",
                              below="must be zero or positive [m]")


@dataclasses.dataclass
class LiftLoadConfig:
    """Lift-Load (Sec. III-C): during Lift, either pad's slip-band vibration
    (tactile/slip_vibration_band: the film's signal above slip_band_hz, RMS over
    slip_window_s) above slip_vibration_mps2 [m/s^2] for slip_s [s] means the object slips;
    back to Load with the grip force times force_factor, and lift again once both SA reach
    grip_fraction of that force."""
    enabled: bool = True
    # The band: the squeeze, the lift's load and the amplifier's decay lie below about
    # 10 Hz; texture slip at 40 mm/s (a lift's speed) rings at 80 Hz. Measured in open-loop
    # grasps of the three objects (docs/model.md, "Vibration (RA) model"): at 80 Hz and
    # 10 ms a normal lift reads at most 0.68 m/s^2, pads sliding along the object at lift
    # speed 1.9-5.1 m/s^2; the threshold 1 m/s^2 (24 mN of pad load) is the one the
    # accelerometer model used.
    slip_vibration_mps2: float = bounded(1.0, low=0.0, high=1000.0, unit="m/s^2",
                                         below="must be zero or positive [m/s^2]")
    # ... and above this many sigmas of the slip band's noise (control/noise_thresholds.py:
    # the band's RMS over slip_window_s of noise alone crosses it in at most one trial of a
    # thousand; the sigma from the film's electronics); 0: the number alone.
    slip_vibration_sigmas: float = bounded(2.34, low=0.0, high=100.0, unit="noise sigmas",
                                           why=_SIGMAS_WHY, below=_SIGMAS_BELOW)
    slip_band_hz: float = bounded(80.0, low=0.0, low_open=True, high=10_000.0, unit="Hz")
    slip_window_s: float = bounded(0.01, low=0.0, low_open=True, high=1.0, unit="s",
                                   below="must be zero or positive [s]")
    slip_s: float = bounded(0.02, low=0.0, high=1.0, unit="s",
                            below="must be zero or positive [s]")
    force_factor: float = bounded(2.0, low=1.0, high=10.0, below="must be at least 1")
    max_lift_loads: int = bounded(2, low=0, high=10, below="must be zero or positive")
    # the 2F-85's largest grip force
    max_grip_force_n: float = bounded(235.0, low=0.0, high=235.0, unit="N",
                                      why="the 2F-85 grips with at most 235 N, Robotiq 2F-85 "
                                          "manual",
                                      below="must be zero or positive [N]")
    # Measured: a 50 N request reads 44.9 N of SA on the box, the contact patch spreading
    # past the taxels; hence 0.8.
    grip_fraction: float = bounded(0.8, low=0.0, low_open=True, high=1.0)
    # and RA quiet (the slip has stopped) before lifting again [s]
    relift_settle_s: float = bounded(0.2, low=0.0, high=10.0, unit="s",
                                     below="must be zero or positive [s]")

    def problem(self, *, ra_rate_hz: float) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) when the slip band does not fit the RA
        stream read at ra_rate_hz [Hz]; None when it does."""
        if self.slip_band_hz >= ra_rate_hz / 2:
            return ("slip_band_hz", "must lie below half the RA rate "
                    f"({ra_rate_hz / 2:g} Hz, vibration.sample_rate_hz / 2): the slip band's "
                    "high-pass runs on the RA samples", self.slip_band_hz)
        return None


@dataclasses.dataclass
class AvoidConfig:
    """Avoid (Sec. III-C): in Hold, either RA above hit_ra_mps2 [m/s^2] is a hit. The
    machine stops for sense_s [s] to see which way the hit pushed (the pad the object was
    pushed into gains more than sa_asymmetry_n [N] over the other: along the stroke; else
    the pads' common acceleration in the horizontal plane), moves distance_m [m] that way
    over move_s [s], then Holds again. Hits are ignored for hit_refractory_s [s] after
    entering Hold (the stop of the lift rings briefly)."""
    enabled: bool = True
    hit_ra_mps2: float = bounded(3.0, low=0.0, high=1000.0, unit="m/s^2",
                                 below="must be zero or positive [m/s^2]")
    # ... and above this many RA noise sigmas (as the slip's)
    hit_ra_sigmas: float = bounded(5.51, low=0.0, high=100.0, unit="noise sigmas",
                                   why=_SIGMAS_WHY, below=_SIGMAS_BELOW)
    hit_refractory_s: float = bounded(0.3, low=0.0, high=10.0, unit="s",
                                      below="must be zero or positive [s]")
    sense_s: float = bounded(0.03, low=0.0, high=1.0, unit="s",
                             below="must be zero or positive [s]")
    sa_asymmetry_n: float = bounded(1.0, low=0.0, high=100.0, unit="N",
                                    below="must be zero or positive [N]")
    distance_m: float = bounded(0.05, low=0.0, high=0.3, unit="m",
                                below="must be zero or positive [m]")
    move_s: float = bounded(0.6, low=0.0, high=10.0, unit="s",
                            below="must be zero or positive [s]")


@dataclasses.dataclass
class PlaceConfig:
    """Place: the object set down on the table, Unload on the Place-Unload event."""
    # without the Place-Unload event, unload anyway this long after the arm stops [s]
    event_timeout_s: float = bounded(1.0, low=0.0, high=60.0, unit="s",
                                     below="must be zero or positive [s]")


@dataclasses.dataclass
class MemorizedCorrectiveConfig:
    """The corrective triggers taken from memorized corrective events (recording/
    corrective_events.py, read from the events folder's CORRECTIVE_EVENTS_FOLDER) matched by
    Eq. 3, instead of the heuristic thresholds of lift_load and avoid."""
    # Any of "hold_avoid" (a hit in Hold -> Avoid; Avoid still waits
    # avoid.hit_refractory_s after entering Hold) and "lift_load" (slip in Lift ->
    # Lift-Load), each matched in its mode. [] (the default): the heuristic triggers, the
    # baseline. lift_load is measured to match every normal lift
    # (docs/controller.md, "Memorized corrective triggers"): recorded for comparison, not
    # for use.
    events: list[str] = dataclasses.field(default_factory=list)
    # Eq. 3 thresholds [SA, RA] of each event, chosen on held-out recorded runs by
    # analysis/choose_corrective_thresholds.py (analysis/corrective_thresholds.md: the rule
    # and the tables), never on the closed-loop trials that judge them.
    # lift_load: no pair finds a held-out slip without a false trigger on a normal lift
    # (RA > 0.55 finds both, with 3 false of 7); the rule's pair finds none. Not usable as a
    # trigger on this robot: leave lift_load out of events.
    lift_load_thresholds: list[float] = bounded(default_factory=lambda: [0.45, 0.85],
                                                length=2, **SCORE_RANGE)
    # hold_avoid: every held-out hit found and no false trigger from RA > -0.05 up to 0.85;
    # the rule takes the admissible region's centre (SA does not tell: a held grip's SA is
    # flat with or without a hit), median latency 25 ms.
    hold_avoid_thresholds: list[float] = bounded(default_factory=lambda: [0.45, 0.40],
                                                 length=2, **SCORE_RANGE)
    # The match comes after the hit (15 ms measured, the target at most 60 ms), when the
    # push has already moved SA: the Avoid direction's SA baseline is the SA this long
    # before the match [s], the latency target, so that it precedes the hit.
    hit_baseline_s: float = bounded(0.06, low=0.0, high=1.0, unit="s",
                                    below="must be zero or positive [s]")
    # The hit event is looked for from this long after entering Hold [s]:
    # avoid.hit_refractory_s (a stop's ringing) plus the events' 0.5 s window, so that the
    # window holds no sample of the ringing. Eq. 3 takes the best of all lags, so a
    # transient anywhere in the window can match the hit's shape whatever its size; armed
    # after hit_refractory_s alone, the stop of each Avoid move matched as a new hit 0.53 s
    # into the next Hold (14 Avoids in a row, README).
    hit_armed_s: float = bounded(0.8, low=0.0, high=10.0, unit="s",
                                 below="must be zero or positive [s]")

    def thresholds(self) -> dict[str, tuple[float, float]]:
        """{corrective transition: (SA, RA)} for the corrective EventMatcher."""
        return {"lift_load": tuple(self.lift_load_thresholds),
                "hold_avoid": tuple(self.hold_avoid_thresholds)}

    def problem(self) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first event that is not a corrective
        event; None when all are."""
        from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS  # Drake: on use
        for k, name in enumerate(self.events):
            if name not in CORRECTIVE_TRANSITIONS:
                return (f"events[{k}]", "must name a corrective event "
                        f"({', '.join(CORRECTIVE_TRANSITIONS)})", name)
        return None


@public_dataclass
@dataclasses.dataclass
class GraspControllerConfig:
    """The grasp state machine's settings, shared by the closed-loop controllers: the tick,
    the contact force, and each corrective action's triggers and numbers (Sec. III-C) in
    its own section."""
    # state machine tick [s]
    update_period_s: float = bounded(0.005, low=0.0, low_open=True, high=0.1, unit="s",
                                     below="must be positive [s]")
    # The tactile systems that take the 1 kHz film samples (the event matchers' RA windows,
    # the slip band) process them in blocks of this long [s], one Python update per block
    # (tactile/sample_block.py: BLOCK_PERIOD_S, 10 ms, about one AD7147 frame); 0 (the
    # default): one update per sample. Blocks save about 1 % of a trial's CPU time and act on
    # each event up to one block later (docs/sweeps.md), so results stay per-sample.
    sensor_block_s: float = bounded(0.0, low=0.0, high=0.1, unit="s",
                                    below="must be zero (one update per sample) or positive [s]")
    # A finger touches when its SA exceeds contact_force_n [N]; a taxel counts toward a
    # contact's shape above taxel_contact_n [N] (0.05: ten times an ideal force taxel's
    # 5 mN noise).
    contact_force_n: float = bounded(0.3, low=0.0, high=50.0, unit="N",
                                     below="must be zero or positive [N]")
    taxel_contact_n: float = bounded(0.05, low=0.0, high=50.0, unit="N",
                                     below="must be zero or positive [N]")
    # Each SA threshold (contact_force_n, taxel_contact_n, avoid.sa_asymmetry_n, the
    # heuristic's contact_force_n) raised to the force that the taxels' noise alone exceeds
    # in at most one trial of a thousand, from the scenario's taxel electronics
    # (control/noise_thresholds.py); False: the numbers alone.
    sa_noise_floor: bool = True
    # Load without the Load-Lift event: give up [s]
    load_event_timeout_s: float = bounded(2.0, low=0.0, high=60.0, unit="s",
                                          below="must be zero or positive [s]")
    # Lost object: in Lift, Hold, Avoid or Place, both SA below contact_force_n.
    drop_check_enabled: bool = True
    # The memorized events carry the object they were recorded on; the controller refuses
    # events of an object that differs from the scenario's, except in the fields listed
    # here (of shape, size, mass, friction, file), e.g. [friction] to grasp a slippery box
    # with the box's events.
    event_object_may_differ: list[str] = dataclasses.field(default_factory=list)
    re_reach: ReReachConfig = dataclasses.field(default_factory=ReReachConfig)
    lift_load: LiftLoadConfig = dataclasses.field(default_factory=LiftLoadConfig)
    avoid: AvoidConfig = dataclasses.field(default_factory=AvoidConfig)
    place: PlaceConfig = dataclasses.field(default_factory=PlaceConfig)
    memorized_corrective: MemorizedCorrectiveConfig = dataclasses.field(
        default_factory=MemorizedCorrectiveConfig)

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        """(field, what it must be, its value) of the first setting that does not fit
        another or the scenario's RA stream, read at ra_rate_hz [Hz] with its approach
        ending at approach_s [s] (each number's own range is declared on its field); the
        field as a path under the controller; None when all fit."""
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


def _block_problem(block_s: float, ra_rate_hz: float) -> tuple[str, str, object] | None:
    """sensor_block_s's problem when its blocks of RA samples do not fall on the sample
    times in floating point."""
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
    """The settings of a state machine whose transitions memorized tactile events trigger,
    matched by Eq. 3."""
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
    """The ideal scripted grasp (control/scripted_grasp.py, from the scenario's `grasp`
    section): no settings of its own."""
    name: typing.ClassVar[str] = "open_loop"
    events_folder: typing.ClassVar[str | None] = None
    extra_time_s: typing.ClassVar[float] = 0.0
    # it matches no memorized corrective event
    memorized_corrective: typing.ClassVar[MemorizedCorrectiveConfig] = MemorizedCorrectiveConfig()


@public_dataclass
@dataclasses.dataclass
class TaxelAwareControllerConfig(EventTriggeredConfig):
    """The paper's algorithm with corrections from the whole taxel array (the rule table of
    control/taxel_aware), its transitions triggered by the memorized events of an ensemble
    of ideal grasps."""
    name: typing.ClassVar[str] = "taxel_aware"
    events_folder: typing.ClassVar[str | None] = "ensemble"
    # Its further corrections: two more Re-Reaches than the paper's (open, move 0.8 s,
    # close: about 2.5 s each) and a re-grasp (put down, open, close, load, lift and hold
    # again: about 9 s), rounded up [s].
    extra_time_s: typing.ClassVar[float] = 15.0
    taxel_aware: TaxelAwareConfig = dataclasses.field(default_factory=TaxelAwareConfig)

    def event_thresholds(self, chosen: dict | None = None) -> dict[str, tuple[float, float]]:
        """{transition: (SA, RA)}: the ensemble events' own (TaxelAwareConfig), else the
        ones `chosen` for the hand's ensemble events."""
        return self.taxel_aware.event_thresholds(chosen)

    def problem(self, *, ra_rate_hz: float, approach_s: float) -> tuple[str, str, object] | None:
        found = super().problem(ra_rate_hz=ra_rate_hz, approach_s=approach_s)
        if found is None:
            found = self.taxel_aware.problem()
            if found is not None:
                found = (f"taxel_aware.{found[0]}",) + found[1:]
        return found
