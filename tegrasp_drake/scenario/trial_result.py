"""TrialResult: what one simulated trial did, judged against the ground truth (Sec. IV-C).
Its JSON form (`to_dict`) is what result.json, `tegrasp trial --json` and a sweep record's
"result" hold; `from_dict` reads one back: every field is required but the few a later
version added (FIELDS_ADDED_LATER), which results written before them lack."""

import dataclasses
import math
import typing

from tegrasp_drake.rig.api_boundary import check_field_types, public_dataclass
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.ranges import SEED_RANGE, bounded, check_ranges, declared_field
from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.object_placement import ObjectPlacementConfig
from tegrasp_drake.scenario.physical_event_search import (SEARCH_FROM,
                                                          physical_event_search_starts)
from tegrasp_drake.control.grasp_modes import Mode, Transition

# The farthest an object's height can be from the table top it started on [m]: in the hand,
# the JACO2's 0.9 m reach from its base on the table (Kinova JACO2 specifications) plus the
# object's own size, or fallen off the table to a floor below it; 2 m bounds either.
MAX_HEIGHT_M = 2.0


HOLD_REQUIRED_S = 3.0  # the paper (Sec. IV-C): a hold succeeds when held at least 3 s
# An event transition earlier than its physical event by more than this [s] is a false
# trigger; within it lie one 108 Hz taxel sample and noise around the truth's threshold.
FALSE_TRIGGER_MARGIN_S = 0.01
# The key of the scenario's hit among the physical events (the others are event transitions).
HIT_EVENT = "hit"
# An unload succeeds only with the object standing upright: tilted less than this [deg].
UPRIGHT_TILT_DEG = 10.0

# How far a latency may lie from its transition's time minus its physical event's, in units in
# the last place (math.ulp) of the larger of the two times. judge_trial takes the difference once
# in float64 and JSON carries each float exactly, so a result run_trial wrote matches to the bit
# (all committed results do); a result written by hand from a decimal latency, its event's time
# taken as the transition's minus it, is off by the rounding of that latency (half a unit), of
# that subtraction (half a unit) and of the check's own (exact or half a unit): under 2. A
# latency off by more is not round-off: 1e-9 s is ten million units at a time of 10 s.
LATENCY_ROUND_OFF_ULPS = 2

# A failure is the reason a controller gives for going to Failed, one sentence (the longest
# in the committed sweep records: 109 characters); ten times a long sentence is not one.
MAX_FAILURE_CHARS = 1000


# The fields a version after the first results added to the JSON form, each with the value
# from_dict reads where it is missing: not measured (None). The committed sweep records of
# those versions (analysis/results_*/, analysis/geometry_contract/) lack them, and the JSON
# form has no version of its own to tell them by; every other field is required.
FIELDS_ADDED_LATER = {"lift_grip_fraction": None, "cpu_time_s": None,
                      "release_height_m": None}


# How far a real-time factor may lie from sim_time_s / wall_time_s (relative): run_trial
# writes that quotient and JSON carries floats exactly; 1e-9 allows the quotient taken again
# from times rounded in the last digits, far below the spread between runs.
REAL_TIME_FACTOR_TOLERANCE = 1e-9


