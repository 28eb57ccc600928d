"""An object's memorized events in one folder as one set: its grasp events are cut from one
ideal grasp (extraction.py), so they share its scenario and come in its order; every event of
the object, corrective ones too, was felt on one object and is matched by one matcher, so
they share the object description, the window and the rates. Asked of every folder read
(events_folder.load_memorized_events) and of every save, before it writes anything."""

from collections.abc import Iterable

from tegrasp_drake.rig.echo import shorten
from tegrasp_drake.rig.number_text import number_text
from tegrasp_drake.rig.objects import description_differences
from tegrasp_drake.events.memorized_event import MemorizedEvent
from tegrasp_drake.events.transitions import GRASP_TRANSITIONS, transition_order


def object_events_problem(events: Iterable[MemorizedEvent]
                          ) -> tuple[MemorizedEvent, str] | None:
    """(event, what is wrong, naming its field and the other event's value) for the first of
    one object's `events` that cannot belong with the others, else None:
    - window_s, sa_rate_hz, ra_rate_hz: one matcher scores all of them;
    - object_description: all were felt on one object;
    - of the grasp transitions (GRASP_TRANSITIONS), `scenario`: one grasp's, the same text
      (an ensemble's note names its runs once for all); `transition_time_s`: strictly
      increasing in grasp order. Corrective events come from runs of their own
      (recording/corrective_events.py) and keep their own scenario and time."""
    events = sorted(events, key=lambda e: transition_order(e.transition))
    if not events:
        return None
    first = events[0]
    for event in events[1:]:
        for field in ("window_s", "sa_rate_hz", "ra_rate_hz"):
            if getattr(event, field) != getattr(first, field):
                return event, (
                    f"field '{field}' is {number_text(getattr(event, field))}, but "
                    f"{first.transition}'s is {number_text(getattr(first, field))}: the "
                    f"events of '{event.object_name}' have different windows or rates, which "
                    "one matcher cannot use")
        differences = description_differences(
            event.object_description, first.object_description,
            labels=("here", f"{first.transition}'s"))
        if differences:
            return event, (f"field 'object_description' differs from {first.transition}'s: "
                           f"{'; '.join(differences)}: an object's events are felt on one "
                           "object")
    grasp = [e for e in events if e.transition in GRASP_TRANSITIONS]
    for earlier, event in zip(grasp, grasp[1:]):
        if event.scenario != grasp[0].scenario:
            return event, (f"field 'scenario' differs from {grasp[0].transition}'s "
                           f"({_first_difference(event.scenario, grasp[0].scenario)}): an "
                           "object's events come from one grasp, one recording")
        if not event.transition_time_s > earlier.transition_time_s:
            return event, (f"field 'transition_time_s' is "
                           f"{number_text(event.transition_time_s)} s, not after "
                           f"{earlier.transition}'s {number_text(earlier.transition_time_s)} "
                           "s: an object's events come from one grasp, in its order")
    return None


def _first_difference(text: str, other: str) -> str:
    """The first line in which two texts differ, both ways: "line 1: 'a' here, 'b' there"."""
    lines, other_lines = text.splitlines(), other.splitlines()
    for number, (line, other_line) in enumerate(zip(lines, other_lines), start=1):
        if line != other_line:
            return (f"line {number}: {shorten(repr(line))} here, "
                    f"{shorten(repr(other_line))} there")
    if len(lines) == len(other_lines):
        return "they differ in line endings only"
    number = min(len(lines), len(other_lines)) + 1
    return (f"it has {len(lines)} lines, the other {len(other_lines)}; line {number} is where "
            "one ends")
