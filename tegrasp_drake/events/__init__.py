"""Memorized tactile events: extraction, file format, live windows and matching (Fig. 3).

- transitions.py: the grasp transitions events can trigger, in grasp order.
- memorized_event.py: MemorizedEvent, one object's four max-normalised windows.
- extraction.py: cuts the events out of a recorded ideal grasp.
- event_file.py: one event's JSON file and the folder's index (FORMAT.md).
- one_grasp.py: an object's events as one set, cut from one grasp.
- events_folder.py: save, load and find an events folder.
- correlation.py: Eq. 3 and the contrast gate, the reference implementation.
- streaming_correlation.py: the exact per-sample update of the Eq. 3 scores.
- event_matcher.py: EventMatcher, the live windows scored against the expected event.
- ra_envelope.py: the RA envelope (a low-pass of both RA windows, beyond the paper).
- ra_noise_floor.py: the RA noise floor measured on the quiet approach.
- event_sequencer.py: EventSequencer, an object's events one after another.
- replay.py: a logged trial through the matcher, offline.
- missed_waits.py: why a memorized event did not come in time.
- synthetic.py: synthetic grasps for tests (not re-exported).
The figure of the events is figures/events.py (kept out, so the loop needs no matplotlib)."""

from tegrasp_drake.events.correlation import (
    channel_score, event_scores_reference, max_normalized_xcorr_reference, window_contrast)
from tegrasp_drake.events.event_matcher import (
    EventMatcher, EventMatcherConfig, add_event_matcher, event_templates)
from tegrasp_drake.events.event_sequencer import EventSequencer, next_sequence_step
from tegrasp_drake.events.extraction import (
    DEFAULT_PRE_TRANSITION_S, DEFAULT_WINDOW_S, TactileTrial, cut_window,
    extract_memorized_events)
from tegrasp_drake.events.event_file import (
    FORMAT_VERSION, INDEX_FILE, MemorizedEventError, RECORD_COMMAND, read_index,
    read_memorized_event)
from tegrasp_drake.events.events_folder import (
    load_all_memorized_events, load_memorized_events, save_memorized_events)
from tegrasp_drake.events.memorized_event import MemorizedEvent, current_package_versions
from tegrasp_drake.events.missed_waits import (
    EventWait, MissedWait, classify_missed_wait, event_waits)
from tegrasp_drake.events.replay import (
    EventReplay, channels_trajectory, live_matcher_config, replay_event_held,
    replay_events_in_sequence, tactile_trial_from_log)
from tegrasp_drake.events.streaming_correlation import SlidingCorrelation, StreamingCorrelator
from tegrasp_drake.events.transitions import (
    NO_EVENT, REQUIRED_TRANSITIONS, TRANSITIONS, event_transition, transition_name,
    transition_order, transition_states)
from tegrasp_drake.tactile.max_normalization import normalize_by_max

__all__ = [
    "DEFAULT_PRE_TRANSITION_S", "DEFAULT_WINDOW_S", "FORMAT_VERSION", "INDEX_FILE",
    "NO_EVENT", "RECORD_COMMAND", "REQUIRED_TRANSITIONS", "TRANSITIONS", "EventMatcher",
    "EventMatcherConfig", "EventReplay", "EventSequencer", "EventWait", "MemorizedEvent",
    "MemorizedEventError", "MissedWait", "SlidingCorrelation",
    "StreamingCorrelator", "TactileTrial", "add_event_matcher", "channel_score",
    "channels_trajectory", "classify_missed_wait", "current_package_versions", "cut_window",
    "event_scores_reference", "event_templates", "event_transition", "event_waits",
    "extract_memorized_events", "live_matcher_config", "load_all_memorized_events",
    "load_memorized_events", "max_normalized_xcorr_reference", "next_sequence_step",
    "normalize_by_max", "read_index", "read_memorized_event",
    "replay_event_held", "replay_events_in_sequence", "save_memorized_events", "tactile_trial_from_log",
    "transition_name", "transition_order", "transition_states",
    "window_contrast",
]