@public_dataclass
@dataclasses.dataclass
class TrialResult:
    """One trial's outcome. Times in seconds of simulated time unless said, lengths in
    metres, angles in degrees; transitions in order, Mode labels in the JSON form."""
    object: str = ""
    offset_m: list[float] = declared_field(ObjectPlacementConfig, "offset")
    controller: str = ""
    seed: int | None = bounded(None, **dataclasses.asdict(SEED_RANGE))
    transitions: tuple[Transition, ...] = ()  # each checks its own; in time order
    hold_success: bool = False  # lifted and held at least HOLD_REQUIRED_S
    unload_success: bool = False  # then placed upright, released, retracted
    final_mode: Mode = Mode.REACH
    hold_time_s: float | None = bounded(None, low=0.0, unit="s", why="a duration")
    # The object's lowest point above its start: its highest minus its start, so never below.
    lift_height_m: float | None = bounded(None, low=0.0, high=MAX_HEIGHT_M, unit="m",
                                          why="the highest point of a path that starts at 0, "
                                              "within the arm's reach")
    final_tilt_deg: float | None = bounded(None, low=0.0, high=180.0, unit="deg",
                                           why="the angle between the object's up and world up")
    placement_error_m: float | None = bounded(None, low=0.0, unit="m", why="a distance")
    released: bool = False
    # The object's lowest point above the table top (where it rested at the start) when
    # Unload began, the gripper's open command: the height it was let go from; None when
    # no transition went to Unload (and in results written before the field).
    release_height_m: float | None = bounded(
        None, low=-MAX_HEIGHT_M, high=MAX_HEIGHT_M, unit="m",
        why="a height either side of the table top (pressed into it, or fallen past its edge), "
            "within the arm's reach")
    # The physical event behind each event transition taken, and "hit" [s]
    # (trial_judge.physical_event_times); None where it was not found.
    physical_events: dict[str, float | None] = bounded(
        default_factory=dict, low=0.0, unit="s", why="simulated times since the trial's start")
    # Each event transition's time minus its physical event's [s]: either sign, since a
    # detection up to FALSE_TRIGGER_MARGIN_S early is still counted as one.
    detection_latency_s: dict[str, float | None] = bounded(
        default_factory=dict, unit="s", why="a detection's time minus its physical event's")
    false_triggers: int = bounded(0, low=0, why="a count")
    # The weaker pad's grip at the first lift as a fraction of the settled grip.
    lift_grip_fraction: float | None = bounded(None, low=0.0, why="a ratio of two pad forces")
    corrective_actions: list[str] = dataclasses.field(default_factory=list)
    failure: str = ""  # the reason of the transition to Failed, "" for none
    sim_time_s: float | None = bounded(None, low=0.0, unit="s", why="a duration")
    wall_time_s: float | None = bounded(None, low=0.0, unit="s", why="a duration")
    cpu_time_s: float | None = bounded(None, low=0.0, unit="s", why="a duration")
    real_time_factor: float | None = bounded(None, low=0.0,
                                             why="simulated time over wall time, two durations")
    # The trial's log (a TrialLog) when run here; not part of the JSON form. (typing.Any:
    # the field `object` hides the builtin in the class body.)
    log: typing.Any = dataclasses.field(default=None, compare=False, repr=False)

    def __post_init__(self):
        """ConfigError naming the first field not of its type or out of its range (the
        transitions' own included), the first transition earlier than the one before it,
        the first transition that leaves a mode other than the one entered before it, or the
        first relation between fields that run_trial guarantees and this result breaks. The
        types first: the relations read the fields' values."""
        name = type(self).__name__
        check_field_types(self)
        check_ranges(self, name)
        for k in range(1, len(self.transitions)):
            earlier, later = self.transitions[k - 1].t, self.transitions[k].t
            if later < earlier:
                raise ConfigError(
                    f"{name}: field 'transitions[{k}].t' must not be before "
                    f"transitions[{k - 1}].t = {number_text(earlier)} s (a timeline is in "
                    f"time order), got {number_text(later)}")
        for k in range(1, len(self.transitions)):
            left, entered = self.transitions[k].from_mode, self.transitions[k - 1].to_mode
            if left != entered:
                raise ConfigError(
                    f"{name}: field 'transitions[{k}].from' must be {entered.label}, the mode "
                    f"transitions[{k - 1}] entered (a timeline is one chain of modes), got "
                    f"{left.label}")
        self._check_relations(name)

    def _check_relations(self, name: str) -> None:
        """The relations judge_trial (trial_judge.py) and run_trial guarantee: Unload is
        judged only after a Hold, in a trial ending Done with the object released and upright;
        a hold succeeds exactly when held HOLD_REQUIRED_S; the final mode is the last
        transition's (_check_final_mode); the controller's (_check_controller); the failure
        is one sentence; every time is within the simulated time (transitions, the physical
        events and the hold are taken during the run, so a latency, a transition's time minus
        its event's, is within it either way), and that within the longest run a trial can last
        (grasp_diagram.longest_trial_s), which also bounds the times when it is not set; last,
        each latency against the timeline (_check_latency)."""
        if len(self.failure) > MAX_FAILURE_CHARS:
            raise ConfigError(f"{name}: field 'failure' must be at most {MAX_FAILURE_CHARS} "
                              f"characters (a controller's one-sentence reason), got "
                              f"{len(self.failure)}")
        if self.unload_success and not self.hold_success:
            raise ConfigError(f"{name}: field 'unload_success' is true but 'hold_success' is "
                              "false (a trial is judged unloaded only after it held)")
        final = getattr(self.final_mode, "label", self.final_mode)
        if self.unload_success and final != Mode.DONE.label:
            raise ConfigError(f"{name}: field 'unload_success' is true but 'final_mode' is "
                              f"{shorten(str(final))} (a trial is judged unloaded only when it "
                              "ends Done)")
        if self.unload_success and not self.released:
            raise ConfigError(f"{name}: field 'unload_success' is true but 'released' is false "
                              "(a trial is judged unloaded only with the object released)")
        if (self.unload_success and self.final_tilt_deg is not None
                and self.final_tilt_deg >= UPRIGHT_TILT_DEG):
            raise ConfigError(f"{name}: field 'unload_success' is true but 'final_tilt_deg' is "
                              f"{number_text(self.final_tilt_deg)} deg (a trial is judged "
                              f"unloaded only with the object upright, tilted less than "
                              f"{number_text(UPRIGHT_TILT_DEG)} deg)")
        if self.hold_time_s is not None and self.hold_success != (
                self.hold_time_s >= HOLD_REQUIRED_S):
            raise ConfigError(f"{name}: field 'hold_success' is {str(self.hold_success).lower()} "
                              f"but 'hold_time_s' is {number_text(self.hold_time_s)} s (a hold "
                              f"succeeds when held at least {number_text(HOLD_REQUIRED_S)} s)")
        self._check_final_mode(name, final)
        self._check_controller(name)
        self._check_events(name)
        self._check_timeline_fields(name)
        self._check_real_time_factor(name)
        from tegrasp_drake.scenario.grasp_diagram import longest_trial_s  # Drake: on use
        longest = longest_trial_s()
        longest_why = ("the longest run a trial can last: the longest grasp script plus the "
                       "time for corrections")
        if self.sim_time_s is not None and self.sim_time_s > longest:
            raise ConfigError(f"{name}: field 'sim_time_s' must be at most "
                              f"{number_text(longest)} s ({longest_why}), got "
                              f"{number_text(self.sim_time_s)}")
        if self.sim_time_s is None:  # not said: the longest run still bounds each time
            limit, end, why = longest, number_text(longest), longest_why
        else:
            limit, why = self.sim_time_s, "within the simulated time"
            end = f"sim_time_s = {number_text(self.sim_time_s)}"
        times = [(f"transitions[{k}].t", entry.t, f"at most {end} s")
                 for k, entry in enumerate(self.transitions)]
        times += [(f"physical_events.{key}", value, f"at most {end} s")
                  for key, value in self.physical_events.items() if value is not None]
        span = number_text(limit)
        times += [(f"detection_latency_s.{key}", value, f"in [-{span}, {span}] s (either sign)")
                  for key, value in self.detection_latency_s.items() if value is not None]
        if self.hold_time_s is not None:
            times.append(("hold_time_s", self.hold_time_s, f"at most {end} s"))
        for field, value, within in times:
            if abs(value) > limit:
                raise ConfigError(f"{name}: field '{field}' must be {within} ({why}), got "
                                  f"{number_text(value)}")
        for key, latency in self.detection_latency_s.items():
            if latency is not None:
                self._check_latency(name, key, latency)

    def _check_events(self, name: str) -> None:
        """The physical events and latencies as judge_trial gives them (trial_judge.py): a
        physical event is "hit" or one of the event transitions (REQUIRED_TRANSITIONS) the
        timeline takes, not before its search start (physical_event_search_starts); a
        latency is keyed by an event transition (REQUIRED_TRANSITIONS) and
        not below -FALSE_TRIGGER_MARGIN_S (a detection earlier by more is a false trigger,
        counted and given no latency); its relation to the timeline is _check_latency's."""
        from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS, event_transition
        taken = [(event_transition(e.from_mode.label, e.to_mode.label), e.trigger.is_event)
                 for e in self.transitions]
        for key in self.physical_events:
            if key != HIT_EVENT and key not in REQUIRED_TRANSITIONS:
                raise ConfigError(f"{name}: field 'physical_events.{shorten(key)}' names no "
                                  f"physical event (one of {HIT_EVENT}, "
                                  f"{', '.join(REQUIRED_TRANSITIONS)})")
            if key != HIT_EVENT and all(event != key for event, _ in taken):
                raise ConfigError(f"{name}: field 'physical_events.{key}' but no transition "
                                  f"{key} was taken (a physical event is looked for behind a "
                                  "transition the trial took)")
        starts = physical_event_search_starts(self.transitions)
        for key, value in self.physical_events.items():
            if key in starts and value is not None and value < starts[key]:
                mode = SEARCH_FROM[key].label
                raise ConfigError(f"{name}: field 'physical_events.{key}' is "
                                  f"{number_text(value)} s, before {number_text(starts[key])} "
                                  f"s, when the trial last entered {mode} before its {key} "
                                  "transition (the event is searched from there); correct the "
                                  "event's time or the timeline")
        for key, latency in self.detection_latency_s.items():
            if key not in REQUIRED_TRANSITIONS:
                raise ConfigError(f"{name}: field 'detection_latency_s.{shorten(key)}' names "
                                  f"no event transition (one of "
                                  f"{', '.join(REQUIRED_TRANSITIONS)})")
            if latency is not None and latency < -FALSE_TRIGGER_MARGIN_S:
                raise ConfigError(f"{name}: field 'detection_latency_s.{key}' must be at least "
                                  f"-{number_text(FALSE_TRIGGER_MARGIN_S)} s (a detection "
                                  "earlier than its physical event by more is a false trigger, "
                                  f"given no latency), got {number_text(latency)}")

    def _check_latency(self, name: str, key: str, latency: float) -> None:
        """A latency is judge_trial's: of an event-triggered transition `key` taken whose
        physical event was found, and equal, within LATENCY_ROUND_OFF_ULPS, to the time of the
        last such detection not a false trigger minus the physical event's (judge_trial keeps
        the last). Checked after the times' bounds, so a latency past the longest run is
        named as such."""
        from tegrasp_drake.events.transitions import event_transition
        detections = [(k, e.t) for k, e in enumerate(self.transitions) if e.trigger.is_event
                      and event_transition(e.from_mode.label, e.to_mode.label) == key]
        if not detections:
            raise ConfigError(f"{name}: field 'detection_latency_s.{key}' but no "
                              f"event-triggered transition {key} was taken (a latency is a "
                              "detection's)")
        physical = self.physical_events.get(key)
        if physical is None:
            raise ConfigError(f"{name}: field 'detection_latency_s.{key}' but "
                              f"'physical_events.{key}' is not given (a latency is the "
                              "detection's time minus its physical event's)")
        counted = [(k, t) for k, t in detections if t >= physical - FALSE_TRIGGER_MARGIN_S]
        if not counted:
            raise ConfigError(f"{name}: field 'detection_latency_s.{key}' but every {key} "
                              f"detection came more than {number_text(FALSE_TRIGGER_MARGIN_S)} s "
                              f"before 'physical_events.{key}' = {number_text(physical)} s "
                              "(false triggers, given no latency)")
        k, t = counted[-1]
        expected = t - physical
        allowed = LATENCY_ROUND_OFF_ULPS * math.ulp(max(abs(t), abs(physical)))
        if abs(latency - expected) > allowed:
            raise ConfigError(f"{name}: field 'detection_latency_s.{key}' must be "
                              f"transitions[{k}].t - physical_events.{key} = "
                              f"{number_text(expected)} s (the last {key} detection's time "
                              f"minus its physical event's), got {number_text(latency)}, off by "
                              f"{number_text(abs(latency - expected))} s")

    def _check_timeline_fields(self, name: str) -> None:
        """The fields judge_trial derives from the timeline alone: the failure is the reason
        of the first transition to Failed ("" when none was taken), the corrective actions
        are those the transitions start, in order (corrective_action_of), and a lift grip
        fraction is taken at the first Load -> Lift, so is given only when one was taken,
        and a release height when Unload begins, so only when a transition went to Unload."""
        failed = next(((k, e) for k, e in enumerate(self.transitions)
                       if e.to_mode == Mode.FAILED), None)
        if self.failure and failed is None:
            raise ConfigError(f"{name}: field 'failure' is {shorten(repr(self.failure))} but "
                              "no transition goes to Failed (the failure is the reason of the "
                              "transition to Failed; leave it \"\" for none)")
        if failed is not None and self.failure != failed[1].reason:
            raise ConfigError(f"{name}: field 'failure' must be the reason of transitions"
                              f"[{failed[0]}], the first to Failed, "
                              f"{shorten(repr(failed[1].reason))}, got "
                              f"{shorten(repr(self.failure))}")
        from tegrasp_drake.control.corrective_actions import corrective_action_of  # Drake
        started = [action for action in (corrective_action_of(e.from_mode, e.to_mode, e.trigger)
                                         for e in self.transitions) if action is not None]
        if self.corrective_actions != started:
            raise ConfigError(f"{name}: field 'corrective_actions' must be the actions the "
                              f"transitions start, in order, [{', '.join(started)}], got "
                              f"{shorten(repr(self.corrective_actions))}")
        if self.release_height_m is not None and not self.entered(Mode.UNLOAD):
            raise ConfigError(f"{name}: field 'release_height_m' is "
                              f"{number_text(self.release_height_m)} but no transition goes "
                              "to Unload (the height is taken when Unload begins)")
        if self.lift_grip_fraction is not None and not any(
                e.from_mode == Mode.LOAD and e.to_mode == Mode.LIFT for e in self.transitions):
            raise ConfigError(f"{name}: field 'lift_grip_fraction' is "
                              f"{number_text(self.lift_grip_fraction)} but no transition goes "
                              "from Load to Lift (the fraction is taken at the first one)")

    def _check_final_mode(self, name: str, final: str) -> None:
        """The final mode is the mode the last transition entered, Reach (the first mode)
        when none was taken, as judge_trial gives it."""
        if self.transitions:
            entered = self.transitions[-1].to_mode
            if final != entered.label:
                raise ConfigError(f"{name}: field 'final_mode' is {shorten(str(final))} but the "
                                  f"last transition enters {entered.label} (a trial ends in the "
                                  "mode its last transition entered)")
        elif final != Mode.REACH.label:
            raise ConfigError(f"{name}: field 'final_mode' is {shorten(str(final))} but no "
                              f"transition was taken (a trial without one ends in "
                              f"{Mode.REACH.label}, where it starts)")

    def _check_real_time_factor(self, name: str) -> None:
        """The real-time factor is what run_trial makes it: simulated over wall time (none
        for a wall time of 0), where the result gives all three."""
        if None in (self.real_time_factor, self.sim_time_s, self.wall_time_s):
            return
        if self.wall_time_s <= 0:
            raise ConfigError(f"{name}: field 'real_time_factor' is "
                              f"{number_text(self.real_time_factor)} but 'wall_time_s' is 0 (no "
                              "factor without a wall time: leave it null)")
        expected = self.sim_time_s / self.wall_time_s
        if not math.isclose(self.real_time_factor, expected,
                            rel_tol=REAL_TIME_FACTOR_TOLERANCE):
            raise ConfigError(f"{name}: field 'real_time_factor' must be sim_time_s / "
                              f"wall_time_s = {number_text(expected)}, got "
                              f"{number_text(self.real_time_factor)}")

    def _check_controller(self, name: str) -> None:
        """The relations with the controller that wrote the result: a registered name ("":
        not said), corrective actions among the controllers' (corrective_actions), and the
        transitions' triggers, codes and scores what it gives (transition_trigger_problem,
        transition_code_problem, transition_scores_problem)."""
        from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES
        if self.controller and self.controller not in CONTROLLER_NAMES:
            raise ConfigError(f"{name}: field 'controller' must be one of "
                              f"{', '.join(CONTROLLER_NAMES)}, got "
                              f"{shorten(repr(self.controller))}")
        if self.corrective_actions:
            known = corrective_action_names()
            for k, action in enumerate(self.corrective_actions):
                if action not in known:
                    raise ConfigError(f"{name}: field 'corrective_actions[{k}]' must be one of "
                                      f"{', '.join(sorted(known))}, got {shorten(repr(action))}")
        problem = transition_trigger_problem(self.transitions, self.controller)
        if problem:
            raise ConfigError(f"{name}: field {problem}; correct the trigger or the result's "
                              "'controller'")
        for check in (transition_code_problem, transition_scores_problem):
            problem = check(self.transitions, self.controller)
            if problem:
                raise ConfigError(f"{name}: field {problem}")

    def to_dict(self) -> dict:
        """The JSON form: all fields but `log`; transitions as dicts, the final mode by label."""
        data = {field.name: getattr(self, field.name) for field in dataclasses.fields(self)
                if field.name != "log"}
        data["transitions"] = [transition.as_dict() for transition in self.transitions]
        data["final_mode"] = self.final_mode.label
        return data

    @property
    def result(self) -> dict:
        """The JSON form (to_dict), for code written when run_trial returned it."""
        return self.to_dict()

    @classmethod
    def from_dict(cls, data: dict) -> "TrialResult":
        """The TrialResult of its JSON form (to_dict); unknown keys ignored. Every field is
        required but FIELDS_ADDED_LATER (read as not measured where missing): ValueError
        naming the first field missing or not of its type or range; TypeError naming the
        argument when `data` is not a dict (as public_api's)."""
        if not isinstance(data, dict):
            raise TypeError(f"TrialResult.from_dict: argument 'data' must be a dict (a trial "
                            f"result's JSON form), got {type(data).__name__} "
                            f"{shorten(repr(data))}")
        fields = [field.name for field in dataclasses.fields(cls) if field.name != "log"]
        missing = [name for name in fields if name not in data and name not in FIELDS_ADDED_LATER]
        if missing:
            raise ValueError(f"not a trial result's JSON form: field '{missing[0]}' is missing "
                             f"({len(missing)} of its {len(fields)} fields are); give the "
                             "whole JSON form TrialResult.to_dict() writes (result.json, a "
                             "sweep record's 'result')")
        values = {**FIELDS_ADDED_LATER, **{name: data[name] for name in fields if name in data}}
        try:  # a hand-edited JSON form: one line naming the field
            transitions = data["transitions"]
            if not isinstance(transitions, list | tuple):
                raise ValueError(f"'transitions' must be a list, got {shorten(repr(transitions))}")
            values["transitions"] = tuple(map(Transition.from_dict, transitions))
            values["final_mode"] = Mode.from_label(data["final_mode"])
            return cls(**values)
        except (ValueError, TypeError) as e:
            raise ValueError(f"not a trial result's JSON form: {shorten(str(e), 300)}") from None

    def entered(self, mode: Mode) -> bool:
        """Whether the trial ever entered `mode`."""
        return any(transition.to_mode == mode for transition in self.transitions)


