"""Memorized tactile events: extraction, file format, live windows and matching.

The record step cuts max-normalised 0.5 s windows of the four channels around each grasp
transition of an ideal grasp (extraction.py); each is a MemorizedEvent (memorized_event.py),
stored as JSON files (event_file.py, FORMAT.md) in an events folder with an index
(events_folder.py). In the control loop (the paper's Fig. 3), the EventMatcher is a
WindowNormalizer (tactile/window_normalizer.py: the live 0.5 s windows) that scores its
windows against the expected event with Eq. 3 (correlation.py, streaming_correlation.py) in
the update that takes each sample; `add_event_matcher` adds it to a diagram. The
EventSequencer expects an object's events one after another. replay.py runs a logged trial
through them offline; missed_waits.py replays the waits for an event that never came and
says why.

Not re-exported here, so that the control loop does not import matplotlib:
`plot.plot_memorized_events` (the Fig. 5c-like figure), `benchmark` (the matcher's cost
per tick; `python -m benchmarks.matcher`) and `synthetic` (synthetic grasps
for tests).
"""

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
