"""The one boundary every message from a device crosses: decode, check, count, skip. A check
returns the checked value or raises `RejectedMessage(reason, detail)` (any other exception counts
as "undecodable"). A rejected message is counted and skipped and the receiver keeps its last good
value, so a device sending nothing usable looks silent to the watchdog. What a stream does that
is no refusal but changes what follows (a device restarting its sequence) is a notice: said
live, counted by the decoder that saw it. Thread-safe."""

import dataclasses
import threading
from collections.abc import Callable

# Reasons shared by several boundaries (a check may name others).
UNDECODABLE = "undecodable"


class RejectedMessage(ValueError):
    """A refused message: `reason`, the short name it is counted under; `detail`, what was wrong."""

    def __init__(self, reason: str, detail: str):
        super().__init__(f"{reason}: {detail}")
        self.reason = reason
        self.detail = detail


@dataclasses.dataclass
class MessageCounters:
    """What a boundary let through and what it threw away, by reason."""
    accepted: int = 0
    rejected: dict = dataclasses.field(default_factory=dict)  # reason -> count
    last_rejection: str = ""

    def count_rejection(self, rejection: RejectedMessage) -> None:
        """Counts `rejection` under its reason."""
        self.rejected[rejection.reason] = self.rejected.get(rejection.reason, 0) + 1
        self.last_rejection = str(rejection)

    @property
    def rejected_total(self) -> int:
        return sum(self.rejected.values())

    def summary(self, noun: str = "messages") -> str:
        """E.g. "2001 messages, 3 rejected (wrong type 2, not finite 1)"."""
        text = f"{self.accepted} {noun}, {self.rejected_total} rejected"
        if self.rejected:
            text += " (" + ", ".join(f"{reason} {count}" for reason, count
                                     in sorted(self.rejected.items())) + ")"
        return text


class MessageBoundary:
    """Checks messages from one `source` ("arm: KINOVA_JACO_STATUS") with
    check(message, *args) -> the checked value, or RejectedMessage."""

    def __init__(self, source: str, check: Callable | None = None):
        self.source = source
        self._check = check
        self._lock = threading.Lock()
        self._counters = MessageCounters()
        self._unreported = []  # RejectedMessage of reasons not yet handed to new_rejections
        self._notices = {}  # what -> [the first detail, how many] not yet handed to new_notices
        self._listeners = []

    def add_listener(self, listener: Callable) -> None:
        """Calls listener(value) with each value `accept` lets through, after counting it."""
        self._listeners.append(listener)

    def accept(self, message, *args):
        """The checked value of `message`, or None (counted) when rejected; listeners see it."""
        try:
            value = self._checked(message, *args)
        except RejectedMessage as rejection:
            self._count(rejection)
            return None
        self.count_accepted()
        for listener in self._listeners:
            listener(value)
        return value

    def check_quietly(self, message, *args, tally: "MessageCounters | None" = None):
        """The checked value of `message`, or None, counting nothing here (a look at a message
        that will be counted when it is taken: lcm_boundary.wait_for_checked_message);
        `tally`, when given, counts it instead, so that a wait can say what it refused."""
        try:
            value = self._checked(message, *args)
        except RejectedMessage as rejection:
            if tally is not None:
                tally.count_rejection(rejection)
            return None
        if tally is not None:
            tally.accepted += 1
        return value

    def _checked(self, message, *args):
        """check(message, *args), any exception but a RejectedMessage made one (undecodable)."""
        try:
            return self._check(message, *args)
        except RejectedMessage:
            raise
        except Exception as e:  # noqa: BLE001: untrusted bytes must never raise out
            raise RejectedMessage(UNDECODABLE, f"{type(e).__name__}: {e}") from None

    def count_accepted(self, count: int = 1) -> None:
        """Counts messages accepted outside `accept` (a framer that checks on its own)."""
        with self._lock:
            self._counters.accepted += count

    def reject(self, reason: str, detail: str) -> None:
        """Counts a rejection found outside `check` (e.g. a transaction with no answer)."""
        self._count(RejectedMessage(reason, detail))

    def _count(self, rejection: RejectedMessage) -> None:
        with self._lock:
            if rejection.reason not in self._counters.rejected:
                self._unreported.append(rejection)
            self._counters.count_rejection(rejection)

    def counters(self) -> MessageCounters:
        """A snapshot of the counts."""
        with self._lock:
            return dataclasses.replace(self._counters,
                                       rejected=dict(self._counters.rejected))

    def new_rejections(self) -> list[RejectedMessage]:
        """The first rejection of each reason not yet handed over, for a live line."""
        with self._lock:
            new, self._unreported = self._unreported, []
        return new

    def notice(self, what: str, detail: str) -> None:
        """Records that the stream did `what` ("restarted its sequence"), `detail` saying
        where, for a live line (new_notices)."""
        with self._lock:
            self._notices.setdefault(what, [detail, 0])[1] += 1

    def new_notices(self) -> list[str]:
        """One line per kind of notice since the last call: the first's detail and, when
        several came together, how many (a stream that keeps doing it is said once a call,
        not once a frame)."""
        with self._lock:
            notices, self._notices = self._notices, {}
        return [f"{self.source}: the stream {what} ({detail})"
                + (f", {count} times since the last report" if count > 1 else "")
                for what, (detail, count) in notices.items()]

    def describe(self, rejection: RejectedMessage) -> str:
        """One line for the first rejection of a reason."""
        return (f"{self.source}: skipped a message ({rejection}); messages like it are "
                "skipped and counted")