def corrective_action_names() -> frozenset[str]:
    """The names of the corrective actions a transition can start (corrective_actions:
    CORRECTIVE_ACTIONS, and taxel_aware's CORRECTIVE_ONLY_ACTIONS)."""
    from tegrasp_drake.control.corrective_actions import (  # Drake: on use
        CORRECTIVE_ACTIONS, CORRECTIVE_ONLY_ACTIONS)
    return frozenset(CORRECTIVE_ACTIONS.values()) | frozenset(CORRECTIVE_ONLY_ACTIONS.values())


# How far past SCORE_RANGE a memorized detector's score may read. A score is a correlation over
# the live window's energy, which the streaming matcher keeps as a running sum (add the
# entering sample's square, drop the leaving one's: events/streaming_correlation.py); its
# round-off is at most one float64 epsilon of the largest window energy per update, 85,000
# updates over the longest run (85 s at 1 kHz): 2e-11 of it. 1e-6 lets a window five orders
# weaker than the run's strongest score a true 1 without a refusal; 7 or 1e300 are not
# round-off. (The committed records' memorized scores reach exactly 1.0, never past it.)
SCORE_ROUND_OFF = 1e-6


def transition_scores_problem(transitions, controller: str | None) -> str | None:
    """"'transitions[k].scores' ..." if a transition's scores are not what the detector of
    `controller` (a registered name) gives, else None. A controller without a detector (the
    open-loop script) gives none; the state machine logs its detector's scores on every
    transition, whatever the trigger. The memorized detector's are Eq. 3 correlations
    (event_matching.SCORE_RANGE, [-1, 1]); the heuristic detector's are channel/threshold
    ratios with no common bound (Transition.scores), so a controller with another detector,
    or none named, has its scores checked only as finite (Transition's own)."""
    from tegrasp_drake.control.controller_registry import (CONTROLLER_NAMES, EVENT_MATCHER,
                                                            controller_entry)
    from tegrasp_drake.rig.event_matching import SCORE_RANGE
    if controller not in CONTROLLER_NAMES:
        return None
    detector = controller_entry(controller).detector
    if detector is None:
        for k, entry in enumerate(transitions):
            if entry.scores is not None:
                return (f"'transitions[{k}].scores' (at {number_text(entry.t)} s) is set, but "
                        f"the {controller} controller has no event detector, so its "
                        "transitions carry no scores; remove them or correct the result's "
                        "'controller'")
        return None
    if detector != EVENT_MATCHER:
        return None
    low, high = SCORE_RANGE["low"], SCORE_RANGE["high"]
    for k, entry in enumerate(transitions):
        for score in entry.scores or ():
            if not low - SCORE_ROUND_OFF <= score <= high + SCORE_ROUND_OFF:
                return (f"'transitions[{k}].scores' holds {number_text(score)}, outside "
                        f"{number_text(low)} to {number_text(high)} ({SCORE_RANGE['why']}, from "
                        f"the {controller} controller's detector)")
    return None


def transition_trigger_problem(transitions, controller: str | None) -> str | None:
    """"'transitions[k].trigger' ..." (its time, its trigger, those the controller fires) if
    a transition (a Transition) carries a trigger the controller named `controller` cannot
    fire (ControllerEntry.triggers), else None; None too for a name no controller has ("":
    not said), which the caller names. The caller says what to do."""
    from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_entry
    if controller not in CONTROLLER_NAMES:
        return None
    fired = controller_entry(controller).triggers()
    for k, entry in enumerate(transitions):
        if entry.trigger not in fired:
            return (f"'transitions[{k}].trigger' (at {number_text(entry.t)} s) is "
                    f"{shorten(str(entry.trigger))}, which the {controller} controller never "
                    f"fires (it fires {', '.join(sorted(fired))})")
    return None


def transition_code_problem(transitions, controller: str | None) -> str | None:
    """"'transitions[k].code' ..." if a transition's code (the deciding rule's name, which
    Transition itself checks names a rule of some controller) names no rule of the rule
    table of `controller`, or a rule that does not apply in the mode the transition left;
    the open-loop script's transitions carry none. None for a name no controller has."""
    from tegrasp_drake.control.controller_registry import CONTROLLER_NAMES, controller_entry
    if controller not in CONTROLLER_NAMES:
        return None
    table = controller_entry(controller).rule_table()
    names = set() if table is None else {rule.name for rule in table.all_rules()}
    for k, entry in enumerate(transitions):
        if entry.code is None:
            continue
        where = f"'transitions[{k}].code' (at {number_text(entry.t)} s) is {entry.code!r}"
        if entry.code not in names:
            rules = ("it has no rules, so its transitions carry no code" if table is None
                     else "docs/controller.md lists its rules")
            return (f"{where}, which names no rule of the {controller} controller ({rules}); "
                    "correct the code or the result's 'controller'")
        if not table.rule(entry.code).applies_in(entry.from_mode):
            return (f"{where}, a rule that does not apply in "
                    f"{entry.from_mode.label}, the mode the transition left "
                    "(docs/controller.md lists each rule's modes): correct the code or "
                    "the transition's 'from'")
    return None
